"""What the tie tolerance of the Griffith BEM costs: a bound, proven from premises that are
checked here numerically, on face rasters and, for every contact set at once, on the infinite
element lattice.

On a flat face pulled monotonically, an element's tension -p = |d| x1 only grows as the pull
goes on and as other elements leave (C_SS^-1 has no positive off-diagonal entry).  Then the
union of two sets that hold at an approach d holds too, so at every d there is one largest set
that holds, and the exact cascade (every element leaving exactly at sigma_c) reaches it from any
set containing it.  With tie tolerance tau the cascade leaves the largest set that holds under
sigma_c (1 - tau) and keeps it until sigma_c is met: its set at d lies inside the exact pull's at
d and contains the exact pull's at d / (1 - tau) (tensions scale with |d|).  The force |d| K(S)
grows with the set, so F_A and the detachment approach lie within a factor [1 - tau, 1] of the
exact ones (``GriffithSettings.tie_tolerance``).  The same property checks the event driver
itself: the set a pull holds at d is the one a single cascade from the whole face at d leaves.
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import pytest

import bem_griffith as bg
import contact_scene as cs
from bem_griffith import preconditioner
from bem_griffith.counters import WorkCounters
from bem_griffith.driver import cascade
from bem_griffith.preconditioner import lattice_inverse_diagonal
from bem_griffith.press import pressed_state
from bem_griffith.problem import WALK_EXPONENTS, build_problem
from bem_griffith.stress_intensity import PaperRule
from crossval.suite import scene as builtin_scene
from halfspace.kernel import (
    graded_influence,
    graded_square_integral,
    love_influence,
    love_influence_periodic,
    point_kernel_transform,
    zero_mean_image_sum,
)

EXACT = 1e-12  # the smallest tie tolerance: ties to round-off only
TAU = 1e-2
#: the CG tolerance's reach into forces and approaches (rtol 1e-10, with room)
SLACK = 1e-8


N = 24  # elements per radius


def _scene(name: str) -> cs.Scene:
    """A built-in scene; "<face> graded" puts that face on the graded k = 0.5 material."""
    face, _, graded = name.partition(" ")
    scene = builtin_scene(face)
    if graded:
        scene = dataclasses.replace(scene, material=builtin_scene("graded_circle_k0.5").material)
    return scene


def _pull(name: str, tau: float, snapshots=(), **options):
    scene = _scene(name)
    scene = dataclasses.replace(scene, outputs=dataclasses.replace(scene.outputs, snapshots=tuple(snapshots)))
    settings = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), tie_tolerance=tau, **options)
    return bg.solve(scene, settings)


def _between(*approaches) -> np.ndarray:
    """Midpoints between consecutive pulling approaches: one inside every interval on which both
    curves hold their sets, except intervals shorter than the CG tolerance's reach (two runs
    solve the same set to rtol separately, so the same event can fall 1e-9 apart)."""
    a = np.unique(np.concatenate(approaches))
    a = a[a < 0]
    lo, hi = a[:-1], a[1:]
    long_enough = hi - lo > 10 * SLACK * np.abs(lo)
    return 0.5 * (lo + hi)[long_enough]


def _bound_failures(name: str, tau: float, **options) -> list[str]:
    """Where the pull with tie tolerance ``tau`` leaves the bound around the exact pull, at an
    approach inside every interval between the events of either pull."""
    exact, tied = _pull(name, EXACT, **options), _pull(name, tau, **options)
    events, tied_events = exact.curve.approach, tied.curve.approach
    inner = _between(events, tied_events)  # tied at d inside exact at d
    outer = _between(events * (1 - tau), tied_events)  # tied at d contains exact at d / (1 - tau)
    wanted = (*inner, *outer, *(outer / (1 - tau)))
    exact, tied = _pull(name, EXACT, wanted, **options), _pull(name, tau, wanted, **options)
    none = np.zeros_like(exact.snapshots[0].contact)  # beyond the detachment: no snapshot, no contact
    sets = {s.approach: s.contact for s in exact.snapshots}
    tied_sets = {s.approach: s.contact for s in tied.snapshots}
    failures = []
    for d in inner:
        if (tied_sets.get(d, none) & ~sets.get(d, none)).any():
            failures.append(f"d = {d:.6g}: the tied set is not inside the exact one")
    for d in outer:
        if (sets.get(d / (1 - tau), none) & ~tied_sets.get(d, none)).any():
            failures.append(f"d = {d:.6g}: the tied set does not contain the exact one at d / (1 - tau)")
    for what in ("pulloff_force", "detachment_approach"):
        ratio = getattr(tied, what) / getattr(exact, what)
        if not 1 - tau - SLACK <= ratio <= 1 + SLACK:
            failures.append(f"{what}: tied / exact = {ratio:.8f} outside [1 - tau, 1]")
    return failures


@pytest.mark.parametrize("name", ["star", "triangle", "star graded"])
def test_a_tie_tolerance_moves_the_pull_within_its_bound(name):
    assert _bound_failures(name, TAU) == []


def test_the_bound_is_exercised_not_vacuous():
    # at N = 24 the star's events batch and its pull-off drops, by less than tau
    exact, tied = _pull("star", EXACT), _pull("star", TAU)
    assert tied.info["events"] < exact.info["events"] / 2
    assert 1 - TAU <= tied.pulloff_force / exact.pulloff_force < 1 - 1e-4


def test_the_fixed_step_driver_is_not_covered():
    # why the bound names the event driver: with fixed steps a tied cascade can run at an
    # approach past several events, where the exact pull would have held a larger set
    assert _bound_failures("star", TAU, driver="fixed_step", step=0.05) != []


def test_a_cascade_that_leaves_below_its_threshold_breaks_the_bound(monkeypatch):
    # mutant: the cascade's threshold ten times further below sigma_c than the tolerance says
    monkeypatch.setattr(PaperRule, "threshold", lambda self, tie: self.critical_stress * (1 - 10 * tie))
    assert _bound_failures("star", TAU) != []


def _influence_table(k: float, nx: int, ny: int) -> np.ndarray:
    """The solver's own influence coefficients at unit spacing (E* = 1, or the graded kernel with
    E0 = c0 = 1), offsets laid out modulo the (2 nx, 2 ny) padded grid."""
    return love_influence(nx, ny, 1.0, 1.0) if k == 0 else graded_influence(nx, ny, 1.0, 1.0, 1.0, k)


def _block(table: np.ndarray, rows: tuple[np.ndarray, np.ndarray], cols: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """The dense block of C between the cells ``rows`` and ``cols`` (index arrays (i, j))."""
    Mx, My = table.shape
    return table[(rows[0][:, None] - cols[0][None, :]) % Mx, (rows[1][:, None] - cols[1][None, :]) % My]


def _premise(name: str, k: float, holes: float = 0.0, seed: int = 0) -> tuple[float, float, float]:
    """Over the face raster of a built-in scene at N per radius, less a random fraction
    ``holes`` of its cells: the largest off-diagonal entry of C_SS^-1 relative to its largest
    diagonal entry, the smallest entry of C_SS^-1 1 relative to its largest, and the largest
    displacement per approach (C x1) of a hole (1 would close its gap).  Every principal
    submatrix of an inverse M-matrix is one (Johnson 1982), so no positive entry on the whole
    face means none on any contact set of it."""
    settings = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N))
    face = build_problem(builtin_scene(name), settings).face.copy()
    contact = face & (np.random.default_rng(seed).random(face.shape) >= holes)
    table = _influence_table(k, *face.shape)
    held = np.nonzero(contact)
    inverse = np.linalg.inv(_block(table, held, held))
    off = inverse - np.diag(np.diag(inverse))
    x1 = inverse.sum(axis=1)
    hole_displacement = _block(table, np.nonzero(face & ~contact), held) @ x1
    largest_hole = float(hole_displacement.max()) if hole_displacement.size else 0.0
    return float(off.max() / np.diag(inverse).max()), float(x1.min() / x1.max()), largest_hole


@pytest.mark.parametrize("k", [0.0, 0.5])
@pytest.mark.parametrize("name", ["star", "triangle"])
def test_tensions_grow_when_elements_leave(name, k):
    # the premises of the bound, for the kernels it is claimed for: no positive off-diagonal
    # entry of C_SS^-1 (on the whole face, hence on every contact set) and x1 = C_SS^-1 1 > 0,
    # and a free element's displacement per approach below one (no gap closes while pulling), on
    # the face and on sets with holes (the lattice tests below cover every set at once)
    for seed, holes in enumerate([0.0, 0.2, 0.4]):
        off_diagonal, smallest_x1, largest_hole = _premise(name, k, holes, seed)
        assert off_diagonal <= 0.0
        assert smallest_x1 > 0.0
        assert largest_hole < 1.0
        assert holes == 0.0 or largest_hole > 0.5  # the holes are pulled along, not inert


@pytest.mark.parametrize("k", [-0.5, -0.1])
def test_the_premise_fails_for_negative_grading(k):
    # why the bound is not claimed for k < 0: removing an element can relieve another
    off_diagonal, _, _ = _premise("star", k)
    assert off_diagonal > 0.0


@functools.cache
def _lattice_inverse(k: float, n: int, rings: int = 2) -> np.ndarray:
    """The coefficients of C^-1 on an n x n torus of elements of unit side (E* = 1; for a graded
    body the kernel r^-(1+k) without its constant), entry [i, j] that of the offset (i, j) modulo
    n, from the symbol of the zero-mean image sum of the solver's element integrals over 2, 4 and
    8 rings of images (``halfspace.kernel.zero_mean_image_sum``), the mean mode of the inverse
    set to zero (the lattice symbol is infinite at zero frequency).  By Poisson
    summation the torus's coefficients are the infinite lattice's summed over their images n
    apart, so they approach the lattice's like n^-(3-k), the decay of the coefficients."""
    if k == 0:
        periodic = love_influence_periodic(n, 1.0, 1.0, images=4 * rings)
    else:
        periodic = zero_mean_image_sum(lambda X, Y: graded_square_integral(X, Y, 0.5, k), n, 1.0, images=4 * rings, k=k)
    symbol = np.fft.fft2(periodic).real
    with np.errstate(divide="ignore"):
        inverse_symbol = 1.0 / symbol
    inverse_symbol[0, 0] = 0.0
    return np.fft.ifft2(inverse_symbol).real


