"""The energy BEM at a finite range: the grid against the process zone l_c = E* rho^2 / w,
and the cvxpy minimiser over a whole pull-off.

Tolerances: the elements per l_c a potential needs come from
benchmarks/study_energy_process_zone.py (quoted in ``bem_energy.potentials``); the grid
envelope 0.16 / N of the fixed-range study (benchmarks/study_energy.py, tests/test_bem_energy.py);
minimisers stopped at a projected gradient g agree on forces to about g relative.
"""

import dataclasses
import math

import hertz_press
import numpy as np
import pytest

import bem_energy as be
import bem_energy.minimisers as minimisers
import contact_scene as cs
from bem_energy.potentials import PROCESS_ZONE_ELEMENTS
from contact_scene import theory as T


def kendall(range_, potential="exponential"):
    """The README's scene (scenes/kendall_circle.toml: E* = 1, w = 1, a = 1), l_c = range^2."""
    return cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0, range_, potential))


FK = T.kendall_adhesion_force(E_star=1.0, radius=1.0, work=1.0)

# -- the grid a finite range picks by itself ---------------------------------------

#: F_A / F_Kendall at l_c = 0.04 a on the finest grid of the study (4 per l_c, 100 per radius)
RESOLVED_004 = 0.8819


def test_default_grid_resolves_the_process_zone():
    """rho = 0.2: l_c = 0.04 a, 1.28 elements per l_c on the former fixed 32 per radius (F_A
    +0.5 % off); the default now takes the exponential potential's two per l_c (50 per
    radius), which the study puts within 0.1 % of 4 per l_c, inside the staircase envelope."""
    sc = kendall(0.2)
    r = be.solve_with_resolution(sc, None)
    assert r.info["process_zone"] == pytest.approx(0.04, rel=1e-12)
    assert r.info["process_zone_per_element"] == pytest.approx(PROCESS_ZONE_ELEMENTS["exponential"][1], rel=1e-9)
    assert r.converged and r.detached and not r.messages
    N = 1.0 / r.grid_spacing
    assert abs(r.pulloff_force / FK - RESOLVED_004) <= 0.16 / N


def test_long_range_keeps_32_per_radius():
    """l_c = 0.16 a needs 12.5 per radius for two per l_c: the face's own 32 decide."""
    g = be.finite_range_grid(kendall(0.4))
    assert g.spacing_for(cs.Circle(1.0)) == pytest.approx(1 / 32, rel=1e-12)
    g = be.finite_range_grid(cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.0, 0.1)))
    assert g.spacing_for(cs.Circle(1.0)) == pytest.approx(1 / 32, rel=1e-12)


# -- the long-range (stiff) limit: l_c >> a --------------------------------------------

#: E* = 1 / (1 - 0.3^2), w = 1, a = 1: eps = a / l_c = w a / (E* rho^2) picks the range
STIFF_E, STIFF_NU = 1.0, 0.3


def stiff(eps=None, *, rho=None, potential="exponential", E=STIFF_E, w=1.0):
    if rho is None:
        rho = math.sqrt(w / (E / (1 - STIFF_NU**2) * eps))
    return cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(E, STIFF_NU), cs.Adhesion(w, rho, potential))


def stiff_ratio(res, scene):
    """F_A over the raster face's area times the peak stress w / rho, and eps = a / l_c."""
    E_star = scene.material.youngs_modulus / (1 - scene.material.poisson_ratio**2)
    w, rho = scene.adhesion.work_of_adhesion, scene.adhesion.range
    return res.pulloff_force / (res.face_area * w / rho), w / (E_star * rho**2)


@pytest.mark.parametrize("eps", [0.1, 0.05, 0.025])
def test_long_range_force_follows_the_stiff_limit_to_first_order(eps):
    """F_A / (A sigma0) = 1 - c eps + b eps^2 + e eps^3 + ..., c = 2 - 16 / (3 pi): the adhesive
    traction's first-order dishing of the surface (``theory.long_range_flat_circle_force``).
    The residual D = F_A / (A sigma0) - (1 - c eps), measured at eps = 0.2 ... 0.00625 on 32 and
    64 per radius alike: +2.6e-3, +3.8e-4, +3.3e-5, -3.5e-6, then a floor of about 5e-6 (the
    maximum's location to the snap tolerance, the raster); fitted b ~ 0.01, e ~ 0.3 (an
    independent second-order estimate gave |b| ~ 0.015).  So |D| <= 0.02 eps^2 + 0.5 eps^3 +
    1e-5.  E instead of E* would move D by 0.03 eps, several times that at every eps here."""
    sc = stiff(eps)
    res = be.solve(sc, be.EnergySettings(grid=cs.Grid(elements_per_radius=32), snap_tolerance=1e-5))
    assert res.converged, res.messages
    ratio, eps_scene = stiff_ratio(res, sc)
    assert eps_scene == pytest.approx(eps)
    E_star = STIFF_E / (1 - STIFF_NU**2)
    closed = T.long_range_flat_circle_force(
        E_star=E_star, radius=1.0, work=1.0, range=sc.adhesion.range, potential="exponential"
    )
    # each force over its own area (the nominal circle's, the raster's) times sigma0
    D = ratio - closed / (math.pi * 1.0 / sc.adhesion.range)
    assert abs(D) <= 0.02 * eps**2 + 0.5 * eps**3 + 1e-5, D


