"""The method-comparison report over the built-in suite: index.html (images embedded),
results.json and PNG plots."""

from __future__ import annotations

import base64
import html
import os
import tempfile
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from contact_scene import rasterise

from . import face_references, plotting
from .cache import ResultCache, package_version
from .compare import check_results, reference_source, reference_values, same_grid_partners
from .jsonio import dumps as json_dumps
from .methods import METHODS, applicable_methods
from .runner import Job, run_jobs
from .study import TIME_NOISE_FLOOR_S, study
from .suite import SUITE

__all__ = ["Report", "report", "report_jobs", "QUICK", "FULL", "ERROR_PANEL_CAPTION"]

#: resolutions per method for the quick (< 3 min on 2 cores) and full report
#: (bem_energy in the zero-range limit: elements per process zone)
QUICK = {m.name: m.sweeps.quick for m in METHODS.values()}
FULL = {m.name: m.sweeps.full for m in METHODS.values()}


def report_jobs(names, *, quick: bool = True) -> list[tuple[str, Job]]:
    """The solves of a report over the suite scenes ``names``, as (scene name, job): every
    applicable method over its sweep and, in the full report, at its default resolution
    (``resolution=None``) where ``Sweeps.full_default`` asks for it.  Those defaults come
    first: they are the longest solves, and a pool that starts them first finishes soonest.

    Parameters
    ----------
    names : iterable of str
        Names of suite scenes (:data:`crossval.SUITE`).
    quick : bool, optional
        The quick sweeps (:data:`QUICK`) instead of the full ones (:data:`FULL`).

    Returns
    -------
    list of (str, crossval.runner.Job)
        The jobs in the order a pool should start them.
    """
    names = list(names)
    res_sets = QUICK if quick else FULL
    methods = {s: applicable_methods(SUITE[s]) for s in names}
    at_default = [] if quick else [(s, m) for s in names for m in methods[s] if m.sweeps.full_default]
    defaults = [(s, Job(SUITE[s], m.name, None)) for s, m in at_default]
    return defaults + [(s, Job(SUITE[s], m.name, r)) for s in names for m in methods[s] for r in res_sets[m.name]]


@dataclass(frozen=True, eq=False)
class Report:
    """What :func:`report` found and where it wrote it.

    Attributes
    ----------
    directory : pathlib.Path
        The directory holding index.html, results.json and the PNG plots.
    studies : dict
        Scene name -> its :class:`crossval.study.Study` (error against resolution and time).
    checks : dict
        Scene name -> the :class:`crossval.Check` of the methods' finest runs.
    passed : bool
        Whether every check of every scene passed.
    wall_time_s : float
        The report's wall time in seconds, solves included.
    """

    directory: Path
    studies: dict
    checks: dict
    passed: bool
    wall_time_s: float


def _write_atomic(path: Path, data: bytes) -> None:
    # an interrupted run leaves the previous file whole
    fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
    with os.fdopen(fd, "wb") as f:
        f.write(data)
    os.chmod(tmp, 0o644)
    os.replace(tmp, path)


def _png(fig, path: Path) -> str:
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100, bbox_inches="tight")
    data = buf.getvalue()
    _write_atomic(path, data)
    import matplotlib.pyplot as plt

    plt.close(fig)
    return base64.b64encode(data).decode()


def _curve_label(method: str, r) -> str:
    """The legend entry of a force-approach curve: the energy BEM's zero-range result carries
    the curve of its finest range, whose force maximum is below the extrapolated F_A."""
    if isinstance(r.info, dict) and "zero_range" in r.info:
        return f"{method} (its finest range; F_A is the zero-range limit)"
    return method


#: the quantities of a result the report lists, and checks where the method has an error bar
QUANTITIES = ("pulloff_force", "pulloff_approach", "stiffness")


