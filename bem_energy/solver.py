"""One finite-range pull-off by energy minimisation.

The algorithm, one module per step: build the discrete problem on the face's grid
(``problem``); press without adhesion and measure the initial stiffness (``press``); switch
adhesion on and follow the attached branch by continuation, bracketing the snap-off when a
pulling step detaches (``continuation``); take the force maximum, refined where it is smooth
or at the fold (``peak``).  Every minimisation is counted (``equilibria``); the grid and
whether it resolves the process zone come from ``resolution``.
"""

from __future__ import annotations

import logging
import time
from typing import TypedDict

import numpy as np

from contact_scene import Curve, Result, Scene, SceneError
from contact_scene.result import unrecorded_snapshots

from .continuation import LoadingPath, pull, snapshot
from .equilibria import Equilibria
from .error_model import error_bars
from .peak import force_maximum
from .potentials import Potential, process_zone_elements
from .press import initial_stiffness, press
from .problem import MAX_MEMORY_GB, build_problem
from .resolution import (
    DEFAULT_ELEMENTS_PER_RADIUS,
    MAX_DEFAULT_SIDE,
    critical_approach_scale,
    default_potential,
    finite_range_grid,
    unresolved_process_zone,
)
from .settings import EnergySettings

__all__ = [
    "pull_off",
    "EnergyInfo",
    "default_potential",
    "unresolved_process_zone",
    "finite_range_grid",
    "MAX_DEFAULT_SIDE",
    "DEFAULT_ELEMENTS_PER_RADIUS",
]

log = logging.getLogger("bem_energy")


class _EnergyInfoRequired(TypedDict):
    minimiser: str
    minimisations: int
    evaluations: int
    grid: list[int]
    padded_grid: list[int]
    face_elements: int
    press_approach: float
    peak: str


class EnergyInfo(_EnergyInfoRequired, total=False):
    """``Result.info`` of a finite-range pull-off (diagnostics for people and JSON).

    ``peak`` says how the force maximum was found (``"step"``, ``"fold"``, ``"refined"``:
    see :class:`bem_energy.peak.PullOffPoint`); the process-zone keys are there with adhesion:
    l_c, l_c per element, and the elements per l_c the potential needs."""

    range: float
    potential: str
    process_zone: float
    process_zone_per_element: float
    process_zone_elements_needed: float


