"""Pulling: the event driver, the detachment cascade at a fixed approach, and the paper's
fixed-step driver.

State and rules (theory sheet, section 3)
-----------------------------------------
* An element of the contact set whose tension -p reaches sigma_c detaches.
* A free element of the face re-attaches when its gap u - (d - h) closes (< 0).
* Simultaneous detachments: at an event every element whose tension exceeds sigma_c
  (less a relative ``tie_tolerance``, for round-off) leaves at once, then the set is
  re-solved at the same approach and the pass repeats until no element exceeds it.
  This is the paper's rule; it keeps symmetric partners together and makes the result
  independent of element ordering.  Detaching one element at a time would be another rule,
  at many more solves.  A larger tolerance merges events that fall close together; for this
  event driver under ``criterion = "paper"`` on a flat face pulled without turning points
  (homogeneous or 0 <= k <= 0.95, not periodic) it keeps F_A and the detachment approach within a
  factor [1 - tie_tolerance, 1] of the exact pull's, up to the CG tolerance
  (``GriffithSettings.tie_tolerance``).

Between events the contact set is fixed and the state is linear in the approach
(``bem_griffith.contact_set``), so the event driver computes the next approach at which an
element reaches sigma_c or a gap closes exactly; the fixed-step driver moves by ``step``.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field

import numpy as np

from contact_scene import Scene, Snapshot

from .contact_set import ContactSolution, Decision, no_contact, solve_contact_set
from .counters import WorkCounters
from .problem import Problem
from .recording import PullRecorder
from .settings import GriffithSettings
from .stress_intensity import DetachmentRule, PaperRule, detachment_rule, pressure_roundoff

__all__ = ["PullOutcome", "pull", "next_event", "cascade", "gap_coefficients", "pull_targets"]

log = logging.getLogger("bem_griffith")


@dataclass
class PullOutcome:
    """How the pull ended.

    final
        The contact state at the last approach (no contact once detached).
    last_stable
        The last contact set that held, at the approach where it let go (None if it never did).
    detachment_approach
        The approach at which the last element let go (None if still attached).
    events
        Driver steps: events (event driver) or steps (fixed-step driver), each with its cascade.
    aborted
        The event limit stopped the pull, or a cascade came back to a contact set it had left
        (``WorkCounters.cycled_cascades``).
    reached_user_limit
        The final target was the scene's ``pull_limit`` (then ending attached is the scene's
        strong adhesion, not a failure).
    messages
        What went wrong or deserves saying, for the result's messages.
    rule_info
        The detachment rule's keys for ``Result.info`` (``DetachmentRule.report``).
    """

    final: ContactSolution
    last_stable: Snapshot | None = None
    detachment_approach: float | None = None
    events: int = 0
    aborted: bool = False
    reached_user_limit: bool = False
    messages: list[str] = field(default_factory=list)
    rule_info: dict = field(default_factory=dict)


def gap_coefficients(problem: Problem, solution: ContactSolution):
    """The free part of the face and its gaps as linear functions of the approach,
    gap(d) = slope d + offset = u(d) - (d - h): (free mask, slope, offset)."""
    if solution.displacement_in_window:
        raise ValueError("the gaps of a state decided without them are unknown beyond its window")
    free = problem.face & ~solution.contact
    slope = solution.displacement_per_approach[free] - 1.0
    offset = problem.height[free] - solution.profile_displacement[free]
    return free, slope, offset


def next_event(
    problem: Problem, solution: ContactSolution, approach: float, target: float, rule: DetachmentRule | None = None
) -> float:
    """The nearest approach between ``approach`` and ``target`` (in the direction of travel)
    at which an element of the contact set meets the detachment ``rule`` (default: Eq. 22,
    sigma_c) or a free element's gap closes; ``target`` if none.  Under the paper's rule only
    a tension that rises along the direction of travel (x1 * direction < 0) makes an event: one
    that falls crosses sigma_c leaving it."""
    if solution.at_approach is not None:
        raise ValueError("a state decided at one approach is not linear in the approach")
    rule = PaperRule(problem.critical_stress) if rule is None else rule
    direction = 1.0 if target > approach else -1.0
    nearest = target
    eps = 1e-13 * max(abs(approach), abs(target), 1e-300)
    at_critical_stress = rule.critical_approaches(solution)
    if isinstance(rule, PaperRule):
        # only a tension that rises along the direction of travel meets sigma_c there; one that
        # falls crosses it leaving (a cell kept at the threshold by ``_falling_at_threshold``)
        at_critical_stress = np.where(solution.pressure_per_approach * direction < 0, at_critical_stress, np.nan)
    ahead = (at_critical_stress - approach) * direction >= -eps
    if ahead.any():
        candidates = at_critical_stress[ahead]
        first = candidates.max() if direction < 0 else candidates.min()
        if (first - nearest) * direction < 0:
            nearest = first
    free, slope, offset = gap_coefficients(problem, solution)
    if slope.size:
        closing = slope * direction < 0  # gap shrinks along the direction of travel
        with np.errstate(divide="ignore"):
            gap_closes_at = -offset[closing] / slope[closing]
        ahead = (gap_closes_at - approach) * direction > eps
        if ahead.any():
            candidates = gap_closes_at[ahead]
            first = candidates.max() if direction < 0 else candidates.min()
            if (first - nearest) * direction < 0:
                nearest = first
    # an event already passed (tension above sigma_c at d) fires at once
    if (nearest - approach) * direction < 0:
        nearest = approach
    return float(nearest)


def _certainly_detached(problem: Problem, contact: np.ndarray, approach: float, settings: GriffithSettings) -> bool:
    """Whether no face of the remaining area can hold at ``approach``: |d| beyond the margin
    times the circle's critical approach of that area (Eq. 14 bounds every flat face of a
    homogeneous body by the circle of its area)."""
    if not (
        problem.flat
        and settings.stop_when_certainly_detached
        and approach < 0
        and problem.effective_modulus is not None
        and problem.work_of_adhesion > 0
        and problem.circle_critical_approach is not None
    ):
        return False
    area = float(contact.sum()) * problem.cell_area
    upper = problem.circle_critical_approach(area)
    margin = 1.0 + max(settings.certainty_margin, 2.0 * problem.spacing / math.sqrt(area / math.pi))
    if abs(approach) > margin * abs(upper):
        log.debug(
            "cascade at d = %.6g cut short with %d elements left: |d| > %.3g |d_c,upper| of the "
            "remaining area (Eq. 14)",
            approach,
            int(contact.sum()),
            margin,
        )
        return True
    return False


def _gap_tolerance(problem: Problem, approach: float) -> float:
    return 1e-12 * max(abs(approach), problem.spacing * 1e-6)


def _residual_bound(problem: Problem, contact: np.ndarray, approach: float, settings: GriffithSettings) -> float:
    """The largest residual entry a set solved to rtol may leave, for x1 and xh together: each
    at most its 2-norm, rtol sqrt(n) times that of the right-hand side (1 for x1, h for xh),
    so rtol sqrt(n) (|d| + max |h|) for the state at d; 0 for an empty set.  Both noise bands
    (:func:`_open_tolerance`, :func:`_pressure_noise`) scale it."""
    n = int(contact.sum())
    if n == 0:
        return 0.0
    return settings.rtol * math.sqrt(n) * (abs(approach) + float(np.abs(problem.height[contact]).max()))


def _open_tolerance(problem: Problem, contact: np.ndarray, approach: float, settings: GriffithSettings) -> float:
    """How far below zero the gap of a free cell that is opening may lie before the cell
    re-attaches: CG's error in the displacements.  Under the walk property a free cell's
    displacement error is a sub-probability average of the residual, so u = d u1 - uh errs by
    at most :func:`_residual_bound`; twice that.  A cell that left at zero pressure (no
    adhesion: sigma_c = 0) has a gap of zero to within this error, and must not re-attach on
    its noise.  Without the walk property (graded k < 0) the same band, not a bound; on a
    periodic grid too (its zero-mean kernel has no walk property).  The gap's own round-off
    (:func:`_gap_tolerance`) where it is larger."""
    return max(_gap_tolerance(problem, approach), 2.0 * _residual_bound(problem, contact, approach, settings))


def _periodic_floor(problem: Problem, n: int) -> float | None:
    """A lower bound on the eigenvalues of every C_SS with n cells on a periodic grid of N:
    the circulant C has the symbol's values as eigenvalues, zero for the mean (its kernel has
    none) and at least s' (the smallest of the others) elsewhere, so x.C x >= s' (||x||^2 -
    (sum x)^2 / N) >= s' (1 - n / N) ||x||^2.  None if that is not positive."""
    values = problem.operator.symbol.ravel()[1:]  # all modes but the mean's
    if values.size == 0:
        return None
    floor = float(values.min()) * (1.0 - n / problem.face.size)
    return floor if floor > 0 else None


