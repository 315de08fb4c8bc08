"""Detachment rules of the event driver: the paper's local criterion (Eq. 22) and a
stress-intensity criterion fitted to the pressure behind the front.

The paper's rule detaches an element whose tension reaches sigma_c = sqrt(E* w / (0.473201
Delta)) (Eq. 22).  Its constant is exact for an element on a straight edge of the grid, but
the most stressed cells of a staircase edge (a circle, a rotated side) meet it at a slightly
different load: on Kendall's circle the pull-off force stops converging at -0.2 to -0.3 %
beyond 128 elements per radius (theory sheet, section 6).

``"stress_intensity"`` asks the continuum question instead: does the energy release rate
G = K^2 / (2 E*) at the front reach w, i.e. K >= K_c = sqrt(2 E* w) (theory sheet, section
1)?  Near a smooth front the pressure is a K-field, p = K / sqrt(2 pi s) at distance s into
the contact, so q = p^-2 = 2 pi s / K^2 grows linearly from the front, with |grad q| =
2 pi / K^2 there.  For each front cell (a contact cell with a 4-neighbour outside the
contact set) q is fitted by a quadratic in the position (x, y) by least squares over the
contact cells within ``radius`` of it whose depth lies in [s_in, s_out]; the cell centre is
projected onto the fit's zero level (the fitted front, by Newton steps along the gradient)
and K = sqrt(2 pi / |grad q|) there.  The quadratic is exact for the flat circle
(q ~ a^2 - r^2) and the elliptical punch, whatever the staircase, and follows a smooth front
to second order elsewhere.  Taking the gradient at the cell centre instead of the fitted
front would bias K by about a quarter of a cell over the front's radius of curvature.  The
depth that selects the window is the Euclidean distance transform of the contact set; it
only decides which cells enter the fit.  The window stays away from the front, where the
discrete pressure departs from the K-field (fitting 3-8 cells from the front overshoots K by
up to a few per cent), and grows like N^(1/3) with the resolution N (elements per equivalent
radius), at least 8 cells deep, so that its physical size shrinks and the fit's bias falls
as the grid is refined.

The moments of every front cell's fit (sums of x^a y^b and q x^a y^b over its disc) are
gathered per front cell (one matrix product per image), once per contact solution.  A front
cell without a usable fit (too few window cells: narrow contacts, the last cells of a
cascade; an ill-posed fit; a fitted front more than s_in / 2 away) and every cell behind the
front fall back to Eq. 22.

What the fit does not resolve: a face with corners lets go at its corners first, and while a
detached corner region is smaller than about one window radius the window straddles the
corner's field, where q is not a smooth function of the position.  Against the energy release
of the free front computed by the solver itself (``free_front_release``, which needs no
window and meets Kendall's compliance formula on circles within 0.05 %), the fit
over-estimates K by 1-3 % on corners rounded with 0.35-0.8 window radii, and by up to 11 %
(2-4 % near the peak force) on the corner fronts that the criterion's own detachments
leave on the square and the triangle at 64 elements per radius; it agrees within 0.3 % on
circles and within 0.4 % on corner radii of 1.2 window radii and more.  The corners therefore
let go too early, and a detached cell comes back only when its gap closes, so the contact does
not recover: the square's and the triangle's pull-offs lie 1 % and 2 % below the energy BEM's
zero-range values.  Other fixed windows do not cure it: s_in = 5-6 keeps the square and the
triangle within 1 % of the default window's value, s_in = 4 at 128 per radius is 1.8 % lower,
and s_in = 12 raises the square by 1.6 % at 64 per radius but by 0.2 % at 128.  The paper's
criterion errs the other way (the released K of its fronts is 0.4-2.5 % above K_c along the
pull), which the contact survives.  ``benchmarks/study_griffith_criterion.py --diagnose`` and
``docs/griffith_criterion.json`` hold the measurements.

For a flat punch the pressure is p = d x1 on a fixed contact set, so q scales with d^-2
and K with |d|: the approach at which a front cell reaches K_c is exact, and the event
driver stays exact.  Curved profiles (K not linear in d) and graded bodies (whose G-K
relation has the graded modulus and the exponent's edge singularity) are refused.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from scipy import ndimage

from contact_scene import Homogeneous, Scene, SceneError

__all__ = [
    "DetachmentRule",
    "PaperRule",
    "pressure_roundoff",
    "StressIntensityRule",
    "FrontFit",
    "fit_front",
    "front_cells",
    "window_depths",
    "detachment_rule",
    "check_supported",
    "FrontRelease",
    "free_front_release",
]


#: round-off of a pressure p = d x1 - xh relative to its two parts |d x1| + |xh|: at its event a
#: cell's tension meets the threshold to a few ulps of them (a hundred, for margin)
PRESSURE_ROUNDOFF = 1e-14


def pressure_roundoff(approach: float, per_approach: np.ndarray, profile: np.ndarray | None = None) -> np.ndarray:
    """Per contact cell, how far its pressure p = d x1 - xh may lie from the exact value by
    forming it: ``PRESSURE_ROUNDOFF`` (|d x1| + |xh|).  The paper's rule detaches a cell whose
    tension lies within it below the threshold: without it, sigma_c = 0 (no adhesion) leaves an
    event's own cell a round-off short of zero tension, and the event repeats at the same approach.

    Parameters
    ----------
    approach : float
        The approach d.
    per_approach : numpy.ndarray
        x1 on the contact set.
    profile : numpy.ndarray or None, optional
        xh on the contact set (None on a flat face).

    Returns
    -------
    numpy.ndarray
        The round-off per contact cell, >= 0.
    """
    size = np.abs(approach * per_approach)
    if profile is not None:
        size = size + np.abs(profile)
    return PRESSURE_ROUNDOFF * size


class DetachmentRule(Protocol):
    """What the event driver asks of a detachment criterion on a contact solution."""

    def critical_approaches(self, solution) -> np.ndarray:
        """Per contact cell (row-major order of the set), the approach at which it meets the
        criterion, assuming the set stays fixed (nan where it never does)."""

    def detaching(self, solution, approach: float, tie_tolerance: float) -> np.ndarray:
        """Boolean mask over the contact cells that detach at ``approach``."""

    def report(self, pulloff_approach: float) -> tuple[list[str], dict]:
        """After the pull, given the approach of its largest tension: messages for the result
        (where the rule's own criterion could not act and left a decision to Eq. 22, each rule
        says when) and keys for ``Result.info``."""


@dataclass(frozen=True, eq=False)
class PaperRule:
    """Eq. 22: a contact cell detaches when its tension -p reaches sigma_c."""

    critical_stress: float

    def critical_approaches(self, solution) -> np.ndarray:
        per_approach, profile = solution.pressure_per_approach, solution.profile_pressure
        out = np.full(per_approach.shape, np.nan)
        loaded = per_approach != 0
        # tension -p = sigma_c  <=>  d = (xh - sigma_c) / x1
        out[loaded] = (profile[loaded] - self.critical_stress) / per_approach[loaded]
        return out

    def threshold(self, tie_tolerance: float) -> float:
        """The tension at or above which a cell detaches: sigma_c less the tie tolerance, so
        that cells within round-off of the largest tension go together.  :meth:`detaching`
        lowers it further, per cell, by the round-off of its pressure
        (:func:`pressure_roundoff`); this value does not include it."""
        return self.critical_stress * (1 - tie_tolerance)

    def detaching(self, solution, approach: float, tie_tolerance: float) -> np.ndarray:
        tension = -solution.pressure(approach)
        roundoff = pressure_roundoff(approach, solution.pressure_per_approach, solution.profile_pressure)
        return tension >= self.threshold(tie_tolerance) - roundoff

    def report(self, pulloff_approach: float) -> tuple[list[str], dict]:
        return [], {}


def front_cells(contact: np.ndarray) -> np.ndarray:
    """The front of a contact set: its cells with a 4-neighbour outside it (or off the grid)."""
    padded = np.pad(contact, 1)  # cells outside the grid are outside the contact set
    eroded = ndimage.binary_erosion(padded, structure=ndimage.generate_binary_structure(2, 1))[1:-1, 1:-1]
    return contact & ~eroded


def window_depths(elements_per_radius: float) -> tuple[float, float, float]:
    """(s_in, s_out, radius) of the fitting window in cells: s_in = max(8, 2 N^(1/3)) (8 at
    N = 64, 16 at N = 512), s_out = 3 s_in, and the neighbourhood radius s_out."""
    inner = max(8.0, 2.0 * elements_per_radius ** (1.0 / 3.0))
    return inner, 3.0 * inner, 3.0 * inner


@dataclass(frozen=True, eq=False)
class FrontFit:
    """The fitted stress-intensity factors of a contact set's front.

    cells
        Flat indices (into the contact set's row-major order) of the front cells with a usable fit.
    intensity_per_approach
        K / |d| at those cells (the pressure per unit approach x1 fitted), > 0.
    front_offset
        The fitted front s0 in cells of the distance transform (about 0.5 on a straight edge).
    """

    cells: np.ndarray
    intensity_per_approach: np.ndarray
    front_offset: np.ndarray


_EXPONENTS = [(a, b) for total in range(5) for a in range(total, -1, -1) for b in [total - a]]  # x^a y^b, degree <= 4
_QUADRATIC = _EXPONENTS[:6]  # 1, x, y, x^2, xy, y^2


class _Kernels:
    """The disc's offsets and their monomials (delta_x / R)^a (delta_y / R)^b: a front cell's
    moments are the window's images gathered over its disc times these monomials (one matrix
    product per image; the fronts are thin, so this is cheaper than correlating whole grids)."""

    CHUNK = 1024

    def __init__(self, radius: float):
        r = int(math.floor(radius))
        self.reach = r
        i, j = np.mgrid[-r : r + 1, -r : r + 1]
        inside = i * i + j * j <= radius * radius
        self.di, self.dj = i[inside], j[inside]
        self.monomials = np.stack([(self.di / radius) ** a * (self.dj / radius) ** b for a, b in _EXPONENTS], -1)
        self.radius = radius

    def gather(self, images, rows, cols, exponent_counts):
        """For each image, sum over each front cell's disc of image(x) * monomial(x - x_cell),
        for the first ``exponent_counts[n]`` monomials of ``_EXPONENTS``."""
        r = self.reach
        shape = images[0].shape
        padded = [np.pad(image, r).ravel() for image in images]
        stride = shape[1] + 2 * r
        offsets = self.di * stride + self.dj
        centres = (rows + r) * stride + (cols + r)
        out = [np.empty((len(rows), m)) for m in exponent_counts]
        for first in range(0, len(rows), self.CHUNK):
            idx = centres[first : first + self.CHUNK, None] + offsets[None, :]
            for n, (image, m) in enumerate(zip(padded, exponent_counts, strict=True)):
                out[n][first : first + self.CHUNK] = image[idx] @ self.monomials[:, :m]
        return out


def fit_front(
    contact: np.ndarray,
    pressure_per_approach: np.ndarray,
    spacing: float,
    depths: tuple[float, float, float],
    kernels: _Kernels | None = None,
    min_cells: int = 24,
) -> FrontFit:
    """Fit q = x1^-2 by a quadratic in the position (x, y) over each front cell's window
    (module doc), project the cell centre onto the fit's zero level (the fitted front) and
    return K / |d| = sqrt(2 pi / |grad q|) there where the fit is usable: enough window
    cells, a well-posed fit and a fitted front within s_in / 2 of the cell."""
    inner, outer, radius = depths
    kernels = kernels if kernels is not None else _Kernels(radius)
    padded = np.pad(contact, 1)  # cells outside the grid are outside the contact set
    depth = ndimage.distance_transform_edt(padded)[1:-1, 1:-1]
    x1 = np.zeros(contact.shape)
    x1[contact] = pressure_per_approach
    in_window = contact & (depth >= inner) & (depth <= outer) & (x1 > 0)
    front = front_cells(contact)
    front_idx = np.flatnonzero(front[contact])
    empty = FrontFit(np.zeros(0, int), np.zeros(0), np.zeros(0))
    if not in_window.any() or front_idx.size == 0:
        return empty
    q = np.zeros(contact.shape)
    q[in_window] = x1[in_window] ** -2
    q_scale = float(np.median(q[in_window]))
    q /= q_scale
    weight = in_window.astype(float)
    rows, cols = np.nonzero(front)
    # sums of w x^a y^b (degree <= 4) and q x^a y^b (degree <= 2) over each front cell's disc
    moments, targets = kernels.gather([weight, q], rows, cols, (len(_EXPONENTS), len(_QUADRATIC)))
    index = {ab: n for n, ab in enumerate(_EXPONENTS)}
    normal = np.empty((len(rows), 6, 6))
    for m, (a, b) in enumerate(_QUADRATIC):
        for n, (c, e) in enumerate(_QUADRATIC):
            normal[:, m, n] = moments[:, index[(a + c, b + e)]]
    count = np.rint(moments[:, 0])
    usable = count >= min_cells
    scale = np.maximum(np.abs(normal).max(axis=(1, 2)), 1e-300)
    usable &= np.linalg.cond(normal / scale[:, None, None]) < 1e10
    if not usable.any():
        return empty
    coef = np.zeros((len(rows), 6))
    coef[usable] = np.linalg.solve(normal[usable], targets[usable][..., None])[..., 0]
    c0, cx, cy, cxx, cxy, cyy = coef.T

    def value_and_gradient(x, y):
        value = c0 + cx * x + cy * y + cxx * x * x + cxy * x * y + cyy * y * y
        return value, cx + 2 * cxx * x + cxy * y, cy + cxy * x + 2 * cyy * y

    # Newton projection of the cell centre (0, 0) onto the zero level, in units of R
    x = np.zeros(len(rows))
    y = np.zeros(len(rows))
    for _ in range(8):
        value, gx, gy = value_and_gradient(x, y)
        g2 = np.where(usable, gx * gx + gy * gy, 1.0)
        g2 = np.where(g2 > 0, g2, 1.0)
        x, y = x - value * gx / g2, y - value * gy / g2
    value, gx, gy = value_and_gradient(x, y)
    gradient = np.hypot(gx, gy)
    offset = np.hypot(x, y) * radius  # cells from the front cell's centre
    usable &= np.isfinite(offset) & (offset <= 0.5 * inner) & (gradient > 0)
    usable &= np.abs(value) <= 1e-8 * np.maximum(np.abs(c0), 1.0) + 1e-10
    # |grad q| in physical units: q_scale * gradient per (R cells)
    slope = q_scale * np.where(usable, gradient, 1.0) / (radius * spacing)
    intensity = np.sqrt(2 * math.pi / slope)
    return FrontFit(front_idx[usable], intensity[usable], offset[usable])


class StressIntensityRule:
    """K >= sqrt(2 E* w) at the fitted front cells, Eq. 22 elsewhere (module doc).  Caches the
    fit of the last contact solution it saw (the driver asks for the next event and then
    cascades on the same solution)."""

    def __init__(
        self,
        *,
        critical_stress: float,
        effective_modulus: float,
        work_of_adhesion: float,
        spacing: float,
        depths: tuple[float, float, float],
    ):
        self.paper = PaperRule(critical_stress)
        self.critical_intensity = math.sqrt(2.0 * effective_modulus * work_of_adhesion)
        self.spacing = spacing
        self.depths = depths
        self._last: tuple[object, FrontFit] | None = None
        self._kernels = _Kernels(depths[2])
        self.fits = 0
        #: fits that found at least one usable front cell (none: every decision was Eq. 22's)
        self.usable_fits = 0

    def front(self, solution) -> FrontFit:
        if self._last is None or self._last[0] is not solution:
            self.fits += 1
            fit = fit_front(solution.contact, solution.pressure_per_approach, self.spacing, self.depths, self._kernels)
            self.usable_fits += bool(len(fit.cells))
            self._last = (solution, fit)
        return self._last[1]

    def critical_approaches(self, solution) -> np.ndarray:
        out = self.paper.critical_approaches(solution)
        fit = self.front(solution)
        # K = -d k  (d < 0 pulls)  reaches K_c at d = -K_c / k
        out[fit.cells] = -self.critical_intensity / fit.intensity_per_approach
        return out

    def detaching(self, solution, approach: float, tie_tolerance: float) -> np.ndarray:
        fit = self.front(solution)
        by_paper = self.paper.detaching(solution, approach, tie_tolerance)
        by_paper[fit.cells] = False
        measure = np.full(solution.pressure_per_approach.shape, -np.inf)
        measure[by_paper] = np.inf
        if approach < 0:
            measure[fit.cells] = -approach * fit.intensity_per_approach / self.critical_intensity
        # everything at or above the criterion, ties with the largest included
        largest = measure.max() if measure.size else -np.inf
        if largest < 1 - tie_tolerance:
            return np.zeros(measure.shape, bool)
        return measure >= 1 - tie_tolerance

    def report(self, pulloff_approach: float) -> tuple[list[str], dict]:
        if not self.fits or self.usable_fits:
            return [], {}
        # the fit needs contact cells s_in .. 3 s_in behind the front: on a grid too coarse for
        # that window every cell falls back to Eq. 22, and the result is the paper criterion's
        return [
            f"criterion 'stress_intensity' found no front cell it could fit (its window reaches "
            f"{self.depths[1]:g} cells behind the front): every detachment followed Eq. 22; refine the grid"
        ], {}


@dataclass(frozen=True, eq=False)
class FrontRelease:
    """The energy released by the free part of a contact set's front, from the solver itself.

    cells
        Flat indices (row-major order of the contact set) of the free-front cells: contact
        cells with a 4-neighbour on the face outside the contact set (detached cells, as
        opposed to the face's own edge).
    ahead
        How many detached face cells touch the contact set (the layer a re-advance would add).
    release_per_approach_squared
        G / d^2 averaged over that front: (S(S + ahead) - S(S - cells)) / (2 * area of both
        layers), S the stiffness sum(x1) Delta^2 of a set held at fixed approach.
    peel_over_add
        The one-sided releases' ratio, (S(S) - S(S - cells)) / cells over (S(S + ahead) -
        S(S)) / ahead: 1 plus the second-order term the central difference cancels.
    intensity_per_approach
        sqrt(2 E* G) / |d|, comparable with ``FrontFit.intensity_per_approach``.
    """

    cells: np.ndarray
    ahead: int
    release_per_approach_squared: float
    peel_over_add: float
    intensity_per_approach: float


def free_front_release(problem, contact: np.ndarray, settings, counters=None, solution=None) -> FrontRelease | None:
    """The mean energy release rate of the free front of ``contact`` (a flat punch at fixed
    approach d: U_el = d^2 S / 2), by a central difference: one layer of front cells peeled
    and one layer of detached face cells added, each set re-solved.  Exact for the discrete
    model up to the second-order term that the two sides cancel, so it checks the fitted K
    without the fit's window: on circular fronts of 20-90 cells' radius the two agree within
    0.1-0.3 % (the difference falls like 1/radius), on corner cuts they need not
    (``benchmarks/study_griffith_criterion.py --diagnose``).  None when there is no free
    front or nothing to add.  Costs two contact solves (``counters`` counts them)."""
    from .contact_set import solve_contact_set
    from .counters import WorkCounters

    counters = counters if counters is not None else WorkCounters()
    four = ndimage.generate_binary_structure(2, 1)
    detached = problem.face & ~contact
    peel = contact & ndimage.binary_dilation(detached, four)
    add = detached & ndimage.binary_dilation(contact, four)
    if not peel.any() or not add.any() or peel.sum() == contact.sum():
        return None
    if solution is None:
        solution = solve_contact_set(problem, contact, settings, None, counters)
    peeled = solve_contact_set(problem, contact & ~peel, settings, solution, counters)
    added = solve_contact_set(problem, contact | add, settings, solution, counters)
    cell = problem.cell_area
    stiffness = [cell * float(s.pressure_per_approach.sum()) for s in (peeled, solution, added)]
    n_peel, n_add = int(peel.sum()), int(add.sum())
    release = 0.5 * (stiffness[2] - stiffness[0]) / ((n_peel + n_add) * cell)
    peel_over_add = ((stiffness[1] - stiffness[0]) / n_peel) / ((stiffness[2] - stiffness[1]) / n_add)
    return FrontRelease(
        np.flatnonzero(peel[contact]),
        n_add,
        release,
        peel_over_add,
        math.sqrt(2.0 * problem.effective_modulus * max(release, 0.0)),
    )


def check_supported(scene: Scene, criterion: str = "stress_intensity", graded_criterion: str = "calibrated") -> None:
    """Refuse the scenes the stress-intensity and energy-release criteria cannot do, naming the
    setting (the energy release needs no G-K relation, so it takes graded bodies).  Periodic
    grids are refused by ``GriffithSettings`` itself, which knows the grid."""
    if criterion == "stress_intensity" and not isinstance(scene.material, Homogeneous):
        raise SceneError(
            "settings.criterion",
            "'stress_intensity' needs a homogeneous body: a graded one needs the graded G-K relation and its "
            "(k - 1)/2 edge singularity, not K^2 / (2 E*); use criterion = 'paper' or 'energy_release'",
        )
    if (
        criterion == "energy_release"
        and not isinstance(scene.material, Homogeneous)
        and graded_criterion != "calibrated"
    ):
        raise SceneError(
            "settings.graded_criterion",
            "'energy_release' nucleates on pinned edges with the graded sigma_c, which must be the calibrated "
            "one (Eq. 42's own constant is 22 % low at k = -0.5 and would decide the pull-off); use "
            "graded_criterion = 'calibrated'",
        )
    if not scene.indenter.profile.is_flat:
        why = (
            "on a curved profile K is not linear in the approach, so each front cell would need its own root-find"
            if criterion == "stress_intensity"
            else "on a curved profile the released energy is not proportional to d^2"
        )
        raise SceneError(
            "settings.criterion", f"{criterion!r} supports flat punches only ({why}); use criterion = 'paper'"
        )


def detachment_rule(problem, scene: Scene, settings, counters=None) -> DetachmentRule:
    """The rule ``settings.criterion`` names, for ``problem`` (``counters`` counts the solves of
    the energy-release rule)."""
    if settings.criterion == "paper":
        return PaperRule(problem.critical_stress)
    check_supported(scene, settings.criterion, settings.graded_criterion)
    if settings.criterion == "energy_release":
        from .counters import WorkCounters
        from .energy_release import EnergyReleaseRule

        return EnergyReleaseRule(problem, settings, counters if counters is not None else WorkCounters())
    elements_per_radius = math.sqrt(problem.face_elements / math.pi)
    return StressIntensityRule(
        critical_stress=problem.critical_stress,
        effective_modulus=problem.effective_modulus,
        work_of_adhesion=problem.work_of_adhesion,
        spacing=problem.spacing,
        depths=window_depths(elements_per_radius),
    )
