"""The Pohrt-Popov BEM against analytic solutions, convergence sweeps and invariances.

Tolerances: the Kendall envelope 0.5 Delta/a is the one the formula sheet reports
(section 6) and the sweep in benchmarks/study_griffith_circle.py reproduces; the stiffness
prefactor 0.15 Delta/a covers the fitted 0.12 Delta/a of the same sweep.
"""

import dataclasses
import math

import hertz_press
import numpy as np
import pytest
from square_quadrature import square_integral_reference

import bem_griffith as bg
import contact_scene as cs
from contact_scene import theory as T
from crossval.suite import SCENE_DIR
from halfspace.kernel import (
    graded_influence,
    lattice_symbol,
    love_influence,
    love_influence_periodic,
    love_square_integral,
    padded_shape,
    point_kernel_transform,
)

E_STAR = 1.0


def circle_scene(radius=1.0, work=1.0, **kw):
    return cs.Scene(cs.Indenter(cs.Circle(radius)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(work), **kw)


def run(scene, N, **kw):
    return bg.solve(scene, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), **kw))


# -- the preconditioner's symbol ----------------------------------------------


def test_lattice_symbol_equals_the_periodic_image_sum():
    """Poisson summation of 2/(E* q) times the element's sinc^2 against the image sum of
    Love's coefficients (love_influence_periodic, an independent construction): the alias
    sum's truncation error falls like a power of the number of terms, to below 1e-4."""
    n, h, E = 16, 0.1, 2.0
    per = np.fft.rfft2(love_influence_periodic(n, h, E)).real
    terms = (3, 10, 40)
    errs = []
    for t in terms:
        lat = lattice_symbol((n, n), h, lambda q: 2.0 / (E * q), terms=t)
        assert np.isinf(lat[0, 0])  # the continuum's 1/q; the periodic kernel has zero mean there
        errs.append(np.max(np.abs(per.ravel()[1:] / lat.ravel()[1:] - 1)))
    rate = -np.polyfit(np.log(terms), np.log(errs), 1)[0]
    assert rate > 1.5 and errs[-1] < 1e-4


@pytest.mark.parametrize("k", [-0.5, -0.25])
def test_window_symbol_of_a_graded_kernel_tends_to_the_lattice_symbol(k):
    """At the highest frequency the truncated window's symbol differs from the infinite
    lattice's by about the kernel at the window's edge, n^-(1+k): slowly for k < 0, where the
    window symbol made a poor preconditioner (bench_graded: 36,259 matvecs at k = -0.5
    before, 3,093 with the lattice symbol)."""
    rate = 1 + k
    A = T.graded_green_coefficient(E0=1.0, c0=1.0, k=k)
    ft = point_kernel_transform(k)
    ns, errs = (32, 64, 128), []
    for n in ns:
        P = (2 * n, 2 * n)
        window = np.fft.rfft2(graded_influence(n, n, 1.0, 1.0, 1.0, k, P)).real
        lattice = lattice_symbol(P, 1.0, lambda q: A * ft(q), terms=20)
        errs.append(window[n, n] / lattice[n, n] - 1)  # the highest frequency
    fitted = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert fitted == pytest.approx(rate, abs=0.05)


def test_point_kernel_transform_at_k0_is_2pi_over_q():
    q = np.array([0.1, 1.0, 7.0])
    assert np.allclose(point_kernel_transform(0.0)(q), 2 * np.pi / q, rtol=1e-14)
    with pytest.raises(ValueError):
        point_kernel_transform(1.0)


def test_elongated_faces_get_a_positive_preconditioner_and_the_same_answer():
    """A 4:1 rectangle's padded window has negative modes; the lattice symbol has none, and
    preconditioning does not change the answer."""
    sc = dataclasses.replace(circle_scene(), indenter=cs.Indenter(cs.Rectangle(4.0, 1.0)))
    prob = bg.solver.build_problem(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=12)))
    assert prob.operator.symbol.min() < 0 < prob.preconditioner.inverse_symbol.min()
    a, b = run(sc, 12), run(sc, 12, preconditioner="none")
    assert a.pulloff_force == pytest.approx(b.pulloff_force, rel=1e-8)
    assert np.array_equal(a.curve.contact_area, b.curve.contact_area)
    assert np.array_equal(a.last_stable.contact, b.last_stable.contact)


