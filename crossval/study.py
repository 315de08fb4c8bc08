"""Error against resolution and against run time, with convergence orders fitted only where a
fit means something.

The error of a run is measured against the best reference the suite has, never against the
same solver at its own finest grid (that error is zero by construction at the finest grid and
meaningless below it):

1. the closed form where the sheet has one (Kendall, JKR, graded Eqs. 34-39);
2. else the FEM for the circular faces it covers, with its a-posteriori estimate as error bar
   (the FEM's own runs are then not measured);
3. else the Griffith BEM's sequence (pull-off forces scaled from the staircase face to the
   nominal one) extrapolated in 1/N (it converges at first order, README "Accuracy, as
   measured"), with :func:`sequence_bar` as error bar (the leave-one-out spread, the
   extrapolation's own correction and the envelope at the finest grid);
4. else no reference: the study says so and measures nothing.

An error smaller than the reference's error bar is not resolved: it is kept in the rows but
not used for a rate.  A convergence order is fitted only where the errors keep their sign and
fall monotonically over at least three resolutions and the power law follows them closely;
otherwise the study reports an envelope, error <= c/N.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

import contact_scene as cs
from contact_scene import theory as T

from .compare import reference_values
from .methods import METHODS, applicable_methods, reference_method
from .runner import Job, run_jobs

__all__ = [
    "StudyRow",
    "Study",
    "Convergence",
    "ErrorReference",
    "study",
    "convergence",
    "extrapolate_first_order",
    "sequence_bar",
    "DEFAULT_RESOLUTIONS",
    "TIME_NOISE_FLOOR_S",
]

#: per method, the resolutions a study sweeps unless told otherwise (BEM: elements per
#: radius; FEM: 1/grading)
DEFAULT_RESOLUTIONS = {m.name: m.sweeps.study for m in METHODS.values()}

#: runs shorter than this measure start-up, caching and the other processes on the machine
#: more than the solve, so no exponent of error against time is fitted through them
TIME_NOISE_FLOOR_S = 0.5

#: a power law is accepted as the sequence's order when no error lies farther from it (in
#: log) than this fraction of the sequence's total fall: a rate has to describe the fall,
#: not one straight line through a wiggle
MAX_RELATIVE_LOG_RESIDUAL = 0.1


@dataclass(frozen=True)
class StudyRow:
    method: str
    resolution: float
    wall_time_s: float
    value: float
    error: float  # |relative error| against the reference; NaN where not measured
    signed_error: float = math.nan  # value / reference - 1


@dataclass(frozen=True)
class ErrorReference:
    """What the errors are measured against."""

    value: float
    name: str
    #: "closed form", "table" (crossval/references/faces.json: converged, with its bar),
    #: "bounded" (one result with a bounded error), "extrapolated" or "none"
    kind: str
    #: relative error bar of the reference itself (0 for a closed form)
    uncertainty: float = 0.0
    #: the method the reference comes from, if any
    own_method: str | None = None
    #: whether it is that method's own extrapolated sequence (its errors against it are
    #: measured, but their order is assumed, not measured)
    own_sequence: bool = False


#: what a study without a closed form, a bounded method or an extrapolated sequence measures against
NO_REFERENCE = ErrorReference(
    math.nan,
    "no reference (no closed form, no bounded method, fewer than 3 resolutions of an extrapolated sequence)",
    "none",
    math.inf,
)


@dataclass(frozen=True)
class Convergence:
    """How one method's error falls with resolution (or time)."""

    #: "order": a fitted power law; "envelope": error <= c / N only; "none": nothing to say
    kind: str
    order: float = math.nan  # fitted order p in error ~ N^-p ("order" only)
    constant: float = math.nan  # c of the envelope error <= c / N (max of error * N)
    reason: str = ""

    @property
    def text(self) -> str:
        if self.kind == "order":
            return f"order {self.order:.2f} (fitted)"
        if self.kind == "envelope":
            return f"no rate ({self.reason}); error <= c/N with c = {self.constant:.3g}"
        return f"no rate ({self.reason})"

    def to_json(self) -> dict:
        return {
            "kind": self.kind,
            "order": self.order,
            "constant": self.constant,
            "reason": self.reason,
            "text": self.text,
        }


