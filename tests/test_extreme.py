"""Stiff and extreme cases: finite, converged (or saying why not), never NaN."""

import dataclasses
import math

import numpy as np
import pytest

import bem_griffith as bg
import contact_scene as cs
import fem_reference as fr
from contact_scene import theory as T


def circle(material, work=1.0, **kw):
    return cs.Scene(cs.Indenter(cs.Circle(1.0)), material, cs.Adhesion(work), **kw)


@pytest.mark.parametrize("nu", [0.49, 0.499, 0.4999, 0.5])
def test_fem_does_not_lock_as_nu_tends_to_half(nu):
    # displacement-only linear elements lock here; the mixed form stays on Kendall (Eqs. 1, 6, 4)
    mat = cs.Homogeneous(1.0, nu)
    r = fr.solve(circle(mat), fr.FemSettings(grading=2.0))
    E = mat.effective_modulus
    assert r.stiffness == pytest.approx(T.kendall_stiffness(E_star=E, radius=1.0), rel=1e-4)
    assert r.pulloff_force == pytest.approx(T.kendall_adhesion_force(E_star=E, radius=1.0, work=1.0), rel=1e-4)
    assert r.pulloff_approach == pytest.approx(T.kendall_critical_approach(E_star=E, radius=1.0, work=1.0), rel=1e-4)


@pytest.mark.parametrize("k", [0.9, 0.95, -0.9, -0.95])
def test_graded_bem_near_the_limits_is_finite_and_stiffness_holds(k):
    mat = cs.PowerLawGraded(1.0, 1.0, k)
    st = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=16))
    r = bg.solve(circle(mat), st)  # inside the calibration, -0.95 <= k <= 0.95
    assert r.converged and np.all(np.isfinite(r.curve.force)) and r.pulloff_force > 0
    assert r.info["graded_criterion"] == "calibrated"
    # Eq. 34 to the first-order envelope of the stiffness sweep (0.15/N)
    assert r.stiffness == pytest.approx(T.graded_stiffness(E0=1.0, c0=1.0, k=k, radius=1.0), rel=0.15 / 16)
    e = bg.solve(circle(mat), dataclasses.replace(st, graded_criterion="eq42"))
    assert e.converged and any("not calibrated" in m for m in e.messages)
    with pytest.raises(cs.SceneError, match="settings.graded_criterion"):
        bg.solve(circle(cs.PowerLawGraded(1.0, 1.0, math.copysign(0.96, k))), st)  # outside it


def test_tiny_and_huge_work_of_adhesion_are_reported():
    E = cs.Homogeneous(0.75, 0.5)
    tiny = bg.solve(circle(E, work=1e-12), bg.GriffithSettings(grid=cs.Grid(elements_per_radius=16)))
    # F_A ~ sqrt(w): the same discretised factor as for w = 1
    unit = bg.solve(circle(E, work=1.0), bg.GriffithSettings(grid=cs.Grid(elements_per_radius=16)))
    assert tiny.detached and tiny.pulloff_force == pytest.approx(unit.pulloff_force * 1e-6, rel=1e-8)
    huge = bg.solve(
        circle(E, work=1e6, loading=cs.Loading(pull_limit=-10.0)),
        bg.GriffithSettings(grid=cs.Grid(elements_per_radius=16)),
    )
    assert not huge.detached and huge.converged
    assert any("still attached" in m for m in huge.messages)


@pytest.mark.parametrize("aspect", [10, 20])
def test_elongated_faces_keep_their_shape(aspect):
    # the last stable state is the rectangle with rounded corners, not the incircle (Figs. 10-11)
    sc = cs.Scene(cs.Indenter(cs.Rectangle(float(aspect), 1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    r = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(spacing=1 / 8)))
    assert r.converged and r.detached
    inc = math.pi * 0.5**2
    assert r.last_stable.contact_area > 0.9 * aspect > 10 * inc


def test_one_element_features_and_coarse_faces():
    # a brush whose pillars span one to two elements still runs; a face below 4 cells is refused
    brush = cs.Brush(side=2.0, pillar_radius=0.06, pitch=0.3)
    sc = cs.Scene(cs.Indenter(brush), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    r = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(spacing=0.03)))
    assert r.converged and r.detached and np.all(np.isfinite(r.curve.force))
    with pytest.raises(cs.SceneError, match="too coarse"):
        bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(spacing=0.04)))


def test_memory_is_estimated_before_allocation():
    sc = circle(cs.Homogeneous(0.75, 0.5))
    with pytest.raises(cs.SceneError, match="needs about .* GB"):
        bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=512), max_memory_gb=0.05))


