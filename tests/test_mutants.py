"""The harness stays sharp: physics bugs from the mutation study (benchmarks/mutation_study.py,
docs/mutation_study.md) that its checks must catch, each injected by monkeypatching.

Each test checks a result without the mutant (the check passes) and with it (the same check
fails).  Mutants already kept elsewhere are not repeated here: Love's integral x 1.01 on the
same-grid stiffness check (tests/test_halfspace.py) and E instead of E* in the Griffith solver
(tests/test_error_models.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import bem_griffith as bg
import contact_scene as cs
from contact_scene import theory as T
from crossval.compare import check_results
from crossval.suite import SUITE


def _checks(scene, results) -> dict:
    return {(c.method, c.quantity): c for c in check_results(scene, results) if c.kind == "relative"}


def _griffith(scene, N):
    r = bg.solve(scene, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)))
    assert r.converged
    return r


def test_criterion_constant_five_percent_high_fails_kendalls_pulloff(monkeypatch):
    """Mutant C1: Eq. 22's sigma_c 5 % high (Eq. 20's constant mistyped as 0.4293: (sqrt 2 - 1)/2
    for (sqrt 2 - 1)/3).  The flat circle's thresholds scale with sigma_c, so F_A and d_c move
    by +5 % at every resolution, beyond the Griffith BEM's bar at 16 per radius (3.6 %) from its
    unmutated error (+2.2 %).
    Caught by: the pull-off force check against Kendall (Eq. 6)."""
    sc = SUITE["kendall_circle"]
    ok = _checks(sc, {"bem_griffith": _griffith(sc, 16)})
    assert ok[("bem_griffith", "pulloff_force")].passed
    critical_stress = T.critical_stress
    monkeypatch.setattr(T, "critical_stress", lambda **kw: 1.05 * critical_stress(**kw))
    bad = _checks(sc, {"bem_griffith": _griffith(sc, 16)})
    moved = bad[("bem_griffith", "pulloff_force")].value / ok[("bem_griffith", "pulloff_force")].value - 1
    assert moved == pytest.approx(0.05, abs=0.005)  # linear in sigma_c between events
    assert not bad[("bem_griffith", "pulloff_force")].passed
    assert not bad[("bem_griffith", "pulloff_approach")].passed


def test_eq34_with_the_wrong_cosine_fails_the_graded_stiffness_check(monkeypatch):
    """Mutant T3: Eq. 34's factor cos(k pi/4) for cos(k pi/2): the closed form 6.2 % high at
    k = 0.25.  A correct solver then disagrees with the theory by more than its bar.
    Caught by: the Griffith BEM's stiffness check against Eq. 34 (graded circle, 32 per radius)."""
    sc = SUITE["graded_circle_k0.25"]
    r = _griffith(sc, 32)
    ok = _checks(sc, {"bem_griffith": r})[("bem_griffith", "stiffness")]
    assert ok.passed

    def eq34_wrong_cosine(*, E0, c0, k, radius):
        return 4.0 * (2.0 + k) * math.cos(k * math.pi / 4) / (3.0 + k) * E0 * radius ** (1.0 + k) / c0**k

    monkeypatch.setattr(T, "graded_stiffness", eq34_wrong_cosine)
    bad = _checks(sc, {"bem_griffith": r})[("bem_griffith", "stiffness")]
    assert bad.reference / ok.reference - 1 == pytest.approx(0.0616, abs=5e-4)
    assert not bad.passed


def test_calibration_applied_inverted_fails_the_graded_circle(monkeypatch):
    """Mutant C4: the graded calibration r(k) multiplies Eq. 42's sigma_c instead of dividing it:
    F_A x r^2 = +13.8 % at k = 0.5.  Caught by: the Griffith BEM's pull-off check against Eq. 39
    on the graded circle (a calibration residual: it must fail when the calibration is misapplied)."""
    import bem_griffith.problem as problem
    from bem_griffith.criterion import calibration

    sc = SUITE["graded_circle_k0.5"]
    ok = _checks(sc, {"bem_griffith": _griffith(sc, 32)})[("bem_griffith", "pulloff_force")]
    assert ok.passed and ok.role == "calibration"
    monkeypatch.setattr(problem, "stress_factor", lambda k, criterion: calibration(k)[0])
    bad = _checks(sc, {"bem_griffith": _griffith(sc, 32)})[("bem_griffith", "pulloff_force")]
    assert bad.value / ok.value == pytest.approx(calibration(0.5)[0] ** 2, rel=1e-6)
    assert not bad.passed