# -- the operator -----------------------------------------------------------


@pytest.mark.parametrize("x,y", [(0.0, 0.0), (0.3, -0.1), (0.5, 0.5), (1.7, 0.4), (-3.0, 2.0)])
def test_love_integral_matches_quadrature(x, y):
    b = 0.5
    ref = square_integral_reference(x, y, 0.0, b)
    assert love_square_integral(x, y, b) == pytest.approx(ref, rel=1e-7)
    assert love_square_integral(0.0, 0.0, b) == pytest.approx(8 * b * math.asinh(1.0), rel=1e-14)


def test_fft_convolution_equals_direct_sum():
    nx, ny = 7, 5
    K = love_influence(nx, ny, 0.3, 2.0, padded_shape(nx, ny))
    op = bg.HalfSpaceOperator(K, (nx, ny))
    p = np.random.default_rng(1).standard_normal((nx, ny))
    X, Y = np.meshgrid(np.arange(nx) * 0.3, np.arange(ny) * 0.3, indexing="ij")
    direct = np.zeros((nx, ny))
    for i in range(nx):
        for j in range(ny):
            direct[i, j] = np.sum(love_square_integral(X[i, j] - X, Y[i, j] - Y, 0.15) * p) / (math.pi * 2.0)
    assert np.allclose(op.apply(p), direct, rtol=1e-11, atol=1e-12)


@pytest.mark.parametrize("k", [0.0, -0.5, 0.5])
def test_window_operator_is_the_grid_operator_on_a_sub_box(k):
    """The smaller window's coefficients are the same C_SS: a pressure that fits into the
    window gives the grid's displacement there, on a much smaller padded grid."""
    nx, ny = 23, 17
    K = (
        love_influence(nx, ny, 0.3, 2.0, padded_shape(nx, ny))
        if k == 0
        else graded_influence(nx, ny, 0.3, 2.0, 1.0, k, padded_shape(nx, ny))
    )
    op = bg.HalfSpaceOperator(K, (nx, ny))
    rng = np.random.default_rng(3)
    for (wx, wy), (i0, j0) in [((9, 6), (5, 11)), ((1, 17), (22, 0)), ((23, 4), (0, 2))]:
        win = op.window((wx, wy))
        assert np.prod(win.padded_shape) < np.prod(op.padded_shape)
        p = np.zeros((nx, ny))
        p[i0 : i0 + wx, j0 : j0 + wy] = rng.standard_normal((wx, wy))
        full = op.apply(p)[i0 : i0 + wx, j0 : j0 + wy]
        assert np.allclose(win.apply(p[i0 : i0 + wx, j0 : j0 + wy]), full, rtol=0, atol=1e-13 * np.abs(full).max())
    with pytest.raises(ValueError, match="fit"):
        op.window((nx + 1, 3))


def test_shrinking_window_changes_nothing():
    """A star loses its tips first, so its later solves run on smaller windows: the same
    events, contact sets and forces as on the whole grid (to CG round-off)."""
    star = dataclasses.replace(circle_scene(), indenter=cs.Indenter(cs.Star(5, 1.0, 0.45)))
    a, b = run(star, 24), run(star, 24, shrink_window=False)
    assert a.info["windowed_solves"] > a.info["solves"] // 2 and b.info["windowed_solves"] == 0
    # the solves may differ: each window has its own (compact) preconditioner, so CG's iterates
    # differ and a pass may leave a cell below the threshold undecided for a later one
    assert a.info["events"] == b.info["events"]
    assert np.array_equal(a.curve.contact_area, b.curve.contact_area)
    assert np.array_equal(a.last_stable.contact, b.last_stable.contact)
    assert a.pulloff_force == pytest.approx(b.pulloff_force, rel=1e-9)
    assert np.allclose(a.curve.force, b.curve.force, rtol=1e-9, atol=1e-9 * b.pulloff_force)


# -- circle: stiffness and Kendall --------------------------------------------

SWEEP = (16, 24, 32, 48, 64, 96)


@pytest.fixture(scope="module")
def kendall_sweep():
    sc = circle_scene()
    return {N: run(sc, N) for N in SWEEP}