def test_identical_runs_are_bit_identical_and_units_scale_to_1e10():
    tri = cs.Scene(cs.Indenter(cs.Triangle.equilateral(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    st = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=16), rtol=1e-13)
    a, b = bg.solve(tri, st), bg.solve(tri, st)
    assert np.array_equal(a.curve.force, b.curve.force) and np.array_equal(a.curve.approach, b.curve.approach)
    L, E, w = 0.03, 6020.0, 0.062  # the paper's triangle (Fig. 13), SI units
    si = cs.Scene(cs.Indenter(cs.Triangle.equilateral(L)), cs.Homogeneous(E * 0.75, 0.5), cs.Adhesion(w))
    c = bg.solve(si, st)
    assert c.pulloff_force / math.sqrt(E * w * L**3) == pytest.approx(a.pulloff_force, rel=1e-10)
    assert c.pulloff_approach / math.sqrt(w * L / E) == pytest.approx(a.pulloff_approach, rel=1e-10)


# -- the energy method --------------------------------------------------------------


def test_energy_method_extremes():
    import bem_energy as be

    st = be.EnergySettings(grid=cs.Grid(elements_per_radius=10))
    rho = math.sqrt(0.2 * 0.02)  # l_c = 0.2 a at E* = 1, w = 0.02
    base = circle(cs.Homogeneous(1.0, 0.0), 0.02)
    sc = cs.Scene(base.indenter, base.material, cs.Adhesion(0.02, rho))
    r1, r2 = be.solve(sc, st), be.solve(sc, st)
    # bit-identical repeated runs (single-threaded BLAS inside the minimisers)
    assert r1.pulloff_force == r2.pulloff_force and np.array_equal(r1.curve.force, r2.curve.force)
    # nu -> 1/2 enters only through E*: equal E* gives the same numbers
    inc = cs.Scene(base.indenter, cs.Homogeneous(0.75, 0.5), cs.Adhesion(0.02, rho))
    assert be.solve(inc, st).pulloff_force == pytest.approx(r1.pulloff_force, rel=1e-12)
    # a pull limit short of the snap is reported as still attached, never silently
    held = cs.Scene(base.indenter, base.material, cs.Adhesion(0.02, rho), cs.Loading(pull_limit=-0.05))
    r = be.solve(held, st)
    assert not r.detached and any("still attached" in m for m in r.messages)
    # w = 1e-12 with its range scaled alike (same l_c): F_A scales exactly with sqrt(w), and a
    # far pull limit after the snap does not keep the solver stepping
    tiny = cs.Scene(base.indenter, base.material, cs.Adhesion(0.02e-12, rho * 1e-6), cs.Loading(pull_limit=-10.0))
    r = be.solve(tiny, st)
    assert r.detached and r.converged
    assert r.pulloff_force / 1e-6 == pytest.approx(r1.pulloff_force, rel=1e-9)
    # a graded body is outside the energy method's validated scope, said so by the registry
    from crossval.methods import METHODS

    assert "homogeneous" in METHODS["bem_energy"].applies(circle(cs.PowerLawGraded(1.0, 1.0, 0.5)))


def test_displacement_only_elements_lock_where_the_mixed_form_does_not():
    """The reason the reference is mixed: with lambda div u div v, linear elements stiffen by
    hundreds of percent as nu -> 1/2, quadratic ones by tens (the mixed form: test above)."""
    from fem_reference.locking import displacement_only_stiffness as K

    nus = (0.3, 0.49, 0.499, 0.4999)
    p1 = [K(nu, grading=0.5) - 1 for nu in nus]
    assert p1[0] < 0.05  # a compressible body: only mesh error
    assert all(b > a for a, b in zip(p1, p1[1:], strict=False))  # worse as nu -> 1/2 ...
    assert p1[-1] > 1.0  # ... beyond +100 % at nu = 0.4999
    p2 = K(0.4999, order=2, grading=0.5) - 1
    assert p1[-1] > 10 * p2 > 0
    with pytest.raises(cs.SceneError, match="poisson_ratio"):
        K(0.5)


def test_fem_near_k_one_is_finite_and_its_estimate_covers_the_error():
    # k = 0.95 maps depth by zeta^20; a round-off duplicate of the bottom row once made a
    # layer of zero-area elements and a failed factorisation
    k = 0.95
    r = fr.solve(circle(cs.PowerLawGraded(1.0, 1.0, k)), fr.FemSettings(grading=2.0))
    err = abs(r.stiffness / T.graded_stiffness(E0=1.0, c0=1.0, k=k, radius=1.0) - 1)
    assert r.converged and math.isfinite(r.pulloff_force) and err <= r.accuracy_estimate


def test_float32_preconditioner_does_not_change_the_answer():
    """The Griffith solver's float32 path (its Fourier preconditioner runs single-precision
    FFTs) against plain float64 CG: the same result to the CG tolerance (rtol 1e-10)."""
    sc = circle(cs.Homogeneous(0.75, 0.5))
    r32 = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=16), preconditioner="fourier"))
    r64 = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=16), preconditioner="none"))
    assert r32.pulloff_force == pytest.approx(r64.pulloff_force, rel=1e-8)
    assert r32.pulloff_approach == pytest.approx(r64.pulloff_approach, rel=1e-8)
    assert r32.info["events"] == r64.info["events"]
    assert r32.info["matvecs"] < r64.info["matvecs"]


def test_periodic_grid_is_refused_where_not_implemented():
    import bem_energy as be

    sc = circle(cs.Homogeneous(0.75, 0.5))
    grid = cs.Grid(elements_per_radius=8, periodic=True, period=4.0)
    with pytest.raises(cs.SceneError, match="grid.periodic"):
        be.solve(cs.Scene(sc.indenter, sc.material, cs.Adhesion(1.0, 0.3)), be.EnergySettings(grid=grid))
    with pytest.raises(cs.SceneError, match="grid.periodic"):
        bg.solve(circle(cs.PowerLawGraded(1.0, 1.0, 0.5)), bg.GriffithSettings(grid=grid))
    with pytest.raises(cs.SceneError, match="grid.period"):
        cs.Grid(elements_per_radius=8, periodic=True)
    with pytest.raises(cs.SceneError, match="grid.period"):
        cs.Grid(elements_per_radius=8, period=4.0)
    with pytest.raises(cs.SceneError, match="grid.periodic"):
        cs.Grid(elements_per_radius=8, periodic="yes", period=4.0)
    with pytest.raises(cs.SceneError, match="does not fit"):
        bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=8, periodic=True, period=2.0)))
