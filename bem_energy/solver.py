"""Pull-off by energy minimisation: continuation along the attached branch.

The punch is pressed without adhesion (as in the Griffith solver), then adhesion is switched
on and the approach d is lowered in steps, each minimisation warm-started from the previous
state extrapolated along the branch (starting from U = 0 would fall onto the detached branch).
The punch is attached while some face cell lies within the range rho of the potential; the
step that loses the last such cell is the snap-off, located by bisection between the last
attached and the first detached approach, each trial starting from the last attached state.
"""
from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy import optimize

from contact_scene import Curve, Grid, Homogeneous, Result, Scene, SceneError, Snapshot, theory
from contact_scene.materials import PowerLawGraded

from .minimisers import Minimum, minimise
from .potentials import (PROCESS_ZONE_ELEMENTS, Potential, process_zone_exponent, process_zone_length,
                         process_zone_modulus, range_for_process_zone)
from .problem import EnergyProblem, build_problem
from .settings import EnergySettings

__all__ = ["pull_off", "default_potential", "unresolved_process_zone", "finite_range_grid"]

log = logging.getLogger("bem_energy")


def default_potential(scene: Scene) -> Potential | None:
    ad = scene.adhesion
    if ad.work_of_adhesion <= 0:
        return None
    if ad.range is None:
        raise SceneError("adhesion.range", "a finite-range run needs a range > 0 (None means the zero-range limit)")
    return Potential(ad.work_of_adhesion, ad.range, ad.potential)


def unresolved_process_zone(scene: Scene, prob: EnergyProblem, potential: Potential) -> str | None:
    """Why the grid is too coarse for the process zone (None when it is fine): below the
    potential's fewest elements per l_c (:data:`PROCESS_ZONE_ELEMENTS`) the zone is trapped by
    the mesh and the pull-off force overshoots, e.g. 2.4 x Kendall at 0.08 elements per l_c."""
    need = PROCESS_ZONE_ELEMENTS[potential.kind][0]
    lc = prob.process_zone
    per = lc / prob.spacing
    if per >= need * (1 - 1e-9):
        return None
    a = scene.indenter.shape.equivalent_radius
    formula = "E* rho^2 / w" if prob.exponent == 0 else f"(E_k rho^2 / w)^(1/(1-k)), k = {prob.exponent:g}"
    return (f"the grid has {per:.3g} elements per process zone l_c = {lc:.3g} ({formula}, {lc / a:.3g} a); "
            f"the {potential.kind} potential needs at least {need:g}, below which the result is trapped by the mesh: "
            f"use --resolution {math.ceil(need * a / lc * (1 - 1e-9)):d} or more (elements per radius sqrt(A/pi)), "
            "or a longer range")


#: the largest raster side a finite-range run picks by itself (the padded FFT grid is twice
#: that): a pull-off's time grows about 4x per doubling of the elements per radius N (l_c =
#: 0.02 a: 36, 152, 572 s at 50, 100, 200 per radius, benchmarks/study_energy_process_zone.py),
#: so 1024 cells across (512 per radius for a circle) is about an hour, and past it the user
#: decides
MAX_DEFAULT_SIDE = 1024

#: elements per radius sqrt(A/pi) when the process zone asks for fewer (a long range, or no
#: adhesion): the staircase error of the face is then within 0.5 % (0.16 Delta / a)
DEFAULT_ELEMENTS_PER_RADIUS = 32.0


