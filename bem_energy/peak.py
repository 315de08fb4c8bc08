"""The force maximum and the snap-off of a pull.

Two kinds of maximum occur.  With a finite range the edge peels gradually and F(d) often
peaks before the snap: a smooth maximum, bracketed by recorded attached states and refined by
Brent's method on F(d).  Otherwise the tension grows up to the snap-off, a fold of the
attached branch where F - F* ~ sqrt(d - d*): bisection between the last attached and the
first detached approach locates the fold to its tolerance, F* only to the square root of it,
so the vertex of the parabola d(F) through the last attached points gives F*.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from scipy import optimize

from .equilibria import Equilibria
from .minimisers import Minimum

if TYPE_CHECKING:
    from .continuation import LoadingPath

__all__ = [
    "SnapOff",
    "PullOffPoint",
    "locate_snap_off",
    "fold_vertex",
    "force_maximum",
    "flattening_slope",
    "brent_tolerance",
]

#: the last secant slope of the tension must be below this fraction of the one before for the
#: attached points to count as flattening toward a smooth maximum (a clear bend, not the
#: path's jaggedness), which lets the snap-off search stop on a bound of the tension
FLATTENING = 0.5

#: the trial that should end the snap-off search goes this fraction of the way to where the
#: tension bound meets the tolerance, and only where that is at least 1/``CLOSEST`` of the
#: bracket's width
CLOSING, CLOSEST = 0.9, 8.0


@dataclass(frozen=True, eq=False)
class SnapOff:
    """The snap-off bracketed: the last attached and the first detached state, the fold's
    vertex (d*, F*) if the last attached points bend toward one, and the index on the loading
    path of the last attached point."""

    attached_approach: float
    attached_state: Minimum
    detached_approach: float
    detached_state: Minimum
    fold: tuple[float, float] | None
    fold_index: int


@dataclass(frozen=True)
class PullOffPoint:
    """The largest tension and its approach; ``kind`` says how it was found: ``"step"`` (a
    recorded state), ``"fold"`` (the vertex at the snap-off) or ``"refined"`` (Brent)."""

    force: float
    approach: float
    kind: str


def fold_vertex(points) -> tuple[float, float] | None:
    """Vertex (d*, F*) of the parabola d = alpha F^2 + beta F + gamma through the three
    attached points closest to the fold; None if they do not bend toward one."""
    pts = sorted(set(points))[:3]  # smallest d: closest to the snap (pulling)
    if len(pts) < 3:
        return None
    d = np.array([p[0] for p in pts])
    F = np.array([p[1] for p in pts])
    if np.ptp(F) <= 0:
        return None
    F_mean, F_span = F.mean(), np.ptp(F)
    x = (F - F_mean) / F_span
    try:
        alpha, beta, gamma = np.linalg.solve(np.c_[x**2, x, np.ones(3)], d)
    except np.linalg.LinAlgError:
        return None
    if alpha == 0:
        return None
    xv = -beta / (2 * alpha)
    return float(gamma - beta**2 / (4 * alpha)), float(F_mean + F_span * xv)


def flattening_slope(points) -> float | None:
    """The tension's slope (per unit of pull, 0 if negative) over the last two of the
    attached points ``points`` ((d, F) in pulling order), if the last three flatten clearly
    toward a smooth maximum (the last secant slope below ``FLATTENING`` times the one before,
    both measured in the direction of pulling); None otherwise (still rising steadily, as
    toward a fold).

    Where the tension is concave beyond the last point, it stays below the tangent there and
    so below the last point's tension plus this slope times the further pull.  That concavity
    is assumed, not checked: a tension that flattens and then steepens again into a fold
    within the bracket would break the bound."""
    if len(points) < 3:
        return None
    (d1, F1), (d2, F2), (d3, F3) = points[-3:]
    pull1, pull2 = d1 - d2, d2 - d3  # pulling lowers d
    if pull1 <= 0 or pull2 <= 0:
        return None
    s1, s2 = (F1 - F2) / pull1, (F2 - F3) / pull2  # tension = -F
    if s1 <= 0 or s2 >= FLATTENING * s1:
        return None
    return max(s2, 0.0)


def locate_snap_off(
    eq: Equilibria,
    path: LoadingPath,
    d_att: float,
    m_att: Minimum,
    d_det: float,
    m_det: Minimum,
    adhesive: bool,
    *,
    tolerance: float,
    locate_detachment: bool = True,
    force_tolerance: float | None = None,
    previous: tuple[float, np.ndarray] | None = None,
) -> SnapOff:
    """Bisect between the attached state at ``d_att`` and the detached one at ``d_det`` until
    they are ``tolerance`` apart, every trial starting from the last attached state (a trial
    started from a detached one stays detached), extrapolated along the secant from the
    attached state before it (``previous``, (d, U); the continuation's own predictor) when one
    is known: near the snap-off a trial's iterations go into relaxing the peeling front, and a
    start on that secant leaves less of it to relax.  Attached trials join the
    loading path.
    Without ``locate_detachment`` the bisection stops as soon as attached states on the path
    bracket a smooth maximum of the tension, which then no longer depends on the snap-off.

    With ``force_tolerance`` (relative to the largest tension) as well, it also stops once the
    last attached points flatten toward a smooth maximum (:func:`flattening_slope`) so that
    the tension between the last attached and the first detached state cannot exceed the
    largest recorded one by more than that fraction (the tangent bound of a tension assumed
    concave there).  While they flatten, the next trial goes ``CLOSING`` of the way to where
    that bound would meet the tolerance, if that lies between 1/``CLOSEST`` and half of the
    bracket's width from the attached state, else halfway: the trials that detach close to the
    snap-off creep for longest, so one such trial is cheaper than the bisection's several."""
    fold_points = [(path.approach[-2], path.force[-2])] if len(path) > 1 else []
    fold_points.append((d_att, eq.force(m_att)))
    while d_att - d_det > tolerance:
        if not locate_detachment and path.largest.after is not None and path.largest.after[1]:
            break
        d_mid = 0.5 * (d_att + d_det)
        if not locate_detachment and force_tolerance is not None:
            slope = flattening_slope(fold_points)
            largest = -path.largest.force  # the largest tension recorded
            if slope is not None and largest > 0:  # a relative tolerance needs a tension
                margin = largest * (1.0 + force_tolerance) + fold_points[-1][1]  # above the last tension
                if slope * (d_att - d_det) <= margin:
                    break
                # just inside the bound, so that a detached trial there ends the search; a
                # trial much closer than the bracket's width would mostly measure the path's
                # jaggedness in the next slope, so the bracket is halved until it is not
                reach = CLOSING * margin / slope  # slope > 0 here: a zero slope has stopped
                if reach >= (d_att - d_det) / CLOSEST:
                    d_mid = max(d_mid, d_att - reach)
        start = m_att.U
        if previous is not None and previous[0] != d_att:
            start = m_att.U + (m_att.U - previous[1]) * ((d_mid - d_att) / (d_att - previous[0]))
        m_mid = eq.pulling_trial(start, d_mid, adhesive)
        if eq.attached(m_mid, d_mid, adhesive):
            previous = (d_att, m_att.U)
            d_att, m_att = d_mid, m_mid
            path.record(d_mid, m_mid)
            fold_points.append((d_mid, eq.force(m_mid)))
        else:
            d_det, m_det = d_mid, m_mid
    return SnapOff(float(d_att), m_att, float(d_det), m_det, fold_vertex(fold_points), len(path) - 1)


def brent_tolerance(path: LoadingPath, tolerance: float, force_tolerance: float | None) -> float:
    """Brent's tolerance on the approach of a smooth maximum: ``tolerance``, or with
    ``force_tolerance`` (relative to the largest tension) the distance from the maximum at
    which the parabola through the largest recorded tension and its two neighbours has lost
    that fraction, if larger.  scipy's bounded Brent ends with the minimum within 2/3 of its
    ``xatol`` of the best point, so on that parabola the force found is within 4/9 of the
    tolerance."""
    j = path.largest.index
    if force_tolerance is None or j < 1 or j + 1 >= len(path):
        return tolerance
    d = np.array(path.approach[j - 1 : j + 2])
    F = np.array(path.force[j - 1 : j + 2])
    if not (d[0] - d[1]) * (d[1] - d[2]) > 0:  # neighbours on both sides, distinct
        return tolerance
    curvature = (
        2.0 * ((F[2] - F[1]) / (d[2] - d[1]) - (F[1] - F[0]) / (d[1] - d[0])) / (d[2] - d[0])
    )  # F'' of the parabola; a tension maximum is a minimum of F
    if not curvature > 0:
        return tolerance
    return max(tolerance, float(np.sqrt(2.0 * force_tolerance * abs(F[1]) / curvature)))


def _refine_smooth_maximum(
    eq: Equilibria, path: LoadingPath, tolerance: float, force_tolerance: float | None = None
) -> tuple[float, float]:
    """Brent on F(d) between the neighbours of the largest recorded tension, each trial warm-
    started from that state, to :func:`brent_tolerance`: (F, d) at the minimum found.  The
    trials join the loading path in loading order, between those neighbours."""
    largest = path.largest
    # force_maximum calls this only for a recorded state with neighbours on both sides
    assert largest.U is not None and largest.before is not None and largest.after is not None
    lower_d, upper_d = sorted((largest.before, largest.after[0]))
    xatol = brent_tolerance(path, tolerance, force_tolerance)
    extra = []

    start = largest.U

    def force_at(x):
        m = eq.minimum(start, x, True)
        F_x = eq.force(m)
        extra.append((float(x), F_x, eq.contact_area(m, x)))
        if path.callback is not None:  # a point of the curve (placed in loading order below)
            path.callback(*extra[-1])
        return F_x

    r = optimize.minimize_scalar(force_at, bounds=(lower_d, upper_d), method="bounded", options={"xatol": xatol})
    j = largest.index
    seg = sorted(
        [(path.approach[k], path.force[k], path.contact_area[k]) for k in (j - 1, j, j + 1)] + extra,
        key=lambda t: t[0],
        reverse=path.approach[j - 1] > path.approach[j + 1],
    )
    path.approach[j - 1 : j + 2] = [t[0] for t in seg]
    path.force[j - 1 : j + 2] = [t[1] for t in seg]
    path.contact_area[j - 1 : j + 2] = [t[2] for t in seg]
    return float(r.fun), float(r.x)


def force_maximum(
    eq: Equilibria,
    path: LoadingPath,
    snap: SnapOff | None,
    adhesive: bool,
    *,
    tolerance: float,
    force_tolerance: float | None = None,
) -> PullOffPoint:
    """The pull-off point of a finished loading path: the largest recorded tension, replaced
    by the fold's vertex when the tension grows up to the snap-off, or refined by Brent (to
    ``tolerance`` in d, or to :func:`brent_tolerance` with ``force_tolerance``) when a smooth
    maximum lies between two attached states."""
    tensile = -np.array(path.force)
    i = int(np.argmax(tensile))
    pulloff = float(max(tensile[i], 0.0))
    pulloff_d = float(path.approach[i])
    largest = path.largest
    if (
        snap is not None
        and snap.fold is not None
        and i == snap.fold_index
        and -snap.fold[1] >= pulloff
        and snap.detached_approach <= snap.fold[0] <= pulloff_d
    ):
        return PullOffPoint(float(-snap.fold[1]), float(snap.fold[0]), "fold")
    if adhesive and largest.before is not None and largest.after is not None and largest.after[1]:
        F, d = _refine_smooth_maximum(eq, path, tolerance, force_tolerance)
        if -F > pulloff:
            return PullOffPoint(float(-F), d, "refined")
    return PullOffPoint(pulloff, pulloff_d, "step")
