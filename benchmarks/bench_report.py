"""What the method-comparison report costs: the full report (the energy BEM's accurate
zero-range sequence checked on every face it applies to) and the quick one.

    python benchmarks/bench_report.py [--workers N] [--quick-only] [--update]

Each report runs from scratch (no cache) in local processes.  The table gives the report's wall
time and its CPU time (this process and its workers), and per method and kind of run the number
of solves, the sum of their wall times and the longest one: the longest solve bounds how far
more workers could help.  The machine may be shared, so the CPU time over the workers is the
steadier measure of the work; the load average at the start is in the provenance line.
``--update`` writes docs/performance_report.json (rendered into docs/performance.md by
``python benchmarks/docs_tables.py``).
"""

from __future__ import annotations

import resource
import sys
import tempfile
import time
from collections import defaultdict

import _timing

import crossval

HEADERS = [
    "report",
    "runs",
    "solves",
    "sum of solve wall s",
    "longest solve s",
    "report wall s",
    "report CPU s",
    "checks passed",
    "failed",
]


def _cpu() -> float:
    own, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def run(quick: bool, workers: int) -> list[list]:
    times: dict[str, list[float]] = defaultdict(list)

    def record(job, result):
        kind = "default" if job.resolution is None else "sweep"
        times[f"{job.method} {kind}"].append(result.wall_time_s)

    label = "quick" if quick else "full"
    c0, t0 = _cpu(), time.perf_counter()
    with tempfile.TemporaryDirectory() as out:
        rep = crossval.report(out, quick=quick, workers=workers, cache_dir=None, callback=record)
    wall, cpu = time.perf_counter() - t0, _cpu() - c0
    checks = [c for cs_ in rep.checks.values() for c in cs_]
    failed = sum(not c.passed for c in checks)
    every = [t for ts in times.values() for t in ts]
    rows = [
        [label, "all", len(every), f"{sum(every):.0f}", f"{max(every):.1f}", f"{wall:.0f}", f"{cpu:.0f}"]
        + [len(checks) - failed, failed]
    ]
    for what in sorted(times):
        ts = times[what]
        method, kind = what.split()
        name = "accurate zero-range sequence" if (method, kind) == ("bem_energy", "default") else kind
        rows.append([label, f"{method} {name}", len(ts), f"{sum(ts):.0f}", f"{max(ts):.1f}", "", "", "", ""])
    return rows


def main(argv: list[str]) -> None:
    workers = int(argv[argv.index("--workers") + 1]) if "--workers" in argv else 2
    record = _timing.provenance_record()
    rows = run(True, workers)
    if "--quick-only" not in argv:
        rows += run(False, workers)
    print(_timing.table(rows, HEADERS))
    print(f"{workers} workers; " + _timing.provenance())
    if "--update" in argv:
        _timing.write_doc_table("performance_report", HEADERS, rows, record)


if __name__ == "__main__":
    main(sys.argv[1:])