def _pressure_noise(problem: Problem, contact: np.ndarray, approach: float, settings: GriffithSettings) -> float:
    """CG's error in the pressures p = d x1 - xh of a set solved to rtol: under the walk
    property each errs by at most twice ``inverse_diagonal`` times the residual's largest
    entry (:func:`_residual_bound`), otherwise by at most the residual over
    ``eigenvalue_floor`` (on a periodic grid the circulant's floor, :func:`_periodic_floor`);
    twice the bound, 0 where none is known."""
    residual = _residual_bound(problem, contact, approach, settings)
    if residual == 0.0:
        return 0.0
    if problem.walk_bounds and problem.inverse_diagonal is not None:
        return 2.0 * 2.0 * problem.inverse_diagonal * residual
    floor = _periodic_floor(problem, int(contact.sum())) if problem.operator.periodic else problem.eigenvalue_floor
    if floor is not None:
        return 2.0 * residual / floor
    return 0.0


def _tensions_rise(problem: Problem, direction: float) -> bool:
    """Whether every contact cell's tension rises along the direction of travel: while pulling
    under the walk property, where x1 = C_SS^-1 1 > 0 (positive row sums of C_SS^-1)."""
    return problem.walk_bounds and direction < 0


def _falling_at_threshold(
    problem: Problem,
    solution: ContactSolution,
    approach: float,
    settings: GriffithSettings,
    rule: PaperRule,
    direction: float,
) -> np.ndarray:
    """The contact cells whose tension lies above the threshold by less than CG's error in the
    pressures and falls along the direction of travel (x1 times the direction positive: p
    rises): at the threshold and leaving it, so they stay.  Without adhesion (sigma_c = 0) a
    cell that re-attaches as its gap closes carries a pressure of zero, to CG's noise, and
    would otherwise leave again at once.  Asked only where some tension may fall
    (``_tensions_rise``); there a decided state has no leaving cell in that band whose tension
    may fall (``early_decision`` waits for it)."""
    tension = -solution.pressure(approach)
    noise = _pressure_noise(problem, solution.contact, approach, settings)
    return (tension < rule.threshold(settings.tie_tolerance) + noise) & (solution.pressure_per_approach * direction > 0)