def unchecked_values(finest: dict, checks: Sequence, theory: dict) -> list[tuple[str, str]]:
    """(method, quantity) of the finest results' values that the scene has a reference for but
    that no check covers: the method gives no error bar for them (a coarse sequence, a quantity
    no study bounds), so "all checks passed" says nothing about them.

    Parameters
    ----------
    finest : dict
        Method -> its finest result.
    checks : list of crossval.Check
        The scene's checks.
    theory : dict
        :func:`crossval.reference_values` of the scene.

    Returns
    -------
    list of tuple
        (method, quantity) pairs, in the order of ``finest`` and :data:`QUANTITIES`.
    """
    covered = {(c.method, c.quantity.removesuffix(" bracket")) for c in checks}
    return [
        (m, q)
        for m, r in finest.items()
        if m in METHODS
        for q in QUANTITIES
        if q in theory and (m, q) not in covered and getattr(r, q, None) is not None
    ]


#: what the numbers of the scenes' tables and panels are measured in
UNITS_NOTE = (
    "Forces, approaches, stiffnesses and areas are in each scene's own units: the suite's scenes are "
    "dimensionless (face radius or side of order 1, E* and w of order 1; `crossval scene check NAME` "
    "prints a scene with its closed-form scales).  Tension is negative: F_A is the largest tension, "
    "d at F_A the approach there, 'initial area' the contact area when the pull starts."
)


#: how to read the error panel of every scene (the figure's right-hand panel)
ERROR_PANEL_CAPTION = (
    "The right-hand panel of each scene: the relative error of every run against its wall time, "
    "one line per method joining its runs in order of resolution; a marker points up for a run above "
    "the reference and down for one below it. The number beside each run is its resolution in its "
    "method's own measure, named in the legend (elements per radius for the Griffith BEM, elements per "
    "process zone for the energy BEM's zero-range sequence, 1/grading for the FEM): these numbers do not "
    "compare across methods, so every panel shares one axis, wall time. Runs in the hatched band took "
    f"under {TIME_NOISE_FLOOR_S:g} s, where start-up, caching and the machine's other load weigh more "
    "than the solve: their errors are measured, their positions in time are noise. A legend entry says "
    "so where a method's time does not grow with its resolution. A cached run keeps the time of the "
    "solve that computed it."
)


#: the line under the agreement map: what its cells and its hatched cells mean
AGREEMENT_CAPTION = (
    "Each cell: |F_A / reference - 1| of the method's finest run, against the scene's reference "
    "(closed form; else, for the built-in non-circular faces, the reference table's converged value; else "
    "the FEM; else the Griffith BEM extrapolated in 1/N). 'own extrap.' and 'own table value': the reference "
    "is that method's own converged value, so the cell is its convergence error, not an agreement between "
    "methods. "
    "'calib.': a calibration residual, matching by construction; '< ref. error bar': the difference is "
    "smaller than the reference's own error bar, so not resolved; 'no bar': the run carries no error bar "
    "on its force, so no check held it to the reference, whatever the difference. Hatched cells have no "
    "value: " + "; ".join(f"'{k}' = {v}" for k, v in plotting.BLANK_REASONS.items()) + "."
)


def _calibrated(checks, quantity: str) -> set[str]:
    """The methods whose check of ``quantity`` is a calibration residual (fitted to the reference
    it is checked against, as the graded criterion is to Eq. 39)."""
    return {c.method for c in checks if c.quantity == quantity and c.role == "calibration"}


