"""Early decisions in the Griffith BEM's cascades (``GriffithSettings.decide_early``).

A cascade's passing contact sets are solved only until a bound on their error fixes the next
pass.  The bounds rest on facts tested here against dense matrices: no eigenvalue of any
C_SS lies below ``Problem.eigenvalue_floor``, no displacement error exceeds ``kernel_norm``
times the pressures' Euclidean error, the energy bounds of the Fourier preconditioner, and
(homogeneous or 0 <= k <= 0.95) the sign structure behind the residual's largest entry.  The
decisions, and so the contact sets, must be those of full solves.
"""

import dataclasses
import math

import numpy as np
import pytest
import scipy.fft
import scipy.linalg

import bem_griffith as bg
import contact_scene as cs
from bem_griffith.driver import early_decision
from bem_griffith.linear import conjugate_gradient
from bem_griffith.preconditioner import compact_period, fourier_preconditioner
from bem_griffith.press import press_to_approach
from bem_griffith.stress_intensity import PaperRule
from crossval.suite import SUITE, scene as builtin_scene

#: the kernels the bounds are checked on: homogeneous, graded with k >= 0 and with k < 0
MATERIALS = pytest.mark.parametrize(
    "material",
    [cs.Homogeneous(0.75, 0.5), cs.PowerLawGraded(1.0, 0.5, 0.3), cs.PowerLawGraded(1.0, 0.5, -0.5)],
    ids=["homogeneous", "graded k=0.3", "graded k=-0.5"],
)
SHAPES = pytest.mark.parametrize("shape", [cs.Circle(1.0), cs.Star(5, 1.0, 0.45)], ids=["circle", "star"])


def scene(shape, material=None):
    return cs.Scene(cs.Indenter(shape), material or cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))


def settings(N, **kw):
    return bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), **kw)


def dense_preconditioner(problem, padded):
    """The Fourier preconditioner M on the face's grid as a dense matrix, over the padded grid
    or the compact period."""
    nx, ny = problem.face.shape
    period = problem.operator.padded_shape if padded else compact_period((nx, ny))
    preconditioner = fourier_preconditioner((nx, ny), period, problem.spacing, problem.point_kernel, padded=padded)
    m = preconditioner.operator.kernel
    rows, cols = np.divmod(np.arange(nx * ny), ny)
    return m[(rows[:, None] - rows[None, :]) % period[0], (cols[:, None] - cols[None, :]) % period[1]]


@pytest.mark.parametrize("name", ["star", "triangle"])
def test_the_compact_preconditioner_pulls_as_the_padded_one(name, monkeypatch):
    """Problems with the walk property take the preconditioner over a compact period (no
    padding: it wraps), the others the padded one; a pull with either passes through the same
    contact sets to the same F_A, within CG's tolerance."""
    sc = builtin_scene(name)
    st = settings(24)
    problem = bg.solver.build_problem(sc, st)
    assert problem.walk_bounds and not problem.preconditioner.padded
    assert problem.preconditioner.period == compact_period(problem.face.shape)
    graded = bg.solver.build_problem(scene(cs.Circle(1.0), cs.PowerLawGraded(1.0, 0.5, -0.5)), st)
    assert graded.preconditioner.padded and graded.preconditioner.period == graded.operator.padded_shape
    compact = bg.solve(sc, st)
    monkeypatch.setattr(bg.problem, "COMPACT_PRECONDITIONER", False)
    padded = bg.solve(sc, st)
    assert np.array_equal(compact.curve.contact_area, padded.curve.contact_area)
    assert compact.pulloff_force == pytest.approx(padded.pulloff_force, rel=1e-8)
    assert compact.info["matvecs"] != padded.info["matvecs"]  # a different preconditioner ran


def test_premature_decisions_change_the_contact_sets_the_comparison_above_reads(monkeypatch):
    """The mutant behind the test above: with the padded preconditioner and its energy bound
    shrunk 2e4-fold (SAMPLING_MARGIN 1e-4), passes are decided before their leavers are
    certain, and the star's pull no longer passes through the contact sets the compact
    preconditioner's does (F_A itself moves only at the CG tolerance here)."""
    sc = builtin_scene("star")
    st = settings(24)
    compact = bg.solve(sc, st)
    monkeypatch.setattr(bg.problem, "COMPACT_PRECONDITIONER", False)
    monkeypatch.setattr(bg.contact_set, "SAMPLING_MARGIN", 1e-4)
    premature = bg.solve(sc, st)
    assert not np.array_equal(compact.curve.contact_area, premature.curve.contact_area)


def dense_operator(problem):
    """C on the face's grid as a dense matrix (row-major cells), from the padded kernel."""
    nx, ny = problem.face.shape
    Mx, My = problem.operator.kernel.shape
    rows, cols = np.divmod(np.arange(nx * ny), ny)
    return problem.operator.kernel[(rows[:, None] - rows[None, :]) % Mx, (cols[:, None] - cols[None, :]) % My]


