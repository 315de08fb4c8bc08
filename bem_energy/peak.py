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

__all__ = ["SnapOff", "PullOffPoint", "locate_snap_off", "fold_vertex", "force_maximum"]


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
) -> SnapOff:
    """Bisect between the attached state at ``d_att`` and the detached one at ``d_det`` until
    they are ``tolerance`` apart, every trial starting from the last attached state (a trial
    started from a detached one stays detached); attached trials join the loading path.
    Without ``locate_detachment`` the bisection stops as soon as attached states on the path
    bracket a smooth maximum of the tension, which then no longer depends on the snap-off."""
    fold_points = [(path.approach[-2], path.force[-2])] if len(path) > 1 else []
    fold_points.append((d_att, eq.force(m_att)))
    while d_att - d_det > tolerance:
        if not locate_detachment and path.largest.after is not None and path.largest.after[1]:
            break
        d_mid = 0.5 * (d_att + d_det)
        m_mid = eq.pulling_trial(m_att.U, d_mid, adhesive)
        if eq.attached(m_mid, d_mid, adhesive):
            d_att, m_att = d_mid, m_mid
            path.record(d_mid, m_mid)
            fold_points.append((d_mid, eq.force(m_mid)))
        else:
            d_det, m_det = d_mid, m_mid
    return SnapOff(float(d_att), m_att, float(d_det), m_det, fold_vertex(fold_points), len(path) - 1)


def _refine_smooth_maximum(eq: Equilibria, path: LoadingPath, tolerance: float) -> tuple[float, float]:
    """Brent on F(d) between the neighbours of the largest recorded tension, each trial warm-
    started from that state: (F, d) at the minimum found.  The trials join the loading path in
    loading order, between those neighbours."""
    largest = path.largest
    # force_maximum calls this only for a recorded state with neighbours on both sides
    assert largest.U is not None and largest.before is not None and largest.after is not None
    lower_d, upper_d = sorted((largest.before, largest.after[0]))
    extra = []

    start = largest.U

    def force_at(x):
        m = eq.minimum(start, x, True)
        F_x = eq.force(m)
        extra.append((float(x), F_x, eq.contact_area(m, x)))
        return F_x

    r = optimize.minimize_scalar(force_at, bounds=(lower_d, upper_d), method="bounded", options={"xatol": tolerance})
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
    eq: Equilibria, path: LoadingPath, snap: SnapOff | None, adhesive: bool, *, tolerance: float
) -> PullOffPoint:
    """The pull-off point of a finished loading path: the largest recorded tension, replaced
    by the fold's vertex when the tension grows up to the snap-off, or refined by Brent (to
    ``tolerance`` in d) when a smooth maximum lies between two attached states."""
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
        F, d = _refine_smooth_maximum(eq, path, tolerance)
        if -F > pulloff:
            return PullOffPoint(float(-F), d, "refined")
    return PullOffPoint(pulloff, pulloff_d, "step")
