"""The stress-intensity detachment criterion of the Griffith BEM (``bem_griffith.stress_intensity``):
the fit is exact on the fields it is built for, Kendall's circle follows from its own stiffness,
a 90-degree rotation of the grid changes nothing, and what it cannot do is refused.  The rotation
and the refusals shared with the energy-release criterion are checked here for both
(the rest of that criterion: tests/test_energy_release_rule.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import ndimage

import bem_griffith as bg
import contact_scene as cs
from bem_griffith import stress_intensity as si
from contact_scene import SceneError, theory as T

KENDALL = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))

#: |F_A / F_Kendall(a_H) - 1| on the circle, a_H the Holm radius of the solve's own stiffness
#: (Eqs. 6, 15-17), is the fit's own bias: 0.06-0.12 % at 32-64 elements per radius with the
#: default window, 0.03-0.06 % at 128-512 (benchmarks/study_griffith_criterion.py,
#: docs/griffith_criterion.json); the paper's criterion sits at +0.7 to +1.1 % at 24-64 and
#: wanders from +0.13 % (128) to -0.14 % (256).
HOLM_TOLERANCE = 2e-3


def si_settings(N, **kw):
    return bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), criterion="stress_intensity", **kw)


def disc_contact(radius_cells: float, centre=(0.31, -0.17), size=None):
    n = size or int(2 * radius_cells + 8)
    i, j = np.mgrid[0:n, 0:n].astype(float)
    x, y = i - n / 2 + centre[0], j - n / 2 + centre[1]
    return x, y, x * x + y * y < radius_cells**2


# -- the fit on analytic fields ---------------------------------------------------------------


@pytest.mark.parametrize("radius_cells", [30.0, 45.5])
def test_fit_is_exact_for_the_flat_circle_pressure(radius_cells):
    """p = C / sqrt(a^2 - r^2) (the flat circular punch) has q = p^-2 quadratic in (x, y), so
    every front cell's fitted K is C sqrt(pi / a) to round-off, for a continuum edge a that
    is off the cell centres by a fraction of a cell."""
    spacing, C = 0.01, 2.5
    x, y, contact = disc_contact(radius_cells)
    edge = math.sqrt((x[contact] ** 2 + y[contact] ** 2).max()) + 0.37  # continuum front, cells
    x1 = C / np.sqrt((edge * spacing) ** 2 - (x[contact] ** 2 + y[contact] ** 2) * spacing**2)
    fit = si.fit_front(contact, x1, spacing, si.window_depths(radius_cells))
    front = contact & ~ndimage.binary_erosion(contact, ndimage.generate_binary_structure(2, 1))
    assert fit.cells.size == np.count_nonzero(front)  # every front cell has a fit
    exact = C * math.sqrt(math.pi / (edge * spacing))
    assert np.max(np.abs(fit.intensity_per_approach / exact - 1)) < 1e-8
    # the fitted front is the continuum edge: 0.37 cells beyond the outermost cell centre
    assert np.all(fit.front_offset < 1.5) and np.all(fit.front_offset > 0.3)


def test_fit_follows_the_varying_intensity_of_an_elliptical_front():
    """The elliptical punch's p ~ (1 - x^2/a^2 - y^2/b^2)^(-1/2) gives q quadratic in (x, y);
    K at a front point is p0 sqrt(2 pi / |grad g|), g = x^2/a^2 + y^2/b^2, which varies by a
    factor a/b around the front.  The fit projects each front cell onto the fitted front,
    which lies within (half a cell)^2 times the curvature of the nearest front point."""
    spacing, p0, a, b = 1.0, 1.0, 60.3, 30.2
    n = 140
    i, j = np.mgrid[0:n, 0:n].astype(float)
    x, y = i - n / 2 + 0.2, j - n / 2 - 0.1
    g = x**2 / a**2 + y**2 / b**2
    contact = g < 1
    x1 = p0 / np.sqrt(1 - g[contact])
    fit = si.fit_front(contact, x1, spacing, (8.0, 24.0, 24.0))
    front = contact & ~ndimage.binary_erosion(contact, ndimage.generate_binary_structure(2, 1))
    assert fit.cells.size == np.count_nonzero(front)  # every front cell has a fit
    xs, ys = x[contact][fit.cells], y[contact][fit.cells]
    # nearest point of the ellipse to each front cell centre, by dense sampling
    t = np.linspace(0, 2 * np.pi, 200001)
    ex, ey = a * np.cos(t), b * np.sin(t)
    nearest = np.array([np.argmin((ex - u) ** 2 + (ey - v) ** 2) for u, v in zip(xs, ys, strict=True)])
    gradient = 2 * np.hypot(ex[nearest] / a**2, ey[nearest] / b**2)
    exact = p0 * np.sqrt(2 * np.pi / gradient)
    assert exact.max() / exact.min() > 1.3  # the test sees K vary along the front
    # 1.1e-4 seen; the gradient taken at the cell centre instead of the fitted front is off by
    # about (offset / 2) / b ~ 1 %
    assert np.max(np.abs(fit.intensity_per_approach / exact - 1)) < 1e-3


# -- the solver with the criterion -------------------------------------------------------------


def holm_error(result):
    a_holm = T.holm_radius(stiffness=result.stiffness, E_star=1.0)
    return result.pulloff_force / T.kendall_adhesion_force(E_star=1.0, radius=a_holm, work=1.0) - 1


@pytest.mark.parametrize("N", [32, 48])
def test_kendall_circle_follows_from_its_own_stiffness(N):
    """A circle detaches where K = sqrt(2 E* w) (G = w), so its pull-off is Kendall's force
    of the radius that its discrete stiffness implies (Holm radius, Eqs. 6 and 15-17): the
    grid's stiffness error (-0.12/N in the radius) is the solver's, not the criterion's.  The
    paper's criterion misses this by +0.7 to +1.1 % at the same grids; the tolerance is the
    fit's bias over 32-64 elements per radius (HOLM_TOLERANCE)."""
    result = bg.solve(KENDALL, si_settings(N))
    assert result.converged and result.detached
    assert abs(holm_error(result)) < HOLM_TOLERANCE


