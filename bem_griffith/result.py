"""Assembling a Griffith solve's ``Result``: the pull-off point from the recorded curve,
convergence and messages, typed work counters, and the method's own diagnostics."""

from __future__ import annotations

import logging
from typing import Literal, TypedDict

from contact_scene import PowerLawGraded, Result, Scene
from contact_scene.result import unrecorded_snapshots, zero_range_note

from .counters import WorkCounters
from .criterion import calibration
from .driver import PullOutcome
from .error_model import error_bars
from .problem import Problem
from .recording import PullRecorder
from .settings import GriffithSettings

__all__ = ["GriffithInfo", "assemble_result", "graded_criterion_note"]

log = logging.getLogger("bem_griffith")


class _GriffithInfoBase(TypedDict):
    matvecs: int  # operator applications (= stats.operator_applications)
    solves: int  # contact-set solves (= stats.linear_solves)
    events: int  # driver steps (= stats.events)
    grid: list[int]  # [nx, ny] of the face's grid
    face_elements: int  # elements of the face (= stats.unknowns)
    critical_stress: float  # sigma_c as used (calibrated for graded bodies)
    press_approach: float  # the approach the press reached
    cascades_cut: int  # cascades ended early by the Eq. 14 certainty bound
    windowed_solves: int  # contact-set solves on a smaller window of the grid
    decided_solves: int  # solves of a cascade's passing sets stopped once the next pass was certain
    criterion: str  # the detachment rule: "paper" (Eq. 22), "stress_intensity" or "energy_release"


class GriffithInfo(_GriffithInfoBase, total=False):
    """``Result.info`` of the Griffith BEM: diagnostics for people and JSON.

    Attributes
    ----------
    matvecs : int
        Operator applications (= ``stats.operator_applications``).
    solves : int
        Contact-set solves (= ``stats.linear_solves``).
    events : int
        Driver steps (= ``stats.events``).
    grid : list of int
        [nx, ny] of the face's grid.
    face_elements : int
        Elements of the face (= ``stats.unknowns``).
    critical_stress : float
        sigma_c as used (Eq. 22; Eq. 42, calibrated by default, for graded bodies).
    press_approach : float
        The approach the press reached.
    cascades_cut : int
        Detachment cascades ended early by the Eq. 14 certainty bound.
    windowed_solves : int
        Contact-set solves on a smaller window of the grid.
    decided_solves : int
        Solves of a cascade's passing contact sets, stopped as soon as a bound on their error
        showed which elements leave next (``GriffithSettings.decide_early``).
    criterion : str
        The detachment rule: ``"paper"`` (Eq. 22), ``"stress_intensity"`` or ``"energy_release"``.
    pulloff_by_cap : bool
        ``"energy_release"`` under the event driver only: the cells that let go at the pull-off
        were all held by the rule's nucleation cap (Eq. 22 at ``NUCLEATION_FACTOR`` sigma_c), not
        by a measured release, so the pull-off is Eq. 22's at the cap.
    graded_criterion : str
        ``"calibrated"`` or ``"eq42"``; present for graded bodies with adhesion and k != 0 only,
        like the two keys below.
    criterion_ratio : float
        r(k) that divides Eq. 42's sigma_c (calibrated only).
    criterion_uncertainty : float
        u(k), the uncertainty of r (calibrated only).
    """

    graded_criterion: Literal["calibrated", "eq42"]
    criterion_ratio: float  # r(k) that divides Eq. 42's sigma_c (calibrated only)
    criterion_uncertainty: float  # u(k), r's uncertainty (calibrated only)
    pulloff_by_cap: bool  # energy_release, event driver: the pull-off was the nucleation cap's


def graded_criterion_note(scene: Scene, settings: GriffithSettings) -> tuple[dict, str | None]:
    """The graded criterion's info keys and the message that says how sigma_c was set;
    nothing for homogeneous bodies, k = 0 or no adhesion, where Eq. 22 holds as it is."""
    material = scene.material
    if not (isinstance(material, PowerLawGraded) and material.exponent != 0 and scene.adhesion.work_of_adhesion > 0):
        return {}, None
    k = material.exponent
    if settings.graded_criterion == "calibrated":
        r, u = calibration(k)
        return (
            {"graded_criterion": "calibrated", "criterion_ratio": r, "criterion_uncertainty": u},
            f"graded criterion: Eq. 42's sigma_c / {r:.4f}, calibrated so that the flat circle follows "
            f"the homogeneous one on the same grid (+-{100 * u:.2f} %, fitted over 32-181 elements per "
            "radius); other faces inherit the factor (bem_griffith.criterion)",
        )
    return (
        {"graded_criterion": "eq42"},
        "graded criterion kappa(k) (Eq. 42) is not calibrated for k != 0: on the circle the pull-off "
        "force stays 43 % below (k = -0.75) to 7 % above (k = 0.5) Eq. 39 under refinement "
        "(benchmarks/study_griffith_graded.py)",
    )