@dataclass(frozen=True, eq=False)
class Study:
    scene: cs.Scene
    quantity: str
    reference: float
    reference_name: str
    rows: tuple[StudyRow, ...]
    #: method -> fitted order in resolution, NaN where no order is meaningful (see ``convergence``)
    rates: dict = field(default_factory=dict)
    #: method -> fitted exponent of error against wall time, NaN where the timings or the
    #: errors do not support one
    time_rates: dict = field(default_factory=dict)
    results: dict = field(default_factory=dict)  # (method, resolution) -> Result
    reference_info: ErrorReference = field(default_factory=lambda: NO_REFERENCE)
    convergence: dict = field(default_factory=dict)  # method -> Convergence in resolution
    time_convergence: dict = field(default_factory=dict)  # method -> Convergence in wall time


def _envelope(x, e) -> float:
    return float(np.max(np.abs(e) * x))


def convergence(resolutions, errors, *, floor: float = 0.0) -> Convergence:
    """The convergence of a sequence of (signed or absolute) relative errors over increasing
    ``resolutions``.

    An order is fitted only if at least three errors above ``floor`` (the reference's own
    error bar) keep their sign, fall monotonically and lie on the fitted power law within
    ``MAX_RELATIVE_LOG_RESIDUAL`` of their total fall in log; otherwise the envelope
    error <= c/N, c = max(|error| N), is what the sequence supports."""
    x = np.asarray(resolutions, float)
    e = np.asarray(errors, float)
    ok = np.isfinite(x) & np.isfinite(e) & (x > 0)
    x, e = x[ok], e[ok]
    if len(x) == 0:
        return Convergence("none", reason="no measured error")
    order = np.argsort(x)
    x, e = x[order], e[order]
    c = _envelope(x, e)
    if len(x) == 1:
        # one run bounds nothing: c/N through one point is that point, not an envelope
        return Convergence("none", reason="one resolution")
    resolved = np.abs(e) > floor
    if not np.all(resolved):
        if not np.any(resolved):
            return Convergence("none", reason="every error is below the reference's error bar")
        below = ", ".join(f"{v:.3g}" for v in x[~resolved])
        reason = f"the errors at N = {below} are below the reference's error bar"
        return Convergence("envelope", constant=c, reason=reason)
    if len(x) < 3:
        return Convergence(
            "envelope", constant=c, reason=f"{len(x)} resolution{'s' if len(x) != 1 else ''}, a rate needs 3"
        )
    a = np.abs(e)
    if np.any(np.sign(e) != np.sign(e[0])) or np.any(np.diff(a) >= 0):
        return Convergence("envelope", constant=c, reason="errors zig-zag")
    lx, ly = np.log(x), np.log(a)
    slope, icpt = np.polyfit(lx, ly, 1)
    resid = np.max(np.abs(ly - (slope * lx + icpt)))
    if resid > MAX_RELATIVE_LOG_RESIDUAL * (ly[0] - ly[-1]):
        return Convergence("envelope", constant=c, reason="errors not on a power law")
    return Convergence("order", order=float(-slope), constant=c)


def extrapolate_first_order(resolutions, values) -> tuple[float, float]:
    """The N -> infinity limit of values converging like v + b/N (least squares over all
    resolutions) and its error bar: the largest distance of the leave-one-out extrapolations
    from it (0 from two resolutions, where the fit is exact and says nothing about its error,
    so the caller needs at least three)."""
    x = 1.0 / np.asarray(resolutions, float)
    v = np.asarray(values, float)
    if len(x) < 3:
        raise ValueError("a first-order extrapolation with an error bar needs at least 3 resolutions")
    lim = float(np.polyfit(x, v, 1)[1])
    loo = [float(np.polyfit(np.delete(x, i), np.delete(v, i), 1)[1]) for i in range(len(x))]
    return lim, max(abs(t - lim) for t in loo)


#: the Griffith BEM's envelope on Kendall's circle, |F_A / F_K - 1| <= 0.5 / N (tested for
#: N = 16 ... 96; docs/accuracy.md)
SEQUENCE_ENVELOPE = 0.5
#: past 128 per radius the paper criterion's error on the circle settles at a few tenths of a
#: per cent instead of shrinking: the largest error of the reference table's 1/N extrapolations
#: over windows reaching 181 and 256 per radius (its circle check, docs/references.md)
SEQUENCE_PLATEAU = 0.0062
#: the finest resolution below which the plateau is not added
SEQUENCE_PLATEAU_FROM = 128


