"""The ``crossval`` command line.  Only this module prints."""

from __future__ import annotations

import dataclasses
import logging
import sys
import tempfile
import time
from functools import wraps
from pathlib import Path

import click

from contact_scene import SceneError, summarise

from .jsonio import dumps as json_dumps
from .methods import METHODS, applicable_methods, get_method
from .suite import BUILTIN, SUITE, load_scene_or_builtin as load_scene

log = logging.getLogger("crossval")


def _scene_errors_exit_2(f):
    """A bad scene or option is the user's to fix: one clear line on stderr, exit status 2."""

    @wraps(f)
    def wrapper(*args, **kwargs):
        try:
            return f(*args, **kwargs)
        except SceneError as exc:
            click.echo(f"error: {exc}", err=True)
            sys.exit(2)

    return wrapper


def _fmt(v) -> str:
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, list):
        return "(" + ", ".join(_fmt(x) for x in v) + ")"
    return str(v)


_SOLVER_LOGGERS = (*METHODS, "crossval")


class _LiveStatus:
    """What a long solve is doing, on stderr: a tqdm status line on a terminal (the solvers'
    stage messages as its description, the latest point of the curve as its postfix), and with
    ``-v`` elsewhere a plain log line at most every few seconds.  The libraries stay silent: they
    only call the callback and log."""

    def __init__(self, desc: str, *, every_s: float = 5.0):
        from tqdm import tqdm

        self.bar = tqdm(desc=desc, unit=" pts", disable=None, leave=False, file=sys.stderr)
        self.desc = desc
        self.every_s = every_s
        self._last = 0.0
        self._handler: logging.Handler | None = None

    def __enter__(self):
        from tqdm.contrib.logging import logging_redirect_tqdm

        if not self.bar.disable:
            live = self

            class Stage(logging.Handler):
                def emit(self, record):
                    try:
                        live.bar.set_description(f"{live.desc}: {record.getMessage()[:70]}", refresh=True)
                    except Exception:  # a malformed record must not disturb the solve it reports on
                        pass

            self._handler = Stage(logging.INFO)
            for name in _SOLVER_LOGGERS:
                lg = logging.getLogger(name)
                lg.addHandler(self._handler)
                if lg.getEffectiveLevel() > logging.INFO:
                    lg.setLevel(logging.INFO)
        root = logging.getLogger()
        levels = [h.level for h in root.handlers]
        filters = [f for h in root.handlers for f in h.filters]
        self._redirect = logging_redirect_tqdm()
        self._redirect.__enter__()
        for h in root.handlers:  # tqdm's replacement handler keeps neither level nor filters
            h.setLevel(max(levels, default=logging.WARNING))
            for f in filters:
                h.addFilter(f)
        return self

    def point(self, method: str, approach: float, force: float, area: float) -> None:
        self.bar.update(1)
        text = f"{method}: d = {approach:.5g}, F = {force:.5g}, contact area {area:.4g}"
        self.bar.set_postfix_str(text, refresh=False)
        now = time.monotonic()
        if self.bar.disable and now - self._last >= self.every_s:
            self._last = now
            log.info("%s", text)

    def __exit__(self, *exc):
        self._redirect.__exit__(*exc)
        if self._handler is not None:
            for name in _SOLVER_LOGGERS:
                logging.getLogger(name).removeHandler(self._handler)
        self.bar.close()
        return False


def _version() -> str:
    from .cache import package_version

    return (
        f"adhesive-punch {package_version()}\n"
        "Cite the package (CITATION.cff) and the method's source: V.L. Popov, R. Pohrt, Q. Li, "
        "Strength of adhesive contacts: influence of contact geometry and material gradients, "
        "Friction 5(3):308-325 (2017)."
    )