def test_fem_scaled_by_the_effective_modulus_fails_kendalls_stiffness(monkeypatch):
    """Mutant M3: the FEM scales its unit solution by E* where Young's E belongs (its
    dimensionless problem already carries nu): K x 1/(1 - nu^2) = +9.9 % at nu = 0.3.
    Caught by: the FEM's stiffness check against Eq. 1 (its bar is a bound of about 1e-5)."""
    import fem_reference.solver as fs

    sc = SUITE["kendall_circle"]
    settings = fs.FemSettings(grading=2.0, order=3)
    ok = _checks(sc, {"fem_reference": fs.solve(sc, settings)})
    assert all(c.passed for c in ok.values()) and ("fem_reference", "stiffness") in ok
    material = fs._material

    def with_effective_modulus(scene):
        mat, _ = material(scene)
        return mat, scene.material.effective_modulus

    monkeypatch.setattr(fs, "_material", with_effective_modulus)
    bad = _checks(sc, {"fem_reference": fs.solve(sc, settings)})
    assert bad[("fem_reference", "stiffness")].difference == pytest.approx(1 / (1 - 0.3**2) - 1, abs=1e-3)
    assert not bad[("fem_reference", "stiffness")].passed
    assert not bad[("fem_reference", "pulloff_force")].passed


def test_paraboloid_of_half_the_radius_fails_the_jkr_pulloff(monkeypatch):
    """Mutant P1: the paraboloid's height r^2 / R where r^2 / (2 R) belongs (a sphere of half the
    radius): the JKR pull-off 1.5 pi w R halves.  Caught by: the Griffith BEM's pull-off check
    against JKR on the suite's sphere (bar 2.5/N)."""
    sc = SUITE["jkr_sphere"]
    ok = _checks(sc, {"bem_griffith": _griffith(sc, 16)})[("bem_griffith", "pulloff_force")]
    assert ok.passed
    monkeypatch.setattr(
        cs.Paraboloid, "height", lambda self, x, y: ((x - self.apex[0]) ** 2 + (y - self.apex[1]) ** 2) / self.radius
    )
    bad = _checks(sc, {"bem_griffith": _griffith(sc, 16)})[("bem_griffith", "pulloff_force")]
    assert bad.value / ok.value == pytest.approx(0.5, abs=0.05)
    assert not bad.passed


def _mutated_module(monkeypatch, path: str, package: str, old: str, new: str, count: int = 1) -> dict:
    """The namespace of ``path`` executed with ``old`` replaced by ``new`` (the mutation study's
    text substitution, in memory; ``old`` must occur ``count`` times), registered as a module
    while the test runs."""
    import sys
    import types
    from pathlib import Path

    import contact_scene

    src = (Path(contact_scene.__file__).parents[1] / path).read_text()
    assert src.count(old) == count
    mod = types.ModuleType(f"{package}._mutant")
    mod.__package__ = package
    monkeypatch.setitem(sys.modules, mod.__name__, mod)
    exec(compile(src.replace(old, new), path, "exec"), mod.__dict__)
    return mod.__dict__


@pytest.mark.parametrize("scene", ["kendall_circle", "triangle"])
def test_raster_shifted_by_half_a_cell_fails_the_raster_checks(monkeypatch, scene):
    """Mutant R1: cell centres at the nodes (corners taken for centres).  The face is still a
    staircase of the right area, so the forces move within the Griffith BEM's bar (the circle's
    pull-off by -2.9 % at 32 per radius, 0.7 % from Kendall); but the raster is no longer
    equivariant under a quarter turn, which is exact for the correct rule.
    Caught by: the raster checks of every grid result (crossval.compare.raster_checks)."""
    sc = SUITE[scene]
    r = _griffith(sc, 16)
    exact = [c for c in check_results(sc, {"bem_griffith": r}) if c.kind == "exact"]
    assert {c.quantity for c in exact} == {"raster mirror", "raster rotation 90"}
    assert all(c.passed for c in exact)
    ns = _mutated_module(
        monkeypatch,
        "contact_scene/raster.py",
        "contact_scene",
        "x = cx + (i0 + 0.5 + np.arange(nx)) * spacing",
        "x = cx + (i0 + np.arange(nx)) * spacing",
    )
    monkeypatch.setattr(cs, "rasterise", ns["rasterise"])
    failed = [c.quantity for c in check_results(sc, {"bem_griffith": r}) if c.kind == "exact" and not c.passed]
    # centres on whole multiples of h in x and half multiples in y: the mirror x -> -x still maps
    # the centres onto themselves, the quarter turn (x <-> y) does not
    assert "raster rotation 90" in failed


