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
    """Press the scene's punch without adhesion, then pull it off; see the module doc.

    ``callback(approach, force, contact_area)`` is called at every recorded point.
    """
    settings = settings or GriffithSettings()
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
    """Press without adhesion as the scene's loading says (a flat face: just touching) and
    return the state; no pull.  Cheap: stiffness studies (Eq. 9) need only this."""
    settings = settings or GriffithSettings()
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
    """The registry's entry: ``resolution`` = elements across sqrt(A/pi) (default 32)."""
    grid = Grid(elements_per_radius=resolution if resolution is not None else 32.0)
    return solve(scene, GriffithSettings(grid=grid), callback=callback)