def finite_range_grid(scene: Scene, resolution: float | None = None) -> Grid:
    """The grid of a finite-range run: ``resolution`` elements per radius sqrt(A/pi) when
    given (a grid too coarse for the process zone is run and reported not converged), else
    the finer of 32 per radius and the potential's default elements per process zone
    (:data:`PROCESS_ZONE_ELEMENTS`).  A default grid wider than :data:`MAX_DEFAULT_SIDE`
    cells is refused, naming the shortest range that fits."""
    if resolution is not None:
        return Grid(elements_per_radius=resolution)
    shape = scene.indenter.shape
    a = shape.equivalent_radius
    h = a / DEFAULT_ELEMENTS_PER_RADIUS
    potential = default_potential(scene)
    if potential is None:
        return Grid(spacing=h)
    mat = scene.material
    E, k = process_zone_modulus(mat), process_zone_exponent(mat)
    lc = process_zone_length(modulus=E, work=potential.work, range=potential.range, exponent=k)
    per = PROCESS_ZONE_ELEMENTS[potential.kind][1]
    h = min(h, lc / per)
    xmin, ymin, xmax, ymax = shape.bounds
    width = max(xmax - xmin, ymax - ymin)
    side = math.ceil(width / h)
    if side > MAX_DEFAULT_SIDE:
        lc_min = per * width / MAX_DEFAULT_SIDE
        rho_min = range_for_process_zone(modulus=E, work=potential.work, length=lc_min, exponent=k)
        unit = 10.0 ** (math.floor(math.log10(rho_min)) - 2)
        rho_min = math.ceil(rho_min / unit * (1 - 1e-12)) * unit      # three digits, rounded up: it fits
        raise SceneError("adhesion.range", (
            f"range {potential.range:g} gives a process zone l_c = {lc:.3g} ({lc / a:.3g} a); resolving it "
            f"({per:g} elements per l_c for the {potential.kind} potential) needs a {side} x {side} grid "
            f"({a / h:.0f} elements per radius), wider than the {MAX_DEFAULT_SIDE} a run picks by itself "
            f"(an hour or more): use a range >= {rho_min:.3g} (l_c >= {lc_min / a:.3g} a), "
            "the zero-range limit (no range), "
            "or give --resolution (a grid too coarse for l_c is run but reported not converged)"))
    return Grid(spacing=h)


def critical_approach_scale(scene: Scene) -> float:
    """|d_c| of the circle of the face's area (Eq. 14 / Eq. 38): the scale of the pull."""
    w = scene.adhesion.work_of_adhesion
    area = scene.indenter.shape.area
    mat = scene.material
    if w <= 0:
        return 0.0
    if isinstance(mat, Homogeneous):
        return abs(theory.upper_bound_approach(E_star=mat.effective_modulus, work=w, area=area))
    assert isinstance(mat, PowerLawGraded)
    return abs(theory.graded_critical_approach(E0=mat.surface_modulus, c0=mat.reference_depth, k=mat.exponent,
                                               radius=math.sqrt(area / math.pi), work=w))


@dataclass
class _Stats:
    minimisations: int = 0
    iterations: int = 0
    evaluations: int = 0
    unconverged: int = 0
    worst_gradient: float = 0.0
    notes: list = field(default_factory=list)

    def add(self, m: Minimum, d: float):
        self.minimisations += 1
        self.iterations += m.iterations
        self.evaluations += m.evaluations
        self.worst_gradient = max(self.worst_gradient, m.gradient)
        if not m.converged:
            self.unconverged += 1
            if len(self.notes) < 5:
                self.notes.append(f"minimisation at d = {d:.6g} did not converge "
                                  f"(projected gradient {m.gradient:.3g}; {m.message})")


def _minimise(prob, U, d, adhesive, settings: EnergySettings, stats: _Stats) -> Minimum:
    m = minimise(prob, U, d, adhesive, method=settings.minimiser, gtol=settings.gtol,
                 max_iterations=settings.max_iterations, memory=settings.memory)
    stats.add(m, d)
    return m


def _contact(prob: EnergyProblem, m: Minimum, d: float) -> np.ndarray:
    """Face cells at the wall (on the padded grid)."""
    L = prob.potential.range if prob.potential is not None else max(abs(d), prob.spacing)
    C = np.zeros(prob.padded, bool)
    C[prob.face] = prob.gap(m.U, d) <= 1e-9 * L
    return C


def _attached(prob: EnergyProblem, m: Minimum, d: float, adhesive: bool) -> bool:
    """Some face cell within the range of the potential, or (without adhesion) at the wall."""
    if adhesive and prob.potential is not None:
        return bool(prob.gap(m.U, d).min() < prob.potential.range)
    return bool(_contact(prob, m, d).any())