def test_a_rate_bracket_without_the_smooth_edge_fails_kendalls_bracket():
    """Mutant Z1: the zero-range tail's rate bracket (1, 1.5) instead of (0.5, 1.5), i.e.
    without the sqrt(l_c) tail of a smooth edge.  The estimate (the larger distance from F0 to
    the two limits) hardly changes, because the fitted F0 lies beyond both; but the limits
    the finest step then allows exclude Kendall's force, which the correct bracket contains.
    Caught by: the check that the closed form lies in the energy BEM's bracket."""
    import dataclasses

    import bem_energy as be
    from bem_energy.zero_range import tail_bracket

    sc = SUITE["kendall_circle"]
    r = be.solve_with_resolution(sc, 1.0)  # the quick report's coarse sequence
    assert r.converged and r.error_bars["pulloff_force"].interval is not None
    ok = {c.quantity: c for c in check_results(sc, {"bem_energy": r}) if c.method == "bem_energy"}
    assert ok["pulloff_force bracket"].passed and ok["pulloff_force"].passed
    seq = r.info["zero_range"]
    lcs = np.array(seq["process_zone_ratios"]) * sc.indenter.shape.radius
    bracket = tail_bracket(lcs, np.array(seq["pulloff_forces"]), rates=(1.0, 1.5))
    est = max(abs(r.pulloff_force - b) for b in bracket) / r.pulloff_force
    force = r.error_bars["pulloff_force"]
    bars = {**r.error_bars, "pulloff_force": dataclasses.replace(force, relative=est, interval=tuple(sorted(bracket)))}
    bad = {
        c.quantity: c
        for c in check_results(sc, {"bem_energy": dataclasses.replace(r, error_bars=bars)})
        if c.method == "bem_energy"
    }
    assert bad["pulloff_force"].passed  # the symmetric bar alone does not see it
    assert not bad["pulloff_force bracket"].passed


def test_effective_modulus_over_one_minus_nu_fails_the_fem_against_kendall(monkeypatch):
    """Mutant M1: E* = E / (1 - nu) instead of E / (1 - nu^2), everywhere at once: both BEMs
    and every closed form move together, so only a method that reads E and nu itself can tell.
    The FEM does (its body is E, nu): at nu = 0.3 Kendall's stiffness moves by +30 %.
    Caught by: the FEM's checks against Eqs. 1 and 6."""
    import fem_reference as fr

    sc = SUITE["kendall_circle"]
    r = fr.solve(sc, fr.FemSettings(grading=2.0, order=3))
    ok = _checks(sc, {"fem_reference": r})
    assert ok[("fem_reference", "stiffness")].passed and ok[("fem_reference", "pulloff_force")].passed
    monkeypatch.setattr(
        cs.Homogeneous, "effective_modulus", property(lambda self: self.youngs_modulus / (1.0 - self.poisson_ratio))
    )
    bad = _checks(sc, {"fem_reference": r})
    assert bad[("fem_reference", "stiffness")].difference == pytest.approx(0.7 / 0.91 - 1, abs=1e-3)
    assert not bad[("fem_reference", "stiffness")].passed
    assert not bad[("fem_reference", "pulloff_force")].passed


