"""The Griffith BEM's two detachment criteria compared: the paper's local one (Eq. 22) and the
stress-intensity criterion (``bem_griffith.stress_intensity``).

    python benchmarks/study_griffith_criterion.py                      # everything, default grids
    python benchmarks/study_griffith_criterion.py --circle 32 64 128   # only these circle grids
    python benchmarks/study_griffith_criterion.py --circle --square 64 --rotation 0 30

Measures, for both criteria:

* Kendall's circle: F_A / F_Kendall - 1, the force scaled from the rasterised area to the
  nominal one (``theory.force_at_nominal_area``) and unscaled, the approach at F_A, and the
  stiffness against the rasterised radius (the press does not use the criterion, so it
  is the same for both); then a c/N fit of the scaled error over N >= 64;
* the square: F_A / F_A,upper (Eq. 13, scaled to the nominal area) at each rotation of the
  face against the grid, and its beta (Eq. 9) from the stiffness.

Each run merges its rows into ``docs/griffith_criterion.json`` (keyed by case, criterion and
grid), so the fine grids can run separately; the table printed at the end is the whole file.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time

import _timing
import numpy as np

import bem_griffith as bg
import contact_scene as cs
from contact_scene import theory as T

CRITERIA = ("paper", "stress_intensity")
OUTPUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "griffith_criterion.json")


def circle_row(N: int, criterion: str) -> dict:
    scene = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    start = time.perf_counter()
    result = bg.solve(scene, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), criterion=criterion))
    wall = time.perf_counter() - start
    kendall = T.kendall_adhesion_force(E_star=1.0, radius=1.0, work=1.0)
    scaled = T.force_at_nominal_area(result.pulloff_force, area=result.face_area, nominal_area=math.pi)
    raster_radius = math.sqrt(result.face_area / math.pi)
    return {
        "case": "circle",
        "criterion": criterion,
        "N": N,
        "force_error_scaled": scaled / kendall - 1,
        "force_error_nominal": result.pulloff_force / kendall - 1,
        "approach_error": result.pulloff_approach / T.kendall_critical_approach(E_star=1.0, radius=1.0, work=1.0) - 1,
        "stiffness_error_raster": result.stiffness / T.kendall_stiffness(E_star=1.0, radius=raster_radius) - 1,
        "solves": result.stats.linear_solves,
        "converged": result.converged,
        "wall_s": wall,
    }


def square_row(N: int, angle: float, criterion: str) -> dict:
    shape = cs.Square(math.sqrt(math.pi))
    if angle:
        shape = shape.rotated(angle)
    scene = cs.Scene(cs.Indenter(shape), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    start = time.perf_counter()
    result = bg.solve(scene, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), criterion=criterion))
    wall = time.perf_counter() - start
    upper = T.upper_bound_force(E_star=1.0, work=1.0, area=math.pi)
    scaled = T.force_at_nominal_area(result.pulloff_force, area=result.face_area, nominal_area=math.pi)
    beta = result.stiffness / (2.0 * math.sqrt(result.face_area / math.pi))  # Eq. 9 with E* = 1
    return {
        "case": "square",
        "criterion": criterion,
        "N": N,
        "angle": angle,
        "force_ratio_scaled": scaled / upper,
        "force_ratio_nominal": result.pulloff_force / upper,
        "beta_raster": beta,
        "solves": result.stats.linear_solves,
        "converged": result.converged,
        "wall_s": wall,
    }


def key(row: dict) -> str:
    return f"{row['case']}/{row['criterion']}/{row['N']}" + (f"/{row['angle']:g}" if "angle" in row else "")


def load() -> dict:
    if os.path.exists(OUTPUT):
        with open(OUTPUT) as f:
            return json.load(f)
    return {"description": __doc__.strip().splitlines()[0], "rows": {}}


def first_order_fit(rows: list[dict], criterion: str, smallest: int = 64) -> dict | None:
    """c and the limit e0 of the scaled circle error e(N) = e0 + c / N over N >= smallest."""
    picked = sorted(
        (r["N"], r["force_error_scaled"])
        for r in rows
        if r["case"] == "circle" and r["criterion"] == criterion and r["N"] >= smallest
    )
    if len(picked) < 2:
        return None
    N, e = np.array(picked, float).T
    c, e0 = np.polyfit(1.0 / N, e, 1)
    worst = float(np.max(np.abs(e - (e0 + c / N))))
    return {
        "criterion": criterion,
        "grids": [int(n) for n in N],
        "c": float(c),
        "limit": float(e0),
        "largest_residual": worst,
    }


def report(data: dict) -> str:
    rows = list(data["rows"].values())
    out = []
    circle = sorted((r for r in rows if r["case"] == "circle"), key=lambda r: (r["N"], r["criterion"]))
    if circle:
        out.append("Kendall's circle: F_A / F_Kendall - 1 (%), scaled to the nominal area and unscaled")
        out.append(
            _timing.table(
                [
                    [
                        r["N"],
                        r["criterion"],
                        f"{100 * r['force_error_scaled']:+.3f}",
                        f"{100 * r['force_error_nominal']:+.3f}",
                        f"{100 * r['approach_error']:+.3f}",
                        f"{100 * r['stiffness_error_raster']:+.3f}",
                        r["solves"],
                        f"{r['wall_s']:.1f}",
                    ]
                    for r in circle
                ],
                ["N", "criterion", "dF scaled %", "dF nominal %", "dd %", "dK raster %", "solves", "wall s"],
            )
        )
        for criterion in CRITERIA:
            fit = first_order_fit(rows, criterion)
            if fit:
                out.append(
                    f"{criterion}: scaled error = {100 * fit['limit']:+.3f} % + {fit['c']:+.3f} / N over N = "
                    f"{fit['grids']} (largest residual {100 * fit['largest_residual']:.3f} %)"
                )
    square = sorted((r for r in rows if r["case"] == "square"), key=lambda r: (r["N"], r["criterion"], r["angle"]))
    if square:
        out.append("")
        out.append("Square: F_A / F_A,upper (Eq. 13) scaled to the nominal area, and beta (Eq. 9)")
        out.append(
            _timing.table(
                [
                    [
                        r["N"],
                        r["criterion"],
                        f"{r['angle']:g}",
                        f"{r['force_ratio_scaled']:.5f}",
                        f"{r['force_ratio_nominal']:.5f}",
                        f"{r['beta_raster']:.5f}",
                        r["solves"],
                        f"{r['wall_s']:.1f}",
                    ]
                    for r in square
                ],
                ["N", "criterion", "angle", "F/Fup scaled", "F/Fup nominal", "beta", "solves", "wall s"],
            )
        )
        for criterion in CRITERIA:
            for N in sorted({r["N"] for r in square}):
                values = [r["force_ratio_scaled"] for r in square if r["criterion"] == criterion and r["N"] == N]
                if len(values) > 1:
                    out.append(
                        f"{criterion}, N = {N}: rotation spread of F/Fup (max - min) / mean = "
                        f"{100 * (max(values) - min(values)) / np.mean(values):.3f} %"
                    )
    return "\n".join(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--circle", type=int, nargs="*", help="circle grids (elements per radius)")
    parser.add_argument("--square", type=int, nargs="*", help="square grids (elements per radius)")
    parser.add_argument("--rotation", type=float, nargs="+", default=[0.0, 30.0], help="square rotations (degrees)")
    parser.add_argument("--criteria", nargs="+", default=list(CRITERIA), choices=CRITERIA)
    parser.add_argument("--report-only", action="store_true", help="print the stored table and exit")
    args = parser.parse_args(argv)
    if args.circle is None and args.square is None and not args.report_only:
        args.circle, args.square = [32, 64, 128, 256], [64]
    circle = [] if args.circle is None else (args.circle or [32, 64, 128, 256])
    square = [] if args.square is None else (args.square or [64])
    data = load()
    if not args.report_only:
        for N in circle:
            for criterion in args.criteria:
                row = circle_row(N, criterion)
                data["rows"][key(row)] = row
                print(
                    f"circle N = {N} {criterion}: {100 * row['force_error_scaled']:+.3f} % ({row['wall_s']:.0f} s)",
                    flush=True,
                )
        for N in square:
            for angle in args.rotation:
                for criterion in args.criteria:
                    row = square_row(N, angle, criterion)
                    data["rows"][key(row)] = row
                    print(
                        f"square N = {N} at {angle:g} deg {criterion}: {row['force_ratio_scaled']:.5f} "
                        f"({row['wall_s']:.0f} s)",
                        flush=True,
                    )
        data["fits"] = [fit for c in CRITERIA if (fit := first_order_fit(list(data["rows"].values()), c))]
        data["provenance"] = _timing.provenance()
        data["rows"] = dict(sorted(data["rows"].items()))
        with open(OUTPUT, "w") as f:
            json.dump(data, f, indent=1)
            f.write("\n")
    print(report(data))
    print(data.get("provenance", ""))


if __name__ == "__main__":
    main()