@pytest.mark.parametrize("eps", [0.1, 0.5])
def test_maugis_dugdale_long_range_force_is_the_peak_stress_times_the_area(eps):
    """Every gap stays below the range at the last touch (eps < 1 / (2 - 4/pi)), so each cell
    pulls with exactly sigma0: F_A = A sigma0 to the minimisers' tolerance."""
    sc = stiff(eps, potential="maugis_dugdale")
    settings = be.EnergySettings(grid=cs.Grid(elements_per_radius=32))
    res = be.solve(sc, settings)
    assert res.converged, res.messages
    # the force is summed from the elastic pressures, each within the convergence measure's
    # unit (at most ADHESIVE_UNIT sigma0) times gtol of the adhesive traction
    assert stiff_ratio(res, sc)[0] == pytest.approx(1.0, abs=minimisers.ADHESIVE_UNIT * settings.gtol)


STIFF_CASES = {
    "rho = 100 a": dict(rho=100.0),
    "rho = 1000 a": dict(rho=1000.0),
    "E = 1e6": dict(rho=1.0, E=1e6),
    "w = 1e-4": dict(rho=1.0, w=1e-4),
    "Maugis-Dugdale, rho = 100 a": dict(rho=100.0, potential="maugis_dugdale"),
    "Maugis-Dugdale, rho = 1000 a": dict(rho=1000.0, potential="maugis_dugdale"),
}


@pytest.mark.parametrize("case", list(STIFF_CASES))
def test_a_very_long_process_zone_still_resolves_the_adhesive_stress(case):
    """l_c from 1e4 a to 1e6 a with the default settings: the element's pressure unit (rho /
    C_00) is then 1e5 ... 1e7 times the adhesive stress w / rho, and a minimum accepted in it
    takes the first trial for converged (the mutant below: F_A zero at rho = 1000).  With the
    unit capped at ``ADHESIVE_UNIT`` w / rho: F_A / (A sigma0) lies between 1 - c eps less the
    snap tolerance's share (the maximum is located to snap_tolerance times the pull's scale)
    and 1 (no cell pulls harder than sigma0) plus the minimisers' tolerance.  The default
    projected CG; L-BFGS-B stalls at its objective's round-off here (see ``ADHESIVE_UNIT``)."""
    sc = stiff(**STIFF_CASES[case])
    settings = be.EnergySettings()
    res = be.solve(sc, settings)
    assert res.converged, res.messages
    ratio, eps = stiff_ratio(res, sc)
    assert eps <= 1e-4
    # the pull's scale is rho plus the critical approach, which is below rho in every case; the
    # force, summed from the elastic pressures, may exceed A sigma0 by the minimisers' tolerance
    upper = 1 + minimisers.ADHESIVE_UNIT * settings.gtol
    assert 1 - T.UNIFORM_DISC_DISHING * eps - 2 * settings.snap_tolerance <= ratio <= upper


def test_an_uncapped_pressure_unit_misses_the_adhesive_stress(monkeypatch):
    """The mutant: the element's unit alone (no cap) accepts the first trial at l_c = 1e6 a."""
    monkeypatch.setattr(minimisers, "ADHESIVE_UNIT", math.inf)
    sc = stiff(rho=1000.0)
    res = be.solve(sc, be.EnergySettings())
    assert stiff_ratio(res, sc)[0] < 0.5


