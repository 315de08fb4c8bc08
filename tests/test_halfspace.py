"""The half-space layer: the point-collocated kernel (halfspace.collocation) as a discretisation
of its own, converging to the continuum, and the two BEMs built on different kernels, so that
an error in either kernel shows up as a disagreement between them.

Stiffnesses here are solved directly (C_SS p = 1 on the raster, K = Delta^2 sum p) so that the
kernel is tested apart from either solver's iteration."""

import math

import numpy as np
import pytest
import scipy.fft as sfft
from scipy.integrate import quad
from scipy.sparse.linalg import LinearOperator, cg

import bem_energy as be
import contact_scene as cs
import halfspace
import halfspace.collocation as hc
import halfspace.kernel as hk
from contact_scene import theory as T
from crossval.compare import compare
from halfspace import HalfSpaceOperator, padded_shape


def flat_stiffness(shape, spacing, kernel, k=0.0):
    """Stiffness of the rigid flat face on the half-space E* = 1 (k = 0) or E0 = c0 = 1 (graded),
    and the raster's area."""
    r = cs.rasterise(shape, spacing)
    nx, ny = r.shape
    P = padded_shape(nx, ny)
    if k == 0.0:
        K = kernel(nx, ny, spacing, 1.0, P)
    else:
        K = kernel(nx, ny, spacing, 1.0, 1.0, k, P)
    op = HalfSpaceOperator(K, (nx, ny))
    m = r.mask
    n = int(m.sum())
    A = LinearOperator((n, n), matvec=lambda v: op.apply_masked(v, m)[m], dtype=float)
    p, info = cg(A, np.ones(n), rtol=1e-11, maxiter=10_000)
    assert info == 0
    return spacing**2 * float(p.sum()), r.area


def square_centre_integral(half_width, k):
    """Integral of r^-(1+k) over the square |x|, |y| <= b at its centre: eight triangles,
    8 b^(1-k) / (1-k) * integral_0^(pi/4) sec^(1-k)."""
    angular, _ = quad(lambda t: math.cos(t) ** (k - 1.0), 0.0, math.pi / 4, epsabs=0.0, epsrel=1e-13)
    return 8.0 * half_width ** (1.0 - k) / (1.0 - k) * angular


def element_centre_self_term(monkeypatch):
    """The mutant: the self term of the element's own centre displacement instead of the
    lattice-consistent one (what Love's squares have on their diagonal)."""
    monkeypatch.setattr(hc, "square_lattice_zeta", lambda s: -square_centre_integral(0.5, s - 1.0))


# -- the self term -------------------------------------------------------------


def test_lattice_zeta_is_the_glasser_zucker_constant_and_has_the_continuum_pole():
    # Z(1) = 4 zeta(1/2) beta(1/2), tabulated independently (halfspace.kernel.MADELUNG_SQUARE)
    assert hc.square_lattice_zeta(1.0) == pytest.approx(halfspace.MADELUNG_SQUARE, rel=1e-12)
    # near s = 2 the lattice sum diverges like the integral of r^-s outside a disk, 2 pi / (2 - s)
    # r0^(2-s): Z(s) = 2 pi / (s - 2) + a finite remainder, so (s - 2) Z(s) -> 2 pi linearly
    for eps in (1e-3, 1e-4):
        assert (-eps) * hc.square_lattice_zeta(2.0 - eps) == pytest.approx(2.0 * math.pi, abs=20 * eps)
    with pytest.raises(ValueError):
        hc.square_lattice_zeta(2.0)