def test_circle_stiffness_converges_first_order(kendall_sweep):
    errs = []
    for N, r in kendall_sweep.items():
        a_r = math.sqrt(cs.rasterise(cs.Circle(1.0), 1.0 / N).area / math.pi)  # staircase removed
        err = r.stiffness / T.kendall_stiffness(E_star=E_STAR, radius=a_r) - 1
        assert abs(err) <= 0.15 / N
        errs.append(abs(err))
    rate = -np.polyfit(np.log(SWEEP), np.log(errs), 1)[0]
    assert 0.7 < rate < 1.4


def test_kendall_pulloff_within_first_order_envelope(kendall_sweep):
    FK = T.kendall_adhesion_force(E_star=E_STAR, radius=1.0, work=1.0)
    dK = T.kendall_critical_approach(E_star=E_STAR, radius=1.0, work=1.0)
    for N, r in kendall_sweep.items():
        assert r.converged and r.detached
        assert abs(r.pulloff_force / FK - 1) <= 0.5 / N
        assert abs(r.pulloff_approach / dK - 1) <= 0.6 / N
        # Kendall's contact is unstable: it goes at once, at the pull-off approach
        assert r.detachment_approach == pytest.approx(r.pulloff_approach, rel=0.02)
    assert abs(kendall_sweep[96].pulloff_approach / dK - 1) < 0.01
    assert abs(kendall_sweep[64].pulloff_approach / dK - 1) < 0.01


def test_cut_cascade_changes_nothing():
    for scene, N in [
        (circle_scene(), 24),
        (dataclasses.replace(circle_scene(), indenter=cs.Indenter(cs.Square(2.0))), 20),
        (dataclasses.replace(circle_scene(), indenter=cs.Indenter(cs.Star(5, 1.0, 0.5))), 16),
        (
            dataclasses.replace(
                circle_scene(), indenter=cs.Indenter(cs.TwoCircles(radius1=1.0, radius2=0.6, distance=1.5))
            ),
            16,
        ),
    ]:
        cut, full = run(scene, N), run(scene, N, stop_when_certainly_detached=False)
        assert cut.pulloff_force == pytest.approx(full.pulloff_force, rel=1e-9)
        assert cut.pulloff_approach == pytest.approx(full.pulloff_approach, rel=1e-9)
        assert cut.detachment_approach == pytest.approx(full.detachment_approach, rel=1e-9)
        assert cut.info["solves"] <= full.info["solves"]


def test_fixed_step_converges_to_event_driven():
    sc = circle_scene()
    ev = run(sc, 16)
    K = ev.stiffness
    dK = abs(T.kendall_critical_approach(E_star=E_STAR, radius=1.0, work=1.0))
    errs = []
    steps = [dK / 10, dK / 40, dK / 160]
    for h in steps:
        fx = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=16), driver="fixed_step", step=h))
        gap = ev.pulloff_force - fx.pulloff_force
        assert -1e-9 * ev.pulloff_force <= gap <= K * h * (1 + 1e-9)  # the peak lags by at most one step
        errs.append(gap)
    assert errs[-1] < errs[0] / 10


# -- square, triangle, invariances --------------------------------------------------


def square_scene(**kw):
    return cs.Scene(cs.Indenter(cs.Square(2.0, **kw)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))


def test_square_stiffness_factor_approaches_1021():
    Ns = (16, 32, 64)
    beta = []
    for N in Ns:
        r = bg.press(square_scene(), bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)))
        a_r = math.sqrt(cs.rasterise(cs.Square(2.0), math.sqrt(4 / math.pi) / N).area / math.pi)
        beta.append(r.stiffness / (2 * E_STAR * a_r))
    # Richardson for first-order convergence (the sheet: beta converges like 1/N)
    c, b_inf = np.polyfit(1 / np.array(Ns), beta, 1)
    assert b_inf == pytest.approx(T.SQUARE_BETA, abs=0.002)
    assert beta[0] < beta[1] < beta[2] < b_inf