def test_a_range_too_short_to_resolve_is_refused_with_the_shortest_that_fits():
    """The README's former example, rho = 0.05 (l_c = 0.0025 a: 0.08 elements per l_c at 32
    per radius, F_A = 2.44 x Kendall) would need 800 per radius: refused before any run,
    naming the field and the shortest range whose grid fits."""
    with pytest.raises(cs.SceneError, match="adhesion.range") as e:
        be.solve_with_resolution(kendall(0.05), None)
    msg = str(e.value)
    assert "1600 x 1600" in msg and "--resolution" in msg
    rho_min = float(msg.split("use a range >= ")[1].split(" ")[0])
    h = be.finite_range_grid(kendall(rho_min)).spacing_for(cs.Circle(1.0))
    assert math.ceil(2.0 / h) <= be.solver.MAX_DEFAULT_SIDE
    with pytest.raises(cs.SceneError, match="adhesion.range"):
        be.finite_range_grid(kendall(0.99 * rho_min))


def test_resolution_too_coarse_for_the_process_zone_is_not_converged():
    """l_c = 0.16 a at 4 per radius: 0.64 elements per l_c, the zone trapped by the mesh and
    F_A about 20 % high (the study: +12 to +33 % at half an element per l_c).  Run, but
    reported not converged, with the resolution that suffices (one per l_c: 6.25 -> 7)."""
    sc = kendall(0.4)
    coarse = be.solve_with_resolution(sc, 4)
    fine = be.solve_with_resolution(sc, 16)
    assert coarse.pulloff_force > 1.1 * fine.pulloff_force
    assert not coarse.converged and fine.converged
    (msg,) = [m for m in coarse.messages if "process zone" in m]
    assert "0.64 elements per process zone" in msg and "use --resolution 7 or more" in msg
    assert be.solve_with_resolution(sc, 7).converged
    # pull_off called directly with such a grid says the same
    r = be.pull_off(sc, be.EnergySettings(grid=cs.Grid(elements_per_radius=4)))
    assert not r.converged and r.messages == coarse.messages


def test_a_zero_range_sequence_too_coarse_advises_its_own_resolution():
    """The zero-range sequence's --resolution counts elements per process zone, not per
    radius: its note names that measure and the potential's fewest (one per l_c), and that
    resolution resolves every range (in elements per radius it would be 25x finer)."""
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    coarse = be.solve_with_resolution(sc, 0.5)
    notes = [m for m in coarse.messages if "trapped by the mesh" in m]
    assert notes and not coarse.converged
    assert all("use --resolution 1 or more (elements per process zone" in m for m in notes)
    enough = be.solve_with_resolution(sc, 1)
    assert not [m for m in enough.messages if "trapped by the mesh" in m]


def test_maugis_dugdale_needs_more_elements_per_process_zone():
    """Its constant-stress cohesive zone converges slowly: +3 to +4 % at 8 per l_c, +2 % at
    16 (the study).  8 per l_c is reported not converged and asks for 16."""
    assert PROCESS_ZONE_ELEMENTS["maugis_dugdale"][0] > PROCESS_ZONE_ELEMENTS["exponential"][0]
    sc = kendall(math.sqrt(0.32), "maugis_dugdale")
    r = be.solve_with_resolution(sc, 25)
    assert not r.converged
    assert any("needs at least 16" in m and "use --resolution 50 or more" in m for m in r.messages)
    g = be.finite_range_grid(sc)
    assert 0.32 / g.spacing_for(cs.Circle(1.0)) == pytest.approx(PROCESS_ZONE_ELEMENTS["maugis_dugdale"][1])


# -- the cvxpy minimiser ----------------------------------------------------------------


def test_cvxpy_is_exact_at_the_degenerate_flat_press():
    """A flat face at d = 0 without adhesion: every cell at the wall under zero pressure.  An
    interior point stops about 1e-4 short of such a minimum whatever the length scale (it
    reported a projected gradient of 2.7e-4 and every pull-off unconverged); solving the
    contact set it finds exactly gives U = 0."""
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.02, 0.1))
    prob = be.build_problem(sc, 1 / 6, be.Potential(0.02, 0.1))
    for lift in (0.0, 1e-3):
        U0 = np.zeros(prob.padded)
        U0[prob.face] = lift
        m = be.minimise(prob, U0, 0.0, False, method="cvxpy")
        assert m.converged and m.gradient <= 1e-12
        assert np.max(np.abs(m.U)) <= 1e-15 and prob.force(m.P) == pytest.approx(0.0, abs=1e-15)
    # the contact QP itself at that degenerate point: min 1/2 s.K s subject to s >= 0
    from bem_energy.minimisers import _FaceQP

    qp = _FaceQP(prob)
    n = qp.K.shape[0]
    s, at_wall = qp.step(np.zeros(n), np.zeros(n))
    assert np.all(s == 0.0)