def _window(k: float, n: int, reach: int) -> np.ndarray:
    """The n-torus's coefficients at offsets |m|_inf <= reach, relative to its diagonal, as a
    (2 reach + 1)^2 array centred on the zero offset."""
    torus = _lattice_inverse(k, n)
    m = np.arange(-reach, reach + 1) % n
    return torus[np.ix_(m, m)] / torus[0, 0]


def _extrapolated(k: float, n: int, reach: int) -> np.ndarray:
    """The lattice's coefficients at |m|_inf <= reach relative to its diagonal, extrapolated in
    n^-(3-k) from the tori of n / 2 and n cells."""
    coarse, fine = _window(k, n // 2, reach), _window(k, n, reach)
    return fine + (fine - coarse) / (2.0 ** (3.0 - k) - 1.0)


def _near_field(k: float) -> tuple[np.ndarray, np.ndarray]:
    """The lattice inverse's off-diagonal coefficients at |m|_inf <= 4 relative to its diagonal,
    extrapolated from tori of 32 and 64 cells, and the change from the extrapolation of 16 and 32
    (an estimate of the extrapolation's error), flattened, the zero offset left out."""
    fine, coarse = _extrapolated(k, 64, 4), _extrapolated(k, 32, 4)
    off = np.ones(fine.shape, bool)
    off[4, 4] = False
    return fine[off], np.abs(fine - coarse)[off]


def _section_row(k: float, reach: int, offsets) -> np.ndarray:
    """The central row of C_SS^-1 on the square section of the solver's own influence coefficients
    with |m|_inf <= reach, at ``offsets``, relative to its diagonal: sections approach the
    lattice as they grow, an independent route to its coefficients."""
    n = 2 * reach + 1
    cells = np.divmod(np.arange(n * n), n)
    centre = reach * n + reach
    row = np.linalg.solve(_block(_influence_table(k, n, n), cells, cells), np.eye(n * n)[centre])
    return np.array([row[(reach + a) * n + reach + b] for a, b in offsets]) / row[centre]


def _lattice_diagonal(k: float) -> tuple[float, float]:
    """The lattice inverse's diagonal coefficient D0 at unit spacing, extrapolated in n^-(3-k)
    from the tori of 32 and 64 cells, and the change from the extrapolation of 16 and 32."""

    def extrapolated(n):
        coarse, fine = _lattice_inverse(k, n // 2)[0, 0], _lattice_inverse(k, n)[0, 0]
        return fine + (fine - coarse) / (2.0 ** (3.0 - k) - 1.0)

    return float(extrapolated(64)), float(abs(extrapolated(64) - extrapolated(32)))


def _diagonal_bound(k: float) -> float:
    # the point kernel of the tori's coefficients: 1 / (pi E*) at k = 0 (E* = 1), r^-(1+k) otherwise
    return lattice_inverse_diagonal(1.0, (1.0 / math.pi if k == 0 else 1.0, k))


@pytest.mark.parametrize("k", [-0.9, -0.5, 0.0, 0.5, 0.95])
def test_the_inverse_diagonal_bound_holds_the_lattice_diagonal(k):
    # the bound the early decisions take for every (C_SS^-1)_ii (``Problem.inverse_diagonal``),
    # from the lattice symbol in Fourier space, against D0 from the solver's own coefficients on
    # tori in real space: above it, and by little (the decisions wait on it)
    diagonal, error = _lattice_diagonal(k)
    assert diagonal + error <= _diagonal_bound(k) <= 1.02 * diagonal


def test_an_inverse_diagonal_bound_without_its_margin_is_caught(monkeypatch):
    # five aliases, no margin: the sampled mean then lies below D0 at k = 0.5
    monkeypatch.setattr(preconditioner, "DIAGONAL_ALIASES", 5)
    monkeypatch.setattr(preconditioner, "DIAGONAL_MARGIN", 1.0)
    diagonal, error = _lattice_diagonal(0.5)
    assert _diagonal_bound(0.5) < diagonal - error


@pytest.mark.parametrize("k", [WALK_EXPONENTS[0], 0.1, 0.25, 0.5, 0.75, 0.9, WALK_EXPONENTS[1]])
def test_the_lattice_inverse_has_no_positive_off_diagonal_coefficient(k):
    # the premises on every contact set at once: C_SS is a section of the infinite lattice's C,
    # whose inverse is D0 (I - P) with P the steps of a random walk (P >= 0 off the diagonal
    # exactly when these coefficients are <= 0; rows summing to one, since the symbol is infinite
    # at zero frequency), transient (its steps' tail |m|^-(3-k) is heavy: D0 C_00 is finite), with
    # Green matrix D0 C.  Watched only on S, the walk gives C_SS^-1 = D0 (I - Q_S), Q_S its first
    # returns to S: no positive off-diagonal entry, and C_SS^-1 1 = D0 P(never returning to S) > 0,
    # no smaller on any subset of S.  Near field: negative by more than the extrapolation's error
    near, error = _near_field(k)
    assert np.all(near + error < 0.0)
    # out to |m|_inf = 8 (a quarter of the coarser torus) still negative; beyond, the coefficients
    # follow the continuum's negative tail (next test)
    window = _extrapolated(k, 64, 8)
    window[8, 8] = -np.inf
    assert window.max() < 0.0


@pytest.mark.parametrize("k", [-0.1, WALK_EXPONENTS[0], 0.5, WALK_EXPONENTS[1]])
def test_the_lattice_inverse_has_the_continuum_tail(k):
    # far from the diagonal the coefficients of C^-1 approach those of the continuum's inverse
    # symbol |q|^(1-k) / c_k (c_k the transform of the kernel, ``point_kernel_transform``), a
    # fractional Laplacian whose kernel is -C_s / (c_k |m|^(3-k)), s = (1 - k)/2, negative for
    # every k; the lattice's correction falls like |m|^-2 (5.5 % or less at |m| = 4)
    s = (1.0 - k) / 2.0
    constant = 4.0**s * math.gamma(1.0 + s) / (np.pi * abs(math.gamma(-s)))
    c_k = 2.0 if k == 0 else point_kernel_transform(k)(1.0)  # Love's 1/(pi r) at E* = 1, else r^-(1+k)
    lattice = _extrapolated(k, 64, 8) * _lattice_inverse(k, 64)[0, 0]
    for m in ((8, 0), (6, 6)):
        r = math.hypot(*m)
        assert lattice[8 + m[0], 8 + m[1]] * c_k * r ** (3.0 - k) / -constant == pytest.approx(1.0, abs=0.02)


@pytest.mark.parametrize("k", [-0.1, WALK_EXPONENTS[0], 0.5, WALK_EXPONENTS[1]])
def test_the_lattice_inverse_is_that_of_the_solvers_coefficients(k):
    # an independent route: central rows of sections of the solver's own coefficients (halfspace
    # .kernel) converge to the lattice's; the torus extrapolation lies within three times their
    # last step of the larger one (measured: 0.3 to 1.3 steps, an error falling about like
    # 1/size; three steps would cover one falling like size^-0.55)
    offsets = [(1, 0), (1, 1), (2, 0), (3, 1), (4, 4)]
    small, large = _section_row(k, 12, offsets), _section_row(k, 20, offsets)
    lattice = _extrapolated(k, 64, 4)
    torus = np.array([lattice[4 + a, 4 + b] for a, b in offsets])
    assert np.all(np.abs(torus - large) <= 3.0 * np.abs(large - small))


def test_the_lattice_inverse_has_a_positive_coefficient_at_negative_grading():
    # and it sees why the bound is not claimed for k < 0: at k = -0.1 the offset (2, 0) turns
    # positive, so some contact set has a positive off-diagonal entry of C_SS^-1 (the rasters
    # above find one)
    near, error = _near_field(-0.1)
    assert (near - error).max() > 0.0
    offsets = [(i, j) for i in range(-4, 5) for j in range(-4, 5) if (i, j) != (0, 0)]
    positive = {offsets[i] for i in np.flatnonzero(near - error > 0)}
    assert positive == {(2, 0), (-2, 0), (0, 2), (0, -2)}


def test_a_zero_tie_tolerance_is_refused():
    with pytest.raises(cs.SceneError, match="settings.tie_tolerance"):
        bg.GriffithSettings(tie_tolerance=0.0)


@pytest.mark.parametrize("name", ["star", "triangle", "star graded"])
def test_the_pulled_set_is_the_largest_that_holds(name):
    # the bound's consequence for the driver itself: the set an event-driven pull holds at d does
    # not depend on its history, it is what one cascade from the whole face at d leaves
    scene = _scene(name)
    settings = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N))
    pulled = _pull(name, settings.tie_tolerance)
    at = _between(pulled.curve.approach)[::3]
    pulled = _pull(name, settings.tie_tolerance, at)
    problem = build_problem(scene, settings)
    counters = WorkCounters()
    approach, whole_face = pressed_state(problem, scene, settings, counters)
    assert approach == 0.0 and whole_face.contact.sum() == problem.face.sum()
    for snapshot in pulled.snapshots:
        left = cascade(problem, whole_face, snapshot.approach, settings, counters, [])
        assert np.array_equal(left.contact, snapshot.contact), f"d = {snapshot.approach:.6g}"
    assert len(pulled.snapshots) >= 10


def test_a_driver_that_steps_past_its_events_is_caught(monkeypatch):
    # mutant: every event taken a relative 1e-3 too late, so the pull holds sets too long
    import bem_griffith.driver as driver

    exact_event = driver.next_event

    def late(problem, solution, approach, target, rule=None):
        event = exact_event(problem, solution, approach, target, rule)
        return event if event == target else event * (1 + 1e-3)

    monkeypatch.setattr(driver, "next_event", late)
    with pytest.raises(AssertionError, match="d = "):
        test_the_pulled_set_is_the_largest_that_holds("star")