def test_square_detaches_from_corners_to_near_incircle():
    sc = dataclasses.replace(square_scene(), outputs=cs.Outputs(snapshots=(-1.0,)))
    r = run(sc, 32)
    assert r.converged and r.detached
    # the first detachment event: only cells next to the corners leave
    first_drop = np.flatnonzero(np.diff(r.curve.contact_area) < 0)[0]
    lost = r.curve.contact_area[0] - r.curve.contact_area[first_drop + 1]
    h = math.sqrt(4 / math.pi) / 32
    assert lost <= 4 * 3 * h * h + 1e-12
    # last stable state close to the incircle (Eqs. 18-19)
    ls = r.last_stable
    assert ls is not None
    a_in = 1.0
    assert ls.contact_area == pytest.approx(math.pi * a_in**2, rel=0.15)
    dl = T.lower_bound_approach(E_star=E_STAR, work=1.0, incircle_radius=a_in)
    assert r.detachment_approach == pytest.approx(dl, rel=0.05)
    # bounded by the closed forms
    up = T.upper_bound_force(E_star=E_STAR, work=1.0, area=4.0)
    lo = T.lower_bound_force(E_star=E_STAR, work=1.0, incircle_radius=1.0)
    assert lo * 0.97 < r.pulloff_force < up


def test_rotation_and_mirror_invariance():
    base = run(square_scene(), 24)
    rot = run(square_scene(rotation_deg=30.0), 24)
    # only the staircase differs: the force scales like area^(3/4) for the same shape
    assert rot.pulloff_force == pytest.approx(base.pulloff_force, rel=0.03)
    tri = cs.Scene(
        cs.Indenter(cs.Triangle.equilateral(2.0, rotation_deg=10)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0)
    )
    mir = dataclasses.replace(tri, indenter=cs.Indenter(tri.indenter.shape.mirrored()))
    a, b = run(tri, 20), run(mir, 20)
    assert b.pulloff_force == pytest.approx(a.pulloff_force, rel=1e-9)
    assert b.pulloff_approach == pytest.approx(a.pulloff_approach, rel=1e-9)
    assert np.allclose(b.curve.force, a.curve.force, rtol=1e-8)