def _agreement_row(scene, st, fin, checks, methods):
    """One row of the agreement map: the relative difference of each method's finest run from
    the study's reference, and each cell's note (why it is blank, or what its value is)."""
    ref = st.reference_info
    calibrated = _calibrated(checks, "pulloff_force")
    # the table's value is one method's own converged value: that method's cell is its
    # convergence error, not an agreement with another method
    table = face_references.for_scene(scene).get("pulloff_force") if ref.kind == "table" else None
    row, note = [], []
    for m in methods:
        r = fin.get(m)
        if r is None:
            row.append(float("nan"))
            note.append("n/a")
        elif m == ref.own_method and not ref.own_sequence:
            row.append(float("nan"))
            note.append("is ref.")
        elif ref.kind == "none" or not ref.value:
            row.append(float("nan"))
            note.append("no ref.")
        else:
            v = abs(r.pulloff_force / ref.value - 1)
            row.append(v)
            own = ref.own_sequence and m == ref.own_method
            own_table = table is not None and table.method == m
            tags = (
                ["calib."] * (m in calibrated)
                + ["own extrap."] * own
                + ["own table value"] * own_table
                + ["< ref. error bar"] * (v <= ref.uncertainty)
                + ["no bar"] * (r.error_bars.get("pulloff_force") is None)
            )
            note.append("\n".join(tags))
    return row, note


def _error_sentence(st) -> str:
    """What the error panel measures against, and what each method's sequence supports."""
    ref = st.reference_info
    kind = {
        "closed form": "the closed form",
        "table": (
            "the reference table's converged value (crossval/references/faces.json, "
            "benchmarks/reference_table.py); its relative bar is the error bar"
        ),
        "bounded": f"{ref.own_method}'s finest run; its a-posteriori bound is the error bar",
        "extrapolated": (
            f"{ref.own_method}'s sequence, forces scaled to the nominal face area, extrapolated to "
            "N -> infinity in 1/N; the error bar (crossval.study.sequence_bar) adds the spread of the "
            "leave-one-out extrapolations, the extrapolation's own correction and the finest grid's "
            "envelope, and errors inside it are not resolved"
        ),
        "none": "nothing: there is no trustworthy reference",
    }[ref.kind]
    parts = [f"Error of the {st.quantity.replace('_', ' ')} measured against {st.reference_name}: {kind}."]
    conv = "; ".join(f"{m}: {c.text}" for m, c in st.convergence.items())
    if conv:
        parts.append(f"Convergence in resolution: {conv}.")
    timed = [f"{m}: error ~ time^-{c.order:.2f}" for m, c in st.time_convergence.items() if c.kind == "order"]
    parts.append(
        f"Against wall time: {', '.join(timed)}."
        if timed
        else "No exponent of error against wall time (runs too short, or no rate in resolution)."
    )
    return " ".join(parts)