#: the scaled Kendall error e(N) = F_A(A / A_face)^(3/4) / F_Kendall - 1 (theory.force_at_nominal_area) of
#: the stress-intensity criterion at 128 and 256 elements per radius: -0.191 % and -0.101 %, so
#: e = E0 + C / N with E0 = -0.011 %, C = -23.0 % (benchmarks/study_griffith_criterion.py).  The
#: coarser grids stay within 0.035 % (64) and 0.13 % (32) of that line.
KENDALL_FIRST_ORDER = (-0.011e-2, -23.04e-2)


def test_kendall_circle_error_follows_the_fine_grids_first_order_line():
    """On 64 elements per radius Kendall's force is met within 0.1 % of the first-order line
    fitted on the 128 and 256 grids (the 64 grid is outside the fit: it sits 0.035 % off);
    the paper's criterion is +0.55 % there, 0.9 % off the line."""
    N = 64
    result = bg.solve(KENDALL, si_settings(N))
    scaled = T.force_at_nominal_area(result.pulloff_force, area=result.face_area, nominal_area=math.pi)
    error = scaled / T.kendall_adhesion_force(E_star=1.0, radius=1.0, work=1.0) - 1
    limit, slope = KENDALL_FIRST_ORDER
    assert error == pytest.approx(limit + slope / N, abs=1e-3)


def test_a_two_percent_wrong_threshold_fails_the_kendall_check(monkeypatch):
    """Mutant: K_c = 1.02 sqrt(2 E* w).  The pull-off moves by 2 %, ten times the tolerance."""
    original = si.StressIntensityRule.__init__

    def wrong(self, **kw):
        original(self, **kw)
        self.critical_intensity *= 1.02

    monkeypatch.setattr(si.StressIntensityRule, "__init__", wrong)
    result = bg.solve(KENDALL, si_settings(32))
    assert abs(holm_error(result)) > 5 * HOLM_TOLERANCE