def _print_version(ctx, param, value):
    if value and not ctx.resilient_parsing:
        click.echo(_version())
        ctx.exit()


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.option("-v", "--verbose", count=True, help="More log output on stderr (-v: progress and stages, -vv: debug).")
@click.option(
    "--version",
    is_flag=True,
    expose_value=False,
    is_eager=True,
    callback=_print_version,
    help="Print the package version and how to cite it, then exit.",
)
def main(verbose):
    """Adhesive punch detachment: solve scenes and cross-check methods against theory.

    A scene FILE is a TOML scene file or the name of a built-in scene (crossval scene list); a
    built-in name always means the built-in scene, so write ./NAME for a file of that name."""
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("%(levelname)s %(name)s: %(message)s"))
    level = [logging.WARNING, logging.INFO, logging.DEBUG][min(verbose, 2)]
    # the handler, not the loggers, decides what is printed: the live status line may raise a
    # solver logger to INFO to read its stage messages without printing them
    handler.setLevel(level)
    if verbose == 1:
        # -v is this package's progress; other libraries' INFO (scikit-fem's assembly) only with -vv
        handler.addFilter(lambda r: r.levelno >= logging.WARNING or r.name.split(".")[0] in _SOLVER_LOGGERS)
    root = logging.getLogger()
    root.handlers[:] = [handler]
    root.setLevel(level)


@main.group()
def scene():
    """Inspect scene files."""


@scene.command("list")
def scene_list():
    """List the built-in scenes (usable wherever a scene FILE is asked for)."""
    width = max(map(len, BUILTIN))
    for name, sc in BUILTIN.items():
        tag = "suite" if name in SUITE else "     "
        click.echo(f"{name:<{width}}  {tag}  {sc.indenter.shape.kind}, {type(sc.material).__name__}")


@scene.command("check")
@click.argument("file", type=click.Path())
@click.option("--json", "as_json", is_flag=True, help="Print the summary as JSON.")
@_scene_errors_exit_2
def scene_check(file, as_json):
    """Validate FILE (a scene file, or a built-in scene's name) and print its geometry and closed-form bounds."""
    summary = summarise(load_scene(file))
    if as_json:
        click.echo(json_dumps(summary, indent=2))
        return
    width = max(map(len, summary))
    for k, v in summary.items():
        click.echo(f"{k:<{width}}  {_fmt(v)}")


@main.command("solve")
@click.argument("file", type=click.Path())
@click.option("--method", "method_name", required=True, type=click.Choice(sorted(METHODS)), help="Which solver.")
@click.option(
    "--resolution",
    type=float,
    default=None,
    help="bem_griffith, and bem_energy at a finite range: elements across the equivalent radius "
    "sqrt(A/pi) (bem_energy's default resolves the process zone: 2 elements per l_c with the "
    "exponential potential); bem_energy in the zero-range limit: elements per process zone; "
    "fem_reference: 1/grading. Default: the method's own.",
)
@click.option(
    "--range",
    "range_",
    type=float,
    default=None,
    help="Interaction range rho of the adhesive potential (bem_energy only): run this finite range "
    "instead of the zero-range limit. Its process zone l_c = E* rho^2 / w is resolved by default; "
    "a range whose grid would exceed 1024 cells across is refused, naming the shortest that fits.",
)
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON (fixed keys for every method).")
@_scene_errors_exit_2
def solve_cmd(file, method_name, resolution, range_, as_json):
    """Run one method on the scene in FILE (a scene file, or a built-in scene's name).

    Exit status 1 when the solve did not converge (its notes say why)."""
    sc = load_scene(file)
    method = get_method(method_name)
    if range_ is not None:
        if not method.uses_range:
            users = ", ".join(m.name for m in METHODS.values() if m.uses_range)
            raise SceneError(
                "--range",
                f"{method.name} is a zero-range (Griffith) method and has no interaction "
                f"range; drop --range, or use --method {users}",
            )
        sc = dataclasses.replace(sc, adhesion=dataclasses.replace(sc.adhesion, range=range_))
    why_not = method.applies(sc)
    if why_not:
        raise SceneError("method", why_not)
    method.check_resolution(sc, resolution, field="--resolution")
    with _LiveStatus(f"{method.name} on {sc.name or file}") as live:
        res = method.solve(sc, resolution=resolution, callback=lambda d, F, A: live.point(method.name, d, F, A))
    if as_json:
        click.echo(json_dumps(res.to_json()))
    else:
        _print_result(res)
    if not res.converged:
        # a script reading the status must not take an unconverged solve for an answer
        ctx = click.get_current_context()
        ctx.exit(1)


