"""The grid a finite-range pull-off runs on, and whether it resolves the process zone.

A finite range rho gives a process zone l_c at the punch edge (``potentials``); a grid coarser
than the potential's fewest elements per l_c traps the zone and the force overshoots, so the
default grid follows l_c, and a grid too large to run in reasonable time is refused with the
shortest range that fits.
"""

from __future__ import annotations

import math

from contact_scene import Grid, Homogeneous, Scene, SceneError, theory
from contact_scene.materials import PowerLawGraded

from .potentials import (
    Potential,
    process_zone_elements,
    process_zone_exponent,
    process_zone_length,
    process_zone_modulus,
    range_for_process_zone,
)
from .problem import EnergyProblem

__all__ = [
    "default_potential",
    "unresolved_process_zone",
    "finite_range_grid",
    "critical_approach_scale",
    "MAX_DEFAULT_SIDE",
    "DEFAULT_ELEMENTS_PER_RADIUS",
]


def default_potential(scene: Scene) -> Potential | None:
    ad = scene.adhesion
    if ad.work_of_adhesion <= 0:
        return None
    if ad.range is None:
        raise SceneError("adhesion.range", "a finite-range run needs a range > 0 (None means the zero-range limit)")
    return Potential(ad.work_of_adhesion, ad.range, ad.potential)


def unresolved_process_zone(
    scene: Scene, prob: EnergyProblem, potential: Potential, remedy: str | None = None
) -> str | None:
    """Why the grid is too coarse for the process zone (None when it is fine): below the
    potential's fewest elements per l_c (:func:`~bem_energy.potentials.process_zone_elements`) the zone is trapped by
    the mesh and the pull-off force overshoots, e.g. 2.4 x Kendall at 0.08 elements per l_c.
    ``remedy`` ends the note; by default that of a finite-range run, whose ``--resolution`` is
    elements per radius (a zero-range sequence gives its own, in elements per l_c)."""
    need = process_zone_elements(potential.kind, prob.exponent)[0]
    lc = prob.process_zone
    per = lc / prob.spacing
    if per >= need * (1 - 1e-9):
        return None
    a = scene.indenter.shape.equivalent_radius
    formula = "E* rho^2 / w" if prob.exponent == 0 else f"(c_k E_k rho^2 / w)^(1/(1-k)), k = {prob.exponent:g}"
    if not lc > 0:
        return (
            f"the process zone l_c = {formula} underflows to {lc:g}: no grid resolves it and the result is "
            "trapped by the mesh; use a longer range, or the zero-range limit (no range)"
        )
    if remedy is None:
        remedy = (
            f"use --resolution {math.ceil(need * a / lc * (1 - 1e-9)):d} or more (elements per radius sqrt(A/pi)), "
            "or a longer range"
        )
    return (
        f"the grid has {per:.3g} elements per process zone l_c = {lc:.3g} ({formula}, {lc / a:.3g} a); "
        f"the {potential.kind} potential needs at least {need:.3g}, below which the result is trapped by the mesh: "
        + remedy
    )


#: the largest raster side a finite-range run picks by itself (the padded FFT grid is twice
#: that): a pull-off's time grows about 4x per doubling of the elements per radius N (l_c =
#: 0.02 a: 36, 152, 572 s at 50, 100, 200 per radius, benchmarks/study_energy_process_zone.py),
#: so 1024 cells across (512 per radius for a circle) is about an hour, and past it the user
#: decides
MAX_DEFAULT_SIDE = 1024

#: elements per radius sqrt(A/pi) when the process zone asks for fewer (a long range, or no
#: adhesion): the staircase error of the face is then within 0.5 % (0.16 Delta / a)
DEFAULT_ELEMENTS_PER_RADIUS = 32.0


def finite_range_grid(scene: Scene, resolution: float | None = None) -> Grid:
    """The grid of a finite-range run, fine enough for its process zone.

    ``resolution`` elements per radius sqrt(A/pi) when given (a grid too coarse for the process
    zone is run and reported not converged), else the finer of 32 per radius and the potential's
    default elements per process zone (:func:`~bem_energy.potentials.process_zone_elements`).  A default grid wider than
    :data:`MAX_DEFAULT_SIDE` cells is refused, naming the shortest range that fits.

    Parameters
    ----------
    scene : contact_scene.Scene
        The scene; its adhesion range and material set the process zone.
    resolution : float or None, optional
        Elements per radius sqrt(A/pi), > 0; None for the default above.

    Returns
    -------
    contact_scene.Grid
        The grid, by ``elements_per_radius`` when a resolution is given, else by ``spacing``.

    Raises
    ------
    contact_scene.SceneError
        Naming ``adhesion.range``: adhesion without a range, or a range whose process zone needs
        a default grid wider than :data:`MAX_DEFAULT_SIDE` (the message gives the shortest range
        that fits).
    """
    if resolution is not None:
        return Grid(elements_per_radius=resolution)
    shape = scene.indenter.shape
    a = shape.equivalent_radius
    h = a / DEFAULT_ELEMENTS_PER_RADIUS
    potential = default_potential(scene)
    if potential is None:
        return Grid(spacing=h)
    mat = scene.material
    E, k = process_zone_modulus(mat), process_zone_exponent(mat)
    lc = process_zone_length(modulus=E, work=potential.work, range=potential.range, exponent=k)
    per = process_zone_elements(potential.kind, k)[1]
    h = min(h, lc / per)
    xmin, ymin, xmax, ymax = shape.bounds
    width = max(xmax - xmin, ymax - ymin)
    # a process zone that underflows (l_c^(1-k) ~ rho^2 near k = 1) needs an endless grid
    side = math.ceil(width / h) if h > 0 else math.inf
    if side > MAX_DEFAULT_SIDE:
        lc_min = per * width / MAX_DEFAULT_SIDE
        rho_min = range_for_process_zone(modulus=E, work=potential.work, length=lc_min, exponent=k)
        unit = 10.0 ** (math.floor(math.log10(rho_min)) - 2)
        rho_min = math.ceil(rho_min / unit * (1 - 1e-12)) * unit  # three digits, rounded up: it fits
        raise SceneError(
            "adhesion.range",
            (
                f"range {potential.range:g} gives a process zone l_c = {lc:.3g} ({lc / a:.3g} a); resolving it "
                f"({per:.3g} elements per l_c for the {potential.kind} potential) needs a {side} x {side} grid "
                f"({a / h:.0f} elements per radius), wider than the {MAX_DEFAULT_SIDE} a run picks by itself "
                f"(an hour or more): use a range >= {rho_min:.3g} (l_c >= {lc_min / a:.3g} a), "
                "the zero-range limit (no range), "
                "or give --resolution (a grid too coarse for l_c is run but reported not converged)"
            ),
        )
    return Grid(spacing=h)


def critical_approach_scale(scene: Scene) -> float:
    """|d_c| of the circle of the face's area (Eq. 14 / Eq. 38): the scale of the pull."""
    w = scene.adhesion.work_of_adhesion
    area = scene.indenter.shape.area
    mat = scene.material
    if w <= 0:
        return 0.0
    if isinstance(mat, Homogeneous):
        return abs(theory.upper_bound_approach(E_star=mat.effective_modulus, work=w, area=area))
    assert isinstance(mat, PowerLawGraded)
    return abs(
        theory.graded_critical_approach(
            E0=mat.surface_modulus, c0=mat.reference_depth, k=mat.exponent, radius=math.sqrt(area / math.pi), work=w
        )
    )