def _press(prob: EnergyProblem, scene: Scene, settings: EnergySettings, stats: _Stats, d_scale: float):
    lo = scene.loading
    U = np.zeros(prob.padded)
    if lo.press_force is not None and lo.press_force > 0:
        target = lo.press_force
        state = {"U": U}

        def excess(d):
            m = _minimise(prob, state["U"], d, False, settings, stats)
            state["U"] = m.U
            return prob.force(m.P) - target

        hmin = float(prob.height.min())
        lo_d, hi_d = hmin, hmin + max(d_scale, prob.spacing)
        while excess(hi_d) < 0:
            lo_d, hi_d = hi_d, hmin + 2 * (hi_d - hmin)
        d0 = optimize.brentq(excess, lo_d, hi_d, xtol=1e-10 * (hi_d - hmin), rtol=1e-12)
        return d0, _minimise(prob, state["U"], d0, False, settings, stats)
    d0 = lo.press_approach if lo.press_approach is not None else 0.0
    if prob.height.size and d0 <= prob.height.min() and not scene.indenter.profile.is_flat:
        raise SceneError("loading.press_approach", f"approach {d0:g} brings no element of the face into contact")
    return d0, _minimise(prob, U, d0, False, settings, stats)


def _stiffness(prob, scene, d0, m0: Minimum, settings, stats, d_scale) -> float:
    """Initial slope of the non-adhesive force: exact for a flat face in full contact; a
    one-sided difference over 1e-3 of the press depth for a curved one."""
    if scene.indenter.profile.is_flat:
        dd = max(d_scale, prob.spacing)
        m1 = _minimise(prob, m0.U + dd * prob.face, d0 + dd, False, settings, stats)
        return (prob.force(m1.P) - prob.force(m0.P)) / dd
    dd = 1e-3 * max(d0 - float(prob.height.min()), prob.spacing)
    m1 = _minimise(prob, m0.U, d0 + dd, False, settings, stats)
    return (prob.force(m1.P) - prob.force(m0.P)) / dd


def _fold(points):
    """Vertex (d*, F*) of the parabola d = alpha F^2 + beta F + gamma through the three
    attached points closest to the fold; None if they do not bend toward one."""
    pts = sorted(set(points))[:3]          # smallest d: closest to the snap (pulling)
    if len(pts) < 3:
        return None
    d = np.array([p[0] for p in pts])
    F = np.array([p[1] for p in pts])
    if np.ptp(F) <= 0:
        return None
    Fm, Fs = F.mean(), np.ptp(F)
    x = (F - Fm) / Fs
    try:
        alpha, beta, gamma = np.linalg.solve(np.c_[x**2, x, np.ones(3)], d)
    except np.linalg.LinAlgError:
        return None
    if alpha == 0:
        return None
    xv = -beta / (2 * alpha)
    return float(gamma - beta**2 / (4 * alpha)), float(Fm + Fs * xv)


