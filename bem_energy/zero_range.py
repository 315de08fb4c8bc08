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
from dataclasses import fields, replace
from typing import TypedDict, cast

import numpy as np

from contact_scene import Circle, Grid, Result, Scene, SolverStats, rasterise, theory

from .error_model import error_bars
from .potentials import (
    PROCESS_ZONE_ELEMENTS,
    Potential,
    graded_zone_elements,
    process_zone_exponent,
    process_zone_modulus,
    range_for_process_zone,
)
from .settings import ZeroRangeSettings
from .solver import EnergyInfo, pull_off

__all__ = [
    "zero_range",
    "sequence_range",
    "sequence_run",
    "richardson",
    "tail_bracket",
    "ZeroRangeInfo",
    "SequenceInfo",
    "COARSE_LIMIT",
    "RATE_BRACKET",
    "tail_rates",
]

#: a sequence whose finest process zone is above this (in units of a) cannot see the cornered
#: faces' late convergence (their local rate passes 0.8 only below 0.04 a)
COARSE_LIMIT = 0.02

log = logging.getLogger("bem_energy")


class SequenceInfo(TypedDict):
    """The finite ranges behind a zero-range limit, coarsest first: their process zones l_c / a,
    ranges, grid spacings and pull-off forces (scaled to the nominal face area when the
    settings ask for it, and raw) and approaches; the extrapolation's rate (given, or fitted:
    None when no single rate fitted) and whether the sequence stops above :data:`COARSE_LIMIT`."""

    process_zone_ratios: list[float]
    ranges: list[float]
    spacings: list[float]
    pulloff_forces: list[float]
    raw_pulloff_forces: list[float]
    pulloff_approaches: list[float]
    rate: float | None
    fitted_rate: float | None
    coarse: bool


class ZeroRangeInfo(EnergyInfo):
    """``Result.info`` of a zero-range limit: the finest range's :class:`EnergyInfo` and the sequence.

    The sequence (:class:`SequenceInfo`: process zones, ranges, spacings, forces scaled and raw,
    approaches, the rate used) is under ``"zero_range"``.
    """

    zero_range: SequenceInfo


def _sum_stats(results) -> SolverStats:
    """The work of a sequence of solves: every counter summed over it (the unknowns too: the
    problem sizes of all the ranges solved)."""
    return SolverStats(**{f.name: sum(getattr(r.stats, f.name) for r in results) for f in fields(SolverStats)})


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

    p_min, p_max = 0.2, 2.0
    ps = np.linspace(p_min, p_max, 37)
    j = int(np.argmin([misfit(p) for p in ps]))
    a, b = ps[max(j - 1, 0)], ps[min(j + 1, len(ps) - 1)]
    p = float(minimize_scalar(misfit, bounds=(a, b), method="bounded", options={"xatol": 1e-10}).x)
    if p < p_min + 1e-3 or p > p_max - 1e-3:
        return None
    return _lsq(h, F, [p]), p


#: the effective rate q of the shortfall left beyond the finest range (see :func:`tail_bracket`)
#: is taken to lie in this bracket: from a smooth edge's sqrt(l_c) (the circle's tail rate is
#: 0.50 ... 0.58 at l_c <= 0.08 a) to the third order of an expansion in sqrt(l_c / a); a
#: bracket ending at 1 is too narrow (the square's tail passes 1 below 0.04 a; see richardson)
RATE_BRACKET = (0.5, 1.5)

#: the coarsest finest-range l_c / a of the windows the estimate is validated on: at 0.16 a the
#: circle's tail rate is 0.45, below the bracket
VALIDATED_FINEST_RATIO = 0.08


def tail_bracket(h, F, rates: tuple[float, float] = RATE_BRACKET) -> tuple[float, float]:
    """The zero-range values the last step of the sequence allows: B(q) = F_n + (F_n - F_(n-1)) /
    (t^q - 1) for q at either end of ``rates``, t = h_(n-1) / h_n (the finest two points).

    The shortfall left beyond the finest range is S = F(0) - F_n; writing it as the last step
    over t^q - 1 defines the tail's effective rate q: the power of a pure power law, and between
    the smallest and the largest power of a sum of power laws of one sign.  If q lies in ``rates``
    the limit lies between the two values returned (in that order: slowest rate first)."""
    h = np.asarray(h, float)
    F = np.asarray(F, float)
    order = np.argsort(h)[::-1]
    h, F = h[order], F[order]
    t = h[-2] / h[-1]
    step = F[-1] - F[-2]
    low, high = (float(F[-1] + step / (t**q - 1.0)) for q in rates)
    return low, high