def _print_result(res) -> None:
    rows = [
        ("method", res.method),
        ("pulloff_force", res.pulloff_force),
        ("pulloff_approach", res.pulloff_approach),
        ("stiffness", res.stiffness),
        ("detached", res.detached),
        ("converged", res.converged),
        ("iterations", res.iterations),
        ("grid_spacing", res.grid_spacing),
        ("wall_time_s", res.wall_time_s),
    ]
    for k, v in rows:
        click.echo(f"{k:<18}{_fmt(v)}")
    for m in res.messages:
        click.echo(f"note: {m}")


@main.command("compare")
@click.argument("file", type=click.Path())
@click.option("--resolution", type=float, default=None, help="BEM elements across sqrt(A/pi) (default 32).")
@click.option(
    "--quick",
    is_flag=True,
    help="The energy method's coarse zero-range sequence (seconds, with an error "
    "bar of about 8 %) instead of its accurate default (minutes, about 1-4 %).",
)
@click.option("--json", "as_json", is_flag=True, help="Print the comparison as JSON.")
@_scene_errors_exit_2
def compare_cmd(file, resolution, quick, as_json):
    """Run every method that applies to FILE; check against theory and each other.

    Values that no check holds (no error bar on this face, nothing to compare with) are listed
    as unchecked.  Exit status 1 when a check fails."""
    from .compare import compare, reference_source

    sc = load_scene(file)
    for m in applicable_methods(sc):
        if m.resolution_is_grid(sc):
            m.check_resolution(sc, resolution, field="--resolution")
    with _LiveStatus(f"compare {sc.name or file}") as live:
        cmp = compare(
            sc, resolution=resolution, resolutions=_compare_quick(sc) if quick else None, point_callback=live.point
        )
    if as_json:
        click.echo(
            json_dumps(
                {
                    "scene": sc.name,
                    "passed": cmp.passed,
                    "theory": cmp.theory,
                    "skipped": cmp.skipped,
                    "unchecked": cmp.unchecked,
                    "results": {
                        k: {
                            q: getattr(r, q)
                            for q in (
                                "pulloff_force",
                                "pulloff_approach",
                                "stiffness",
                                "converged",
                                "wall_time_s",
                                "grid_spacing",
                            )
                        }
                        for k, r in cmp.results.items()
                    },
                    "checks": [
                        {
                            "method": c.method,
                            "quantity": c.quantity,
                            "value": c.value,
                            "reference": c.reference,
                            "reference_name": c.reference_name,
                            "difference": c.difference,
                            "tolerance": c.tolerance,
                            "passed": c.passed,
                            "role": c.role,
                        }
                        for c in cmp.checks
                    ],
                }
            )
        )
    else:
        click.echo(f"scene: {sc.name}")
        hdr = f"{'method':<16}{'F_A':>12}{'d at F_A':>12}{'stiffness':>12}{'wall s':>9}  converged"
        click.echo(hdr)
        for k, r in cmp.results.items():
            click.echo(
                f"{k:<16}{r.pulloff_force:>12.6g}{r.pulloff_approach:>12.6g}{r.stiffness:>12.6g}"
                f"{r.wall_time_s:>9.2f}  {r.converged}"
            )
        for k, v in cmp.theory.items():
            if isinstance(v, float):
                src = reference_source(cmp.theory, k)
                bar = cmp.theory.get("bars", {}).get(k)
                click.echo(f"{'theory':<16}{k} = {v:.6g}{f' +- {bar:.2%}' if bar else ''}  ({src})")
        for k, why in cmp.skipped.items():
            click.echo(f"skipped {k}: {why}")
        for c in cmp.checks:
            click.echo(f"{c.label:<6}" + c.explain())
        for k, qs in cmp.unchecked.items():
            click.echo(
                f"unchecked {k}: {', '.join(qs)} (no check holds it: the method gives it no error bar "
                "on this scene, or nothing else has a value to compare it with)"
            )
        for r in cmp.results.values():
            for m in r.messages:
                click.echo(f"note ({r.method}): {m}")
    if not cmp.passed:
        sys.exit(1)