def report(
    out_dir="report",
    *,
    quick: bool = True,
    workers: int = 1,
    scheduler=None,
    cache_dir=".crossval-cache",
    scenes=None,
    callback=None,
    extremes: bool | None = None,
) -> Report:
    """Run the suite, check every method, write the report; returns what it found.

    Each scene runs through every method that applies to it, over the method's quick or full
    sweep (:data:`QUICK`, :data:`FULL`); each method's error is studied against the scene's best
    reference (:func:`crossval.study`), and the finest run of each method (in the full report,
    its default where ``Sweeps.full_default`` says so: the energy BEM's accurate zero-range
    sequence) is checked against the
    closed forms and the other methods (:func:`crossval.compare`); on flat faces each grid method
    also runs on the other's grid without adhesion, which holds their stiffnesses to the kernels'
    measured same-grid difference.  The page shows the agreement map and, per scene, the results,
    the checks, the force-approach curves and the error against wall time.

    Parameters
    ----------
    out_dir : str or os.PathLike, optional
        Directory (created if missing) for index.html (images embedded), results.json,
        agreement.png and one PNG per scene; each file is replaced whole, so an interrupted run
        leaves the previous one.
    quick : bool, optional
        The coarse sweeps (under 3 minutes on 2 cores) instead of the full ones.
    workers : int, optional
        Local processes; more than one runs the solves in a process pool.
    scheduler : str or distributed.Client, optional
        A dask.distributed address or client to run the solves on instead.
    cache_dir : str or os.PathLike or None, optional
        Reuses stored results and stores new ones; None keeps them in memory only.
    scenes : iterable of str, optional
        Names of suite scenes (:data:`crossval.SUITE`); all of them by default.
    callback : callable, optional
        ``callback(job, result)`` after each solve of the sweeps (progress).
    extremes : bool or None, optional
        Add the stiff and extreme cases table of :mod:`crossval.extremes` (about a minute on
        2 cores); None: for the full report only.

    Returns
    -------
    Report
        The studies and checks per scene, whether every check passed, the output directory and
        the wall time.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t0 = time.perf_counter()
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    res_sets = QUICK if quick else FULL
    names = list(scenes) if scenes is not None else list(SUITE)
    cache = ResultCache(cache_dir)
    named = report_jobs(names, quick=quick)
    solved = run_jobs([j for _, j in named], workers=workers, scheduler=scheduler, cache=cache, callback=callback)
    # the results at a method's default resolution, checked in place of its sweep's finest
    defaults = {(s, j.method): r for (s, j), r in zip(named, solved, strict=True) if j.resolution is None}

    studies, checks, finest = {}, {}, {}
    for s in names:
        st = study(SUITE[s], resolutions=res_sets, cache=cache)
        studies[s] = st
        fin = {}
        for m in dict.fromkeys(r.method for r in st.rows):
            rmax = max(r.resolution for r in st.rows if r.method == m)
            fin[m] = defaults.get((s, m)) or st.results[(m, rmax)]
        finest[s] = fin
    # each grid method also on the other's grid, without adhesion: the kernels' same-grid check
    partners = [(s, key, job) for s in names for key, job in same_grid_partners(SUITE[s], finest[s]).items()]
    partner_jobs = [Job(*job) for _, _, job in partners]
    for (s, key, _), r in zip(
        partners, run_jobs(partner_jobs, workers=workers, scheduler=scheduler, cache=cache), strict=True
    ):
        finest[s][key] = r
    for s in names:
        checks[s] = check_results(SUITE[s], finest[s])

    methods = list(METHODS)
    matrix, notes = [], []
    for s in names:
        row, note = _agreement_row(SUITE[s], studies[s], finest[s], checks[s], methods)
        matrix.append(row)
        notes.append(note)

    sections: list[str] = []
    unchecked: dict[str, list[tuple[str, str]]] = {}
    data: dict[str, Any] = {"package_version": package_version(), "quick": quick, "scenes": {}}
    fig, ax = plt.subplots(figsize=(7, 0.45 * len(names) + 1.6), layout="constrained")
    plotting.plot_agreement(matrix, names, methods, ax, notes=notes)
    agreement_png = _png(fig, out / "agreement.png")
    for s in names:
        st = studies[s]
        fig, axs = plt.subplots(1, 3, figsize=(15, 4.2), layout="constrained", width_ratios=(1.1, 0.8, 1.25))
        for m, r in finest[s].items():
            # the same-grid runs without adhesion (keys beyond the methods) have no pull
            if r.curve is not None and m in METHODS:
                plotting.plot_curve(r, axs[0], label=_curve_label(m, r), color=plotting.METHOD_COLOURS.get(m))
        levels = []  # the horizontal lines' heights: they do not widen the axes by themselves
        for m, r in finest[s].items():
            # the curve is the finest range's; its zero-range F_A is the table's value, so drawn too
            if m in METHODS and isinstance(r.info, dict) and "zero_range" in r.info:
                levels.append(-r.pulloff_force)
                axs[0].axhline(
                    levels[-1],
                    color=plotting.METHOD_COLOURS.get(m),
                    lw=0.8,
                    ls="--",
                    label=f"-F_A of {m}: its zero-range limit",
                )
        th = reference_values(SUITE[s])
        if "pulloff_force" in th:
            source = reference_source(th, "pulloff_force").split(" (crossval")[0]
            levels.append(-th["pulloff_force"])
            axs[0].axhline(levels[-1], color="grey", lw=0.6, ls=":", label=f"-F_A: {source}")
        if levels:  # a limit below every curve sat on the frame
            low, high = axs[0].get_ylim()
            pad = 0.05 * (high - low)
            axs[0].set_ylim(min(low, min(levels) - pad), max(high, max(levels) + pad))
        axs[0].legend(fontsize=7)
        axs[0].set_title(f"{s} (tension F < 0)")
        # the last stable contact of the first method that recorded one (a grid method's)
        m_bem, bem = next(((m, r) for m, r in finest[s].items() if r.last_stable is not None), (None, None))
        if bem is not None:
            face = rasterise(SUITE[s].indenter.shape, bem.last_stable.spacing).mask
            same = face.shape == bem.last_stable.contact.shape
            plotting.plot_contact(bem.last_stable, axs[1], face=face if same else None)
            axs[1].set_title(
                f"last stable contact, {m_bem}, d = {bem.last_stable.approach:.4g}"
                + ("\n(grey: the face, black: in contact)" if same else ""),
                fontsize=9,
            )
            axs[1].set_xlabel("x")
            axs[1].set_ylabel("y")
        else:
            axs[1].axis("off")
        # a method fitted to the reference here (the graded criterion's calibration) says so
        calibrated = {m: "calibration residual" for m in _calibrated(checks[s], st.quantity) if m in METHODS}
        plotting.plot_error_vs_time(st, axs[2], notes=calibrated)
        img = _png(fig, out / f"{s}.png")
        rows = "".join(
            f"<tr><td>{html.escape(m)}</td>"
            # the same-grid runs without adhesion (keys beyond the methods) are pressed only
            + (
                f"<td>{r.pulloff_force:.6g}</td><td>{r.pulloff_approach:.6g}</td>"
                if m in METHODS
                else "<td>- (w = 0)</td><td>-</td>"
            )
            + f"<td>{r.stiffness:.6g}</td>"
            f"<td>{r.curve.contact_area[0] if r.curve is not None else float('nan'):.4g}</td>"
            f"<td>{r.wall_time_s:.2f}</td><td>{r.converged}</td></tr>"
            for m, r in finest[s].items()
        )
        # a quantity from the reference table names it: it is a converged number, not a closed form
        theory_rows = "".join(
            f"<tr><td>{html.escape(k)}</td><td>{v:.6g}"
            + (f" &plusmn; {th['bars'][k]:.2%}" if k in th.get("bars", {}) else "")
            + f"</td><td>{html.escape(reference_source(th, k))}</td></tr>"
            for k, v in th.items()
            if isinstance(v, float)
        )
        # the table's value of each method: a method is checked against the other's, not its own
        for q, table_ref in face_references.for_scene(SUITE[s]).items():
            theory_rows += "".join(
                f"<tr><td>{html.escape(q)}, {html.escape(other.method)}'s converged value</td>"
                f"<td>{other.value:.6g} &plusmn; {other.relative:.2%}</td><td>each method is checked against "
                "the other method's value where the table has one</td></tr>"
                for other in table_ref.by_method
                if other.method != table_ref.method
            )
        chk = "".join(
            f"<li class={'ok' if c.passed else 'fail'}>{c.label}: {html.escape(c.explain())}</li>" for c in checks[s]
        )
        not_checked = unchecked[s] = unchecked_values(finest[s], checks[s], th)
        chk += "".join(
            f"<li>{html.escape(m)} {html.escape(q)}: not checked (the method gives no error bar for it here)</li>"
            for m, q in not_checked
        )
        notes_html = "".join(
            f"<li>{html.escape(m)}: {html.escape(msg)}</li>" for m, r in finest[s].items() for msg in r.messages
        )
        sections.append(
            f"<h2 id='{s}'>{html.escape(s)}</h2><table><tr><th>method</th><th>F_A</th><th>d at F_A</th>"
            f"<th>stiffness</th>"
            f"<th>initial area</th><th>wall s</th><th>converged</th></tr>{rows}</table>"
            f"<p>Theory and reference values:</p><table>{theory_rows}</table>"
            f"<p>{html.escape(_error_sentence(st))}</p>"
            f"<ul>{chk}</ul><ul>{notes_html}</ul><img src='data:image/png;base64,{img}' alt='{html.escape(s)}'>"
        )
        ref = st.reference_info
        data["scenes"][s] = {
            "reference": {
                "value": st.reference,
                "name": st.reference_name,
                "kind": ref.kind,
                "uncertainty": ref.uncertainty,
            },
            "runs": [
                {
                    "method": r.method,
                    "resolution": r.resolution,
                    "wall_time_s": r.wall_time_s,
                    "pulloff_force": r.value,
                    "error": r.error,
                    "signed_error": r.signed_error,
                }
                for r in st.rows
            ],
            "finest": {m: {k: v for k, v in r.to_json().items() if k != "curve"} for m, r in finest[s].items()},
            "checks": [
                {
                    "method": c.method,
                    "quantity": c.quantity,
                    "value": c.value,
                    "reference": c.reference,
                    "tolerance": c.tolerance,
                    "passed": c.passed,
                    "role": c.role,
                }
                for c in checks[s]
            ],
            "rates": st.rates,
            "time_rates": st.time_rates,
            "convergence": {m: c.to_json() for m, c in st.convergence.items()},
        }
    extreme_html = ""
    if extremes if extremes is not None else not quick:
        from . import extremes as ex

        extreme_rows = ex.extreme_cases()
        data["extremes"] = [dict(zip(ex.HEADERS, r, strict=True)) for r in extreme_rows]
        head = "".join(f"<th>{html.escape(h)}</th>" for h in ex.HEADERS)
        body = "".join("<tr>" + "".join(f"<td>{html.escape(str(v))}</td>" for v in r) + "</tr>" for r in extreme_rows)
        extreme_html = (
            f"<h2 id='extremes'>Stiff and extreme cases</h2><p>Stiffness error against Eq. 1 / Eq. 34 "
            f"(n/a where there is no closed form).</p><table><tr>{head}</tr>{body}</table>"
        )
    passed = all(c.passed for cs_ in checks.values() for c in cs_)
    n_checks = sum(len(cs_) for cs_ in checks.values())
    n_calibration = sum(c.role == "calibration" for cs_ in checks.values() for c in cs_)
    data["passed"] = passed
    data["unchecked"] = {s: [{"method": m, "quantity": q} for m, q in unchecked[s]] for s in names}
    unchecked_total = sum(len(v) for v in unchecked.values())
    wall = time.perf_counter() - t0
    data["wall_time_s"] = wall
    page = (
        "<!doctype html><meta charset='utf-8'><title>adhesive-punch method comparison</title>"
        "<style>body{font-family:sans-serif;max-width:1300px;margin:auto}img{max-width:100%;height:auto}table{border-collapse:collapse}"
        "td,th{border:1px solid #ccc;padding:2px 6px;font-size:13px}.fail{color:#b00}.ok{color:#060}</style>"
        f"<h1>Method comparison ({'quick' if quick else 'full'} suite)</h1>"
        f"<p>package {package_version()}; {len(names)} scenes; "
        + (
            f"all checks passed: {n_checks - n_calibration} checks and {n_calibration} calibration residuals"
            if passed
            else "SOME CHECKS FAILED"
        )
        + (
            f" ({unchecked_total} values without an error bar are not checked; each scene lists them)"
            if unchecked_total
            else ""
        )
        + "; "
        f"{wall:.0f} s.</p><h2>Agreement</h2><img src='data:image/png;base64,{agreement_png}' alt='agreement'>"
        f"<p>{html.escape(AGREEMENT_CAPTION)}</p><p>{html.escape(UNITS_NOTE)}</p>"
        f"<p>{html.escape(ERROR_PANEL_CAPTION)}</p>" + "".join(sections) + extreme_html
    )
    _write_atomic(out / "index.html", page.encode())
    _write_atomic(out / "results.json", json_dumps(data, indent=1).encode())
    return Report(out, studies, checks, passed, wall)