def test_paper_criterion_is_the_default_and_misses_the_holm_check():
    """The default stays the paper's Eq. 22 (whose bias the new criterion removes)."""
    assert bg.GriffithSettings().criterion == "paper"
    result = bg.solve(KENDALL, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=32)))
    assert holm_error(result) > 3 * HOLM_TOLERANCE


@pytest.mark.parametrize(("criterion", "N"), [("stress_intensity", 32), ("energy_release", 24)])
def test_rotation_by_ninety_degrees_changes_nothing(criterion, N):
    """An off-centre ellipse and its copy rotated by 90 degrees about the origin rasterise to
    rotated masks, and either criterion is covariant under the rotation (the fit's disc windows,
    distance transform and quadratic in (x, y); the energy release's 8-connected stretches and
    4-neighbour layers): same pull-off, approach, stiffness and contact sets up to FFT round-off,
    although the windows and layers see the grid from another side."""
    centre = (0.013, 0.007)
    shapes = [
        cs.Ellipse(1.0, 0.6, center=centre),
        cs.Ellipse(1.0, 0.6, rotation_deg=90.0, center=(-centre[1], centre[0])),
    ]
    masks = [cs.rasterise(s, s.equivalent_radius / N).mask for s in shapes]
    assert np.array_equal(np.rot90(masks[0]), masks[1])
    settings = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), criterion=criterion)
    results = [
        bg.solve(cs.Scene(cs.Indenter(s), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0)), settings) for s in shapes
    ]
    assert results[0].stats.linear_solves == results[1].stats.linear_solves
    assert np.array_equal(np.rot90(results[0].last_stable.contact), results[1].last_stable.contact)
    for q in ("pulloff_force", "pulloff_approach", "stiffness"):
        assert getattr(results[1], q) == pytest.approx(getattr(results[0], q), rel=1e-9)


# -- what it refuses ----------------------------------------------------------------------------


def test_unknown_criterion_is_refused():
    with pytest.raises(SceneError, match="settings.criterion"):
        bg.GriffithSettings(criterion="griffith")


@pytest.mark.parametrize("criterion", ["stress_intensity", "energy_release"])
def test_periodic_grid_is_refused(criterion):
    with pytest.raises(SceneError, match=f"settings.criterion.*{criterion}"):
        bg.GriffithSettings(grid=cs.Grid(elements_per_radius=8, periodic=True, period=4.0), criterion=criterion)


def test_graded_body_is_refused_with_the_reason():
    scene = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.PowerLawGraded(1.0, 1.0, 0.5), cs.Adhesion(1.0))
    with pytest.raises(SceneError, match="settings.criterion.*G-K"):
        bg.solve(scene, si_settings(8))


@pytest.mark.parametrize("criterion", ["stress_intensity", "energy_release"])
def test_curved_profile_is_refused(criterion):
    scene = cs.Scene(
        cs.Indenter(cs.Circle(1.0), cs.Paraboloid(5.0)),
        cs.Homogeneous(1.0, 0.5),
        cs.Adhesion(1.0),
        cs.Loading(press_approach=0.05),
    )
    with pytest.raises(SceneError, match="settings.criterion.*flat"):
        bg.solve(scene, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=8), criterion=criterion))


def test_a_grid_too_coarse_for_the_fit_says_the_result_is_eq22s():
    # at 8 per radius no front cell has the window's 8 .. 24 cells behind it: every decision falls
    # back to Eq. 22, and the result must say so rather than pass for the other criterion
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    coarse = bg.solve(sc, si_settings(8))
    paper = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=8)))
    assert coarse.pulloff_force == paper.pulloff_force
    assert any("found no front cell it could fit" in m for m in coarse.messages)
    fitted = bg.solve(sc, si_settings(32))
    assert fitted.pulloff_force != paper.pulloff_force
    assert not any("found no front cell" in m for m in fitted.messages)