def _progress(total: int, desc: str):
    """A tqdm bar and a callback that advances it (log lines are routed around the bar)."""
    from tqdm import tqdm

    bar = tqdm(total=total, desc=desc, unit="run", disable=None)

    def cb(job, result):
        bar.update(1)
        bar.set_postfix_str(f"{job.scene.name}/{job.method}", refresh=False)

    return bar, cb


def _compare_quick(sc) -> dict:
    """``compare --quick``: each method's own quick resolution, where it has one and its resolution
    is not a grid on this scene (the energy BEM's elements per process zone of its zero-range
    sequence; at a finite range or without adhesion its resolution is elements per radius,
    which ``--resolution`` gives)."""
    return {
        m.name: m.sweeps.compare_quick
        for m in applicable_methods(sc)
        if m.sweeps.compare_quick is not None and not m.resolution_is_grid(sc)
    }


def _check_out_dir(out_dir: str) -> None:
    """Refuse, before any solve, an output directory that cannot be made or written."""
    if not out_dir:
        raise SceneError("--out", "must name a directory (got an empty path)")
    path = Path(out_dir)
    try:
        path.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=path):
            pass
    except OSError as exc:
        raise SceneError("--out", f"cannot write into {out_dir!r}: {exc.strerror or exc}") from None


@main.command("report")
@click.option("--quick", is_flag=True, help="Coarse resolutions: under 3 minutes on 2 cores.")
@click.option(
    "--out",
    "out_dir",
    default="report",
    show_default=True,
    type=click.Path(file_okay=False),
    help="Directory for index.html, results.json and the PNGs (made if missing; files of those names "
    "are replaced, other files left as they are).",
)
@click.option(
    "--workers", type=click.IntRange(min=1), default=None, help="Local processes (default: the machine's cores)."
)
@click.option("--scheduler", default=None, help="dask.distributed scheduler address (instead of local processes).")
@click.option("--no-cache", is_flag=True, help="Recompute everything (results are cached in .crossval-cache).")
@_scene_errors_exit_2
def report_cmd(quick, out_dir, workers, scheduler, no_cache):
    """Run the built-in suite through every method and write OUT/index.html, results.json and plots.

    The full report (without --quick) also runs the energy BEM's accurate zero-range sequence on
    each face and checks that, not its coarse sweep, against the other methods.  Exit status 1
    when a check fails."""
    from tqdm.contrib.logging import logging_redirect_tqdm

    from .report import report, report_jobs
    from .runner import default_workers

    if scheduler is not None and workers is not None:
        raise SceneError("--workers", "has no effect with --scheduler: the cluster's workers run the jobs; drop one")
    if scheduler is not None:
        # checked before the cache is read: with every result cached no connection is made, and
        # a malformed address would pass unnoticed
        from distributed.comm import get_address_host_port

        try:
            get_address_host_port(scheduler)
        except ValueError as exc:
            raise SceneError("--scheduler", f"not a scheduler address ({exc}); e.g. tcp://host:8786") from None
    _check_out_dir(out_dir)
    bar, cb = _progress(len(report_jobs(SUITE, quick=quick)), "report")
    with bar, logging_redirect_tqdm():
        rep = report(
            out_dir,
            quick=quick,
            workers=workers or default_workers(),
            scheduler=scheduler,
            cache_dir=None if no_cache else ".crossval-cache",
            callback=cb,
        )
    every = [(s, c) for s, cs_ in rep.checks.items() for c in cs_]
    failed = [(s, c) for s, c in every if not c.passed]
    residuals = sum(c.passed and c.role == "calibration" for _, c in every)
    click.echo(
        f"wrote {rep.directory / 'index.html'} ({rep.wall_time_s:.0f} s); "
        f"{len(every) - len(failed) - residuals} checks passed, {len(failed)} failed, "
        f"{residuals} calibration residuals within their bounds"
    )
    for s, c in failed:
        click.echo(f"FAIL {s}: {c.explain()}")
    if failed:
        sys.exit(1)