def test_cvxpy_pull_off_agrees_with_projected_cg():
    """A whole pull-off with the cvxpy minimiser (112 face cells, l_c = 0.4 a at 6 per radius:
    2.4 elements per l_c) reports converged and agrees with the projected CG: both stop at a
    projected gradient of 1e-8, so force and approach agree to about 1e-8 relative (1e-6
    asserted; stopped at 1e-6 instead they differ by 1.5e-6)."""
    W = 0.02
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(W, math.sqrt(0.4 * W)))
    out = {
        m: be.solve(sc, be.EnergySettings(grid=cs.Grid(elements_per_radius=6), minimiser=m, gtol=1e-8))
        for m in ("pk", "cvxpy")
    }
    ref, r = out["pk"], out["cvxpy"]
    assert ref.converged and r.converged and not r.messages
    assert r.info["face_elements"] == 112 and r.detached
    assert r.pulloff_force == pytest.approx(ref.pulloff_force, rel=1e-6)
    assert r.pulloff_approach == pytest.approx(ref.pulloff_approach, rel=1e-6)
    assert r.stiffness == pytest.approx(ref.stiffness, rel=1e-6)
    assert r.residual <= 1e-8


# -- the levers that make the zero-range sequence fast keep its answers ----------------


def _rho(ratio, work=0.02):
    return math.sqrt(ratio * work)  # E* = 1, a = 1: l_c = rho^2 / w


def _graded_rho(ratio, work=0.02, k=0.5):
    from bem_energy.potentials import process_zone_modulus, range_for_process_zone

    E = process_zone_modulus(cs.PowerLawGraded(1.0, 1.0, k))
    return range_for_process_zone(modulus=E, work=work, length=ratio, exponent=k)


#: pulling steps where a detaching trial can be told from an attached one only by a rule that
#: scales with l_c / a: circles with s = 0.8 and 0.4, a JKR sphere (paraboloid, R = 2 a)
#: whose contact shrinks over the whole pull, and a graded body (k = 0.5)
PEEL_CASES = {
    "circle l_c = 0.08 a": (
        cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.02, _rho(0.08))),
        24,
    ),
    "circle l_c = 0.04 a": (
        cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.02, _rho(0.04))),
        25,
    ),
    "JKR sphere": (
        cs.Scene(
            cs.Indenter(cs.Circle(1.0), cs.Paraboloid(2.0)),
            cs.Homogeneous(1.0, 0.0),
            cs.Adhesion(0.02, _rho(0.1)),
            loading=cs.Loading(press_approach=0.2),
        ),
        20,
    ),
    # l_c = 0.06 a (s = 0.6) on the coarsest grid that resolves a graded zone (2 per l_c at k = 0.5)
    "graded k = 0.5": (
        cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.PowerLawGraded(1.0, 1.0, 0.5), cs.Adhesion(0.02, _graded_rho(0.06))),
        34,
    ),
}


def _peel_pair(name):
    sc, N = PEEL_CASES[name]
    return [
        be.solve(sc, be.EnergySettings(grid=cs.Grid(elements_per_radius=N), stop_peeling_trials=stop))
        for stop in (False, True)
    ]


@pytest.mark.parametrize("name", list(PEEL_CASES))
def test_stopping_peeling_trials_keeps_the_loading_path(name):
    """A pulling step whose contact falls below (1 - s) of its most, s = max(0.1, 10 l_c / a),
    is detaching: stopping it and converging the detached state from U = 0 classifies every
    step as the full minimisation does, so the path is the same and F_A, its approach and the
    detachment approach agree to round-off (1e-9).  A fixed s = 0.1 classifies attached steps
    as detached (test_a_fixed_peel_fraction_is_caught)."""
    full, fast = _peel_pair(name)
    assert full.converged and fast.converged and fast.detached
    assert fast.pulloff_force == pytest.approx(full.pulloff_force, rel=1e-9)
    assert fast.pulloff_approach == pytest.approx(full.pulloff_approach, rel=1e-9)
    assert fast.detachment_approach == pytest.approx(full.detachment_approach, rel=1e-9)
    assert fast.iterations <= full.iterations


def test_a_fixed_peel_fraction_is_caught(monkeypatch):
    """The mutant the rule guards against, kept as a test: with s fixed at 0.1 attached
    steps of the JKR sphere, whose contact shrinks over the whole pull, are taken for
    detaching, and it detaches about a fifth earlier in the approach (the correct rule: the
    same approach to 1e-9, test_stopping_peeling_trials_keeps_the_loading_path)."""
    import bem_energy.equilibria as eqm

    monkeypatch.setattr(eqm, "PEEL_FRACTION_PER_PROCESS_ZONE", 0.0)
    full, fast = _peel_pair("JKR sphere")
    assert abs(fast.detachment_approach / full.detachment_approach - 1) > 0.05


