"""The Pohrt-Popov adhesive BEM: press without adhesion, then pull off with the local
Griffith criterion sigma_c = sqrt(E* w / (0.473201 Delta)) (theory sheet, section 3).

The face is rasterised (``contact_scene.raster``); a contact set S of face elements carries
the pressure p (compressive > 0), the rest of the face is free.  The modules, in the order a
solve uses them:

* ``problem``: the discretised problem (grid, face, operator, critical stress);
* ``contact_set``: the pressures of a given contact set, linear in the approach
  (``windows``: solved on a smaller sub-grid when the set has shrunk into one);
* ``press``: pressing without adhesion;
* ``driver``: the event driver, the detachment cascade and the fixed-step driver, with the
  rules of detachment and re-attachment;
* ``recording`` and ``result``: the curve, snapshots and the assembled ``Result``.
"""

from __future__ import annotations

import time

from contact_scene import Result, Scene
from contact_scene.discretisation import Grid
from contact_scene.errors import check_type

from .counters import WorkCounters
from .driver import pull
from .press import PressResult, pressed_state
from .problem import Problem, build_problem, max_elements_per_radius
from .recording import PullRecorder
from .result import assemble_result
from .settings import GriffithSettings

__all__ = [
    "solve",
    "solve_with_resolution",
    "press",
    "PressResult",
    "Problem",
    "build_problem",
    "max_elements_per_radius",
]


def solve(scene: Scene, settings: GriffithSettings | None = None, *, callback=None) -> Result:
    """Press the scene's punch without adhesion, then pull it off with the local Griffith criterion.

    The face is rasterised on the grid of ``settings.grid``; an element of the contact detaches
    when its tensile stress exceeds sigma_c (Eq. 22; Eq. 42 with its calibration on a graded
    half-space), and re-attaches when its gap closes.  See the module for the steps.

    Parameters
    ----------
    scene : contact_scene.Scene
        The punch, material, adhesion, loading and outputs.
    settings : bem_griffith.GriffithSettings or None, optional
        Grid, driver, criterion and solver tolerances; ``GriffithSettings()`` by default.
    callback : callable, optional
        ``callback(approach, force, contact_area)``, called at every recorded point of the curve
        (progress).

    Returns
    -------
    contact_scene.Result
        ``method = "bem_griffith"``; ``pulloff_force`` (the largest tension on the recorded
        curve, 0 if it never goes tensile) and ``pulloff_approach``; ``stiffness`` (dF/dd of the
        pressed contact with its contact set held fixed); ``converged`` (False, with a message,
        when a contact solve missed its tolerance, a detachment cascade did not settle or the
        pull was aborted); ``grid_spacing``; ``curve`` (when the scene's outputs ask for it);
        ``detached`` and ``detachment_approach``; ``snapshots`` at the requested approaches the
        pull passes; ``last_stable`` (with its fields when the scene asks for them);
        ``iterations`` (conjugate-gradient iterations) and ``residual`` (the worst relative
        residual); ``timings`` (setup, press, pull); ``messages`` (among them the requested
        snapshot approaches the pull did not reach, and why, and for a scene with an adhesion
        range that the range is ignored: the result is the zero-range limit); ``info``
        (:class:`bem_griffith.GriffithInfo`); ``stats``; ``face_area`` (the rasterised face);
        ``discretisation = "grid"``; ``error_bars`` from the method's error model.
        ``accuracy_estimate`` is not set.

    Raises
    ------
    contact_scene.SceneError
        Naming the field: ``grid.spacing`` (a grid too coarse for the face), ``grid.period`` or
        ``grid.periodic`` (a periodic cell too large, or a graded periodic body),
        ``settings.max_memory_gb`` (a grid beyond the memory limit), ``loading.press_approach``
        (a press that touches nothing), ``settings.graded_criterion`` (a calibrated criterion
        outside its measured exponents), ``material`` (lengths and moduli whose ratio leaves the
        floating-point range), ``scene`` or ``settings`` (an object of the wrong type).

    References
    ----------
    - Pohrt, R., Popov, V.L., "Adhesive contact simulation of elastic solids using local mesh-dependent
      detachment criterion in boundary elements method", Facta Universitatis, Mech. Eng. 13(1):3-10 (2015).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    check_type("scene", scene, Scene)
    settings = check_type("settings", settings or GriffithSettings(), GriffithSettings)
    t0 = time.perf_counter()
    problem = build_problem(scene, settings)
    counters = WorkCounters()
    t1 = time.perf_counter()
    pressed_approach, pressed = pressed_state(problem, scene, settings, counters)
    t2 = time.perf_counter()
    recorder = PullRecorder(problem, scene.outputs.snapshots, scene.outputs.fields, callback)
    recorder.point(pressed_approach, pressed)
    outcome = pull(problem, scene, settings, counters, pressed_approach, pressed, recorder)
    t3 = time.perf_counter()
    return assemble_result(
        problem=problem,
        scene=scene,
        settings=settings,
        counters=counters,
        pressed_approach=pressed_approach,
        stiffness=pressed.stiffness(problem.cell_area),
        recorder=recorder,
        outcome=outcome,
        timings={"setup": t1 - t0, "press": t2 - t1, "pull": t3 - t2},
    )


def press(scene: Scene, settings: GriffithSettings | None = None) -> PressResult:
    """Press without adhesion as the scene's loading says, and return the state; no pull.

    A flat face without a press approach or force is just touching.  Cheap: stiffness studies
    (Eq. 9) need only this.

    Parameters
    ----------
    scene : contact_scene.Scene
        The punch, material and loading (its adhesion is not used).
    settings : bem_griffith.GriffithSettings or None, optional
        Grid and solver tolerances; ``GriffithSettings()`` by default.

    Returns
    -------
    bem_griffith.PressResult
        Approach, force, contact set and area, and the unloading stiffness of the pressed state.

    Raises
    ------
    contact_scene.SceneError
        Naming the field, as :func:`solve`.
    RuntimeError
        If the contact solve does not converge.
    """
    check_type("scene", scene, Scene)
    settings = check_type("settings", settings or GriffithSettings(), GriffithSettings)
    problem = build_problem(scene, settings)
    approach, state = pressed_state(problem, scene, settings, WorkCounters())
    cell = problem.cell_area
    if not state.converged:
        raise RuntimeError(f"press: contact solve did not converge (residual {state.residual:.3g})")
    return PressResult(
        approach,
        state.force(approach, cell),
        state.contact,
        float(state.contact.sum()) * cell,
        state.stiffness(cell),
        problem.spacing,
        problem.origin,
    )


def solve_with_resolution(scene: Scene, resolution: float | None, *, callback=None) -> Result:
    """Solve at a resolution, the entry of the method registry (:mod:`crossval`).

    Parameters
    ----------
    scene : contact_scene.Scene
        The scene to solve.
    resolution : float or None
        Elements across the equivalent radius sqrt(A/pi) (A the nominal face area), > 0; 32 when
        None.
    callback : callable, optional
        ``callback(approach, force, contact_area)`` at every recorded point, as for :func:`solve`.

    Returns
    -------
    contact_scene.Result
        As :func:`solve` with default settings on that grid.

    Raises
    ------
    contact_scene.SceneError
        Naming the field, as :func:`solve`.
    """
    grid = Grid(elements_per_radius=resolution if resolution is not None else 32.0)
    return solve(scene, GriffithSettings(grid=grid), callback=callback)