@main.command("regress")
@click.option("--update", is_flag=True, help="Rewrite the stored reference file with the current results.")
@click.option(
    "--workers", type=click.IntRange(min=1), default=None, help="Local processes (default: the machine's cores)."
)
def regress_cmd(update, workers):
    """Compare results with the reference file stored in the package (exit 1 on a mismatch)."""
    from .regress import CASES, REFERENCE_FILE, regress, regression_jobs
    from .runner import default_workers

    bad = regress(update=update, workers=workers or default_workers())
    if update:
        click.echo(f"updated {REFERENCE_FILE}")
        return
    for m in bad:
        click.echo(f"MISMATCH {m.explain()}")
    cases = len(regression_jobs())
    click.echo(
        f"{len(bad)} mismatches over {cases} cases (every suite scene through each method that applies, at "
        f"{', '.join(f'{m} {r:g}' for m, r in CASES.items())}), against {REFERENCE_FILE}"
    )
    if bad:
        sys.exit(1)


@main.command("study")
@click.argument("file", type=click.Path())
@click.option(
    "--method",
    "method_names",
    multiple=True,
    type=click.Choice(sorted(METHODS)),
    help="Method(s) to study (default: every one that applies).",
)
@click.option("--resolutions", default=None, help="Comma-separated resolutions (default: each method's own set).")
@click.option(
    "--quantity",
    default="pulloff_force",
    show_default=True,
    type=click.Choice(["pulloff_force", "pulloff_approach", "stiffness"]),
    help="Which result to measure the error of.",
)
@click.option(
    "--workers",
    type=click.IntRange(min=1),
    default=1,
    show_default=True,
    help="Local processes to spread the runs over.",
)
@click.option("--json", "as_json", is_flag=True, help="Print the study as JSON.")
@_scene_errors_exit_2
def study_cmd(file, method_names, resolutions, quantity, workers, as_json):
    """Error against resolution and wall time, with fitted convergence rates."""
    from .study import study

    sc = load_scene(file)
    for m in method_names:
        why = METHODS[m].applies(sc)
        if why:
            raise SceneError("method", why)
    res = None
    if resolutions is not None:
        try:
            vals = tuple(float(v) for v in resolutions.split(","))
        except ValueError:
            raise SceneError("resolutions", f"must be comma-separated numbers (got {resolutions!r})") from None
        res = {m: vals for m in (method_names or [m.name for m in applicable_methods(sc)])}
        for m in res:
            for v in vals:
                METHODS[m].check_resolution(sc, v, field="--resolutions")
    from tqdm.contrib.logging import logging_redirect_tqdm

    from .study import DEFAULT_RESOLUTIONS

    names = list(method_names) or [m.name for m in applicable_methods(sc)]
    bar, cb = _progress(sum(len((res or DEFAULT_RESOLUTIONS)[m]) for m in names), "study")
    with bar, logging_redirect_tqdm():
        st = study(sc, methods=names, resolutions=res, quantity=quantity, workers=workers, callback=cb)
    if as_json:
        click.echo(
            json_dumps(
                {
                    "scene": sc.name,
                    "quantity": quantity,
                    "reference": st.reference,
                    "reference_name": st.reference_name,
                    "rates": st.rates,
                    "time_rates": st.time_rates,
                    "reference_kind": st.reference_info.kind,
                    "reference_uncertainty": st.reference_info.uncertainty,
                    "convergence": {m: c.to_json() for m, c in st.convergence.items()},
                    "time_convergence": {m: c.to_json() for m, c in st.time_convergence.items()},
                    "rows": [r.__dict__ for r in st.rows],
                }
            )
        )
        return
    click.echo(f"{quantity} of {sc.name}: error against {st.reference_name}, reference value {st.reference:.8g}")
    for m in sorted({r.method for r in st.rows}):
        click.echo(f"  resolution of {m}: {METHODS[m].resolution(sc).label}")
    click.echo(f"{'method':<16}{'resolution':>11}{'value':>15}{'rel. error':>12}{'wall s':>9}")
    for r in st.rows:
        click.echo(f"{r.method:<16}{r.resolution:>11.4g}{r.value:>15.8g}{r.error:>12.3e}{r.wall_time_s:>9.2f}")
    for m, c in st.convergence.items():
        t = st.time_convergence[m]
        click.echo(
            f"{m}: {c.text}"
            + (
                f"; error ~ time^-{t.order:.2f}"
                if t.kind == "order"
                else f"; no exponent in time ({t.reason})"
                if c.kind == "order"
                else ""
            )
        )


if __name__ == "__main__":  # pragma: no cover
    main()