def tail_rates(exponent: float = 0.0) -> tuple[float, float]:
    """The bracket of tail rates for a body of grading k: :data:`RATE_BRACKET` with its slow end
    scaled by (1 - k) for k > 0.  A smooth edge's shortfall goes like (l_c / a)^((1-k)/2) (the
    edge field's exponent, sqrt(l_c) at k = 0): the flat circle at k = 0.5 steps down by a
    factor of about 2^0.25 per halving of l_c (benchmarks/study_graded_shape_ratio.py
    --zero-range).  The fast end is kept, which widens the bracket."""
    lo, hi = RATE_BRACKET
    return (lo * (1.0 - exponent), hi) if exponent > 0 else (lo, hi)


def richardson(h: np.ndarray, F: np.ndarray, rate: float | None = None, rates: tuple[float, float] = RATE_BRACKET):
    """Extrapolate F(h) to h = 0 and estimate the error of the extrapolation.

    ``rate`` None (default): F0 + c h^p with p fitted as well (needs three points); when no
    rate in [0.2, 2] fits, the two-term F0 + c1 h^(1/2) + c2 h (rate None).  The apparent rate
    is not universal: over l_c / a = 0.32 ... 0.01 the circle's local rate rises from 0.3 to
    0.6 and the square's from 0.4 to 0.95 (benchmarks/study_energy_zero_range.py), so a rate
    fixed from one face biases another.  A given ``rate``: least squares with that rate.

    The estimate bounds abs(F0 - F(0)) if the tail's effective rate (:func:`tail_bracket`) lies in
    ``rates`` (:data:`RATE_BRACKET`; :func:`tail_rates` on a graded body): it is the larger
    distance from F0 to the two limits the finest step then allows, so it covers a limit
    anywhere between them whichever procedure gave F0 (a fitted rate that overshoots, as the
    circle's 0.3 over its coarse ranges does, widens it).
    It is of the order of the last step, F_n - F_(n-1): a few points do not tell a tail going
    like sqrt(l_c) from one going like l_c, and a model fitted to them (the earlier spread
    between fits) fell short of the error by up to a factor 30.

    Parameters
    ----------
    h : numpy.ndarray
        The parameter of the sequence (the process zones l_c), > 0, at least two distinct values,
        in any order.
    F : numpy.ndarray
        The values at ``h`` (pull-off forces).
    rate : float or None, optional
        The power p of the leading term, > 0; fitted when None (with fewer than three points,
        1/2).
    rates : tuple of float, optional
        The bracket of the tail's effective rate the estimate assumes (:func:`tail_bracket`);
        :data:`RATE_BRACKET` by default, :func:`tail_rates` for a graded body.

    Returns
    -------
    F0 : float
        The extrapolated value at h = 0.
    rate : float or None
        The rate used: the fitted or given p; None when the two-term fit was used.
    estimate : float
        The error estimate described above, in the units of F.

    Notes
    -----
    Validated on the study stored in tests/data/zero_range_study.json (written by
    ``benchmarks/study_energy_zero_range.py --no-griffith --json``; checked by
    tests/test_zero_range_estimator.py): circle, square and equilateral triangle, E* = 1,
    w = 0.02, l_c / a = 0.32 ... 0.01 at two elements per l_c (at least 24 per radius) and
    0.32 ... 0.04 at one (the harness's coarse sequence), forces scaled to the nominal area;
    every window of three or more consecutive ranges, with the fitted rate and with rate 1/2.
    References: Kendall for the circle; for the square and the triangle the hull of the Griffith
    solver's 1/N extrapolations and the finest window's own value (half-widths 0.14 % of
    F_upper), by which the error may exceed the estimate.  In all 78 windows the estimate covers
    the error, by a factor 1.09 at least (the square's 0.32 ... 0.01 at rate 1/2); half of it
    fails in 43 (the earlier spread between fits failed in 52).  The tail rates there: circle
    0.50 ... 0.58 (0.45 at 0.16 a, where no window ends), square 0.66 ... 1.05 and triangle
    0.76 ... 1.00 (up to 1.17 and 1.09 within the references' uncertainty): a bracket ending
    at 1 leaves three windows uncovered (estimate / error down to 0.88).
    """
    h = np.asarray(h, float)
    F = np.asarray(F, float)
    order = np.argsort(h)[::-1]
    h, F = h[order], F[order]
    n = len(h)
    if rate is None and n >= 3:
        fit = _fit_free(h, F)
        if fit is None:
            F0, used = _lsq(h, F, [0.5, 1.0]), None
        else:
            F0, used = fit
    else:
        used = 0.5 if rate is None else float(rate)
        F0 = _lsq(h, F, [used])
    est = max(abs(F0 - b) for b in tail_bracket(h, F, rates))
    return float(F0), used, float(est)