def test_unit_scaling():
    # the triangle in SI units (the paper's Fig. 13 fit) and in scaled units
    si = cs.load_scene(SCENE_DIR / "paper_fig13_triangle.toml")
    L, E, w = 0.03, si.material.effective_modulus, 0.062
    scaled = cs.Scene(cs.Indenter(cs.Triangle.equilateral(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    a, b = run(si, 20), run(scaled, 20)
    assert a.pulloff_force / math.sqrt(E * w * L**3) == pytest.approx(b.pulloff_force, rel=1e-9)
    assert a.pulloff_approach / math.sqrt(w * L / E) == pytest.approx(b.pulloff_approach, rel=1e-9)
    assert a.stiffness / (E * L) == pytest.approx(b.stiffness, rel=1e-9)


# -- sphere: JKR ---------------------------------------------------------------


def jkr_scene():
    return cs.load_scene(SCENE_DIR / "jkr_sphere.toml")


def test_jkr_sphere_converges_to_1_5_pi_w_R():
    sc = jkr_scene()
    FJ = T.jkr_pulloff_force(work=0.01, sphere_radius=1.0)
    Ns = np.array([16, 20, 24, 28, 32])
    err = np.array([run(sc, N).pulloff_force / FJ - 1 for N in Ns])
    assert np.all(err > 0)  # the mesh-dependent criterion errs on the strong side
    rate = -np.polyfit(np.log(Ns), np.log(err), 1)[0]
    assert 0.6 < rate < 1.4  # first order
    c, e_inf = np.polyfit(1 / Ns, err, 1)  # Richardson: F = F_inf + c / N
    assert abs(e_inf) < 0.01


@pytest.mark.slow
def test_jkr_sphere_within_one_percent_without_extrapolation_slow():
    """The issue's 1 % on the raw pull-off force needs a fine grid: measured +2.71, +1.65,
    +1.03, +0.56 % at 80, 112, 160, 192 elements per face radius (one run each; the contact
    radius at pull-off is 0.78 of the face's, so 192 is about 150 across it), 13 min at 192
    with another run sharing the machine."""
    sc = jkr_scene()
    r = run(sc, 192)
    assert r.converged and r.detached
    err = r.pulloff_force / T.jkr_pulloff_force(work=0.01, sphere_radius=1.0) - 1
    assert 0 < err <= 0.01


# -- robustness ----------------------------------------------------------------


def test_no_adhesion_detaches_at_contact_and_strong_adhesion_is_reported():
    r = run(circle_scene(work=0.0), 16)
    assert r.pulloff_force == 0.0 and r.detached and r.converged
    sc = circle_scene(work=1.0, loading=cs.Loading(pull_limit=-0.5))
    r = run(sc, 16)
    assert not r.detached and any("pull limit" in m for m in r.messages)
    assert r.curve.approach[-1] == -0.5 and np.all(np.isfinite(r.curve.force))


def test_coarse_grid_and_memory_are_refused():
    with pytest.raises(cs.SceneError, match="too coarse"):
        run(circle_scene(), 1.5)
    with pytest.raises(cs.SceneError, match="max_memory_gb"):
        bg.solve(circle_scene(), bg.GriffithSettings(grid=cs.Grid(elements_per_radius=64), max_memory_gb=0.001))


def test_a_step_is_taken_by_the_fixed_step_driver_only():
    """The event driver takes no step: one given to it is refused, not ignored; the fixed-step
    driver needs one."""
    with pytest.raises(cs.SceneError, match=r"settings\.step: only the fixed-step driver"):
        bg.GriffithSettings(step=0.01)
    with pytest.raises(cs.SceneError, match=r"settings\.step: the fixed-step driver needs"):
        bg.GriffithSettings(driver="fixed_step")
    assert bg.GriffithSettings(driver="fixed_step", step=0.01).step == 0.01


def test_result_reports_its_work_and_the_discretised_face():
    """The typed counters and the face area that the harness reads instead of ``info``: the
    face area is the rasterised face's (``contact_scene.rasterise``), the whole face is in
    contact after pressing, every CG step costs one operator product and one preconditioner
    FFT pair, and an unconverged contact solve is counted and said, never silent."""
    N = 12
    r = run(square_scene(), N)
    raster = cs.rasterise(cs.Square(2.0), math.sqrt(4 / math.pi) / N)
    assert r.discretisation == "grid" and r.converged
    assert r.face_area == pytest.approx(raster.area, rel=1e-12) == r.curve.contact_area[0]
    st = r.stats
    assert st.unknowns == raster.mask.sum() == r.info["face_elements"]
    assert st.linear_iterations == r.iterations and st.unconverged == 0
    assert st.linear_solves == r.info["solves"] and st.events == r.info["events"] >= 1
    assert st.operator_applications == r.info["matvecs"] >= 2 * st.linear_iterations
    declared = bg.GriffithInfo.__required_keys__ | bg.GriffithInfo.__optional_keys__
    assert bg.GriffithInfo.__required_keys__ <= set(r.info) <= declared
    bad = run(square_scene(), N, maxiter=1)
    assert not bad.converged and bad.stats.unconverged >= 1
    assert any(m.startswith(f"{bad.stats.unconverged} contact solves did not reach rtol") for m in bad.messages)


def test_snapshots_and_fields_only_when_asked():
    """At d = -1 the circle (Kendall: d_c = -2.5) is still whole: Boussinesq's flat punch on
    the staircase's equivalent radius a_r, F = 2 E* a_r d and p(r) = E* d / (pi sqrt(a_r^2 - r^2)).
    Both converge at first order: the force like the stiffness (-0.12/N measured over 8-48 per
    radius; 0.15/N, as for the stiffness), the pressure inside r < a/2 within 0.14-0.16/N
    (0.2/N allowed)."""
    sc = circle_scene(outputs=cs.Outputs(snapshots=(-1.0, -2.0)))
    r = run(sc, 16)
    assert [s.approach for s in r.snapshots] == [-1.0, -2.0]
    assert all(s.pressure is None for s in r.snapshots)
    N = 16
    sc = circle_scene(outputs=cs.Outputs(snapshots=(-1.0,), fields=True))
    s = run(sc, N).snapshots[0]
    assert s.pressure is not None and s.contact.sum() == cs.rasterise(cs.Circle(1.0), 1.0 / N).mask.sum()
    a_r = math.sqrt(s.contact_area / math.pi)
    assert abs(s.force / (2 * E_STAR * a_r * -1.0) - 1) <= 0.15 / N
    X, Y = s.centres()
    inner = s.contact & (np.hypot(X, Y) < 0.5)
    boussinesq = E_STAR * -1.0 / (math.pi * np.sqrt(a_r**2 - X[inner] ** 2 - Y[inner] ** 2))
    assert np.abs(s.pressure[inner] / boussinesq - 1).max() <= 0.2 / N
    # the displacement field: the face moves with the punch
    assert np.allclose(s.displacement[s.contact], -1.0, rtol=1e-8)


def test_press_to_force_matches_hertz():
    sc, E, F0 = hertz_press.SCENE, hertz_press.E_STAR, hertz_press.F0
    d_hertz, a_hertz = hertz_press.APPROACH, hertz_press.CONTACT_RADIUS
    errs = []
    for N in (24, 48):
        r = bg.press(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)))
        h = 0.4 / N
        assert r.force == pytest.approx(F0, rel=1e-9)
        # the contact area is a staircase: within sqrt(2) P h of the Hertz disc
        assert abs(r.contact_area - math.pi * a_hertz**2) <= math.sqrt(2) * 2 * math.pi * a_hertz * h
        assert r.stiffness == pytest.approx(2 * E * a_hertz, abs=2 * E * h)  # unloading stiffness 2 E* a
        errs.append(abs(r.approach / d_hertz - 1))
    assert errs[1] < errs[0] / 2.5 and errs[1] < 1e-3  # better than first order


def test_unload_reload_reattaches_the_whole_face():
    # pull past the first detachments, push back to d > 0: every free face element's gap closes,
    # so the face is whole again and the final pull-off repeats the plain one
    st = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=16))
    plain = run(square_scene(), 16)
    turn = 0.5 * (plain.pulloff_approach + plain.detachment_approach)
    sc = dataclasses.replace(square_scene(), loading=cs.Loading(turning_points=(turn, 0.2)))
    r = bg.solve(sc, st)
    assert r.converged and r.detached
    top = int(np.argmax(r.curve.approach))
    assert r.curve.approach[top] == 0.2
    assert r.curve.contact_area[top] == pytest.approx(plain.curve.contact_area[0], rel=1e-12)
    assert r.curve.contact_area[np.flatnonzero(r.curve.approach == turn)].min() < plain.curve.contact_area[0]
    assert r.pulloff_force == pytest.approx(plain.pulloff_force, rel=1e-9)