def pull_off(
    scene: Scene,
    settings: EnergySettings,
    *,
    spacing: float | None = None,
    potential: Potential | None = None,
    callback=None,
    max_memory_gb: float = MAX_MEMORY_GB,
    resolution_remedy: str | None = None,
) -> Result:
    """One finite-range pull-off by energy minimisation under a hard wall.

    Press without adhesion, switch the adhesive potential on and follow the attached branch by
    continuation until it snaps off; the force maximum is the pull-off force (see the module).

    Parameters
    ----------
    scene : contact_scene.Scene
        The punch, material, adhesion, loading and outputs.
    settings : bem_energy.EnergySettings
        Grid, minimiser, tolerances and continuation steps.
    spacing : float or None, optional
        Element side, > 0; overrides ``settings.grid`` when given.
    potential : bem_energy.Potential or None, optional
        The adhesive potential (work, range, kind); the scene's adhesion by default.
    callback : callable, optional
        ``callback(approach, force, contact_area)``, called at every recorded point of the curve
        (progress).
    max_memory_gb : float, optional
        Largest working memory allowed for the grid (GB), > 0.
    resolution_remedy : str or None, optional
        How to refine the grid, ending the note of a grid too coarse for the process zone; by
        default a finite-range run's (``--resolution`` in elements per radius).

    Returns
    -------
    contact_scene.Result
        ``method = "bem_energy"``; ``pulloff_force`` and ``pulloff_approach`` (the force maximum
        of the pull, refined at the snap-off fold or where the curve is smooth); ``stiffness``
        (the initial slope of the non-adhesive force); ``converged`` (False, with a message,
        when a minimisation did not converge, the pull stopped early or the grid does not
        resolve the process zone); ``grid_spacing``; ``curve`` (when the scene's outputs ask for
        it); ``detached`` and ``detachment_approach`` (the snap-off); ``snapshots`` (each a
        continuation step of its own, so asking for them moves the steps and with them F_A, as
        a change of the step count does: by 2e-6 and 9e-6 of it with one and two snapshots on
        a Kendall circle of 16 elements per radius); ``last_stable`` (the attached state before
        the snap-off); ``iterations`` and ``residual`` (the worst scaled projected gradient);
        ``timings``; ``messages`` (among them the requested snapshot approaches the pull did
        not reach, and why); ``info`` (:class:`bem_energy.EnergyInfo`); ``stats``;
        ``face_area`` (the rasterised face); ``discretisation = "grid"``; ``error_bars``.
        ``accuracy_estimate`` is not set.

    Raises
    ------
    contact_scene.SceneError
        Naming the field: ``adhesion.range`` (adhesion without a range), ``grid.periodic`` (the
        method has no periodic half-space), ``grid.spacing`` (a grid too coarse for the face),
        ``settings.grid`` (beyond ``max_memory_gb``), ``settings.kernel``, ``settings.minimiser``
        (cvxpy on a large grid), ``material`` (an influence matrix that is not positive definite)
        or ``loading.press_approach`` (a press that touches nothing).

    References
    ----------
    - Rey, V., Anciaux, G., Molinari, J.-F., "Normal adhesive contact on rough surfaces: efficient algorithm
      for FFT-based BEM resolution", Comput. Mech. 60:69-81 (2017).
    """
    t0 = time.perf_counter()
    if settings.grid.periodic:
        raise SceneError(
            "grid.periodic",
            "the energy method models the infinite (non-periodic) half-space only; use periodic = false",
        )
    potential = potential if potential is not None else default_potential(scene)
    h = spacing if spacing is not None else settings.grid.spacing_for(scene.indenter.shape)
    prob = build_problem(
        scene, h, potential, memory=settings.memory, max_memory_gb=max_memory_gb, kernel=settings.kernel
    )
    face_elements = int(prob.face.sum())
    if settings.minimiser == "cvxpy" and face_elements > settings.max_face_elements_cvxpy:
        raise SceneError(
            "settings.minimiser",
            f"cvxpy is for small grids: {face_elements} face elements "
            f"> {settings.max_face_elements_cvxpy}; use lbfgsb or pk",
        )
    eq = Equilibria(prob, settings, scene.indenter.shape.equivalent_radius)
    approach_scale = critical_approach_scale(scene)
    adhesive = potential is not None
    t1 = time.perf_counter()
    d0, m = press(eq, scene, approach_scale)
    stiffness = initial_stiffness(eq, scene, d0, m, approach_scale)
    t2 = time.perf_counter()

    path = LoadingPath(eq, callback)
    if adhesive:
        m = eq.minimum(m.U, d0, True)
    path.record(d0, m)
    rho = potential.range if potential is not None else 0.0
    # the length scale of the pull: the critical approach and the range with adhesion (a grid
    # spacing would swamp both when w is tiny), the element without
    pull_scale = approach_scale + rho if adhesive else prob.spacing
    span = abs(d0) + 2.0 * approach_scale + 5.0 * rho + (0.0 if adhesive else prob.spacing)
    tolerance = settings.snap_tolerance * pull_scale
    outcome = pull(
        eq,
        scene,
        path,
        d0,
        m,
        adhesive,
        step=span / settings.steps,
        snap_tolerance=tolerance,
        max_steps=20 * settings.steps + 100,
    )
    peak = force_maximum(
        eq, path, outcome.snap_off, adhesive, tolerance=tolerance, force_tolerance=settings.peak_tolerance
    )
    t3 = time.perf_counter()

    msgs = list(outcome.messages)
    if outcome.attached and scene.loading.pull_limit is not None:
        msgs.append(f"still attached at the pull limit d = {scene.loading.pull_limit:g} (strong adhesion)")
    if scene.outputs.snapshots:
        if outcome.stopped:
            end = f"where the pull stopped after {outcome.steps} steps"
        elif not outcome.attached:
            end = "where the punch detached"
        elif scene.loading.pull_limit is not None:
            end = "the pull limit"
        else:
            end = "where the pull ended"
        missed = unrecorded_snapshots(
            scene.outputs.snapshots,
            [s.approach for s in outcome.snapshots],
            start=float(d0),
            highest=max(path.approach),
            lowest=min(path.approach),
            end=end,
            method="bem_energy",
        )
        if missed is not None:
            msgs.append(missed)
    resolved = True
    if potential is not None:
        note = unresolved_process_zone(scene, prob, potential, resolution_remedy)
        if note:
            msgs.append(note)
            resolved = False
    msgs.extend(eq.work.messages())
    snap = outcome.snap_off
    curve = Curve(np.array(path.approach), np.array(path.force), np.array(path.contact_area))
    info = EnergyInfo(
        minimiser=settings.minimiser,
        minimisations=eq.work.minimisations,
        evaluations=eq.work.evaluations,
        grid=list(prob.n),
        padded_grid=list(prob.padded),
        face_elements=face_elements,
        press_approach=float(d0),
        peak=peak.kind,
    )
    if potential is not None:
        info["range"] = potential.range
        info["potential"] = potential.kind
        info["process_zone"] = prob.process_zone
        info["process_zone_per_element"] = prob.process_zone / prob.spacing
        info["process_zone_elements_needed"] = process_zone_elements(potential.kind, prob.exponent)[0]
    return Result(
        method="bem_energy",
        pulloff_force=peak.force + 0.0,  # never -0.0
        pulloff_approach=peak.approach,
        stiffness=float(stiffness),
        converged=eq.work.unconverged == 0 and not outcome.stopped and resolved,
        grid_spacing=prob.spacing,
        curve=curve if scene.outputs.curve else None,
        detached=not outcome.attached,
        detachment_approach=None if snap is None else snap.detached_approach,
        snapshots=tuple(outcome.snapshots),
        last_stable=None
        if snap is None
        else snapshot(eq, snap.attached_approach, snap.attached_state, scene.outputs.fields),
        iterations=eq.work.iterations,
        residual=eq.work.worst_gradient,
        timings={"setup": t1 - t0, "press": t2 - t1, "pull": t3 - t2},
        messages=tuple(msgs),
        info=info,
        stats=eq.work.solver_stats(events=outcome.steps, unknowns=face_elements),
        face_area=face_elements * prob.cell,
        discretisation="grid",
        error_bars=error_bars(scene, spacing=prob.spacing, face_area=face_elements * prob.cell),
    )