def sequence_bar(resolutions, values, limit: float, spread: float) -> float:
    """An error bar on a Griffith sequence's 1/N limit (:func:`extrapolate_first_order`), in
    the units of ``values``: the leave-one-out ``spread`` plus the extrapolation's own
    correction (the limit's distance from the finest value) plus the envelope at the finest
    resolution, ``SEQUENCE_ENVELOPE`` / N, and ``SEQUENCE_PLATEAU`` when that resolution is
    past ``SEQUENCE_PLATEAU_FROM``.

    The spread alone is no bound: the staircase makes the sequence zig-zag about 1/N, and on
    Kendall's circle it fell short of the limit's error in six of the nine windows of three
    consecutive grids from 16 to 510 per radius (by up to 15x).  This sum covers the error in
    all nine, and on the reference table's six faces (every window of three of 32 ... 128 per
    radius, against the energy BEM's converged value and its bar) in all eighteen; it is several
    times the error there, the price of a bound (tests/test_report_view.py).  Validated on the
    pull-off force only; a study of the approach or the stiffness takes the same sum (the
    approach's tested envelope on the circle is 0.6 / N, not 0.5 / N)."""
    ns = np.asarray(resolutions, float)
    v = np.asarray(values, float)
    finest = int(np.argmax(ns))
    bar = spread + abs(limit - v[finest]) + SEQUENCE_ENVELOPE / ns[finest] * abs(limit)
    if ns[finest] > SEQUENCE_PLATEAU_FROM:
        bar += SEQUENCE_PLATEAU * abs(limit)
    return float(bar)


def _at_nominal_area(scene, result, quantity) -> tuple[float, bool]:
    """The pull-off force of a Griffith run scaled from its staircase face to the nominal face,
    F ~ A^((3+k)/4) (contact_scene.theory.force_at_nominal_area), and whether it was scaled.
    The staircase's area zig-zags with N; without it the 1/N extrapolation fits the zig-zag
    rather than the convergence.  Both sequences have the same limit (the staircase's area
    tends to the nominal one), so the scaling changes the error bar, not the reference."""
    v = getattr(result, quantity)
    area = result.face_area
    if quantity != "pulloff_force" or area is None or not scene.indenter.profile.is_flat:
        return v, False
    k = getattr(scene.material, "exponent", 0.0)
    return float(T.force_at_nominal_area(v, area=area, nominal_area=scene.indenter.shape.area, k=k)), True


def _reference_method(scene, kind: str) -> str | None:
    method = reference_method(scene, kind)
    return None if method is None else method.name


def _reference(scene, quantity, by, res) -> ErrorReference:
    theory = reference_values(scene)
    if quantity in theory and quantity in theory.get("bars", {}):
        u = theory["bars"][quantity]
        return ErrorReference(theory[quantity], f"{theory['sources'][quantity]} (relative bar {u:.1e})", "table", u)
    if quantity in theory:
        return ErrorReference(theory[quantity], theory["source"], "closed form")
    bounded = _reference_method(scene, "bounded")
    if bounded is not None and bounded in res:
        finest = max(res[bounded])
        r = by[(bounded, finest)]
        bar = r.error_bars.get(quantity)
        u = bar.relative if bar is not None else math.inf
        return ErrorReference(
            getattr(r, quantity),
            f"{bounded} at {METHODS[bounded].resolution(scene).label} = {finest:g} (relative bar {u:.1e})",
            "bounded",
            u,
            own_method=bounded,
        )
    seq = _reference_method(scene, "sequence")
    if seq is not None and len(res.get(seq, ())) >= 3:
        ns = sorted(res[seq])
        vals, scaled = zip(*(_at_nominal_area(scene, by[(seq, n)], quantity) for n in ns), strict=True)
        lim, spread = extrapolate_first_order(ns, vals)
        err = sequence_bar(ns, vals, lim, spread)
        u = err / abs(lim) if lim else math.inf
        how = ", forces scaled to the nominal area," if all(scaled) else ""
        return ErrorReference(
            lim,
            f"{seq}{how} extrapolated in 1/N over N = {', '.join(f'{n:g}' for n in ns)} (relative bar {u:.1e})",
            "extrapolated",
            u,
            own_method=seq,
            own_sequence=True,
        )
    return NO_REFERENCE


def _time_convergence(rows, floor) -> Convergence:
    rows = sorted(rows, key=lambda r: r.resolution)
    t = np.array([r.wall_time_s for r in rows])
    if len(t) and t.min() < TIME_NOISE_FLOOR_S:
        return Convergence("none", reason=f"runs under {TIME_NOISE_FLOOR_S:g} s: timings are noise")
    if np.any(np.diff(t) <= 0):
        return Convergence("none", reason="wall time does not grow with resolution")
    cv = convergence(t, [r.signed_error for r in rows], floor=floor)
    return cv if cv.kind == "order" else Convergence("none", reason=cv.reason)