def early_decision(
    problem: Problem, approach: float, settings: GriffithSettings, rule: DetachmentRule, direction: float = -1.0
) -> Decision | None:
    """For a cascade at ``approach`` on a flat face under the paper's rule: a test whether an
    unfinished solve of a contact set already fixes the cascade's next pass, i.e. every tension
    and every free gap lies farther from its threshold than its error bound, and some element
    certainly leaves.  Then the pass (``cascade``) detaches and attaches exactly the elements it
    would after a full solve.  While pulling under ``Problem.walk_bounds`` the test asks for no
    gaps, every free gap being open there, and only for the tensions at or above the threshold
    to be certain: the pass may then keep a cell that a full solve would detach, which leaves
    in a later pass instead, and the cascade ends at the same contact set.  The test is
    ``decide(contact, x1, displacement, error, displacement_error=None)``
    (``bem_griffith.contact_set.Decision``): ``error`` bounds each pressure's error,
    ``displacement_error`` each free displacement's (by default ``kernel_norm * error``).  None
    where it does not apply.  ``direction`` is the cascade's direction of travel (-1 pulling):
    where tensions may fall along it (``_tensions_rise`` false: pressing, or a kernel without
    the walk property) the test declines while a leaving cell may lie within CG's pressure
    error (``_pressure_noise``, plus the iterate's own) of the threshold and its tension may
    fall, since the pass then needs that cell's x1 (``_falling_at_threshold``).  On a flat face
    the iterate is x1, to within ``error``, so a leaver whose tension certainly rises passes; on
    a curved face it is p / d, which says nothing of x1."""
    if not (settings.decide_early and isinstance(rule, PaperRule) and approach != 0):
        return None
    threshold = rule.threshold(settings.tie_tolerance)
    gap_tolerance = _gap_tolerance(problem, approach)
    # where the lattice's C^-1 is a random walk's, while a flat face is pulled (d < 0): a free
    # cell's displacement per approach is the walk's chance of ever meeting the contact set, below
    # one, so each free gap (1 - u) |d| is open and none needs checking, nor computing; and a
    # tension only grows as other cells leave, so a cell below the threshold may stay undecided:
    # if it truly reaches the threshold it leaves in a later pass, and the cascade ends at the
    # same set (the largest that holds), only the passes that lead there differ
    walk = problem.walk_bounds and approach < 0 and problem.flat
    rising = _tensions_rise(problem, direction)  # none is kept at the threshold as falling

    def decide(
        contact: np.ndarray, x1: np.ndarray, displacement, error: float, displacement_error: float | None = None
    ) -> bool:
        # x1 is the pressure per approach on a flat face; on a curved one the pressure at this
        # approach over it (``solve_contact_set``): either way the tension is -d x1
        tension = -approach * x1
        # a decided state carries x1 (on a curved face, p / d) with no profile part: its cells'
        # round-off is that of d x1 alone, as the pass computes it
        distance = tension - (threshold - pressure_roundoff(approach, x1))
        leaving = distance >= 0  # as the pass detaches (``PaperRule.detaching``)
        if not leaving.any():
            return False  # nothing leaves (this set may hold)
        if not rising:
            # a leaver whose tension may lie within CG's noise of the threshold (the iterate's
            # error added) stays in the pass if it falls: the pass needs its x1, which a flat
            # face's iterate is, to within ``error``; a curved face's is p / d
            noise = _pressure_noise(problem, contact, approach, settings) + abs(approach) * error
            near = tension[leaving] < threshold + noise
            if problem.flat:
                near &= ~(x1[leaving] * direction < -error)  # certainly rising
            if near.any():
                return False
        if np.abs(distance[leaving] if walk else distance).min() <= abs(approach) * error:
            return False  # a tension is too close to call
        free = problem.face & ~contact
        if walk or not free.any():
            return True
        gap = (displacement()[free] - 1.0) * approach + problem.height[free]
        if displacement_error is None:  # Cauchy-Schwarz on each row of C
            displacement_error = problem.kernel_norm * error
        gap_error = abs(approach) * displacement_error
        # each free gap certainly open (> tolerance) or certainly closed (< -open tolerance): the
        # pass then leaves or re-attaches it whichever way the gap moves
        closed = -_open_tolerance(problem, contact, approach, settings) - gap_error
        return bool(np.all((gap > gap_tolerance + gap_error) | (gap < closed)))

    return decide


