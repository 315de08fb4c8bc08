"""Speed of the energy BEM's zero-range limit against the previous algorithm, in one run.

Each face's default sequence (``ZeroRangeSettings()``: l_c / a = 0.08 ... 0.01) is solved by
the current ``bem_energy`` and by the package as it was at ``--baseline`` (a git revision,
extracted to a temporary directory and imported beside it), alternating the two so that both
see the same machine load.  Printed: median CPU time of each (the solver runs on one thread;
the wall times are in the JSON), their ratio, the extrapolated F_A of each (scaled to Eq. 13's
upper bound, F_up for the face's area), the change in units of the new result's own error
estimate, and the largest change of a single range's force.  The table and the raw numbers go
to ``--json`` (default ``docs/performance_energy_zero_range.json``) with the date, the machine
and the load average at the start.  No timed tests use this.

    python benchmarks/bench_energy_zero_range.py [--faces circle,square,triangle] [--repeats 1]
        [--baseline REV] [--json PATH] [--update] [--quick]

The baseline default is the last revision before the zero-range speed-ups (same numbers as
the pull-off before the modules were split, bit for bit).
"""

from __future__ import annotations

import argparse
import importlib
import json
import os
import statistics
import sys
import tempfile
import time
from datetime import UTC, datetime
from pathlib import Path

import _timing  # thread settings first
from _timing import table

import bem_energy as be
import contact_scene as cs
from contact_scene import theory as T

ROOT = Path(__file__).resolve().parent.parent
BASELINE = "4e10c03"
W = 0.02
FACES = {
    "circle": lambda: cs.Circle(1.0),
    "square": lambda: cs.Square(2.0),
    "triangle": lambda: cs.Triangle.equilateral(2.0),
}


def load_baseline(rev: str, where: Path):
    """``bem_energy`` at git revision ``rev``, importable as ``bem_energy_baseline``."""
    _timing.extract_revision(rev, ["bem_energy"], where)
    (where / "bem_energy").rename(where / "bem_energy_baseline")
    sys.path.insert(0, str(where))
    return importlib.import_module("bem_energy_baseline")


def run(package, shape, quick: bool):
    """(CPU seconds, wall seconds, result) of one sequence.  CPU time is the measure: the
    solver runs on one thread, and on a shared machine the wall time also counts the others'
    load."""
    sc = cs.Scene(cs.Indenter(shape), cs.Homogeneous(1.0, 0.0), cs.Adhesion(W))
    t, w = time.process_time(), time.perf_counter()
    r = package.solve(sc, package.ZeroRangeSettings.coarse(1.0) if quick else None)
    return time.process_time() - t, time.perf_counter() - w, r


HEADERS = (
    "face",
    "old CPU s",
    "new CPU s",
    "old/new",
    "F_A/F_up old",
    "F_A/F_up new",
    "change",
    "|change|/estimate",
    "max range change",
)


def write(path: Path, args, record: dict, rows, records):
    """``record``: ``_timing.provenance_record()`` taken when the run started (date, machine,
    load, thread settings, revision, flagged when the tree had uncommitted changes)."""
    out = {
        "written_by": _timing.command(),
        **record,
        "baseline": args.baseline,
        "repeats": args.repeats,
        "headers": list(HEADERS),
        "rows": [list(r) for r in rows],
        "faces": dict(records),
    }
    if args.update and path.exists():
        previous = json.loads(path.read_text())
        kept = [r for r in previous.get("rows", []) if r[0] not in records]
        out["rows"] = kept + out["rows"]
        out["faces"] = {**{k: v for k, v in previous.get("faces", {}).items() if k not in records}, **records}
    path.write_text(json.dumps(out, indent=1) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--faces", default="circle,square,triangle")
    ap.add_argument("--repeats", type=int, default=1, help="runs of each algorithm per face (median)")
    ap.add_argument("--baseline", default=BASELINE, help="git revision of the previous algorithm")
    ap.add_argument("--json", default=str(ROOT / "docs" / "performance_energy_zero_range.json"))
    ap.add_argument("--quick", action="store_true", help="the harness's coarse sequence instead (a smoke test)")
    ap.add_argument(
        "--update",
        action="store_true",
        help="keep the other faces already in --json (each face keeps its own date and load)",
    )
    args = ap.parse_args(argv)
    faces = [f.strip() for f in args.faces.split(",") if f.strip()]
    record = _timing.provenance_record()
    load = record["machine"]["load_average_at_start"]
    rows, records = [], {}
    with tempfile.TemporaryDirectory() as tmp:
        old_pkg = load_baseline(args.baseline, Path(tmp))
        for name in faces:
            shape = FACES[name]()
            face_load = os.getloadavg()
            F_up = T.upper_bound_force(E_star=1.0, work=W, area=shape.area)
            times: dict[str, list[float]] = {"old": [], "new": []}
            walls: dict[str, list[float]] = {"old": [], "new": []}
            results = {}
            for _ in range(args.repeats):
                for label, pkg in (("old", old_pkg), ("new", be)):
                    dt, wall, r = run(pkg, shape, args.quick)
                    times[label].append(dt)
                    walls[label].append(wall)
                    results[label] = r
                    print(
                        f"  {name} {label}: {dt:.1f} s CPU ({wall:.1f} s wall), "
                        f"F_A / F_up = {r.pulloff_force / F_up:.6f}",
                        flush=True,
                    )
            old, new = results["old"], results["new"]
            t_old, t_new = statistics.median(times["old"]), statistics.median(times["new"])
            f_old = old.info["zero_range"]["pulloff_forces"]
            f_new = new.info["zero_range"]["pulloff_forces"]
            worst_range = max(abs(b / a - 1) for a, b in zip(f_old, f_new, strict=True))
            change = new.pulloff_force / old.pulloff_force - 1
            rows.append(
                (
                    name,
                    f"{t_old:.1f}",
                    f"{t_new:.1f}",
                    f"{t_old / t_new:.2f}",
                    f"{old.pulloff_force / F_up:.5f}",
                    f"{new.pulloff_force / F_up:.5f}",
                    f"{change:+.1e}",
                    f"{abs(change) / new.accuracy_estimate:.3f}",
                    f"{worst_range:.1e}",
                )
            )
            records[name] = {
                "date": datetime.now(UTC).isoformat(timespec="seconds"),
                "load_average_at_start": face_load,
                "sequence": "coarse" if args.quick else "default",
                "old_cpu_s": times["old"],
                "new_cpu_s": times["new"],
                "old_wall_s": walls["old"],
                "new_wall_s": walls["new"],
                "ratio": t_old / t_new,
                "F_old": old.pulloff_force,
                "F_new": new.pulloff_force,
                "F_upper": F_up,
                "estimate_new": new.accuracy_estimate,
                "estimate_old": old.accuracy_estimate,
                "ranges": new.info["zero_range"]["process_zone_ratios"],
                "range_forces_old": f_old,
                "range_forces_new": f_new,
                "largest_range_change": worst_range,
                "minimiser_iterations_old": old.iterations,
                "minimiser_iterations_new": new.iterations,
            }
            if args.json:  # after every face, so that a long run leaves what it measured
                write(Path(args.json), args, record, rows, records)
    print(
        f"\nzero-range limit, {'coarse' if args.quick else 'default'} sequence, E* = 1, w = {W}; "
        f"baseline {args.baseline}; "
        f"load average {load[0]:.1f} at the start"
    )
    print(table(rows, HEADERS))
    if args.json:
        print(f"written {args.json}")


if __name__ == "__main__":
    main()