@MATERIALS
def test_eigenvalue_floor_bounds_every_contact_submatrix(material):
    """The smallest eigenvalue of C_SS, for the whole face and for random subsets of it, is
    at least the floor (rigour), and the floor is not wasteful: within a factor 2.5 of the
    face's smallest eigenvalue (the lattice symbol's infimum, halved, against a finite
    section's, which lies just above the infimum)."""
    problem = bg.solver.build_problem(scene(cs.Circle(1.0), material), settings(9))
    C = dense_operator(problem)
    face = problem.face.ravel()
    smallest = np.linalg.eigvalsh(C[np.ix_(face, face)])[0]
    assert problem.eigenvalue_floor <= smallest <= 2.5 * problem.eigenvalue_floor
    rng = np.random.default_rng(3)
    for share in (0.9, 0.5, 0.1):
        subset = face & (rng.random(face.size) < share)
        assert np.linalg.eigvalsh(C[np.ix_(subset, subset)])[0] >= problem.eigenvalue_floor
    # Cauchy-Schwarz: every row of C is no longer than all the coefficients together
    assert np.linalg.norm(C, axis=1).max() <= problem.kernel_norm


@MATERIALS
@SHAPES
def test_energy_bounds_hold_for_every_contact_submatrix(material, shape):
    """The bounds behind the early decisions with the Fourier preconditioner M, against dense
    matrices on coarse grids (the sampled symbol is coarsest there), for the whole face and
    random subsets S:

    * r.C_SS^-1 r <= SAMPLING_MARGIN r.M r for every residual r (the largest generalised
      eigenvalue of C_SS^-1 against M_SS): the error's energy norm from the preconditioned
      residual;
    * (C_SS^-1)_ii <= ``inverse_diagonal`` for every i in S (the infinite lattice's diagonal,
      from a fine sample of its inverse symbol), and not wastefully so (within 2 %: a whole
      face's interior cells come within 0.1 % of the lattice's diagonal);
    * c.C_SS^-1 c < C_00 = ``self_influence`` for every free cell's influences c.

    The sampled r.M r alone falls short of the dense r.C_SS^-1 r on these grids: without
    SAMPLING_MARGIN the first bound fails.  The diagonal's bound is also tested against the
    lattice itself (``tests/test_bem_griffith_ties.py``)."""
    problem = bg.solver.build_problem(scene(shape, material), settings(9 if isinstance(shape, cs.Circle) else 12))
    C = dense_operator(problem)
    # the padded preconditioner, which problems without the walk property (here k = -0.5) take
    assert problem.preconditioner.padded == (not problem.walk_bounds)
    M = dense_preconditioner(problem, padded=True)
    face = problem.face.ravel()
    rng = np.random.default_rng(5)
    largest_diagonal, largest_energy_ratio = 0.0, 0.0
    for share in (1.0, 0.5, 0.1):
        subset = face & (rng.random(face.size) < share) if share < 1 else face
        inverse = np.linalg.inv(C[np.ix_(subset, subset)])
        largest_diagonal = max(largest_diagonal, inverse.diagonal().max())
        ratio = scipy.linalg.eigh(inverse, M[np.ix_(subset, subset)], eigvals_only=True)[-1]
        largest_energy_ratio = max(largest_energy_ratio, ratio)
        free = face & ~subset
        if free.any():
            c = C[np.ix_(subset, free)]
            assert np.einsum("if,ij,jf->f", c, inverse, c).max() < problem.self_influence
    assert 1.0 < largest_energy_ratio <= bg.problem.SAMPLING_MARGIN
    assert largest_diagonal <= problem.inverse_diagonal <= 1.02 * largest_diagonal