@pytest.mark.parametrize("k", [0.0, 0.5, 0.9])
def test_uniform_pressure_on_a_block_gives_the_exact_centre_displacement(k):
    """Uniform pressure on an M x M block of elements: the point sum plus the self term must
    give the exact centre displacement A_k * integral over the block.  What is left is the
    midpoint rule's error on the elements outside the block (the self term absorbs all the
    others): about (1+k)^2/24 Delta^4 r^-(3+k) per element, summed beyond the inscribed
    circle r > L/2, (1+k) pi / 12 * Delta^2 (L/2)^-(1+k)."""
    M, h = 33, 1.0
    K = (
        hc.collocated_graded_influence(M, M, h, 1.0, 1.0, k, padded_shape(M, M))
        if k
        else hc.collocated_influence(M, M, h, 1.0, padded_shape(M, M))
    )
    A = T.graded_green_coefficient(E0=1.0, c0=1.0, k=k) if k else 1.0 / math.pi
    u = HalfSpaceOperator(K, (M, M)).apply(np.ones((M, M)))[M // 2, M // 2]
    L = M * h
    exact = A * square_centre_integral(L / 2, k)
    bound = A * (1 + k) * math.pi / 12 * h**2 * (L / 2) ** -(1 + k)
    assert abs(u - exact) <= bound
    # the element-centre self term misses by (S_k(h/2) + Z(1+k)) A_k h^(1-k): 23x the bound at
    # k = 0, more for k > 0 (the remainder above is 0.83-0.90 of the bound)
    miss = A * (square_centre_integral(h / 2, k) + hc.square_lattice_zeta(1 + k)) * h ** (1 - k)
    assert abs(miss) > 20 * bound


# -- convergence of the flat-punch stiffness ------------------------------------


def _fitted_rate(Ns, errors):
    return -np.polyfit(np.log(Ns), np.log(np.abs(errors)), 1)[0]


@pytest.mark.parametrize("k", [0.0, 0.5, 0.9])
def test_collocated_circle_stiffness_converges_first_order_to_eqs_1_and_34(k):
    """Flat circle at N = 16, 32, 64 elements per radius against Eq. 1 (k = 0) / Eq. 34 at
    the raster's area (the staircase's area change is the raster's, not the kernel's).
    Measured (this test's numbers): k = 0: -1.04, -0.50, -0.25 %; k = 0.5: -0.84, -0.41,
    -0.21 %; k = 0.9: -0.23, -0.11, -0.06 %: first order, |error| <= 0.17 / N.  With the
    element-centre self term the graded errors stall near +0.7 % (k = 0.5) and +1.0 %
    (k = 0.9): rates of 0.2 and 0."""
    Ns = np.array([16, 32, 64])
    errs = []
    for N in Ns:
        if k:
            K, area = flat_stiffness(cs.Circle(1.0), 1.0 / N, hc.collocated_graded_influence, k)
            ref = T.graded_stiffness(E0=1.0, c0=1.0, k=k, radius=math.sqrt(area / math.pi))
        else:
            K, area = flat_stiffness(cs.Circle(1.0), 1.0 / N, hc.collocated_influence)
            ref = T.kendall_stiffness(E_star=1.0, radius=math.sqrt(area / math.pi))
        errs.append(K / ref - 1)
    errs = np.array(errs)
    assert np.all(np.abs(errs) * Ns <= 0.2)
    assert 0.8 <= _fitted_rate(Ns, errs) <= 1.3


def test_collocated_square_stiffness_extrapolates_to_beta_1021():
    """Square of side 2 with 16, 32, 64 elements per half side (the raster is the square
    itself): beta = K / (2 E* sqrt(A/pi)) rises like 1/N (measured 1.00794, 1.01449,
    1.01782: steps halve) and its first-order extrapolation is Eq. 9's 1.021, to the three
    digits Eq. 9 quotes; Love's squares extrapolate to the same value from 1.01049,
    1.01577, 1.01846 (the same on the same grids to 0.2-0.3 %, not to round-off)."""
    Ns = np.array([16, 32, 64])
    beta = {}
    for name, kernel in (("collocation", hc.collocated_influence), ("love", halfspace.love_influence)):
        beta[name] = np.array(
            [flat_stiffness(cs.Square(2.0), 1.0 / N, kernel)[0] / (2 * math.sqrt(4 / math.pi)) for N in Ns]
        )
    for b in beta.values():
        steps = np.diff(b)
        assert np.all(steps > 0) and 1.7 <= steps[0] / steps[1] <= 2.4
        assert 2 * b[-1] - b[-2] == pytest.approx(1.021, abs=1e-3)
    # two discretisations: on a common grid they differ by their own first-order errors only
    assert np.all(np.abs(beta["collocation"] / beta["love"] - 1) <= 0.1 / Ns)
    assert np.all(np.abs(beta["collocation"] / beta["love"] - 1) >= 0.01 / Ns)


def test_element_centre_self_term_stalls_for_a_graded_body(monkeypatch):
    """The mutant the self term is chosen against: the graded circle's error no longer falls."""
    element_centre_self_term(monkeypatch)
    k, Ns = 0.5, np.array([16, 32, 64])
    errs = []
    for N in Ns:
        K, area = flat_stiffness(cs.Circle(1.0), 1.0 / N, hc.collocated_graded_influence, k)
        errs.append(K / T.graded_stiffness(E0=1.0, c0=1.0, k=k, radius=math.sqrt(area / math.pi)) - 1)
    assert _fitted_rate(Ns, errs) < 0.5


# -- the two BEMs on different kernels ---------------------------------------------


def test_energy_settings_name_the_kernels():
    assert be.EnergySettings().kernel == "collocation"
    with pytest.raises(cs.SceneError, match="settings.kernel.*'collocation', 'love'"):
        be.EnergySettings(kernel="boussinesq")


#: the two kernels' same-grid stiffness difference K_love / K_collocation - 1 times N (N
#: elements per equivalent radius): measured +0.045 ... +0.069 on the flat circle, square
#: (also at 45 degrees), equilateral triangle, 4:1 rectangle and 5-ray star at N = 8 ... 64
#: (the star the largest); 0.047, 0.046, 0.046 for the square at N = 8, 16, 32 through the
#: two solvers
MEASURED_SAME_GRID = (0.045, 0.069)


def _bem_stiffness_check(shape, N):
    """``crossval compare``'s check of K_griffith against K_energy for the non-adhesive flat
    punch at N elements per radius, and N (K_griffith / K_energy - 1)."""
    sc = cs.Scene(cs.Indenter(shape), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.0, None, "exponential"))
    c = compare(sc, methods=["bem_griffith", "bem_energy"], resolution=N)
    (check,) = [ch for ch in c.checks if ch.method == "bem_griffith vs bem_energy" and ch.quantity == "stiffness"]
    return check, N * (c.results["bem_griffith"].stiffness / c.results["bem_energy"].stiffness - 1)