def assemble_result(
    *,
    problem: Problem,
    scene: Scene,
    settings: GriffithSettings,
    counters: WorkCounters,
    pressed_approach: float,
    stiffness: float,
    recorder: PullRecorder,
    outcome: PullOutcome,
    timings: dict[str, float],
) -> Result:
    """The Result of a finished pull: the pull-off force is the largest tension on the
    recorded curve (0 if the curve never goes tensile)."""
    curve = recorder.curve()
    tensile = -curve.force
    peak = recorder.peak()
    pulloff = float(max(tensile[peak], 0.0)) + 0.0  # never -0.0
    detached = not outcome.final.attached
    messages = list(outcome.messages)
    if not detached and not outcome.reached_user_limit and not outcome.aborted:
        messages.append("the punch did not detach within the default pull range")
    if not detached and outcome.reached_user_limit:
        messages.append(f"still attached at the pull limit d = {scene.loading.pull_limit:g} (strong adhesion)")
    if scene.outputs.snapshots:
        if detached:
            end = "where the punch detached"
        elif outcome.aborted:
            end = f"where the pull stopped after {outcome.events} events"
        elif outcome.reached_user_limit:
            end = "the pull limit"
        else:
            end = "the end of the default pull range"
        missed = unrecorded_snapshots(
            scene.outputs.snapshots,
            [s.approach for s in recorder.snapshots],
            start=pressed_approach,
            highest=float(curve.approach.max()),
            lowest=float(curve.approach.min()),
            end=end,
            method="bem_griffith",
        )
        if missed is not None:
            messages.append(missed)
    range_message = zero_range_note(scene, "bem_griffith")
    if range_message is not None:
        messages.append(range_message)
    graded_info, graded_message = graded_criterion_note(scene, settings)
    if graded_message is not None:
        messages.append(graded_message)
    converged = counters.unconverged_solves == 0 and counters.unsettled_cascades == 0 and not outcome.aborted
    if settings.driver == "fixed_step":
        assert settings.step is not None  # GriffithSettings requires it for this driver
        # the driver samples the pull every step, so its F_A lags the event driver's by up to the
        # force one step changes, K step (tests/test_bem_griffith.py); the error model is the
        # event driver's and gives it no pull-off bars
        lag = stiffness * settings.step
        if pulloff <= 0 or lag > 1e-3 * pulloff:
            messages.append(
                f"the fixed-step driver's step {settings.step:g} changes the force by up to K step = {lag:.3g} "
                f"({'no tensile force was recorded' if pulloff <= 0 else f'{lag / pulloff:.2g} of F_A'}): its F_A may "
                "lag the event driver's by that much; driver = 'event' finds every detachment exactly"
            )
    if counters.unconverged_solves:
        messages.append(
            f"{counters.unconverged_solves} contact solves did not reach rtol = {settings.rtol:g} "
            f"(worst relative residual {counters.worst_residual:.3g})"
        )
    log.info(
        "bem_griffith: %d solves, %d CG iterations, %d matvecs, pull-off %.6g at d = %.6g",
        counters.contact_solves,
        counters.cg_iterations,
        counters.operator_applications,
        pulloff,
        curve.approach[peak],
    )
    face_elements = problem.face_elements
    info: GriffithInfo = {
        "matvecs": counters.operator_applications,
        "solves": counters.contact_solves,
        "events": outcome.events,
        "grid": list(problem.face.shape),
        "face_elements": face_elements,
        "critical_stress": problem.critical_stress,
        "press_approach": pressed_approach,
        "cascades_cut": counters.cascades_cut,
        "windowed_solves": counters.windowed_solves,
        "decided_solves": counters.decided_solves,
        "criterion": settings.criterion,
        **graded_info,
        **outcome.rule_info,
    }
    return Result(
        method="bem_griffith",
        pulloff_force=pulloff,
        pulloff_approach=float(curve.approach[peak]),
        stiffness=stiffness,
        converged=converged,
        grid_spacing=problem.spacing,
        curve=curve if scene.outputs.curve else None,
        detached=detached,
        detachment_approach=outcome.detachment_approach,
        snapshots=tuple(recorder.snapshots),
        last_stable=outcome.last_stable,
        iterations=counters.cg_iterations,
        residual=counters.worst_residual,
        timings=timings,
        messages=tuple(messages),
        info=info,
        stats=counters.stats(events=outcome.events, face_elements=face_elements),
        face_area=face_elements * problem.spacing**2,
        discretisation="grid",
        error_bars=error_bars(
            scene,
            spacing=problem.spacing,
            face_area=face_elements * problem.spacing**2,
            graded_criterion=settings.graded_criterion,
            criterion=settings.criterion,
            driver=settings.driver,
            detached=detached,
        ),
    )