def test_kendalls_force_with_2_pi_fails_the_griffith_pulloff(monkeypatch):
    """Mutant T1: Eq. 6 as sqrt(2 pi E* w a^3), the closed form halved.
    Caught by: the Griffith BEM's pull-off check against Kendall."""
    sc = SUITE["kendall_circle"]
    r = _griffith(sc, 16)
    assert _checks(sc, {"bem_griffith": r})[("bem_griffith", "pulloff_force")].passed
    monkeypatch.setattr(
        T, "kendall_adhesion_force", lambda *, E_star, radius, work: math.sqrt(2 * math.pi * E_star * work * radius**3)
    )
    bad = _checks(sc, {"bem_griffith": r})[("bem_griffith", "pulloff_force")]
    assert bad.difference == pytest.approx(1.0, abs=0.05) and not bad.passed


def test_fem_stiffness_without_the_radius_fails_the_radius_2_circle(monkeypatch):
    """Mutant F5: the FEM's K = E K^ instead of E a K^ (right for a = 1 only).  The suite's
    incompressible circle has a = 2, so its stiffness halves.
    Caught by: the FEM's stiffness check against Eq. 1 on that scene."""
    import fem_reference.solver as fs

    sc = SUITE["incompressible_circle"]
    settings = fs.FemSettings(grading=2.0, order=3)
    assert _checks(sc, {"fem_reference": fs.solve(sc, settings)})[("fem_reference", "stiffness")].passed
    ns = _mutated_module(
        monkeypatch,
        "fem_reference/solver.py",
        "fem_reference",
        "K = modulus_scale * a * u.stiffness",
        "K = modulus_scale * u.stiffness",
    )
    # the mutated module defines its own FemSettings, which its solve checks for
    mutated_settings = ns["FemSettings"](grading=2.0, order=3)
    bad = _checks(sc, {"fem_reference": ns["solve"](sc, mutated_settings)})[("fem_reference", "stiffness")]
    assert bad.difference == pytest.approx(-0.5, abs=1e-3) and not bad.passed


def test_the_pulloff_read_as_the_largest_absolute_force_fails_the_jkr_sphere(monkeypatch):
    """Mutant S1: the Griffith BEM's pull-off as the largest abs(F) of the curve, compressive or
    tensile.  The suite's sphere is pressed before it is pulled, harder than it adheres.
    Caught by: the pull-off check against JKR (1.5 pi w R)."""
    import bem_griffith.solver as gs

    sc = SUITE["jkr_sphere"]
    assert _checks(sc, {"bem_griffith": _griffith(sc, 16)})[("bem_griffith", "pulloff_force")].passed
    ns = _mutated_module(
        monkeypatch,
        "bem_griffith/result.py",
        "bem_griffith",
        "tensile = -curve.force\n    peak = recorder.peak()",
        "tensile = abs(curve.force)\n    peak = int(tensile.argmax())",
    )
    monkeypatch.setattr(gs, "assemble_result", ns["assemble_result"])
    bad = _checks(sc, {"bem_griffith": _griffith(sc, 16)})[("bem_griffith", "pulloff_force")]
    # the press's peak compression, not a crash of the mutated module
    assert bad.difference > 0.5 and not bad.passed


def test_a_potential_of_half_the_work_fails_the_energy_pulloff(monkeypatch):
    """Mutant E1: the adhesive potential's depth w / 2 (surface energy taken for the work of
    adhesion w = 2 gamma), in its energy, stress and curvature alike: the zero-range pull-off
    falls by about sqrt(2), to 0.67 of itself on the quick report's coarse sequence (whose
    ranges are still sized for w, so each process zone is twice as long).  Caught by: the
    energy BEM's pull-off check against Kendall."""
    import bem_energy as be

    sc = SUITE["kendall_circle"]
    ok = _checks(sc, {"bem_energy": be.solve_with_resolution(sc, 1.0)})[("bem_energy", "pulloff_force")]
    assert ok.passed
    ns = _mutated_module(
        monkeypatch,
        "bem_energy/potentials.py",
        "bem_energy",
        "w, r = self.work, self.range",
        "w, r = 0.5 * self.work, self.range",
        count=4,
    )
    for name in ("energy", "evaluate", "stress", "curvature"):
        monkeypatch.setattr(be.Potential, name, ns["Potential"].__dict__[name])
    bad = _checks(sc, {"bem_energy": be.solve_with_resolution(sc, 1.0)})[("bem_energy", "pulloff_force")]
    assert bad.value < 0.75 * ok.value and not bad.passed