def sequence_range(scene: Scene, ratio: float, settings: ZeroRangeSettings) -> tuple[float, float]:
    """(rho, spacing) of the range of a zero-range sequence at l_c = ``ratio`` a: the range whose
    process zone is that l_c, and a grid with ``settings.elements_per_process_zone`` elements per
    l_c, times :func:`~bem_energy.potentials.graded_zone_elements` on a graded body, and at least
    ``settings.minimum_elements_per_radius`` per radius a = sqrt(A / pi)."""
    a = scene.indenter.shape.equivalent_radius
    k = process_zone_exponent(scene.material)
    lc = ratio * a
    rho = range_for_process_zone(
        modulus=process_zone_modulus(scene.material), work=scene.adhesion.work_of_adhesion, length=lc, exponent=k
    )
    per = settings.elements_per_process_zone * graded_zone_elements(k)
    return rho, min(lc / per, a / settings.minimum_elements_per_radius)


def sequence_run(scene: Scene, ratio: float, settings: ZeroRangeSettings, *, callback=None) -> tuple[float, Result]:
    """One range of a zero-range sequence, at l_c = ``ratio`` a on its own grid
    (:func:`sequence_range`): its range rho and the finite-range pull-off."""
    rho, spacing = sequence_range(scene, ratio, settings)
    log.info(
        "l_c/a = %g: rho = %.4g, %d elements per radius",
        ratio,
        rho,
        round(scene.indenter.shape.equivalent_radius / spacing),
    )
    potential = Potential(scene.adhesion.work_of_adhesion, rho, settings.potential)
    es = replace(settings.energy, grid=Grid(spacing=spacing))
    # the sequence's grid is set in elements per l_c (times the graded factor, as is the need)
    fewest = PROCESS_ZONE_ELEMENTS[settings.potential][0]
    remedy = (
        f"use --resolution {math.ceil(fewest * (1 - 1e-9)):d} or more (elements per process zone, "
        "ZeroRangeSettings.elements_per_process_zone)"
    )
    return rho, pull_off(scene, es, spacing=spacing, potential=potential, callback=callback, resolution_remedy=remedy)


