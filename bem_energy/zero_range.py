"""The zero-range (JKR / Griffith) limit of the energy method.

A finite range rho gives a process zone l_c = E* rho^2 / w at the punch edge; the pull-off
force tends to the zero-range value as l_c / a -> 0, but only on grids that resolve the zone
(Delta <= l_c; coarser grids trap the zone and overshoot).  So each range runs on a grid with
a fixed number of elements per l_c, and the sequence is extrapolated in l_c with a fitted
rate: the finite-range shortfall is not a power law with one exponent over the ranges a grid
can afford, and its local exponent differs between faces (see :func:`richardson`).
"""
from __future__ import annotations

import logging
import math
import time
from dataclasses import replace

import numpy as np

from contact_scene import Circle, Grid, Result, Scene, rasterise, theory

from .potentials import Potential, process_zone_exponent, process_zone_modulus, range_for_process_zone
from .settings import ZeroRangeSettings
from .solver import pull_off

__all__ = ["zero_range", "richardson", "COARSE_LIMIT"]

#: a sequence whose finest process zone is above this (in units of a) cannot see the cornered
#: faces' late convergence (their local rate passes 0.8 only below 0.04 a)
COARSE_LIMIT = 0.02

log = logging.getLogger("bem_energy")


def _lsq_fit(h, F, powers) -> tuple[float, float]:
    """Least squares F0 + sum c_i h^p_i: (F0, sum of squared residuals)."""
    A = np.c_[[np.ones(len(h))] + [h**p for p in powers]].T
    coef = np.linalg.lstsq(A, F, rcond=None)[0]
    return float(coef[0]), float(np.sum((A @ coef - F) ** 2))


def _lsq(h, F, powers) -> float:
    return _lsq_fit(h, F, powers)[0]


def _fit_free(h, F) -> tuple[float, float] | None:
    """Least-squares F0 + c h^p with the rate p fitted too (variable projection over p in
    [0.2, 2]); (F0, p), or None when the best p sits on a bound (no rate fits the data)."""
    from scipy.optimize import minimize_scalar

    def misfit(p):
        return _lsq_fit(h, F, [p])[1]

    lo, hi = 0.2, 2.0
    ps = np.linspace(lo, hi, 37)
    j = int(np.argmin([misfit(p) for p in ps]))
    a, b = ps[max(j - 1, 0)], ps[min(j + 1, len(ps) - 1)]
    p = float(minimize_scalar(misfit, bounds=(a, b), method="bounded", options={"xatol": 1e-10}).x)
    if p < lo + 1e-3 or p > hi - 1e-3:
        return None
    return _lsq(h, F, [p]), p


def richardson(h: np.ndarray, F: np.ndarray, rate: float | None = None):
    """Extrapolate F(h) to h = 0: (F0, rate, estimate).

    ``rate`` None (default): F0 + c h^p with p fitted as well (needs three points).  The
    apparent rate is not universal: over l_c / a = 0.32 ... 0.01 the circle's local rate rises
    from 0.3 to 0.6 and the square's from 0.4 to 0.95 (benchmarks/study_energy_zero_range.py),
    so a rate fixed from one face biases another.  A given ``rate``: least squares with that
    rate (the earlier default, 1/2, fits the circle over 0.32 ... 0.04 only).

    The estimate is the largest change of F0 under other reasonable models of the same data:
    the two-term F0 + c1 h^(1/2) + c2 h, the free-rate fit of the finest three points and of
    all but the finest (each when the points allow), or with a fixed rate, leaving out the
    coarsest or the finest point and adding a second term h^(2 rate).  It is a spread, not a
    bound; with two points it is |F0 - F_finest|."""
    h = np.asarray(h, float)
    F = np.asarray(F, float)
    order = np.argsort(h)[::-1]
    h, F = h[order], F[order]
    n = len(h)
    if rate is None and n >= 3:
        fit = _fit_free(h, F)
        if fit is None:
            F0, used = _lsq(h, F, [0.5, 1.0]), None
            alts = []
        else:
            F0, used = fit
            alts = [_lsq(h, F, [0.5, 1.0])]
        if n >= 4:
            for sub in (slice(n - 3, n), slice(0, n - 1)):
                f = _fit_free(h[sub], F[sub])
                if f is not None:
                    alts.append(f[0])
        est = max((abs(F0 - x) for x in alts), default=abs(F0 - F[-1]))
        return float(F0), used, float(est)
    used = 0.5 if rate is None else float(rate)
    F0 = _lsq(h, F, [used])
    if n >= 3:
        est = max(abs(F0 - _lsq(h[1:], F[1:], [used])), abs(F0 - _lsq(h[:-1], F[:-1], [used])))
    else:
        est = abs(F0 - F[-1])
    if n >= 4:
        est = max(est, abs(F0 - _lsq(h, F, [used, 2 * used])))
    return F0, used, float(est)