@MATERIALS
@SHAPES
def test_max_norm_bounds_hold_for_every_contact_submatrix(material, shape):
    """The bounds the early decisions take from the residual's largest entry where
    ``Problem.walk_bounds`` holds, against dense matrices, for the whole face and random
    subsets S: every absolute row sum of C_SS^-1 is 2 (C_SS^-1)_ii - (C_SS^-1 1)_i (no positive
    off-diagonal entry), at most 2 ``inverse_diagonal``, and for every free cell f the row
    C_fS C_SS^-1 is nonnegative with sum below one.  At k = -0.5, where ``walk_bounds`` is off,
    the sign structure fails and some row of C_fS C_SS^-1 sums in magnitude beyond one (the
    displacement bound would not hold)."""
    problem = bg.solver.build_problem(scene(shape, material), settings(9 if isinstance(shape, cs.Circle) else 12))
    C = dense_operator(problem)
    face = problem.face.ravel()
    rng = np.random.default_rng(7)
    broken = False
    for share in (1.0, 0.5, 0.1):
        subset = face & (rng.random(face.size) < share) if share < 1 else face
        inverse = np.linalg.inv(C[np.ix_(subset, subset)])
        absolute_rows = np.abs(inverse).sum(axis=1)
        signed = 2.0 * inverse.diagonal() - inverse.sum(axis=1)
        free = face & ~subset
        first_meeting = C[np.ix_(free, subset)] @ inverse if free.any() else np.zeros((0, subset.sum()))
        if problem.walk_bounds:
            assert absolute_rows == pytest.approx(signed, rel=1e-9)
            assert absolute_rows.max() <= 2.0 * problem.inverse_diagonal
            assert first_meeting.min(initial=0.0) >= -1e-12
            assert np.abs(first_meeting).sum(axis=1).max(initial=0.0) < 1.0
        else:
            broken |= not np.allclose(absolute_rows, signed, rtol=1e-9)
            broken |= bool(np.abs(first_meeting).sum(axis=1).max(initial=0.0) > 1.0)
    assert problem.walk_bounds == (material.exponent >= 0 if isinstance(material, cs.PowerLawGraded) else True)
    assert problem.walk_bounds or broken


def test_cg_stops_when_asked_and_only_below_its_threshold():
    rng = np.random.default_rng(0)
    Q = rng.random((30, 30))
    A = Q @ Q.T + 30 * np.eye(30)
    b = rng.random(30)
    asked = []

    def stop(x, image, residual_norm, residual_energy, residual_max):
        asked.append(residual_norm / np.linalg.norm(b))
        assert residual_energy == pytest.approx(residual_norm**2, rel=1e-9)  # r.M r, M = I
        assert residual_max == pytest.approx(np.abs(b - A @ x).max(), rel=1e-6)
        return residual_norm < 1e-6 * np.linalg.norm(b)

    out = conjugate_gradient(lambda v: A @ v, b, rtol=1e-12, early_stop=stop, early_stop_below=1e-3)
    assert out.stopped_early and not out.converged
    assert asked and max(asked) <= 1e-3 and out.residual < 1e-6
    assert np.linalg.norm(b - A @ out.x) == pytest.approx(out.residual * np.linalg.norm(b), rel=1e-6)
    full = conjugate_gradient(lambda v: A @ v, b, rtol=1e-12)
    assert full.converged and not full.stopped_early


@pytest.fixture(scope="module")
def small_flat():
    sc = scene(cs.Circle(1.0))
    st = settings(6)
    problem = bg.solver.build_problem(sc, st)
    return problem, st, PaperRule(problem.critical_stress)