# ---------------------------------------------------------------------------
# periodic half-space (an array of punches)
# ---------------------------------------------------------------------------


def test_periodic_kernel_carries_the_lattice_madelung_constant():
    """The zero-mean periodic coefficients differ from the isolated ones by the lattice sum:
    self-coefficient shift -> Delta^2 M0 / (pi E* L), M0 = 4 zeta(1/2) beta(1/2), with an
    element-size remainder O((Delta/L)^2) (measured 0.096 (Delta/L)^2)."""
    from halfspace.kernel import MADELUNG_SQUARE, love_influence_periodic, love_square_integral

    ns, errs = (8, 16, 32), []
    for n in ns:
        h = 1.0 / n
        C = love_influence_periodic(n, h, 2.0)
        shift = C[0, 0] - love_square_integral(0.0, 0.0, h / 2) / (np.pi * 2.0)
        errs.append(abs(shift / (h * h * MADELUNG_SQUARE / (np.pi * 2.0)) - 1))
        assert abs(C.sum()) <= 1e-12 * np.abs(C).sum()  # zero mean: the mean plane is the datum
        mirror = (-np.arange(n)) % n  # offset -i, modulo the cell
        tol = 1e-12 * np.abs(C).max()  # round-off of the image sums
        assert np.allclose(C, C[mirror][:, mirror], rtol=0, atol=tol) and np.allclose(C, C.T, rtol=0, atol=tol)
    rate = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert 1.8 <= rate <= 2.2 and errs[-1] < 2e-4, (errs, rate)