def cascade(
    problem: Problem,
    solution: ContactSolution,
    approach: float,
    settings: GriffithSettings,
    counters: WorkCounters,
    messages: list,
    direction: float = -1.0,
    rule: DetachmentRule | None = None,
) -> ContactSolution:
    """Detach / re-attach at the fixed approach until no element meets the detachment
    ``rule`` (default: Eq. 22, sigma_c) and no gap is negative; returns ``solution`` itself
    when nothing changes.

    A free element whose gap is zero (to round-off) re-attaches when the gap is closing along
    the direction of travel: that is the gap event that brought the driver here."""
    rule = PaperRule(problem.critical_stress) if rule is None else rule
    decide = early_decision(problem, approach, settings, rule, direction)
    # a pass that comes back to a set already left at this approach would repeat its passes
    # for ever (cells flipping between the two rules): stop there, and say so
    visited = {np.packbits(solution.contact).tobytes()}
    for _ in range(4 * problem.face_elements + 10):
        detaching = rule.detaching(solution, approach, settings.tie_tolerance)
        if isinstance(rule, PaperRule) and detaching.any() and not _tensions_rise(problem, direction):
            detaching &= ~_falling_at_threshold(problem, solution, approach, settings, rule, direction)
        if solution.displacement_in_window:
            # decided with every free gap known to be open (early_decision): none closes
            free = problem.face & ~solution.contact
            attaching = np.zeros(int(free.sum()), bool)
        else:
            free, slope, offset = gap_coefficients(problem, solution)
            gap = slope * approach + offset
            gap_tolerance = _gap_tolerance(problem, approach)
            # a closing gap re-attaches at zero, to its round-off; an opening one only once it
            # lies further below zero than CG's error in the displacements explains
            closed = -_open_tolerance(problem, solution.contact, approach, settings)
            attaching = (gap < closed) | ((gap <= gap_tolerance) & (slope * direction < 0))
        if not detaching.any() and not attaching.any():
            return solution
        contact = solution.contact.copy()
        contact.ravel()[np.flatnonzero(solution.contact.ravel())[detaching]] = False
        contact.ravel()[np.flatnonzero(free.ravel())[attaching]] = True
        counters.detached_elements += int(detaching.sum())
        if not contact.any():
            return no_contact(problem)
        if _certainly_detached(problem, contact, approach, settings):
            counters.cascades_cut += 1
            return no_contact(problem)
        key = np.packbits(contact).tobytes()
        if key in visited:
            messages.append(
                f"cascade at d = {approach:.6g} came back to a contact set of {int(contact.sum())} elements "
                f"it had left: the pull stops there"
            )
            counters.cycled_cascades += 1
            break
        visited.add(key)
        solution = solve_contact_set(problem, contact, settings, solution, counters, decide, approach)
    else:
        messages.append(f"cascade at d = {approach:.6g} did not settle")
    counters.unsettled_cascades += 1
    if solution.displacement_in_window or solution.at_approach is not None:
        # the caller reads the gaps of the whole face, linear in the approach
        solution = solve_contact_set(problem, solution.contact, settings, solution, counters)
    return solution


