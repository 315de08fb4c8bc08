"""FEM reference: the vectorised kernels against scikit-fem's assembly and SuperLU's default ordering.

    python benchmarks/bench_fem.py                 # kendall_circle and graded_circle_k0.5, 3 repeats
    python benchmarks/bench_fem.py --repeat 5 --cases kendall_circle,graded_circle_k0.25,graded_circle_k0.5
    python benchmarks/bench_fem.py --no-json       # print only, do not write docs/performance_fem.json

Both variants (``FemSettings(kernels="scikit-fem")``, the previous algorithm, and the default
``"vectorised"``) solve each built-in scene at the default settings (degree 4, grading 1, the
error estimate's degree-3 solve included), interleaved in one run so that both see the same
machine load.  The table gives the median wall and CPU seconds (one BLAS thread), their ratio,
and the relative changes of K, F_A and d_c next to the solver's own error bound: the
assembled matrices agree to rounding, so the answers may move only by the precision of the
solve and of the finite-difference energy release rate, far inside that bound.  Results go to
docs/performance_fem.json.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import statistics
import subprocess
import time
from pathlib import Path

import _timing

import fem_reference as fr
from crossval.suite import scene

ROOT = Path(__file__).resolve().parents[1]
QUANTITIES = ("stiffness", "pulloff_force", "pulloff_approach")
VARIANTS = ("scikit-fem", "vectorised")


def run(name: str, repeat: int) -> dict:
    sc = scene(name)
    wall = {v: [] for v in VARIANTS}
    cpu = {v: [] for v in VARIANTS}
    results = {}
    for i in range(repeat):
        for v in VARIANTS if i % 2 == 0 else VARIANTS[::-1]:  # alternate who goes first
            t, c = time.perf_counter(), time.process_time()
            results[v] = fr.solve(sc, fr.FemSettings(kernels=v))
            wall[v].append(time.perf_counter() - t)
            cpu[v].append(time.process_time() - c)
    old, new = results["scikit-fem"], results["vectorised"]
    return {
        "case": name,
        "unknowns": new.info["dofs"],
        "previous_wall_s": statistics.median(wall["scikit-fem"]),
        "new_wall_s": statistics.median(wall["vectorised"]),
        "previous_cpu_s": statistics.median(cpu["scikit-fem"]),
        "new_cpu_s": statistics.median(cpu["vectorised"]),
        "previous_timings_s": old.timings,
        "new_timings_s": new.timings,
        "relative_change": {q: getattr(new, q) / getattr(old, q) - 1 for q in QUANTITIES},
        "error_bar": {q: new.error_bars[q].relative for q in QUANTITIES},
        "previous": {q: getattr(old, q) for q in QUANTITIES},
        "new": {q: getattr(new, q) for q in QUANTITIES},
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default="kendall_circle,graded_circle_k0.5")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-json", action="store_true")
    args = ap.parse_args()
    started = datetime.datetime.now(datetime.UTC)
    load = list(os.getloadavg())
    rows = []
    for name in args.cases.split(","):
        rows.append(run(name, args.repeat))
        r = rows[-1]
        print(name, f"{r['previous_wall_s']:.1f} s -> {r['new_wall_s']:.1f} s", flush=True)
    head = [
        "case",
        "unknowns",
        "previous s",
        "new s",
        "ratio",
        "previous CPU s",
        "new CPU s",
        "CPU ratio",
        "dK/K",
        "dF_A/F_A",
        "dd_c/d_c",
        "error bar F_A",
    ]
    table = [
        [
            r["case"],
            r["unknowns"],
            f"{r['previous_wall_s']:.1f}",
            f"{r['new_wall_s']:.1f}",
            f"{r['previous_wall_s'] / r['new_wall_s']:.1f}",
            f"{r['previous_cpu_s']:.1f}",
            f"{r['new_cpu_s']:.1f}",
            f"{r['previous_cpu_s'] / r['new_cpu_s']:.1f}",
            *(f"{r['relative_change'][q]:+.1e}" for q in QUANTITIES),
            f"{r['error_bar']['pulloff_force']:.1e}",
        ]
        for r in rows
    ]
    print(_timing.table(table, head))
    print(_timing.provenance())
    if not args.no_json:
        rev = subprocess.run(
            ["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True, text=True
        ).stdout.strip()
        out = ROOT / "docs" / "performance_fem.json"
        out.write_text(
            json.dumps(
                {
                    "written_by": _timing.command(),
                    "date": started.isoformat(timespec="seconds"),
                    "machine": {
                        "platform": platform.platform(),
                        "processor": platform.processor() or platform.machine(),
                        "cpus": os.cpu_count(),
                        "load_average_at_start": load,
                    },
                    "revision": rev,
                    "repeats": args.repeat,
                    "variants": {
                        "previous": "FemSettings(kernels='scikit-fem')",
                        "new": "FemSettings(kernels='vectorised')",
                    },
                    "headers": head,
                    "rows": table,
                    "cases": rows,
                },
                indent=1,
            )
            + "\n"
        )
        print(f"wrote {out}")


if __name__ == "__main__":
    main()