def pull_off(scene: Scene, settings: EnergySettings, *, spacing: float | None = None,
             potential: Potential | None = None, callback=None, max_memory_gb: float = 8.0) -> Result:
    """One finite-range pull-off (``potential`` defaults to the scene's adhesion)."""
    t0 = time.perf_counter()
    if settings.grid.periodic:
        raise SceneError("grid.periodic", "the energy method models the infinite (non-periodic) half-space only; "
                         "use periodic = false")
    potential = potential if potential is not None else default_potential(scene)
    h = spacing if spacing is not None else settings.grid.spacing_for(scene.indenter.shape)
    prob = build_problem(scene, h, potential, memory=settings.memory, max_memory_gb=max_memory_gb,
                         kernel=settings.kernel)
    if settings.minimiser == "cvxpy" and int(prob.face.sum()) > settings.max_face_elements_cvxpy:
        raise SceneError("settings.minimiser", f"cvxpy is for small grids: {int(prob.face.sum())} face elements "
                         f"> {settings.max_face_elements_cvxpy}; use lbfgsb or pk")
    stats = _Stats()
    msgs: list[str] = []
    d_scale = critical_approach_scale(scene)
    adhesive = potential is not None
    t1 = time.perf_counter()
    d0, m = _press(prob, scene, settings, stats, d_scale)
    stiffness = _stiffness(prob, scene, d0, m, settings, stats, d_scale)
    t2 = time.perf_counter()

    cell = prob.cell
    trace_d, trace_F, trace_A = [], [], []

    # the largest tension so far with the states on either side of it, for refining a smooth
    # maximum (finite range: the edge peels gradually and F(d) peaks before the snap)
    best = {"F": math.inf, "i": -1, "U": None, "before": None, "after": None}

    def record(d, mm, att=True):
        F = prob.force(mm.P)
        A = float(_contact(prob, mm, d).sum()) * cell
        if best["i"] == len(trace_d) - 1 and best["after"] is None:
            best["after"] = (float(d), att)
        if att and F < best["F"]:
            best.update(F=F, i=len(trace_d), U=mm.U, before=trace_d[-1] if trace_d else None, after=None)
        trace_d.append(float(d))
        trace_F.append(F)
        trace_A.append(A)
        if callback is not None:
            callback(float(d), F, A)

    if adhesive:
        m = _minimise(prob, m.U, d0, True, settings, stats)
    record(d0, m)

    rho = potential.range if adhesive else 0.0
    # the length scale of the pull: the critical approach and the range with adhesion (a grid
    # spacing would swamp both when w is tiny), the element without
    pull_scale = d_scale + rho if adhesive else prob.spacing
    span = abs(d0) + 2.0 * d_scale + 5.0 * rho + (0.0 if adhesive else prob.spacing)
    step = span / settings.steps
    user_limit = scene.loading.pull_limit is not None
    final = scene.loading.pull_limit if user_limit else -math.inf
    targets = [*scene.loading.turning_points, final]
    want = sorted(set(scene.outputs.snapshots), reverse=True)
    snaps: list[Snapshot] = []

    def snapshot(d, mm):
        C = prob.crop(_contact(prob, mm, d))
        p = u = None
        if scene.outputs.fields:
            p, u = prob.crop(mm.P).copy(), prob.crop(mm.U).copy()
        return Snapshot(float(d), prob.force(mm.P), C, prob.spacing, prob.origin, p, u)

    d = d0
    U_prev, d_prev = None, None
    attached = _attached(prob, m, d, adhesive)
    last_stable = None
    detach_d = None
    fold = None
    fold_index = -1
    max_steps = 20 * settings.steps + 100
    steps = 0
    for target in targets:
        while d != target:
            sign = 1.0 if target > d else -1.0
            d_next = d + sign * step
            if (d_next - target) * sign > 0:
                d_next = target
            between = [s for s in want if (s - d) * sign > 0 and (s - d_next) * sign <= 0]
            if between:
                d_next = between[0]
            # warm start: extrapolate along the branch (secant), then the minimiser projects
            U0 = m.U if U_prev is None else m.U + (m.U - U_prev) * ((d_next - d) / (d - d_prev))
            m_new = _minimise(prob, U0, d_next, adhesive, settings, stats)
            now = _attached(prob, m_new, d_next, adhesive)
            if attached and not now and sign < 0:
                # snap-off between d (attached) and d_next: bisect, always from the attached state
                d_att, m_att, d_det, m_det = d, m, d_next, m_new
                fold_points = [(trace_d[-2], trace_F[-2])] if len(trace_d) > 1 else []
                fold_points.append((d, prob.force(m.P)))
                tol = settings.snap_tolerance * pull_scale
                while d_att - d_det > tol:
                    d_mid = 0.5 * (d_att + d_det)
                    m_mid = _minimise(prob, m_att.U, d_mid, adhesive, settings, stats)
                    if _attached(prob, m_mid, d_mid, adhesive):
                        d_att, m_att = d_mid, m_mid
                        record(d_mid, m_mid)
                        fold_points.append((d_mid, prob.force(m_mid.P)))
                    else:
                        d_det, m_det = d_mid, m_mid
                fold = _fold(fold_points)
                fold_index = len(trace_d) - 1      # the last attached point on the curve
                last_stable = snapshot(d_att, m_att)
                detach_d = float(d_det)
                d_next, m_new = d_det, m_det
            for s in want:
                if s == d_next:
                    snaps.append(snapshot(d_next, m_new))
                    want.remove(s)
                    break
            U_prev, d_prev = m.U, d
            d, m, attached = d_next, m_new, now
            record(d, m, attached)
            steps += 1
            if not attached and target == final:
                break
            if steps > max_steps:
                msgs.append(f"stopped after {steps} steps at d = {d:.6g}, "
                            f"{'still attached' if attached else 'detached'}")
                break
        if steps > max_steps or (not attached and target == final):
            break
    t3 = time.perf_counter()

    F = np.array(trace_F)
    tensile = -F
    i = int(np.argmax(tensile))
    pulloff = float(max(tensile[i], 0.0))
    pulloff_d = float(trace_d[i])
    peak = "step"
    if (fold is not None and i == fold_index and -fold[1] >= pulloff and detach_d is not None
            and detach_d <= fold[0] <= pulloff_d):
        # the tension grows up to the snap-off, a fold of the attached branch where
        # F - F* ~ sqrt(d - d*): the bisection's last points locate F* to the square root of
        # its tolerance only, the vertex of the parabola d(F) through them to the tolerance
        pulloff_d, pulloff = float(fold[0]), float(-fold[1])
        peak = "fold"
    elif adhesive and best["before"] is not None and best["after"] is not None and best["after"][1]:
        # a smooth maximum between two recorded steps: Brent on F(d), warm-started there
        lo_d, hi_d = sorted((best["before"], best["after"][0]))
        extra = []

        def force_at(x):
            mm = _minimise(prob, best["U"], x, True, settings, stats)
            F_x = prob.force(mm.P)
            extra.append((float(x), F_x, float(_contact(prob, mm, x).sum()) * cell))
            return F_x

        tol = settings.snap_tolerance * pull_scale
        r = optimize.minimize_scalar(force_at, bounds=(lo_d, hi_d), method="bounded", options={"xatol": tol})
        if -r.fun > pulloff:
            pulloff, pulloff_d = float(-r.fun), float(r.x)
            peak = "refined"
        # keep the curve in loading order: the extra points belong between the neighbours
        j = best["i"]
        seg = sorted([(trace_d[k], trace_F[k], trace_A[k]) for k in (j - 1, j, j + 1)] + extra,
                     key=lambda t: t[0], reverse=trace_d[j - 1] > trace_d[j + 1])
        trace_d[j - 1:j + 2] = [t[0] for t in seg]
        trace_F[j - 1:j + 2] = [t[1] for t in seg]
        trace_A[j - 1:j + 2] = [t[2] for t in seg]
        F = np.array(trace_F)
    if attached and user_limit:
        msgs.append(f"still attached at the pull limit d = {scene.loading.pull_limit:g} (strong adhesion)")
    resolved = True
    if adhesive:
        note = unresolved_process_zone(scene, prob, potential)
        if note:
            msgs.append(note)
            resolved = False
    msgs.extend(stats.notes)
    if stats.unconverged > len(stats.notes):
        msgs.append(f"{stats.unconverged} minimisations did not converge in all")
    curve = Curve(np.array(trace_d), F, np.array(trace_A))
    info = {"minimiser": settings.minimiser, "minimisations": stats.minimisations,
            "evaluations": stats.evaluations, "grid": list(prob.n), "padded_grid": list(prob.padded),
            "face_elements": int(prob.face.sum()), "press_approach": float(d0), "peak": peak}
    if adhesive:
        info.update(range=potential.range, potential=potential.kind, process_zone=prob.process_zone,
                    process_zone_per_element=prob.process_zone / prob.spacing,
                    process_zone_elements_needed=PROCESS_ZONE_ELEMENTS[potential.kind][0])
    return Result(
        method="bem_energy",
        pulloff_force=pulloff,
        pulloff_approach=pulloff_d,
        stiffness=float(stiffness),
        converged=stats.unconverged == 0 and steps <= max_steps and resolved,
        grid_spacing=prob.spacing,
        curve=curve if scene.outputs.curve else None,
        detached=not attached,
        detachment_approach=detach_d,
        snapshots=tuple(snaps),
        last_stable=last_stable,
        iterations=stats.iterations,
        residual=stats.worst_gradient,
        timings={"setup": t1 - t0, "press": t2 - t1, "pull": t3 - t2},
        messages=tuple(msgs),
        info=info,
    )