def zero_range(scene: Scene, settings: ZeroRangeSettings | None = None, *, callback=None) -> Result:
    """The zero-range (JKR / Griffith) pull-off by extrapolating finite ranges to l_c -> 0.

    Each process zone l_c = r a of ``settings.ratios`` (a = sqrt(A/pi)) runs as a finite-range
    pull-off (:func:`pull_off`) on a grid that resolves it; the forces (scaled to the nominal
    face area unless ``normalise_area`` is off) are extrapolated by :func:`richardson`.

    Parameters
    ----------
    scene : contact_scene.Scene
        The punch, material, adhesion, loading and outputs.
    settings : bem_energy.ZeroRangeSettings or None, optional
        The sequence, its grids and the extrapolation; ``ZeroRangeSettings()`` (the accurate
        sequence down to l_c = 0.01 a, minutes) by default.
    callback : callable, optional
        ``callback(approach, force, contact_area)``, called at every recorded point of the curve
        (progress).

    Returns
    -------
    contact_scene.Result
        The finest range's result with: ``pulloff_force`` the extrapolated force (the finest
        range's when the extrapolation fails); ``accuracy_estimate`` the extrapolation's error
        estimate relative to that force (None when it failed); ``converged`` False when a range
        did not converge or detach, or the extrapolation failed; ``iterations``, ``timings`` and
        ``stats`` summed over the sequence (``timings["extrapolation"]`` the rest);
        ``messages`` on the extrapolation and every range's own; ``info`` a
        :class:`ZeroRangeInfo`; ``face_area`` None when the forces refer to the nominal area;
        ``discretisation = "extrapolated"``; ``error_bars`` with the extrapolation's estimate
        for the force.  The curve, fields, pull-off approach and stiffness are the finest
        range's: the approach at the force maximum of a finite range does not tend to the
        zero-range one over such a sequence.

    Raises
    ------
    contact_scene.SceneError
        Naming the field: ``adhesion.range`` (adhesion without a range), ``grid.periodic`` (the
        method has no periodic half-space), ``grid.spacing`` (a grid too coarse for the face),
        ``settings.grid`` (beyond ``max_memory_gb``), ``settings.kernel``, ``settings.minimiser``
        (cvxpy on a large grid), ``material`` (an influence matrix that is not positive definite)
        or ``loading.press_approach`` (a press that touches nothing).
    """
    settings = settings or ZeroRangeSettings()
    t0 = time.perf_counter()
    a = scene.indenter.shape.equivalent_radius
    k = process_zone_exponent(scene.material)
    runs = []
    for i, r in enumerate(settings.ratios, 1):
        log.info("range %d of %d: l_c/a = %g", i, len(settings.ratios), r)
        rho, res = sequence_run(scene, r, settings, callback=callback)
        runs.append((r * a, rho, res))
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
    rates = tail_rates(k)
    F0, used_rate, est = richardson(lcs, Fs, settings.rate, rates)
    finest = runs[-1][2]
    how = "fitted" if settings.rate is None else "fixed"
    msgs = [
        f"zero-range limit by extrapolation in l_c (rate {how}: "
        + ("none fits, two-term sqrt + linear fit" if used_rate is None else f"{used_rate:.3g}")
        + ") over l_c/a = "
        + ", ".join(f"{r:g}" for r in settings.ratios)
        + (", forces scaled to the nominal face area" if settings.normalise_area else "")
        + f"; the curve, fields and pull-off approach are those of the finest range (rho = {runs[-1][1]:.4g}): "
        "the approach at the force maximum of a finite range does not tend to the zero-range one "
        "over this sequence (the maximum is broad and moves outward as the edge zone opens)"
    ]
    msgs.append(
        "accuracy estimate: the distance from the extrapolated force to the limits the finest step "
        f"allows for a tail going like l_c^q, q = {rates[0]:g} ... {rates[1]:g}; a bound if the "
        "tail's rate lies there (validated on circle, square and triangle: see bem_energy.richardson)"
    )
    if k != 0:
        msgs.append(
            f"graded body (k = {k:g}): the tail bracket starts at (1-k)/2 = {rates[0]:g}; it is checked against "
            "the closed form on the flat circle at k = 0.5 only (docs/accuracy.md, from "
            "benchmarks/study_graded_shape_ratio.py --zero-range), and a graded limit converges slowly"
        )
    if min(settings.ratios) > VALIDATED_FINEST_RATIO:
        msgs.append(
            f"the finest l_c = {min(settings.ratios):g} a is coarser than the estimate is validated for "
            f"({VALIDATED_FINEST_RATIO:g} a): the tail may be slower than l_c^{rates[0]:g} there"
        )
    # a coarse sequence's estimate is validated on the circle only: on faces with corners the
    # extrapolation overshoots by about its own size (the coarse square 8.6 % above the reference
    # table's value, estimate 7.9 %), so it claims no bar there
    validated = not (min(settings.ratios) > COARSE_LIMIT and not isinstance(scene.indenter.shape, Circle))
    if not validated:
        msgs.append(
            f"the sequence stops at l_c = {min(settings.ratios):g} a: faces with corners converge faster "
            "than the circle below 0.04 a, and such a sequence overshoots their zero-range limit by up to "
            "7 % (square, triangle: benchmarks/study_energy_zero_range.py), about as much as its accuracy "
            "estimate, so the force carries no error bar; the default sequence reaches 0.01 a"
        )
    for lc, _rho, res in runs:
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
    assert finest.face_area is not None  # pull_off reports its grid's face area
    bar = validated and ok and math.isfinite(est) and F0 > 0
    return replace(
        finest,
        pulloff_force=float(F0),
        converged=ok,
        accuracy_estimate=float(est / F0) if math.isfinite(est) and F0 > 0 else None,
        iterations=sum(x[2].iterations for x in runs),
        timings=timings,
        messages=tuple(msgs),
        # finest comes from pull_off, whose info is an EnergyInfo
        info=ZeroRangeInfo(
            **cast(EnergyInfo, finest.info),
            zero_range=SequenceInfo(
                process_zone_ratios=[float(r) for r in settings.ratios],
                ranges=[float(x[1]) for x in runs],
                spacings=[float(x[2].grid_spacing) for x in runs],
                pulloff_forces=Fs.tolist(),
                raw_pulloff_forces=raw.tolist(),
                pulloff_approaches=ds.tolist(),
                rate=settings.rate,
                fitted_rate=used_rate if settings.rate is None else None,
                coarse=min(settings.ratios) > COARSE_LIMIT,
            ),
        ),
        stats=_sum_stats([x[2] for x in runs]),
        # forces scaled to the nominal area refer to the exact face; raw ones to the finest grid's
        face_area=None if settings.normalise_area else finest.face_area,
        discretisation="extrapolated",
        # the finest grid's stiffness bar, and the extrapolation's estimate for the force (a
        # failed or unvalidated extrapolation has no bar: its force is not checked)
        error_bars=error_bars(
            scene,
            spacing=finest.grid_spacing,
            face_area=finest.face_area,
            zero_range_estimate=float(est / F0) if bar else None,
            zero_range_bracket=tail_bracket(lcs, Fs, rates) if bar else None,
        ),
    )