def _scaled(f, factor):
    return lambda *a, **kw: factor * f(*a, **kw)


def test_the_same_grid_window_contains_what_was_measured():
    from crossval.compare import SAME_GRID_WINDOW

    lo, hi = SAME_GRID_WINDOW["love", "collocation"]
    assert lo < MEASURED_SAME_GRID[0] and MEASURED_SAME_GRID[1] < hi
    assert lo > 0  # a sign: the kernels' difference is not noise around zero


@pytest.mark.parametrize("kernel", ["love", "collocation"])
def test_a_one_percent_kernel_error_shows_up_between_the_two_bems(monkeypatch, kernel):
    """A 1 % error in either kernel's code moves the Griffith-vs-energy stiffness ratio of the
    flat square by about 1 %, against a same-grid difference between the unmutated kernels
    of 0.05/N (0.15 % at N = 32).  The stiffness scales as 1/C: the ratio moves by 0.99 %.
    ``crossval compare`` holds the two BEMs on one grid to the window of that measured
    difference (``crossval.compare.SAME_GRID_WINDOW``), so its check fails on the mutant."""
    N = 32
    check, base = _bem_stiffness_check(cs.Square(2.0), N)
    assert check.passed and check.kind == "bounds"
    assert MEASURED_SAME_GRID[0] - 0.002 <= base <= MEASURED_SAME_GRID[1] + 0.002
    if kernel == "love":  # the element integral itself: every user of Love's squares sees it
        monkeypatch.setattr(hk, "love_square_integral", _scaled(hk.love_square_integral, 1.01))
    else:
        monkeypatch.setattr(hc, "_point_layout", _scaled(hc._point_layout, 1.01))
    check, mutated = _bem_stiffness_check(cs.Square(2.0), N)
    assert not check.passed, "crossval compare missed a 1 % kernel error"
    assert abs((1 + mutated / N) / (1 + base / N) - 1) > 0.008


def test_the_collocated_self_term_of_the_elements_own_centre_fails_the_same_grid_window(monkeypatch):
    """Mutant H3: the collocated kernel's self term from the element's own centre displacement
    (8 ln(1 + sqrt 2) = 3.5255 Delta / (pi E*)) instead of the lattice zeta (3.9003): each
    element less compliant by a tenth of its self term, an error of order 1/N that the energy
    BEM's own bar (0.30/N) cannot see, but it turns the same-grid difference from +0.046/N to
    -0.066/N (N = 16, circle).  Caught by: the signed same-grid window."""
    N = 16
    check, base = _bem_stiffness_check(cs.Circle(1.0), N)
    assert check.passed
    monkeypatch.setattr(hc, "square_lattice_zeta", lambda s: -4.0 * math.asinh(1.0))
    check, mutated = _bem_stiffness_check(cs.Circle(1.0), N)
    assert mutated < 0 < base
    assert not check.passed