def test_periodic_operator_is_the_circular_convolution():
    from halfspace.kernel import love_influence_periodic
    from halfspace.operator import HalfSpaceOperator

    n = 12
    C = love_influence_periodic(n, 0.1, 1.0, images=4)
    op = HalfSpaceOperator(C, (n, n), periodic=True)
    p = np.random.default_rng(3).normal(size=(n, n))
    direct = np.zeros((n, n))
    for i in range(n):
        for j in range(n):
            direct += p[i, j] * np.roll(np.roll(C, i, axis=0), j, axis=1)
    assert np.allclose(op.apply(p), direct, rtol=0, atol=1e-12 * np.abs(direct).max())


def test_periodic_punch_array_matches_the_lattice_correction():
    """One circular punch per square cell of side L: the mean-plane compliance is the isolated
    one plus the lattice term, 1/K = 1/K_iso + M0 / (pi E* L), and the pull-off force stays the
    isolated one (the lattice term does not depend on a, so dK/da and K^2 / K' keep their
    values) - both up to the next term of the periodic Green's function, O((a/L)^3).  Same grid
    for both, so the staircase cancels.  Measured at 16 per radius, L/a = 4, 6, 8: K 7.5e-2,
    1.5e-2, 5.4e-3 off the prediction, F 3.0e-2, 8.7e-3, 3.7e-3 off the isolated force."""
    from halfspace.kernel import MADELUNG_SQUARE as M0

    sc = circle_scene()
    E = sc.material.effective_modulus
    N = 16
    iso = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)))
    Ls, dK, dF = (4.0, 6.0, 8.0), [], []
    for L in Ls:
        r = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(spacing=1.0 / N, periodic=True, period=L)))
        assert r.converged and r.detached
        dK.append(abs(r.stiffness * (1 / iso.stiffness + M0 / (np.pi * E * L)) - 1))
        dF.append(abs(r.pulloff_force / iso.pulloff_force - 1))
    for errs in (dK, dF):
        rate = -np.polyfit(np.log(Ls), np.log(errs), 1)[0]
        assert rate >= 2.7, (errs, rate)  # at least (a/L)^3
    assert max(dK[-1], dF[-1]) < 1e-2


def test_progress_callback_sees_every_point_of_the_curve():
    """Through turning points (unload and reload) to detachment: every curve point reaches the
    callback, in loading order."""
    plain = run(square_scene(), 16)
    turn = 0.5 * (plain.pulloff_approach + plain.detachment_approach)
    sc = dataclasses.replace(square_scene(), loading=cs.Loading(turning_points=(turn, 0.2)))
    seen: list[tuple[float, float, float]] = []
    r = bg.solve(
        sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=16)), callback=lambda *point: seen.append(point)
    )
    assert r.converged and r.detached
    assert seen == list(zip(r.curve.approach, r.curve.force, r.curve.contact_area, strict=True))


def test_the_fixed_step_driver_claims_no_pulloff_bar_and_says_when_its_step_is_coarse():
    # the error model was fitted on the event driver; the fixed-step driver's F_A lags it by up to
    # the force one step changes (test_fixed_step_converges_to_event_driven)
    sc = circle_scene()
    event = run(sc, 8)
    assert {"pulloff_force", "pulloff_approach"} <= set(event.error_bars)
    assert not any("fixed-step" in m for m in event.messages)
    d_c = abs(T.kendall_critical_approach(E_star=E_STAR, radius=1.0, work=1.0))
    # K step against 1e-3 F_A, F_A / K = d_c for the circle: coarse above d_c / 1000
    for step, coarse in [(10 * d_c, True), (d_c / 2, True), (d_c / 2000, False)]:
        r = run(sc, 8, driver="fixed_step", step=step)
        assert "pulloff_force" not in r.error_bars and "pulloff_approach" not in r.error_bars
        assert "stiffness" in r.error_bars
        assert any("fixed-step driver's step" in m for m in r.messages) == coarse
        assert r.pulloff_force >= 0.0 and math.copysign(1.0, r.pulloff_force) == 1.0  # never -0.0