def study(
    scene: cs.Scene,
    *,
    methods=None,
    resolutions: dict | None = None,
    quantity: str = "pulloff_force",
    workers: int = 1,
    scheduler=None,
    cache=None,
    callback=None,
) -> Study:
    """Error of each method against resolution and run time, measured against the best reference.

    Each method runs over its resolutions; the error of ``quantity`` is measured against the best
    reference available (the module's list); the runs a reference needs beyond the methods asked
    for (the FEM, the Griffith sequence) are run as well but not reported as rows.

    Parameters
    ----------
    scene : contact_scene.Scene
        The scene to study.
    methods : iterable of str, optional
        Method names (keys of :data:`crossval.METHODS`); every applicable method by default.
    resolutions : dict, optional
        Method name -> its resolutions (BEM: elements per radius; FEM: 1/grading);
        :data:`DEFAULT_RESOLUTIONS` for the others.
    quantity : str, optional
        The :class:`contact_scene.Result` field studied: ``"pulloff_force"`` (default),
        ``"pulloff_approach"`` or ``"stiffness"``.
    workers : int, optional
        Local processes, >= 1.
    scheduler : str or distributed.Client, optional
        A dask.distributed address or client to run the solves on instead.
    cache : crossval.cache.ResultCache, optional
        Reuses stored results and stores new ones.
    callback : callable, optional
        ``callback(job, result)`` after each solve (progress).

    Returns
    -------
    crossval.study.Study
        The rows (method, resolution, wall time, value, error), the reference used, and per
        method the fitted order in resolution and in wall time or an envelope error <= c/N, with
        the reason where no order is meaningful.
    """
    names = [m.name for m in applicable_methods(scene)] if methods is None else list(methods)
    given = dict(resolutions or {})
    res = {m: tuple(given.get(m, DEFAULT_RESOLUTIONS[m])) for m in names}
    if quantity not in reference_values(scene):
        bounded, seq = _reference_method(scene, "bounded"), _reference_method(scene, "sequence")
        if bounded is not None:
            res.setdefault(bounded, given.get(bounded, DEFAULT_RESOLUTIONS[bounded][-1:]))
        elif seq is not None:
            res.setdefault(seq, given.get(seq, DEFAULT_RESOLUTIONS[seq]))
    keys = [(m, r) for m in res for r in res[m]]
    jobs = [Job(scene, m, r) for m, r in keys]
    results = run_jobs(jobs, workers=workers, scheduler=scheduler, cache=cache, callback=callback)
    by = dict(zip(keys, results, strict=True))
    ref = _reference(scene, quantity, by, res)
    rows = []
    for (m, r), result in by.items():
        if m not in names:
            continue
        v = getattr(result, quantity)
        measured = ref.kind != "none" and (m != ref.own_method or ref.own_sequence) and ref.value != 0
        signed = v / ref.value - 1 if measured else math.nan
        rows.append(StudyRow(m, r, result.wall_time_s, v, abs(signed), signed))
    rates, trates, conv, tconv = {}, {}, {}, {}
    for m in names:
        mr = [row for row in rows if row.method == m]
        if m == ref.own_method and not ref.own_sequence:
            conv[m] = tconv[m] = Convergence("none", reason="it is the reference")
        elif m == ref.own_method:
            # its errors against its own 1/N extrapolation have order 1 by construction
            c = convergence([r.resolution for r in mr], [r.signed_error for r in mr], floor=ref.uncertainty)
            reason = "its own 1/N extrapolation is the reference, so the order is assumed, not measured"
            conv[m] = (
                Convergence("envelope", constant=c.constant, reason=reason)
                if math.isfinite(c.constant)
                else Convergence("none", reason=reason)
            )
            tconv[m] = Convergence("none", reason=reason)
        else:
            conv[m] = convergence([r.resolution for r in mr], [r.signed_error for r in mr], floor=ref.uncertainty)
            tconv[m] = (
                _time_convergence(mr, ref.uncertainty)
                if conv[m].kind == "order"
                else Convergence("none", reason=conv[m].reason)
            )
        rates[m], trates[m] = conv[m].order, tconv[m].order
    return Study(scene, quantity, ref.value, ref.name, tuple(rows), rates, trates, by, ref, conv, tconv)
