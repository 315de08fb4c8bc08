"""Energy-minimisation BEM (Rey-style): elastic energy + finite-range adhesive potential,
hard wall on the face, pull-off by continuation; the zero-range limit by extrapolation."""

from __future__ import annotations

from contact_scene import Result, Scene, SceneError
from contact_scene.errors import check_type

from .minimisers import Minimum, minimise
from .potentials import Potential, process_zone_length
from .problem import EnergyProblem, build_problem
from .settings import EnergySettings, ZeroRangeSettings, default_grid
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
    """Solve a scene: its finite range, or the zero-range limit when it has none.

    A scene with an adhesion range runs that range (:func:`pull_off`); one without (and w > 0)
    gets the zero-range limit (:func:`zero_range`).

    Parameters
    ----------
    scene : contact_scene.Scene
        The punch, material, adhesion, loading and outputs.
    settings : bem_energy.EnergySettings or bem_energy.ZeroRangeSettings or None, optional
        The settings of the run; an ``EnergySettings`` given for a zero-range scene becomes the
        settings of each range of the default sequence (its grid must then be the default: each
        range sets its own), and a ``ZeroRangeSettings`` given for a finite range contributes
        its ``energy``.  Defaults when None.
    callback : callable, optional
        ``callback(approach, force, contact_area)``, called at every recorded point of the curve
        (progress).

    Returns
    -------
    contact_scene.Result
        As :func:`pull_off` or :func:`zero_range` returns it.

    Raises
    ------
    contact_scene.SceneError
        Naming the offending field (see :func:`pull_off`).

    References
    ----------
    - Rey, V., Anciaux, G., Molinari, J.-F., "Normal adhesive contact on rough surfaces: efficient algorithm
      for FFT-based BEM resolution", Comput. Mech. 60:69-81 (2017).
    """
    check_type("scene", scene, Scene)
    if settings is not None:
        check_type("settings", settings, (EnergySettings, ZeroRangeSettings))
    ad = scene.adhesion
    if ad.work_of_adhesion > 0 and ad.range is None:
        if isinstance(settings, EnergySettings):
            if settings.grid != default_grid():
                raise SceneError(
                    "settings.grid",
                    "a scene without adhesion.range runs the zero-range sequence, each of whose ranges sets its own "
                    "grid (ZeroRangeSettings.elements_per_process_zone, minimum_elements_per_radius); pass "
                    "ZeroRangeSettings, or give adhesion.range to run one finite range on this grid",
                )
            settings = ZeroRangeSettings(energy=settings)
        return zero_range(scene, settings, callback=callback)
    if isinstance(settings, ZeroRangeSettings):
        settings = settings.energy
    return pull_off(scene, settings or EnergySettings(), callback=callback)


def solve_with_resolution(scene: Scene, resolution: float | None, *, callback=None) -> Result:
    """Solve at a resolution, the entry of the method registry (:mod:`crossval`).

    Finite range: ``resolution`` elements per sqrt(A/pi); without one, a grid that resolves the
    process zone (:func:`finite_range_grid`: at least 32 per radius and the potential's default
    elements per l_c; refused when that grid is too large).  A resolution too coarse for the
    process zone is run and reported not converged.  Zero range: without a resolution the
    default (accurate, minutes) sequence; with one, the harness's coarse sequence
    (:meth:`ZeroRangeSettings.coarse`) at ``resolution`` elements per process zone, whose bias on
    faces with corners the harness allows for.

    Parameters
    ----------
    scene : contact_scene.Scene
        The punch, material, adhesion, loading and outputs.
    resolution : float or None
        Elements per radius sqrt(A/pi) (finite range) or per process zone l_c (zero range), > 0;
        None for the defaults above.
    callback : callable, optional
        ``callback(approach, force, contact_area)``, called at every recorded point of the curve
        (progress).

    Returns
    -------
    contact_scene.Result
        As :func:`pull_off` or :func:`zero_range` returns it.

    Raises
    ------
    contact_scene.SceneError
        Naming the offending field (see :func:`pull_off` and :func:`finite_range_grid`).
    """
    ad = scene.adhesion
    if ad.work_of_adhesion > 0 and ad.range is None:
        zs = ZeroRangeSettings() if resolution is None else ZeroRangeSettings.coarse(resolution)
        return zero_range(scene, zs, callback=callback)
    return pull_off(scene, EnergySettings(grid=finite_range_grid(scene, resolution)), callback=callback)