def test_a_tension_within_its_error_bound_of_sigma_c_leaves_the_pass_undecided(small_flat):
    """One cell above sigma_c by a margin m, the others far below, no free cell: decided when
    the tensions' error bound |d| error is below m, not when it reaches m; never when no cell
    is above sigma_c."""
    problem, st, rule = small_flat
    d = -1.0
    decide = early_decision(problem, d, st, rule)
    contact = problem.face.copy()
    n = int(contact.sum())
    threshold = rule.critical_stress * (1 - st.tie_tolerance)
    margin = 1e-3 * threshold
    x1 = np.full(n, 0.5 * threshold / abs(d))
    x1[n // 2] = (threshold + margin) / abs(d)

    def no_displacement():
        raise AssertionError("no free cell: the gaps are not needed")

    assert decide(contact, x1, no_displacement, 0.9 * margin / abs(d))
    assert not decide(contact, x1, no_displacement, 1.1 * margin / abs(d))
    x1[n // 2] = (threshold - margin) / abs(d)
    assert not decide(contact, x1, no_displacement, 0.0)


def test_a_free_gap_within_its_error_bound_of_closing_leaves_the_pass_undecided(small_flat):
    """A detached cell whose gap is within its error bound (|d| kernel_norm error) of the gap
    tolerance may re-attach: undecided until the bound is below the gap.  (Without the walk
    property, e.g. graded k < 0 or periodic, where the gaps are not known to stay open.)"""
    problem, st, rule = small_flat
    problem = dataclasses.replace(problem, walk_bounds=False)
    d = -1.0
    decide = early_decision(problem, d, st, rule)
    contact = problem.face.copy()
    free_cell = tuple(np.argwhere(contact)[0])
    contact[free_cell] = False
    n = int(contact.sum())
    threshold = rule.critical_stress * (1 - st.tie_tolerance)
    x1 = np.full(n, 0.5 * threshold / abs(d))
    x1[n // 2] = 2 * threshold / abs(d)  # certainly leaves
    gap = 1e-4
    u1 = np.ones(problem.face.shape)
    u1[free_cell] = 1.0 - gap / abs(d)  # gap = (u1 - 1) d

    error_closing = 2 * gap / (abs(d) * problem.kernel_norm)
    assert not decide(contact, x1, lambda: u1, error_closing)
    assert decide(contact, x1, lambda: u1, 0.25 * error_closing)
    # a displacement bound of its own (the energy norm's) replaces kernel_norm times the pressures'
    assert not decide(contact, x1, lambda: u1, 0.0, 2 * gap / abs(d))
    assert decide(contact, x1, lambda: u1, error_closing, 0.25 * gap / abs(d))


def test_pulled_under_the_walk_property_a_decision_needs_no_gaps(small_flat):
    """Where C^-1 is a random walk's, every free gap is open while the face is pulled (a free
    cell's displacement per approach is the walk's chance of meeting S, below one): a decision
    asks for no displacements then, but still does without the walk property."""
    problem, st, rule = small_flat
    assert problem.walk_bounds
    contact = problem.face.copy()
    contact[tuple(np.argwhere(contact)[0])] = False
    n = int(contact.sum())
    threshold = rule.critical_stress * (1 - st.tie_tolerance)
    asked = []

    def displacement():
        asked.append(True)
        return np.zeros(problem.face.shape)  # gaps (u - 1) d wide open at d < 0

    for walk, expect_asked in [(True, False), (False, True)]:
        p = dataclasses.replace(problem, walk_bounds=walk)
        x1 = np.full(n, 0.5 * threshold)
        x1[n // 2] = 2 * threshold  # certainly leaves at d = -1
        asked.clear()
        assert early_decision(p, -1.0, st, rule)(contact, x1, displacement, 0.0)
        assert bool(asked) == expect_asked


def test_pulled_under_the_walk_property_only_the_leaving_tensions_must_be_certain(small_flat):
    """One cell certainly above the threshold, another below it by less than its error bound:
    decided under the walk property (the second, if it truly reaches the threshold, leaves in a
    later pass), undecided without it.  A cell above the threshold by less than its error bound
    keeps the pass undecided either way."""
    problem, st, rule = small_flat
    d = -1.0
    contact = problem.face.copy()
    n = int(contact.sum())
    threshold = rule.critical_stress * (1 - st.tie_tolerance)
    margin = 1e-3 * threshold
    error = 2 * margin / abs(d)
    x1 = np.full(n, 0.5 * threshold / abs(d))
    x1[0] = 2 * threshold / abs(d)
    x1[n // 2] = (threshold - margin) / abs(d)

    def no_displacement():
        raise AssertionError("no free cell: the gaps are not needed")

    walk = early_decision(problem, d, st, rule)
    other = early_decision(dataclasses.replace(problem, walk_bounds=False), d, st, rule)
    assert walk(contact, x1, no_displacement, error)
    assert not other(contact, x1, no_displacement, error)
    x1[n // 2] = (threshold + margin) / abs(d)
    assert not walk(contact, x1, no_displacement, error)
    assert not other(contact, x1, no_displacement, error)


def test_states_decided_without_gaps_carry_no_gaps_beyond_their_window(monkeypatch):
    """A star at 48 per radius shrinks into windows; its passes decided without gaps keep C x1
    on their window only (no whole-grid product), there equal to the whole-grid product (the
    next set's local warm start reads it), never hand such a state to the event search (which
    would raise), and give the same contact sets as full solves (test below)."""
    sc = scene(cs.Star(5, 1.0, 0.45))
    st = settings(48)
    problem = bg.solver.build_problem(sc, st)
    seen = []
    original = bg.contact_set.solve_contact_set

    def spy(solver_problem, *args, **kw):
        solution = original(solver_problem, *args, **kw)
        seen.append(solution.displacement_in_window)
        if solution.displacement_in_window:
            image = solution.displacement_per_approach
            exact = solver_problem.operator.apply_masked(solution.pressure_per_approach, solution.contact)
            inside = image != 0
            assert inside[solution.contact].all()
            np.testing.assert_allclose(image[inside], exact[inside], rtol=1e-9, atol=1e-12)
        return solution

    monkeypatch.setattr(bg.driver, "solve_contact_set", spy)
    a = bg.solve(sc, st)
    assert any(seen) and a.converged
    state = original(problem, problem.face, st, None, bg.counters.WorkCounters())
    assert not state.displacement_in_window
    with pytest.raises(ValueError, match="window"):
        bg.driver.gap_coefficients(problem, dataclasses.replace(state, displacement_in_window=True))


def test_early_decisions_and_local_warm_starts_keep_every_contact_set():
    """A star (tips peel first, long cascades) and a 4:1 rectangle: with early decisions and
    local warm starts the same events, contact sets and forces as with every set solved to
    rtol from the plain warm start (to the CG tolerance), at markedly fewer CG iterations.  A
    pass decided while pulling under the walk property may keep a cell that a full solve
    detaches, which then leaves a pass later: each early set holds the full solves' set of the
    same pass, so the early decisions take at least as many solves, never fewer; without the
    walk property (graded k = -0.5) exactly as many."""
    star_without_walk = scene(cs.Star(5, 1.0, 0.45), cs.PowerLawGraded(1.0, 0.5, -0.5))
    for sc, N in [(scene(cs.Star(5, 1.0, 0.45)), 24), (scene(cs.Rectangle(4.0, 1.0)), 12), (star_without_walk, 24)]:
        a = bg.solve(sc, settings(N))
        b = bg.solve(sc, settings(N, decide_early=False, local_warm_start=False))
        assert a.info["decided_solves"] > 0 and b.info["decided_solves"] == 0
        assert a.info["events"] == b.info["events"] and a.info["solves"] >= b.info["solves"]
        problem = bg.solver.build_problem(sc, settings(N))
        force_rtol = 1e-9
        if not problem.walk_bounds:
            assert a.info["solves"] == b.info["solves"]  # every pass decided as a full solve would
            # the CG tolerance bounds a force's relative error by rtol / (eigenvalue floor x mean
            # x1), with x1 smallest on the pressed face; twice that for two runs (k < 0 is the
            # worse conditioned kernel)
            counters = bg.counters.WorkCounters()
            pressed = bg.contact_set.solve_contact_set(problem, problem.face, settings(N), None, counters)
            force_rtol = 2 * settings(N).rtol / (problem.eigenvalue_floor * pressed.pressure_per_approach.mean())
        assert np.array_equal(a.curve.contact_area, b.curve.contact_area)
        assert np.array_equal(a.last_stable.contact, b.last_stable.contact)
        assert a.pulloff_force == pytest.approx(b.pulloff_force, rel=force_rtol)
        assert a.detachment_approach == pytest.approx(b.detachment_approach, rel=10 * force_rtol)
        assert np.allclose(a.curve.force, b.curve.force, rtol=10 * force_rtol, atol=force_rtol * b.pulloff_force)
        assert a.iterations < 0.75 * b.iterations
        assert a.converged and b.converged


@pytest.mark.parametrize("curved", [False, True], ids=["flat", "sphere"])
def test_local_warm_start_removes_most_of_the_residual_a_change_leaves(curved):
    """Two edge cells leave a solved set (and, curved, one free cell joins): started from the
    previous pressures corrected near the change, CG needs at least two fewer iterations for
    the same solution (to rtol) than from the previous pressures alone."""
    sc = scene(cs.Circle(1.0))
    if curved:
        sc = dataclasses.replace(
            sc, indenter=cs.Indenter(cs.Circle(1.0), cs.Sphere(3.0)), loading=cs.Loading(press_approach=0.05)
        )
    st = settings(16)
    problem = bg.solver.build_problem(sc, st)
    counters = bg.counters.WorkCounters()
    first = problem.face if not curved else problem.face & (problem.height < 0.6 * problem.height[problem.face].max())
    before = bg.contact_set.solve_contact_set(problem, first.copy(), st, None, counters)
    after = first.copy()
    edge = np.argwhere(first)
    after[tuple(edge[0])] = after[tuple(edge[-1])] = False
    if curved:
        joining = np.argwhere(problem.face & ~first)[0]
        after[tuple(joining)] = True
    plain = bg.contact_set.solve_contact_set(
        problem, after, dataclasses.replace(st, local_warm_start=False), before, counters
    )
    local = bg.contact_set.solve_contact_set(problem, after, st, before, counters)
    assert local.iterations <= plain.iterations - 2
    assert np.allclose(
        local.pressure_per_approach, plain.pressure_per_approach, rtol=0, atol=1e-8 * plain.pressure_per_approach.max()
    )
    assert np.allclose(
        local.profile_pressure,
        plain.profile_pressure,
        rtol=0,
        atol=1e-8 * np.abs(plain.profile_pressure).max(initial=1.0),
    )


def test_early_decisions_need_the_setting_and_a_nonzero_approach(small_flat):
    problem, st, rule = small_flat
    assert early_decision(problem, -1.0, dataclasses.replace(st, decide_early=False), rule) is None
    assert early_decision(problem, 0.0, st, rule) is None


def curved_scene(material=None, shape=None):
    return dataclasses.replace(
        scene(shape or cs.Circle(1.0), material),
        indenter=cs.Indenter(shape or cs.Circle(1.0), cs.Sphere(2.0)),
        loading=cs.Loading(press_approach=0.05),
    )


def test_a_curved_face_is_decided_on_its_free_gaps_too(small_flat):
    """A curved face has no walk shortcut: a free gap may close as cells leave, so a pass with
    a certain leaver is decided only once every free gap is certainly open or closed, and the
    gaps are asked for (a flat face pulled under the walk property needs none)."""
    problem, st, rule = small_flat
    curved = bg.solver.build_problem(curved_scene(), st)
    d = -1.0
    contact = curved.face.copy()
    contact[tuple(np.argwhere(contact)[0])] = False  # one free cell
    free = curved.face & ~contact
    threshold = rule.threshold(st.tie_tolerance)
    x1 = np.full(int(contact.sum()), 0.5 * threshold)  # tension -d x1
    x1[0] = 2.0 * threshold

    def displacement_with_gap(gap, asked):
        def displacement():
            asked.append(True)
            u = np.zeros(curved.face.shape)
            u[free] = 1.0 + (gap - curved.height[free]) / d  # gap = (u - 1) d + h
            return u

        return displacement

    for prob, gap, decided, asks in [
        (curved, 1e-3, True, True),
        (curved, 1e-15, False, True),  # within the gaps' error bound of zero
        (problem, 1e-15, True, False),  # flat and pulled: the walk property opens every gap
    ]:
        c = contact if prob is curved else problem.face & ~free
        x = x1 if prob is curved else np.r_[x1, 0.5 * threshold][: int(c.sum())]
        asked: list[bool] = []
        decide = early_decision(prob, d, st, rule)
        assert decide is not None
        assert decide(c, x, displacement_with_gap(gap, asked), 1e-9, 1e-9) is decided
        assert bool(asked) is asks


@pytest.mark.parametrize(
    "material",
    [cs.Homogeneous(0.75, 0.5), cs.PowerLawGraded(1.0, 0.5, 0.5), cs.PowerLawGraded(1.0, 0.5, -0.5)],
    ids=["homogeneous", "graded k=0.5", "graded k=-0.5"],
)
def test_curved_faces_keep_every_contact_set_with_early_decisions(material):
    """The JKR sphere pressed, then pulled off (homogeneous and graded): a passing set decided
    on its pressure at the cascade's approach, p = d y with C_SS y = 1 - h / d, detaches and
    attaches what a full solve of x1 and xh would, so the same passes, events, contact sets and
    forces follow (to the CG tolerance), at markedly fewer CG iterations."""
    sc = dataclasses.replace(SUITE["jkr_sphere"], material=material)
    N = 16
    a = bg.solve(sc, settings(N))
    b = bg.solve(sc, settings(N, decide_early=False))
    assert a.info["decided_solves"] > 0 and b.info["decided_solves"] == 0
    assert a.info["events"] == b.info["events"] and a.info["solves"] == b.info["solves"]
    assert np.array_equal(a.curve.contact_area, b.curve.contact_area)
    assert np.array_equal(a.last_stable.contact, b.last_stable.contact)
    # as for flat faces: the CG tolerance bounds a force's relative error by rtol / (eigenvalue
    # floor x mean x1), twice for two runs
    problem = bg.solver.build_problem(sc, settings(N))
    counters = bg.counters.WorkCounters()
    pressed = bg.contact_set.solve_contact_set(problem, problem.face, settings(N), None, counters)
    force_rtol = 2 * settings(N).rtol / (problem.eigenvalue_floor * pressed.pressure_per_approach.mean())
    assert a.pulloff_force == pytest.approx(b.pulloff_force, rel=force_rtol)
    assert a.pulloff_approach == pytest.approx(b.pulloff_approach, rel=10 * force_rtol)
    assert np.allclose(a.curve.force, b.curve.force, rtol=10 * force_rtol, atol=force_rtol * b.pulloff_force)
    assert a.iterations < 0.75 * b.iterations
    assert a.converged and b.converged


def test_a_state_decided_at_one_approach_is_never_extrapolated(small_flat):
    """A curved face's decided state says at which approach it was decided (a flat face's is
    linear in the approach and says nothing), and the next event refuses it."""
    problem, st, _ = small_flat
    curved = bg.solver.build_problem(curved_scene(), st)

    def always(*args):
        return True

    for prob, marked in ((curved, -0.1), (problem, None)):
        state = bg.contact_set.solve_contact_set(
            prob, prob.face.copy(), st, None, bg.counters.WorkCounters(), always, -0.1
        )
        assert state.residual > st.rtol and state.at_approach == marked  # stopped: decided
    state = bg.contact_set.solve_contact_set(curved, curved.face, st, None, bg.counters.WorkCounters())
    decided = dataclasses.replace(state, at_approach=-0.1)
    with pytest.raises(ValueError, match="approach"):
        bg.driver.next_event(curved, decided, -0.1, -1.0)


def test_a_holding_set_after_a_decided_one_is_solved_to_rtol_near_zero_approach():
    """Near d = 0 a decided set's y = x1 - xh / d is of the size h / |d|: the set that holds
    after it must not start its x1 from y, whose round-off would leave CG's recursive residual
    far below the true one (x1 wrong by percents at |d| ~ 1e-16, reported as converged), and
    the wrong x1 is then extrapolated to the next event or step."""
    sc = dataclasses.replace(
        curved_scene(),
        indenter=cs.Indenter(cs.Circle(0.42), cs.Paraboloid(1.0)),
        adhesion=cs.Adhesion(0.004),
        loading=cs.Loading(press_approach=0.15),
    )
    st = settings(12)
    problem = bg.solver.build_problem(sc, st)
    pressed = press_to_approach(problem, 0.15, st, bg.counters.WorkCounters())
    for d in (-1e-16, 1e-12):
        counters = bg.counters.WorkCounters()
        held = bg.driver.cascade(problem, pressed, d, st, counters, [], -1.0)
        assert counters.decided_solves > 0 and held.at_approach is None and held.converged
        c = held.contact
        for x, b in ((held.pressure_per_approach, np.ones(int(c.sum()))), (held.profile_pressure, problem.height[c])):
            true_residual = np.linalg.norm(b - problem.operator.apply_masked(x, c)[c]) / np.linalg.norm(b)
            assert true_residual <= 10 * st.rtol


def test_the_fixed_step_driver_through_zero_approach_keeps_every_contact_set_with_early_decisions():
    """press 0.1 in steps of 0.002 lands the fixed-step driver on d ~ -7e-17 (round-off), where a
    curved face's cascade decides passing sets: the steps after it see the same contact sets
    and forces as with full solves."""
    sc = dataclasses.replace(
        curved_scene(),
        indenter=cs.Indenter(cs.Circle(0.42), cs.Paraboloid(1.0)),
        adhesion=cs.Adhesion(0.003),
        loading=cs.Loading(press_approach=0.1),
    )
    st = settings(16, driver="fixed_step", step=0.002)
    a = bg.solve(sc, st)
    b = bg.solve(sc, dataclasses.replace(st, decide_early=False))
    assert a.info["decided_solves"] > 0
    assert a.info["solves"] == b.info["solves"]
    assert np.array_equal(a.curve.contact_area, b.curve.contact_area)
    assert np.allclose(a.curve.force, b.curve.force, rtol=1e-8, atol=1e-10)


def _pulled_without_adhesion(N):
    """The JKR sphere's scene without adhesion, pulled from its press: the result, the
    largest relative deviation of the force from Hertz's (4/3) E* sqrt(R) d^(3/2) while the
    contact spans a few cells (d > 0.02, about a seventh of the press), and the lowest
    height of the face's cells."""
    sc = dataclasses.replace(SUITE["jkr_sphere"], adhesion=cs.Adhesion(0.0))
    r = bg.solve(sc, settings(N))
    d, F = r.curve.approach, r.curve.force
    E, R = sc.material.effective_modulus, sc.indenter.profile.radius
    far = d > 0.02
    error = float(np.max(np.abs(F[far] / (4.0 / 3.0 * E * math.sqrt(R) * d[far] ** 1.5) - 1.0)))
    problem = bg.solver.build_problem(sc, settings(N))
    return r, error, float(problem.height[problem.face].min())


def test_a_curved_face_without_adhesion_unloads_along_hertz():
    """With w = 0 the paper's rule has sigma_c = 0: a contact-edge cell leaves where its
    pressure reaches zero, and its gap is then zero too (degenerate).  Each event's own cell
    must leave although its pressure lies a round-off short of zero (``pressure_roundoff``),
    and a cell that left must not re-attach on CG's noise in its gap (``_open_tolerance``):
    the pull then unloads along Hertz's curve, never in tension, and lets go where the
    approach reaches the lowest cells' height, where their pressure (d - h) x1 vanishes.  The
    deviation from Hertz falls with the grid (measured 5.2e-3, 2.2e-3, 6.7e-4 at 8, 16, 32
    per face radius: at least first order is asserted)."""
    errors = []
    for N in (8, 16):
        r, error, lowest = _pulled_without_adhesion(N)
        assert r.converged, r.messages
        assert r.pulloff_force == 0.0 and r.curve.force.min() >= 0.0
        assert r.detachment_approach == pytest.approx(lowest, rel=1e-9)
        errors.append(error)
    assert errors[1] < errors[0] / 2.0, errors
    assert errors[1] < 5e-3, errors


class _CentreAlwaysLeaves:
    """A rule that detaches the face's centre cell whenever it is in contact: pressed, the cell
    then penetrates and re-attaches, and the cascade would flip it for ever."""

    def __init__(self, centre_index):
        self.centre = centre_index

    def critical_approaches(self, solution):
        return np.full(solution.pressure_per_approach.shape, np.nan)

    def detaching(self, solution, approach, tie_tolerance):
        out = np.zeros(solution.pressure_per_approach.shape, bool)
        flat = np.flatnonzero(solution.contact.ravel())
        out[flat == self.centre] = True
        return out

    def report(self, pulloff_approach):
        return [], {}


def test_a_cascade_that_comes_back_to_a_set_stops_and_says_so():
    """A cascade that returns to a contact set it has left would repeat its passes up to the
    pass limit at every later event (a hang, not an answer): it stops at the repeat, counts as
    unsettled and the pull reports it, not converged."""
    sc = dataclasses.replace(SUITE["jkr_sphere"], adhesion=cs.Adhesion(0.0))
    st = settings(8)
    problem = bg.solver.build_problem(sc, st)
    pressed = press_to_approach(problem, 0.15, st, bg.counters.WorkCounters())
    nx, ny = problem.face.shape
    rule = _CentreAlwaysLeaves((nx // 2) * ny + ny // 2)
    counters, messages = bg.counters.WorkCounters(), []
    bg.driver.cascade(problem, pressed, 0.15, st, counters, messages, -1.0, rule)
    assert counters.cycled_cascades == 1 and counters.unsettled_cascades == 1
    assert counters.contact_solves <= 2  # the centre left, came back: stopped at the repeat
    assert any("came back to a contact set" in m for m in messages), messages


@pytest.mark.parametrize("periodic", [False, True], ids=["isolated", "periodic"])
def test_without_adhesion_a_curved_face_unloads_and_reloads_along_one_curve(periodic):
    """Without adhesion the contact problem at each approach has one solution (C_SS is
    positive definite), so unloading to a turning point, pressing again and unloading must
    trace one force curve, piecewise linear between events.  On the way back in a cell
    re-attaches with zero pressure as its gap closes: it must stay (its tension, zero to CG's
    noise, falls along the direction of travel), and its crossing of the threshold is no
    event.  On a periodic grid CG's noise is bounded through the circulant's smallest
    non-zero eigenvalue."""
    sc = dataclasses.replace(
        SUITE["jkr_sphere"],
        adhesion=cs.Adhesion(0.0),
        loading=cs.Loading(press_approach=0.15, turning_points=(0.05, 0.1)),
    )
    grid = cs.Grid(elements_per_radius=12, periodic=periodic, period=1.2 if periodic else None)
    r = bg.solve(sc, bg.GriffithSettings(grid=grid))
    assert r.converged, r.messages
    d, F = r.curve.approach, r.curve.force
    first = int(np.flatnonzero(d == 0.05)[0])
    second = first + int(np.flatnonzero(d[first:] == 0.1)[0])

    def branch(a, b):
        order = np.argsort(d[a : b + 1], kind="stable")
        return d[a : b + 1][order], F[a : b + 1][order]

    down, Fdown = branch(0, first)
    for x, y in (branch(first, second), branch(second, len(d) - 1)):
        both = x >= down.min()
        assert both.sum() > 10
        assert np.max(np.abs(np.interp(x[both], down, Fdown) - y[both])) <= 1e-9 * F.max()


def test_periodic_floor_bounds_every_contact_submatrix():
    """On a periodic grid the circulant C's eigenvalues are its symbol's values, zero for the
    mean: every C_SS of n of the N cells has no eigenvalue below s' (1 - n / N), s' the
    smallest non-zero one (``_periodic_floor``, which bounds CG's pressure error there).
    Checked against dense eigenvalues for the face and random subsets; and not vacuous: within
    a factor 3 of the smallest eigenvalue of a set of a tenth of the cells."""
    sc = cs.Scene(
        cs.Indenter(cs.Circle(0.42), cs.Paraboloid(1.0)),
        cs.Homogeneous(0.75, 0.5),
        cs.Adhesion(0.0),
        cs.Loading(press_approach=0.15),
    )
    problem = bg.solver.build_problem(
        sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=6, periodic=True, period=1.2))
    )
    nx, ny = problem.face.shape
    C = dense_operator(problem)  # the periodic kernel has the grid's shape: a circulant
    rng = np.random.default_rng(3)
    subsets = [problem.face.ravel()] + [rng.random(nx * ny) < f for f in (0.1, 0.5, 0.9, 0.99)]
    for S in subsets:
        n = int(S.sum())
        floor = bg.driver._periodic_floor(problem, n)
        smallest = np.linalg.eigvalsh(C[np.ix_(S, S)])[0]
        assert floor is not None and 0 < floor <= smallest * (1 + 1e-12), (n, floor, smallest)
    tenth = subsets[1]
    assert bg.driver._periodic_floor(problem, int(tenth.sum())) > np.linalg.eigvalsh(C[np.ix_(tenth, tenth)])[0] / 3
    assert bg.driver._periodic_floor(problem, nx * ny) is None  # the whole cell holds the mean's zero mode