def zero_range(scene: Scene, settings: ZeroRangeSettings | None = None, *, callback=None) -> Result:
    settings = settings or ZeroRangeSettings()
    t0 = time.perf_counter()
    w = scene.adhesion.work_of_adhesion
    a = scene.indenter.shape.equivalent_radius
    E = process_zone_modulus(scene.material)
    k = process_zone_exponent(scene.material)
    runs = []
    for r in settings.ratios:
        lc = r * a
        rho = range_for_process_zone(modulus=E, work=w, length=lc, exponent=k)
        spacing = min(lc / settings.elements_per_process_zone, a / settings.minimum_elements_per_radius)
        es = replace(settings.energy, grid=Grid(spacing=spacing))
        log.info("bem_energy zero range: l_c/a = %g, rho = %.4g, Delta = %.4g", r, rho, spacing)
        res = pull_off(scene, es, spacing=spacing, potential=Potential(w, rho, settings.potential), callback=callback)
        runs.append((lc, rho, res))
    lcs = np.array([x[0] for x in runs])
    raw = np.array([x[2].pulloff_force for x in runs])
    ds = np.array([x[2].pulloff_approach for x in runs])
    if settings.normalise_area:
        # each range runs on its own grid, whose staircase face differs in area by up to a few
        # per cent (the square: -1.4 % at 50, +0.85 % at 100 per radius); F ~ A^((3+k)/4) for a
        # face scaled in size, so without this the extrapolation fits staircase noise
        areas = np.array([rasterise(scene.indenter.shape, x[2].grid_spacing).area for x in runs])
        Fs = theory.force_at_nominal_area(raw, area=areas, nominal_area=scene.indenter.shape.area, k=k)
    else:
        Fs = raw
    F0, used_rate, est = richardson(lcs, Fs, settings.rate)
    finest = runs[-1][2]
    how = "fitted" if settings.rate is None else "fixed"
    msgs = [f"zero-range limit by extrapolation in l_c (rate {how}: "
            + ("none fits, two-term sqrt + linear fit" if used_rate is None else f"{used_rate:.3g}")
            + ") over l_c/a = " + ", ".join(f"{r:g}" for r in settings.ratios)
            + (", forces scaled to the nominal face area" if settings.normalise_area else "")
            + f"; the curve, fields and pull-off approach are those of the finest range (rho = {runs[-1][1]:.4g}): "
            "the approach at the force maximum of a finite range does not tend to the zero-range one "
            "over this sequence (the maximum is broad and moves outward as the edge zone opens)"]
    if min(settings.ratios) > COARSE_LIMIT and not isinstance(scene.indenter.shape, Circle):
        msgs.append(f"the sequence stops at l_c = {min(settings.ratios):g} a: faces with corners converge faster "
                    "than the circle below 0.04 a, and such a sequence overshoots their zero-range limit by up to "
                    "7 % (square, triangle: benchmarks/study_energy_zero_range.py); the default sequence reaches 0.01 a")
    for lc, rho, res in runs:
        msgs.extend(f"[l_c/a = {lc / a:g}] {m}" for m in res.messages)
    ok = all(x[2].converged and x[2].detached for x in runs) and math.isfinite(F0) and F0 > 0
    if not (math.isfinite(F0) and F0 > 0):
        msgs.append("the extrapolation failed; the pull-off force reported is that of the finest range")
        F0, est = finest.pulloff_force, math.inf
    t1 = time.perf_counter()
    timings = {"setup": 0.0, "press": 0.0, "pull": 0.0}
    for _, _, res in runs:
        for phase, v in res.timings.items():
            timings[phase] = timings.get(phase, 0.0) + v
    timings["extrapolation"] = max(0.0, (t1 - t0) - sum(timings.values()))
    return replace(
        finest,
        pulloff_force=float(F0),
        converged=ok,
        accuracy_estimate=float(est / F0) if math.isfinite(est) and F0 > 0 else None,
        iterations=sum(x[2].iterations for x in runs),
        timings=timings,
        messages=tuple(msgs),
        info={**finest.info, "zero_range": {
            "process_zone_ratios": [float(r) for r in settings.ratios],
            "ranges": [float(x[1]) for x in runs],
            "spacings": [float(x[2].grid_spacing) for x in runs],
            "pulloff_forces": Fs.tolist(), "raw_pulloff_forces": raw.tolist(), "pulloff_approaches": ds.tolist(),
            "rate": settings.rate, "fitted_rate": used_rate if settings.rate is None else None,
            "coarse": min(settings.ratios) > COARSE_LIMIT}},
    )