def test_a_press_force_below_the_first_touchs_resolution_presses_to_the_first_touch():
    # brentq needs a sign change; a target below the force of the lowest elements pressed by
    # 1e-12 of the bracket has none, and the press is that first touch
    sc = cs.Scene(
        cs.Indenter(cs.Circle(1.0), cs.Paraboloid(10.0)),
        cs.Homogeneous(0.75, 0.5),
        cs.Adhesion(1.0),
        cs.Loading(press_force=1e-16),
    )
    settings = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=16))
    pressed = bg.press(sc, settings)
    lowest = bg.press(dataclasses.replace(sc, loading=cs.Loading(press_force=1e-3)), settings)
    assert 0 < pressed.force < 1e-3 * lowest.force
    assert 0 < pressed.contact_area < lowest.contact_area
    assert bg.solve(sc, settings).converged


def test_a_pull_still_attached_at_its_limit_claims_no_pulloff_bar():
    # the largest tension then sits at the user's limit, which the error model's studies never
    # fitted (the FEM gives it the stiffness's bar: F = K |limit| on its full-contact branch)
    d_c = T.kendall_critical_approach(E_star=E_STAR, radius=1.0, work=1.0)
    held = run(circle_scene(loading=cs.Loading(pull_limit=0.5 * d_c)), 16)
    assert not held.detached and any("pull limit" in m for m in held.messages)
    assert set(held.error_bars) == {"stiffness"}
    assert {"pulloff_force", "pulloff_approach"} <= set(run(circle_scene(), 16).error_bars)


@pytest.mark.parametrize(
    "wanted, loading, missed",
    [
        ((5.0,), cs.Loading(), "d = 5 lies above d = 0, where the pull starts"),
        ((-100.0,), cs.Loading(), "d = -100 lies below d = {detached:g}, where the punch detached"),
        ((-1.0, -2.0), cs.Loading(pull_limit=-1.5), "d = -2 lies below d = -1.5, the pull limit"),
    ],
)
def test_snapshots_the_pull_does_not_reach_are_named(wanted, loading, missed):
    """A snapshot beyond the detachment, above the pull's start or past the pull limit was
    once dropped without a word (Kendall's circle detaches near d_c = -2.5 here)."""
    r = run(circle_scene(loading=loading, outputs=cs.Outputs(snapshots=wanted)), 8)
    notes = [m for m in r.messages if m.startswith("bem_griffith recorded no snapshot")]
    assert len(notes) == 1 and missed.format(detached=r.detachment_approach) in notes[0], r.messages
    assert [s.approach for s in r.snapshots] == ([-1.0] if loading.pull_limit is not None else [])
    assert not any(
        "recorded no snapshot" in m for m in run(circle_scene(outputs=cs.Outputs(snapshots=(-1.0,))), 8).messages
    )


def test_a_finite_range_is_named_as_ignored():
    """The Griffith BEM is the zero-range limit: a scene's range was once ignored silently."""
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0, 0.3))
    r = run(sc, 8)
    notes = [m for m in r.messages if "range rho = 0.3" in m]
    assert len(notes) == 1 and "ignored" in notes[0] and "zero-range" in notes[0]
    plain = run(circle_scene(), 8)
    assert plain.pulloff_force == r.pulloff_force and not any("range rho" in m for m in plain.messages)


def test_json_carries_snapshots_and_last_stable():
    """``to_json`` (``crossval solve --json``) once had no snapshots, no last_stable and no word
    of the fields the scene asked for; the last stable state now carries fields too."""
    import json

    from crossval.jsonio import dumps

    r = run(circle_scene(outputs=cs.Outputs(snapshots=(-1.0, -2.0), fields=True)), 8)
    assert r.last_stable is not None and r.last_stable.pressure is not None
    assert np.allclose(r.last_stable.displacement[r.last_stable.contact], r.last_stable.approach, rtol=1e-8)
    out = json.loads(dumps(r.to_json()))
    assert [s["approach"] for s in out["snapshots"]] == [-1.0, -2.0]
    for s, got in zip((*r.snapshots, r.last_stable), (*out["snapshots"], out["last_stable"]), strict=True):
        assert (got["force"], got["contact_area"]) == (s.force, s.contact_area)
        assert np.array_equal(cs.Snapshot.decode_contact(got["contact"]), s.contact)
        assert got["fields"]["left_out"] == ["pressure", "displacement"]
    assert any("pressure" in x and "displacement" in x for x in out["left_out"])
