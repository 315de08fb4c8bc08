"""Pressing without adhesion, as the paper does before it pulls: to an approach, to a force,
or (a flat face) just touching."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import optimize

from contact_scene import Scene, SceneError

from .contact_set import ContactSolution, solve_contact_set
from .counters import WorkCounters
from .problem import Problem
from .settings import GriffithSettings

__all__ = ["PressResult", "press_to_approach", "pressed_state"]


@dataclass(frozen=True, eq=False)
class PressResult:
    """The non-adhesive indentation state (the paper presses without adhesion).

    Returned by :func:`bem_griffith.press`.

    Attributes
    ----------
    approach : float
        Approach d the press reached (0 for a flat face just touching).
    force : float
        Normal force F there (compressive > 0).
    contact : numpy.ndarray
        Boolean mask of the elements in contact, on the face's grid, indexed ``[ix, iy]``.
    contact_area : float
        Area of the contact: its elements times spacing^2.
    stiffness : float
        dF/dd with the contact set held fixed (the unloading stiffness).
    spacing : float
        Element side of the grid.
    origin : tuple of float
        (x, y) of the centre of element (0, 0).
    """

    approach: float
    force: float
    contact: np.ndarray
    contact_area: float
    stiffness: float  # dF/dd with the contact set held fixed (the unloading stiffness)
    spacing: float
    origin: tuple[float, float]


def press_to_approach(
    problem: Problem, approach: float, settings: GriffithSettings, counters: WorkCounters
) -> ContactSolution:
    """Non-adhesive contact at ``approach``: an active-set iteration (drop tensile elements,
    add penetrating ones, re-solve) from the geometric overlap; returns the solved state."""
    face = problem.face
    contact = face & (approach - problem.height > 0)
    if not contact.any():
        raise SceneError("loading.press_approach", f"approach {approach:g} brings no element of the face into contact")
    solution = None
    for _ in range(10_000):
        solution = solve_contact_set(problem, contact, settings, solution, counters)
        pressure = np.zeros(face.shape)
        pressure[contact] = solution.pressure(approach)
        gap = solution.displacement(approach) - (approach - problem.height)
        tolerance = 1e-12 * max(abs(approach), 1e-300)
        tensile = contact & (pressure < 0)
        penetrating = face & ~contact & (gap < -tolerance)
        if not tensile.any() and not penetrating.any():
            return solution
        contact = (contact & ~tensile) | penetrating
        if not contact.any():  # pragma: no cover - cannot happen for d > 0
            raise SceneError("loading.press_approach", "the press left no contact")
    raise RuntimeError("press: the active set did not settle")  # pragma: no cover


def pressed_state(
    problem: Problem, scene: Scene, settings: GriffithSettings, counters: WorkCounters
) -> tuple[float, ContactSolution]:
    """The approach the scene's press reaches and the solved contact state there."""
    loading = scene.loading
    if problem.flat and (loading.press_approach is None or loading.press_approach <= 0) and loading.press_force is None:
        # touching: the whole face, no stress
        return 0.0, solve_contact_set(problem, problem.face.copy(), settings, None, counters)
    if loading.press_approach is not None:
        return loading.press_approach, press_to_approach(problem, loading.press_approach, settings, counters)
    # press to a force: F(d) is continuous and increasing without adhesion; bracket, then Brent
    target = loading.press_force
    assert target is not None  # Loading gives a press approach, a press force or neither (above)
    if target == 0.0:
        lowest = (
            problem.face.copy()
            if problem.flat
            else problem.face & (problem.height <= problem.height[problem.face].min())
        )
        return 0.0, solve_contact_set(problem, lowest, settings, None, counters)
    cell = problem.cell_area
    lowest_height = float(problem.height[problem.face].min())
    states = {}

    def force_excess(approach):
        states[approach] = press_to_approach(problem, approach, settings, counters)
        return states[approach].force(approach, cell) - target

    upper = lowest_height + problem.spacing
    while force_excess(upper) < 0:
        upper = lowest_height + 2 * (upper - lowest_height)
    lower = lowest_height + 1e-12 * (upper - lowest_height)
    try:
        approach = optimize.brentq(force_excess, lower, upper, xtol=1e-12 * upper, rtol=1e-12)
    except ValueError:
        # no sign change: a target below the force of the first touch's own resolution, and the
        # lowest elements just touching are the press
        # (brentq solved both ends before it refused: the lower end's state is at hand)
        if lower in states and states[lower].force(lower, cell) >= target:
            return lower, states[lower]
        raise
    return approach, states[approach] if approach in states else press_to_approach(
        problem, approach, settings, counters
    )
