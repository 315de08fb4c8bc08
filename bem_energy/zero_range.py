"""The zero-range (JKR / Griffith) limit of the energy method.

A finite range rho gives a process zone l_c = E* rho^2 / w at the punch edge; the pull-off
force tends to the zero-range value as l_c / a -> 0, but only on grids that resolve the zone
(Delta <= l_c; coarser grids trap the zone and overshoot).  So each range runs on a grid with
a fixed number of elements per l_c, and the sequence is extrapolated (Richardson) in l_c.
"""
from __future__ import annotations

import logging
import math
import time
from dataclasses import replace

import numpy as np

from contact_scene import Grid, Result, Scene

from .potentials import Potential
from .settings import ZeroRangeSettings
from .solver import pull_off

__all__ = ["zero_range", "richardson"]

log = logging.getLogger("bem_energy")


def richardson(h: np.ndarray, F: np.ndarray, rate: float | None):
    """F(h) = F0 + c h^p through the finest points: (F0, p, estimate).

    With ``rate`` None and three or more points the rate is fitted through the three finest;
    the estimate is the change of F0 when the coarsest of those three is dropped and the
    fitted rate replaced by the nearest of 1/2 or 1 (the rates a cohesive zone at a crack tip
    produces: sqrt(l_c / a) while the zone is large, l_c / a asymptotically)."""
    h = np.asarray(h, float)
    F = np.asarray(F, float)
    order = np.argsort(h)[::-1]
    h, F = h[order], F[order]

    def two_point(h1, F1, h2, F2, p):
        q = (h1 / h2) ** p
        return F2 + (F2 - F1) / (q - 1.0)

    if rate is None and len(h) >= 3:
        (h1, h2, h3), (F1, F2, F3) = h[-3:], F[-3:]
        p = _fit_rate(h1, h2, h3, F1, F2, F3)
        if p is None:
            p = 1.0
            F0 = two_point(h2, F2, h3, F3, p)
            return F0, p, abs(F0 - F3)
        F0 = two_point(h2, F2, h3, F3, p)
        alt = two_point(h2, F2, h3, F3, 0.5 if abs(p - 0.5) < abs(p - 1.0) else 1.0)
        return F0, p, abs(F0 - alt)
    p = rate if rate is not None else 1.0
    F0 = two_point(h[-2], F[-2], h[-1], F[-1], p)
    est = abs(F0 - F[-1]) if len(h) < 3 else abs(F0 - two_point(h[-3], F[-3], h[-2], F[-2], p))
    return F0, p, est


def _fit_rate(h1, h2, h3, F1, F2, F3):
    """The rate p with (F1 - F2)/(F2 - F3) = (h1^p - h2^p)/(h2^p - h3^p); None when the
    differences are not of one sign (no asymptotic regime)."""
    from scipy.optimize import brentq

    a, b = F1 - F2, F2 - F3
    if a == 0 or b == 0 or (a > 0) != (b > 0):
        return None
    r = a / b

    def f(p):
        return (h1**p - h2**p) / (h2**p - h3**p) - r

    try:
        return float(brentq(f, 0.05, 4.0))
    except ValueError:
        return None


def zero_range(scene: Scene, settings: ZeroRangeSettings | None = None, *, callback=None) -> Result:
    settings = settings or ZeroRangeSettings()
    t0 = time.perf_counter()
    w = scene.adhesion.work_of_adhesion
    a = scene.indenter.shape.equivalent_radius
    E = _modulus(scene)
    runs = []
    for r in settings.ratios:
        lc = r * a
        rho = math.sqrt(lc * w / E)
        spacing = min(lc / settings.elements_per_process_zone, a / settings.minimum_elements_per_radius)
        es = replace(settings.energy, grid=Grid(spacing=spacing))
        log.info("bem_energy zero range: l_c/a = %g, rho = %.4g, Delta = %.4g", r, rho, spacing)
        res = pull_off(scene, es, spacing=spacing, potential=Potential(w, rho, settings.potential), callback=callback)
        runs.append((lc, rho, res))
    lcs = np.array([x[0] for x in runs])
    Fs = np.array([x[2].pulloff_force for x in runs])
    ds = np.array([x[2].pulloff_approach for x in runs])
    F0, p, est = richardson(lcs, Fs, settings.rate)
    d0, _, d_est = richardson(lcs, ds, p)
    finest = runs[-1][2]
    msgs = [f"zero-range limit by Richardson extrapolation in l_c (rate {p:.3g}) over l_c/a = "
            + ", ".join(f"{r:g}" for r in settings.ratios)
            + f"; the curve and fields are those of the finest range (rho = {runs[-1][1]:.4g})"]
    for lc, rho, res in runs:
        msgs.extend(f"[l_c/a = {lc / a:g}] {m}" for m in res.messages)
    ok = all(x[2].converged and x[2].detached for x in runs) and math.isfinite(F0) and F0 > 0
    if not (math.isfinite(F0) and F0 > 0):
        msgs.append("the extrapolation failed; the pull-off force reported is that of the finest range")
        F0, est = finest.pulloff_force, math.inf
    t1 = time.perf_counter()
    timings = {"setup": 0.0, "press": 0.0, "pull": 0.0}
    for _, _, res in runs:
        for k, v in res.timings.items():
            timings[k] = timings.get(k, 0.0) + v
    timings["extrapolation"] = max(0.0, (t1 - t0) - sum(timings.values()))
    return replace(
        finest,
        pulloff_force=float(F0),
        pulloff_approach=float(d0) if math.isfinite(d0) else finest.pulloff_approach,
        converged=ok,
        accuracy_estimate=float(est / F0) if math.isfinite(est) and F0 > 0 else None,
        iterations=sum(x[2].iterations for x in runs),
        timings=timings,
        messages=tuple(msgs),
        info={**finest.info, "zero_range": {
            "process_zone_ratios": [float(r) for r in settings.ratios],
            "ranges": [float(x[1]) for x in runs],
            "spacings": [float(x[2].grid_spacing) for x in runs],
            "pulloff_forces": Fs.tolist(), "pulloff_approaches": ds.tolist(),
            "rate": float(p), "approach_estimate": float(d_est)}},
    )


def _modulus(scene: Scene) -> float:
    from contact_scene import Homogeneous

    mat = scene.material
    return mat.effective_modulus if isinstance(mat, Homogeneous) else mat.surface_modulus