def test_on_loves_squares_both_bems_share_a_kernel_error(monkeypatch):
    """Why the energy BEM's default is its own kernel: with ``kernel="love"`` both methods
    solve the same discrete problem, and a 1 % error in Love's integral moves both alike."""
    import bem_griffith as bg

    monkeypatch.setattr(hk, "love_square_integral", _scaled(hk.love_square_integral, 1.01))
    sc = cs.Scene(cs.Indenter(cs.Square(2.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.0, None, "exponential"))
    grid = cs.Grid(elements_per_radius=16)
    r_e = be.solve(sc, be.EnergySettings(grid=grid, kernel="love"))
    r_g = bg.solve(sc, bg.GriffithSettings(grid=grid))
    assert r_e.stiffness == pytest.approx(r_g.stiffness, rel=1e-6)


# -- the operator's transforms ---------------------------------------------------


def test_products_in_reused_buffers_are_the_dense_matrix_products_whatever_came_before(monkeypatch):
    """The operator transforms in buffers it keeps between products: every product, after a
    denser mask or a product in the other precision, equals the dense matrix C restricted to
    its mask (float64 to round-off, float32 to single precision) and, bit for bit, the product
    scipy.fft computes in freshly allocated arrays."""
    import halfspace.operator as ho

    nx, ny = 13, 9
    P = padded_shape(nx, ny)
    K = hk.love_influence(nx, ny, 0.3, 1.0, P)
    op = HalfSpaceOperator(K, (nx, ny))
    rows, cols = np.divmod(np.arange(nx * ny), ny)
    C = K[(rows[:, None] - rows[None, :]) % P[0], (cols[:, None] - cols[None, :]) % P[1]]
    rng = np.random.default_rng(4)
    masks = [np.ones((nx, ny), bool), rng.random((nx, ny)) < 0.3, rng.random((nx, ny)) < 0.7]
    single = op.symbol.astype(np.float32)
    products = []
    for mask in masks + masks[::-1]:
        v = rng.standard_normal(int(mask.sum()))
        dense = C[:, mask.ravel()] @ v
        u = op.apply_masked(v, mask)
        assert np.allclose(u.ravel(), dense, rtol=0, atol=1e-13 * np.abs(dense).max())
        u32 = op.apply_symbol(v, mask, single)
        assert np.allclose(u32, dense.reshape(nx, ny)[mask], rtol=0, atol=1e-5 * np.abs(dense).max())
        p = np.zeros((nx, ny))
        p[mask] = v
        products.append((v, mask, u, u32, op.apply(p)))
    monkeypatch.setattr(ho, "_pocketfft", None)  # scipy.fft's allocating transforms
    for v, mask, u, u32, whole in products:
        assert np.array_equal(u, op.apply_masked(v, mask))
        assert np.array_equal(u32, op.apply_symbol(v, mask, single))
        p = np.zeros((nx, ny))
        p[mask] = v
        assert np.array_equal(whole, op.apply(p))


@pytest.mark.parametrize("shape", [(7, 9), (101, 97), (2310, 26), (810, 810)])
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_inverse_one_axis_at_a_time_then_scaled_is_irfft2_bit_for_bit(shape, dtype):
    """An inverse run unnormalised one axis at a time (as the energy BEM's transforms run it,
    with the 1/n in their spectral factors) and scaled afterwards by norm_factor is scipy.fft's
    irfft2, bit for bit, at sizes whose 1/n is not a power of two: the split inverse computes
    what the 2-D call does."""
    from halfspace.pocketfft import POCKETFFT, norm_factor

    if POCKETFFT is None:
        pytest.skip("scipy.fft's pocketfft backend is not usable here")
    complex_type = np.complex64 if dtype == np.float32 else np.complex128
    half = sfft.rfft2(np.random.default_rng(7).standard_normal(shape).astype(dtype))
    assert half.dtype == complex_type
    spectrum = half.copy()
    POCKETFFT.c2c(spectrum, (0,), False, 0, spectrum, 1)
    out = POCKETFFT.c2r(spectrum, (1,), shape[1], False, 0, np.empty(shape, dtype), 1)
    out *= norm_factor(shape[0] * shape[1], dtype)
    assert np.array_equal(out, sfft.irfft2(half, s=shape))


def test_private_in_place_transforms_are_used_only_when_they_equal_scipy_fft():
    """The in-place transforms come from scipy's private pocketfft module: they are accepted only
    while they compute scipy.fft's numbers into the arrays given.  A changed normalisation, a
    result returned in a new array or a changed signature each turn them off (the public,
    allocating path), never into a wrong product."""
    import types

    from halfspace.pocketfft import POCKETFFT, same_as_scipy_fft

    real = pytest.importorskip("scipy.fft._pocketfft").pypocketfft
    assert same_as_scipy_fft(real) and POCKETFFT is real

    def mutant(**changes):
        fns = {name: getattr(real, name) for name in ("r2c", "c2c", "c2r", "dct")}
        return types.SimpleNamespace(**{**fns, **changes})

    def rescaled_c2r(a, axes, n, forward, inorm, out, nthreads):
        return real.c2r(a, axes, n, forward, 0, out, nthreads)  # unnormalised inverse

    def fresh_r2c(a, axes, forward, inorm, out, nthreads):
        return real.r2c(a, axes, forward, inorm, None, nthreads)  # ignores ``out``

    def new_signature(a, axes, forward, out=None):
        return real.c2c(a, axes, forward, 0, out, 1)

    def always_normalised_c2r(a, axes, n, forward, inorm, out, nthreads):
        return real.c2r(a, axes, n, forward, 2, out, nthreads)  # ignores an unnormalised request

    assert same_as_scipy_fft(mutant())
    assert not same_as_scipy_fft(mutant(c2r=always_normalised_c2r))
    assert not same_as_scipy_fft(mutant(c2r=rescaled_c2r))
    assert not same_as_scipy_fft(mutant(r2c=fresh_r2c))
    assert not same_as_scipy_fft(mutant(c2c=new_signature))

    def swapped_dct(a, kind, axes, inorm, out, nthreads):
        return real.dct(a, {1: 1, 2: 3, 3: 2}[kind], axes, inorm, out, nthreads)  # II and III swapped

    assert not same_as_scipy_fft(mutant(dct=swapped_dct))


@pytest.mark.parametrize("rows", [1, 2, 7, 8])
def test_mirrors_sees_any_asymmetric_element(rows):
    """``mirrors`` compares half the rows with their images: one changed element anywhere, the
    middle row of an odd grid included, is seen, and the exact mirror image passes."""
    rng = np.random.default_rng(rows)
    grid = rng.random((rows, 5))
    grid = grid + grid[::-1]
    assert halfspace.operator.mirrors(grid)
    for i in range(rows):
        for j in range(5):
            broken = grid.copy()
            broken[i, j] += 1e-12
            # a middle row mirrors onto itself: changing it keeps the mirror symmetry
            assert halfspace.operator.mirrors(broken) == (2 * i == rows - 1)


@pytest.mark.parametrize("shape", [(12, 9), (13, 9), (40, 31), (41, 30)], ids=str)
def test_mirror_symmetric_products_take_half_transforms_and_equal_the_full_ones(shape, count_calls):
    """A pressure that mirrors about the grid's middle row (even and odd row counts) is
    convolved by cosine transforms over half the rows: the product is the dense matrix's, and
    the full transforms', to round-off (double) and single precision (float32), and mirrors
    exactly.  An input off the mirror by one ulp takes the full transforms."""
    import halfspace.operator as ho

    nx, ny = shape
    P = padded_shape(nx, ny)
    if P[0] % 2:
        P = (P[0] + 1, P[1])  # the half transforms need an even padded row count
    K = hk.love_influence(nx, ny, 0.3, 1.0, P)
    op = HalfSpaceOperator(K, (nx, ny))
    rows, cols = np.divmod(np.arange(nx * ny), ny)
    C = K[(rows[:, None] - rows[None, :]) % P[0], (cols[:, None] - cols[None, :]) % P[1]]
    rng = np.random.default_rng(5)
    mask = rng.random((nx, ny)) < 0.6
    mask = mask | mask[::-1]
    p = rng.standard_normal((nx, ny))
    p = np.where(mask, p + p[::-1], 0.0)
    calls = count_calls(ho.HalfSpaceOperator, "_mirrored")
    u = op.apply_masked(p[mask], mask)
    dense = (C[:, mask.ravel()] @ p[mask]).reshape(nx, ny)
    assert calls["_mirrored"] and np.array_equal(u, u[::-1])
    assert np.allclose(u, dense, rtol=0, atol=1e-14 * np.abs(dense).max())
    u32 = op.apply_symbol(p[mask].astype(np.float32), mask, op.symbol.astype(np.float32))
    assert np.allclose(u32, dense[mask], rtol=0, atol=1e-6 * np.abs(dense).max())
    assert calls["_mirrored"] == 2
    q = p.copy()
    q[0, np.flatnonzero(mask[0])[0]] = np.nextafter(q[0, np.flatnonzero(mask[0])[0]], np.inf)
    u_off = op.apply_masked(q[mask], mask)
    assert calls["_mirrored"] == 2 and np.allclose(u_off, dense, rtol=0, atol=1e-14 * np.abs(dense).max())


def test_an_odd_padded_row_count_keeps_the_full_transforms(monkeypatch):
    """The cosine pair needs an even number of padded rows: with an odd one (13 rows padded to
    25) a mirrored pressure takes the full transforms, with the same product."""
    import halfspace.operator as ho

    nx, ny = 13, 9
    P = padded_shape(nx, ny)
    assert P[0] % 2 == 1
    op = HalfSpaceOperator(hk.love_influence(nx, ny, 0.3, 1.0, P), (nx, ny))
    p = np.random.default_rng(6).standard_normal((nx, ny))
    p = p + p[::-1]
    everywhere = np.ones((nx, ny), bool)
    monkeypatch.setattr(ho.HalfSpaceOperator, "_mirrored", lambda self, *a: pytest.fail("half transforms"))
    assert np.array_equal(op.apply_masked(p[everywhere], everywhere), op.convolve(p))


@pytest.mark.parametrize("shape,period", [((12, 9), (14, 10)), ((13, 9), (16, 9)), ((12, 9), (12, 9))], ids=str)
def test_a_periodic_operator_convolves_circularly_over_a_period_longer_than_its_grid(shape, period, count_calls):
    """A circulant over a period at least the grid's (the grid's values zero-extended, as a
    compact preconditioner applies one): the masked products, double and single precision, are
    the dense circular convolution's, a mirrored pressure taking the half transforms (also
    where the period is the grid, a periodic array of faces).  A kernel too small for the grid
    is refused."""
    import halfspace.operator as ho

    nx, ny = shape
    Px, Py = period
    rng = np.random.default_rng(11)
    K = rng.standard_normal(period)
    K = K + K[(-np.arange(Px)) % Px]  # even along each axis, as the influence coefficients are
    K = K + K[:, (-np.arange(Py)) % Py]
    op = HalfSpaceOperator(K, shape, periodic=True)
    rows, cols = np.divmod(np.arange(nx * ny), ny)
    C = K[(rows[:, None] - rows[None, :]) % Px, (cols[:, None] - cols[None, :]) % Py]
    mask = rng.random(shape) < 0.6
    mask = mask | mask[::-1]
    p = rng.standard_normal(shape)
    p = np.where(mask, p + p[::-1], 0.0)
    calls = count_calls(ho.HalfSpaceOperator, "_mirrored")
    dense = (C[:, mask.ravel()] @ p[mask]).reshape(shape)
    scale = np.abs(dense).max()
    assert np.allclose(op.apply_masked(p[mask], mask), dense, rtol=0, atol=1e-13 * scale)
    u32 = op.apply_symbol(p[mask].astype(np.float32), mask, op.symbol.astype(np.float32))
    assert np.allclose(u32, dense[mask], rtol=0, atol=1e-5 * scale)
    assert calls["_mirrored"] == 2
    assert np.allclose(op.convolve(p), dense, rtol=0, atol=1e-13 * scale)
    with pytest.raises(ValueError, match="must hold the grid"):
        HalfSpaceOperator(K[: nx - 1], shape, periodic=True)
