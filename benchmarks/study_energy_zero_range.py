"""The energy BEM's zero-range limit on faces with and without corners, against the Griffith BEM.

1. Finite ranges l_c / a = 0.32 ... 0.01 at two elements per l_c (at least 24 per radius) for
   the circle, the square and the equilateral triangle: F_A / F_upper (Eq. 13; Kendall for the
   circle), raw and scaled to the nominal face area (F ~ A^(3/4)), and the local rate fitted
   through each three consecutive ranges.
2. Extrapolations (``bem_energy.richardson``, fitted rate) over windows of four ranges.
3. The Griffith solver on the same faces, scaled to the nominal area, at several resolutions
   and rotations against the grid: its "converged value" and the staircase spread around it.

    python benchmarks/study_energy_zero_range.py [--quick] [--no-griffith] [--faces circle,square]
        [--ratios 0.32,0.16,...] [--epz 2] [--json PATH] [--full] [--update]

Long: the l_c = 0.01 a runs are 200 per radius; the Griffith solver runs up to 96 per radius
(``--full``: 128, minutes per rotation); --quick stops at 0.02 a and 64 per radius.  ``--json PATH`` stores each
face's sequence with full precision (ratios, spacings, areas, raw and area-scaled forces, the
command) under the key "<face>-epz<elements per l_c>", merged into the file if it exists: the
zero-range estimator is validated on these (tests/test_zero_range_estimator.py).
``--update`` writes the three tables of docs/accuracy.md (accuracy_energy_zero_range_ranges,
accuracy_energy_zero_range_extrapolated, accuracy_energy_zero_range_griffith; rendered by
``python benchmarks/docs_tables.py``).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import shlex
import sys
import time

import _timing  # thread settings first
import numpy as np
from _timing import table

import bem_energy as be
import bem_griffith as bg
import contact_scene as cs
from contact_scene import theory as T

W, E = 0.02, 1.0
SHAPES = {"circle": cs.Circle(1.0), "square": cs.Square(2.0), "triangle": cs.Triangle.equilateral(2.0)}


def upper(shape):
    return T.upper_bound_force(E_star=E, work=W, area=shape.area)


def finite_ranges(name, ratios, epz=2.0, min_per_radius=24.0, record=None):
    """F_A / F_upper per range; ``record`` (a dict) receives the full-precision sequence."""
    shape = SHAPES[name]
    a = shape.equivalent_radius
    sc = cs.Scene(cs.Indenter(shape), cs.Homogeneous(E, 0.0), cs.Adhesion(W))
    rows, scaled = [], []
    raw, spacings, areas, conv, walls = [], [], [], [], []
    for r in ratios:
        lc = r * a
        h = min(lc / epz, a / min_per_radius)
        t = time.perf_counter()
        res = be.pull_off(
            sc, be.EnergySettings(grid=cs.Grid(spacing=h)), spacing=h, potential=be.Potential(W, math.sqrt(lc * W / E))
        )
        dt = time.perf_counter() - t
        area = cs.rasterise(shape, h).area
        f = res.pulloff_force / upper(shape)
        fs = T.force_at_nominal_area(f, area=area, nominal_area=shape.area)
        scaled.append(fs)
        raw.append(res.pulloff_force)
        spacings.append(h)
        areas.append(area)
        conv.append(bool(res.converged and res.detached))
        walls.append(dt)
        rows.append(
            [r, f"{a / h:.0f}", f"{area / shape.area - 1:+.4f}", f"{f:.4f}", f"{fs:.4f}", res.converged, f"{dt:.1f}"]
        )
    for i, row in enumerate(rows):
        loc = "-"
        if 1 <= i <= len(rows) - 2:
            fit = be.richardson(np.array(ratios[i - 1 : i + 2]), np.array(scaled[i - 1 : i + 2]))
            loc = "-" if fit[1] is None else f"{fit[1]:.2f}"
        row.append(loc)
    print(f"\n{name}: finite ranges, F_A / F_upper (Eq. 13)", flush=True)
    print(
        table(rows, ("l_c/a", "N/radius", "area err", "F/F_up", "area-scaled", "converged", "wall s", "local rate")),
        flush=True,
    )
    if record is not None:
        record.update(
            {
                "face": name,
                "shape": repr(shape),
                "equivalent_radius": a,
                "nominal_area": shape.area,
                "youngs_modulus": E,
                "poisson_ratio": 0.0,
                "work_of_adhesion": W,
                "potential": "exponential",
                "elements_per_process_zone": epz,
                "minimum_elements_per_radius": min_per_radius,
                "upper_bound_force": upper(shape),
                "kendall_force": (
                    T.kendall_adhesion_force(E_star=E, radius=a, work=W) if isinstance(shape, cs.Circle) else None
                ),
                "ratios": list(map(float, ratios)),
                "spacings": spacings,
                "raster_areas": areas,
                "raw_pulloff_forces": raw,
                "area_scaled_pulloff_forces": [float(f) * upper(shape) for f in scaled],
                "area_scaled_over_upper": list(map(float, scaled)),
                "converged": conv,
                "wall_seconds": walls,
            }
        )
    return np.array(ratios), np.array(scaled), [row[-1] for row in rows]


def extrapolations(name, lc, F):
    rows = []
    for j in range(len(lc) - 3):
        F0, p, est = be.richardson(lc[j : j + 4], F[j : j + 4])
        F2 = be.richardson(lc[j : j + 4], F[j : j + 4], rate=0.5)[0]
        rows.append(
            [
                ",".join(f"{x:g}" for x in lc[j : j + 4]),
                f"{F0:.4f}",
                "-" if p is None else f"{p:.2f}",
                f"{est / F0:.2%}",
                f"{F2:.4f}",
            ]
        )
    print(f"{name}: extrapolated F_A / F_upper over windows of four ranges")
    print(table(rows, ("ratios", "fitted rate", "rate", "estimate", "sqrt law")), flush=True)
    return rows


def griffith(name, Ns, angles):
    shape = SHAPES[name]
    rows = []
    for N in Ns:
        vals = []
        t = time.perf_counter()
        for ang in angles:
            s = cs.Transformed(shape, rotation_deg=ang) if ang else shape
            sc = cs.Scene(cs.Indenter(s), cs.Homogeneous(E, 0.0), cs.Adhesion(W))
            r = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)))
            vals.append(
                T.force_at_nominal_area(
                    r.pulloff_force, area=cs.rasterise(s, r.grid_spacing).area, nominal_area=shape.area
                )
                / upper(shape)
            )
        rows.append([N] + [f"{v:.4f}" for v in vals] + [f"{np.mean(vals):.4f}", f"{time.perf_counter() - t:.0f}"])
        print(table(rows, ["N/radius"] + [f"{a:g} deg" for a in angles] + ["mean", "wall s"]), flush=True)
    return rows


def _git_commit():
    import subprocess

    try:
        return subprocess.run(
            ["git", "rev-parse", "HEAD"],
            capture_output=True,
            text=True,
            check=True,
            cwd=os.path.dirname(os.path.abspath(__file__)),
        ).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return None


def store(path, key, record):
    """Merge one sequence into the JSON file (read, update, atomic replace)."""
    data = {
        "description": "finite-range pull-off forces of bem_energy at process zones l_c = ratio * a, "
        "written by benchmarks/study_energy_zero_range.py --json",
        "sequences": {},
    }
    if os.path.exists(path):
        with open(path) as fh:
            data = json.load(fh)
    data["sequences"][key] = record
    tmp = f"{path}.{os.getpid()}.tmp"
    with open(tmp, "w") as fh:
        json.dump(data, fh, indent=1, sort_keys=True)
        fh.write("\n")
    os.replace(tmp, path)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--full", action="store_true", help="the Griffith solver up to 128 per radius (default 96)")
    ap.add_argument("--no-griffith", action="store_true", help="skip part 3 (the Griffith solver)")
    ap.add_argument("--faces", default="circle,square,triangle")
    ap.add_argument("--ratios", default=None, help="comma-separated l_c / a (default 0.32 ... 0.01)")
    ap.add_argument("--epz", type=float, default=2.0, help="elements per process zone l_c")
    ap.add_argument("--json", default=None, help="store the sequences in this JSON file")
    ap.add_argument("--update", action="store_true", help="write the docs tables (docs/accuracy_energy_zero_range_*)")
    args = ap.parse_args()
    quick = args.quick
    if args.ratios:
        ratios = tuple(sorted((float(x) for x in args.ratios.split(",")), reverse=True))
    else:
        ratios = (0.32, 0.16, 0.08, 0.04, 0.02) if quick else (0.32, 0.16, 0.08, 0.04, 0.02, 0.01)
    command = "python benchmarks/study_energy_zero_range.py " + " ".join(shlex.quote(x) for x in sys.argv[1:])
    started = _timing.provenance_record()
    ranges, windows = [], []
    for name in args.faces.split(","):
        rec = {} if args.json else None
        lc, F, local = finite_ranges(name, ratios, epz=args.epz, record=rec)
        if args.json:
            rec.update({"command": command, "python": platform.python_version(), "git_commit": _git_commit()})
            store(args.json, f"{name}-epz{args.epz:g}", rec)
        # local rates belong to the interior ranges (each fitted through it and its neighbours)
        ranges.append([name, *(f"{f:.4f}" for f in F), *local[1:-1]])
        if len(lc) >= 4:
            windows += [[name, *w] for w in extrapolations(name, lc, F)]
    if args.update:
        _timing.write_doc_table(
            "accuracy_energy_zero_range_ranges",
            ["face", *(f"F/F_up, l_c/a = {r:g}" for r in ratios), *(f"local rate at {r:g}" for r in ratios[1:-1])],
            ranges,
            started,
        )
        _timing.write_doc_table(
            "accuracy_energy_zero_range_extrapolated",
            ["face", "ratios", "F_0/F_up (fitted rate)", "rate", "estimate", "F_0/F_up (rate 1/2)"],
            windows,
            started,
        )
    if args.no_griffith:
        sys.exit(0)
    Ns = (32, 48, 64) if quick else (48, 64, 96, 128) if args.full else (48, 64, 96)
    angles = (0.0, 15.0, 30.0, 45.0)
    rotations = []
    for name in ("square", "triangle"):
        print(f"\n{name}: Griffith BEM, F_A / F_upper scaled to the nominal area, by rotation against the grid")
        rows = griffith(name, Ns, angles)
        # F = F_inf + c / N through the two finest resolutions
        n1, n2 = rows[-2][0], rows[-1][0]
        m1, m2 = float(rows[-2][-2]), float(rows[-1][-2])
        inf = (n2 * m2 - n1 * m1) / (n2 - n1)
        rotations += [[name, *row] for row in rows]
        rotations.append([name, f"c/N through {n1}, {n2}", *("" for _ in angles), f"{inf:.4f}", ""])
    if args.update:
        _timing.write_doc_table(
            "accuracy_energy_zero_range_griffith",
            ["face", "N/radius", *(f"{a:g} deg" for a in angles), "mean", "wall s"],
            rotations,
            started,
        )
