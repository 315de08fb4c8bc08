"""The loading path: continuation along the attached branch.

After the press, adhesion is switched on and the approach d moves in uniform steps toward
each turning point and then the final pull, each minimisation warm-started from the previous
state extrapolated along the branch (a start from U = 0 would fall onto the detached branch).
The punch is attached while some face cell lies within the range of the potential; a pulling
step that loses the last such cell crosses the snap-off, which :func:`peak.locate_snap_off`
then brackets.  The recorded curve keeps the largest tension of the attached states and its
neighbours, from which :mod:`peak` refines a smooth force maximum.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from contact_scene import Scene, Snapshot

from .equilibria import Equilibria
from .minimisers import Minimum
from .peak import SnapOff, locate_snap_off

__all__ = ["LoadingPath", "LargestTension", "PullOutcome", "pull", "snapshot"]


@dataclass
class LargestTension:
    """The attached state of largest tension recorded so far, with the approaches of the
    recorded states before and after it (``after``: approach and whether attached), which
    bracket a smooth maximum of the tension."""

    force: float = math.inf
    index: int = -1
    U: np.ndarray | None = None
    before: float | None = None
    after: tuple[float, bool] | None = None


class LoadingPath:
    """The curve in loading order: approach, force and contact area of every recorded state."""

    def __init__(self, eq: Equilibria, callback=None):
        self.eq = eq
        self.callback = callback
        self.approach: list[float] = []
        self.force: list[float] = []
        self.contact_area: list[float] = []
        self.largest = LargestTension()

    def __len__(self):
        return len(self.approach)

    def record(self, d: float, m: Minimum, attached: bool = True):
        F = self.eq.force(m)
        A = self.eq.contact_area(m, d)
        largest = self.largest
        if largest.index == len(self.approach) - 1 and largest.after is None:
            largest.after = (float(d), attached)
        if attached and F < largest.force:
            self.largest = LargestTension(
                F, len(self.approach), m.U, self.approach[-1] if self.approach else None, None
            )
        self.approach.append(float(d))
        self.force.append(F)
        self.contact_area.append(A)
        if self.callback is not None:
            self.callback(float(d), F, A)


def snapshot(eq: Equilibria, d: float, m: Minimum, fields: bool) -> Snapshot:
    prob = eq.prob
    contact = prob.crop(eq.contact(m, d))
    p = u = None
    if fields:
        p, u = prob.crop(m.P).copy(), prob.crop(m.U).copy()
    return Snapshot(float(d), eq.force(m), contact, prob.spacing, prob.origin, p, u)


@dataclass
class PullOutcome:
    """Where the loading path ended: the last state, the last snap-off crossed (None if the
    punch never detached while pulling), the snapshots asked for, and the continuation steps
    taken (``stopped``: the step limit ended the path)."""

    approach: float
    state: Minimum
    attached: bool
    snap_off: SnapOff | None
    snapshots: list[Snapshot] = field(default_factory=list)
    steps: int = 0
    stopped: bool = False
    messages: list[str] = field(default_factory=list)


def pull(
    eq: Equilibria,
    scene: Scene,
    path: LoadingPath,
    d0: float,
    m0: Minimum,
    adhesive: bool,
    *,
    step: float,
    snap_tolerance: float,
    max_steps: int,
) -> PullOutcome:
    """Continue from the pressed state (d0, m0) through the scene's turning points to its pull
    limit (or until detached), in steps of ``step``, stopping at requested snapshot approaches;
    a snap-off is bracketed to ``snap_tolerance`` (an approach)."""
    final = scene.loading.pull_limit if scene.loading.pull_limit is not None else -math.inf
    targets = [*scene.loading.turning_points, final]
    wanted = sorted(set(scene.outputs.snapshots), reverse=True)
    fields = scene.outputs.fields
    d, m = d0, m0
    U_prev, d_prev = None, None
    attached = eq.attached(m, d, adhesive)
    out = PullOutcome(d, m, attached, None)
    steps = 0
    for target in targets:
        while d != target:
            sign = 1.0 if target > d else -1.0
            d_next = d + sign * step
            if (d_next - target) * sign > 0:
                d_next = target
            between = [s for s in wanted if (s - d) * sign > 0 and (s - d_next) * sign <= 0]
            if between:
                d_next = between[0]
            # warm start: extrapolate along the branch (secant), then the minimiser projects
            U0 = m.U if U_prev is None or d_prev is None else m.U + (m.U - U_prev) * ((d_next - d) / (d - d_prev))
            m_new = (
                eq.pulling_trial(U0, d_next, adhesive) if attached and sign < 0 else eq.minimum(U0, d_next, adhesive)
            )
            now = eq.attached(m_new, d_next, adhesive)
            if attached and not now and sign < 0:
                snap = locate_snap_off(
                    eq,
                    path,
                    d,
                    m,
                    d_next,
                    m_new,
                    adhesive,
                    tolerance=snap_tolerance,
                    locate_detachment=eq.settings.locate_detachment,
                    force_tolerance=eq.settings.peak_tolerance,
                    previous=None if U_prev is None or d_prev is None else (d_prev, U_prev),
                )
                out.snap_off = snap
                d_next, m_new = snap.detached_approach, snap.detached_state
            for s in wanted:
                if s == d_next:
                    out.snapshots.append(snapshot(eq, d_next, m_new, fields))
                    wanted.remove(s)
                    break
            U_prev, d_prev = m.U, d
            d, m, attached = d_next, m_new, now
            path.record(d, m, attached)
            steps += 1
            if not attached and target == final:
                break
            if steps > max_steps:
                out.messages.append(
                    f"stopped after {steps} steps at d = {d:.6g}, {'still attached' if attached else 'detached'}"
                )
                break
        if steps > max_steps or (not attached and target == final):
            break
    out.approach, out.state, out.attached = d, m, attached
    out.steps, out.stopped = steps, steps > max_steps
    return out
