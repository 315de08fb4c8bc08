"""Energy-minimisation BEM (Rey-style): elastic energy + finite-range adhesive potential,
hard wall on the face, pull-off by continuation; the zero-range limit by extrapolation."""

from __future__ import annotations

from contact_scene import Result, Scene

from .minimisers import Minimum, minimise
from .potentials import Potential, process_zone_length
from .problem import EnergyProblem, build_problem
from .settings import EnergySettings, ZeroRangeSettings
from .solver import EnergyInfo, finite_range_grid, pull_off
from .zero_range import ZeroRangeInfo, richardson, zero_range

__all__ = [
    "solve",
    "solve_with_resolution",
    "pull_off",
    "finite_range_grid",
    "zero_range",
    "richardson",
    "EnergySettings",
    "ZeroRangeSettings",
    "Potential",
    "process_zone_length",
    "EnergyProblem",
    "build_problem",
    "Minimum",
    "minimise",
    "EnergyInfo",
    "ZeroRangeInfo",
]


def solve(scene: Scene, settings: EnergySettings | ZeroRangeSettings | None = None, *, callback=None) -> Result:
    """A scene with an adhesion range runs that range; one without (and w > 0) gets the
    zero-range limit (:func:`zero_range`)."""
    ad = scene.adhesion
    if ad.work_of_adhesion > 0 and ad.range is None:
        if isinstance(settings, EnergySettings):
            settings = ZeroRangeSettings(energy=settings)
        return zero_range(scene, settings, callback=callback)
    if isinstance(settings, ZeroRangeSettings):
        settings = settings.energy
    return pull_off(scene, settings or EnergySettings(), callback=callback)


def solve_with_resolution(scene: Scene, resolution: float | None, *, callback=None) -> Result:
    """The registry's entry.  Finite range: ``resolution`` = elements per sqrt(A/pi); without
    one, a grid that resolves the process zone (:func:`finite_range_grid`: at least 32 per
    radius and the potential's default elements per l_c; refused when that grid is too large).
    A resolution too coarse for the process zone is run and reported not converged.  Zero
    range: without a resolution the default (accurate, minutes) sequence; with one, the
    harness's coarse sequence (:meth:`ZeroRangeSettings.coarse`) at ``resolution`` elements
    per process zone, whose bias on faces with corners the harness allows for."""
    ad = scene.adhesion
    if ad.work_of_adhesion > 0 and ad.range is None:
        zs = ZeroRangeSettings() if resolution is None else ZeroRangeSettings.coarse(resolution)
        return zero_range(scene, zs, callback=callback)
    return pull_off(scene, EnergySettings(grid=finite_range_grid(scene, resolution)), callback=callback)