def test_snap_off_need_not_be_located_once_a_smooth_maximum_is_bracketed():
    """Without ``locate_detachment`` the bisection stops once attached states bracket the
    smooth maximum: Brent's bracket is the same, so F_A is identical, with fewer
    minimisations; the detachment approach is then known to within one continuation step."""
    sc, N = PEEL_CASES["circle l_c = 0.08 a"]
    st = be.EnergySettings(grid=cs.Grid(elements_per_radius=N))
    full = be.solve(sc, st)
    fast = be.solve(sc, dataclasses.replace(st, locate_detachment=False))
    assert full.info["peak"] == fast.info["peak"] == "refined"
    assert fast.pulloff_force == full.pulloff_force and fast.pulloff_approach == full.pulloff_approach
    assert fast.stats.linear_solves < full.stats.linear_solves
    step = full.curve.approach[1] - full.curve.approach[2]
    assert fast.detachment_approach <= full.detachment_approach <= fast.detachment_approach + step


def test_press_to_force_matches_hertz():
    """The press to a force (bracketing, then Brent on the non-adhesive force) of a sphere: the
    force reached is the one asked for, to the minimiser's tolerance (1e-6); the approach
    converges to Hertz's at second order (3.5e-5 at 24 per radius, 3.6e-7 at 48, with a floor
    near 1e-6 from the tolerance at 96: at 48 it must lie below the second-order step from 24,
    8.9e-6, plus that floor); the unloading stiffness is 2 E* a within the staircase's one cell
    of radius, and converges to it."""
    sc, E, F0 = hertz_press.SCENE, hertz_press.E_STAR, hertz_press.F0
    d_hertz, a_hertz = hertz_press.APPROACH, hertz_press.CONTACT_RADIUS
    errors, stiffness_errors = [], []
    for N in (24, 48):
        r = be.pull_off(sc, be.EnergySettings(grid=cs.Grid(elements_per_radius=N)))
        assert r.converged, r.messages
        assert r.curve.force[0] == pytest.approx(F0, rel=1e-6)
        assert r.stiffness == pytest.approx(2 * E * a_hertz, abs=2 * E * 0.4 / N)
        errors.append(abs(r.curve.approach[0] / d_hertz - 1))
        stiffness_errors.append(abs(r.stiffness / (2 * E * a_hertz) - 1))
    assert errors[1] <= errors[0] / 4 + 1e-6
    # the stiffness converges at least at first order (-0.34 %, -0.11 %, +0.02 % at 24, 48, 96)
    assert stiffness_errors[1] <= stiffness_errors[0] / 2


def test_snapshots_fields_and_progress_callback():
    """Snapshots at the approaches asked for, each a state of the curve; fields only when asked,
    and then the pressure sums over the face to the snapshot's force and the face's cells in
    contact sit on the punch (u = d for a flat face).  The progress callback sees every point of
    the curve, the force maximum's Brent trials included."""
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0, 0.4))
    st = be.EnergySettings(grid=cs.Grid(elements_per_radius=16))
    plain = be.pull_off(sc, st)
    wanted = (0.5 * plain.pulloff_approach, 0.9 * plain.pulloff_approach)
    seen: list[tuple[float, float, float]] = []
    for fields in (True, False):
        seen.clear()
        outputs = cs.Outputs(snapshots=wanted, fields=fields)
        r = be.pull_off(dataclasses.replace(sc, outputs=outputs), st, callback=lambda *point: seen.append(point))
        assert r.converged, r.messages
        curve = list(zip(r.curve.approach, r.curve.force, r.curve.contact_area, strict=True))
        assert sorted(seen) == sorted(curve)
        assert [s.approach for s in r.snapshots] == list(wanted)
        for s in r.snapshots:
            assert (s.approach, s.force) in [(d, F) for d, F, _ in curve]
            assert 0 < s.contact.sum() <= cs.rasterise(cs.Circle(1.0), s.spacing).mask.sum()
            if not fields:
                assert s.pressure is None and s.displacement is None
                continue
            assert s.pressure is not None and s.displacement is not None
            face = cs.rasterise(cs.Circle(1.0), s.spacing).mask
            assert float(s.pressure[face].sum()) * s.spacing**2 == pytest.approx(s.force, rel=1e-12)
            assert np.array_equal(s.displacement[s.contact], np.full(int(s.contact.sum()), s.approach))