def pull_targets(scene: Scene, pressed_approach: float, problem: Problem) -> tuple[list[float], bool]:
    """Target approaches: the turning points, then the final pull; and whether the final
    target is a user limit (so reaching it attached is reported, not an error)."""
    limit = scene.loading.pull_limit
    if limit is not None:
        final, user = limit, True
    else:
        # far beyond any detachment the bounds allow (flat) or the press depth (curved)
        scale = abs(pressed_approach) + problem.spacing
        if problem.circle_critical_approach is not None:
            scale += abs(problem.circle_critical_approach(float(problem.face.sum()) * problem.cell_area))
        final, user = pressed_approach - 1e3 * scale, False
    return [*scene.loading.turning_points, final], user


def _next_approach(
    problem: Problem,
    solution: ContactSolution,
    approach: float,
    target: float,
    settings: GriffithSettings,
    rule: DetachmentRule,
) -> float:
    if settings.driver == "event":
        return next_event(problem, solution, approach, target, rule)
    assert settings.step is not None  # GriffithSettings requires a step for the fixed-step driver
    step = settings.step if target > approach else -settings.step
    return approach + step if (approach + step - target) * np.sign(step) < 0 else target


def pull(
    problem: Problem,
    scene: Scene,
    settings: GriffithSettings,
    counters: WorkCounters,
    pressed_approach: float,
    pressed: ContactSolution,
    recorder: PullRecorder,
) -> PullOutcome:
    """Drive the approach through the scene's turning points to the final pull, cascading at
    every event (or step), until the face detaches, the final target is reached or the event
    limit stops it; every curve point and snapshot goes to ``recorder``."""
    targets, reached_user_limit = pull_targets(scene, pressed_approach, problem)
    outcome = PullOutcome(final=pressed, reached_user_limit=reached_user_limit)
    max_events = 20 * problem.face_elements + 1000
    solution, approach = pressed, pressed_approach
    rule = detachment_rule(problem, scene, settings, counters)
    for target in targets:
        while solution.attached and approach != target:
            upcoming = _next_approach(problem, solution, approach, target, settings, rule)
            recorder.snapshots_between(approach, upcoming, solution)
            previous, approach = approach, upcoming
            before = solution
            if settings.driver == "event":
                # admissible: at an event the first element sits exactly at sigma_c (a peak)
                recorder.point(approach, solution)
            solution = cascade(
                problem,
                solution,
                approach,
                settings,
                counters,
                outcome.messages,
                1.0 if target > previous else -1.0,
                rule,
            )
            if solution is not before:
                if not solution.attached:
                    # with the fields when the scene asks for them (Outputs.fields: "at pull-off")
                    outcome.last_stable = recorder.snapshot(approach, before)
                    outcome.detachment_approach = approach
                recorder.point(approach, solution)
            elif settings.driver == "fixed_step":
                # the paper's driver: the force after the step's cascade
                recorder.point(approach, solution)
            outcome.events += 1
            if counters.cycled_cascades:
                outcome.aborted = True
                break
            if outcome.events > max_events:
                outcome.messages.append(f"stopped after {outcome.events} events without detaching")
                outcome.aborted = True
                break
        if not solution.attached or outcome.aborted:
            break
    messages, outcome.rule_info = rule.report(recorder.approach[recorder.peak()])
    outcome.messages.extend(messages)
    outcome.final = solution
    return outcome
