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

``--diagnose`` asks why the stress-intensity criterion's square and triangle lie 1-2.5 % below the
energy BEM's zero-range values, with a measure of K that needs no fitting window: the solver's
own energy release of the free front (``stress_intensity.free_front_release``, a central
difference of the stiffness at fixed approach).  It stores under ``diagnostics``:

* ``circle_fit``: fitted K over released K on circular contacts inside a square face (the
  calibration: the fit is exact for the continuum circle);
* ``corner_fit``: the same on the square face's contact with its corners detached along
  tangent arcs, against the corner radius in window radii, for the default window and the
  smallest one (s_in = 4);
* ``pull_snapshots``: along the pull of the square (and with ``--diagnose-faces``, other
  faces), the contact's free front released K over K_c and the fitted K over K_c, for both
  criteria;
* ``window_sweep``: the pull-off with the window's depth s_in fixed at several values
  (``window_depths`` replaced for the run, since the settings do not expose the window).
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
from bem_griffith import stress_intensity as si
from bem_griffith.contact_set import solve_contact_set
from bem_griffith.counters import WorkCounters
from bem_griffith.problem import build_problem
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


def square_scene(angle: float = 0.0) -> cs.Scene:
    shape = cs.Square(math.sqrt(math.pi))
    return cs.Scene(cs.Indenter(shape.rotated(angle) if angle else shape), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))


def face_scene(face: str) -> cs.Scene:
    """'square' (side sqrt(pi), area pi) or a built-in crossval scene by name (E* = 1, w = 1)."""
    if face == "square":
        return square_scene()
    from crossval.suite import load_scene_or_builtin

    return load_scene_or_builtin(face)


def fitted_over_released(problem, settings, contact, depths) -> tuple[float, si.FrontRelease | None]:
    """sqrt(mean fitted G / released G) over the free-front cells, and the release."""
    solution = solve_contact_set(problem, contact, settings, None, WorkCounters())
    release = si.free_front_release(problem, contact, settings, solution=solution)
    if release is None:
        return math.nan, None
    fit = si.fit_front(contact, solution.pressure_per_approach, problem.spacing, depths)
    k = np.full(int(contact.sum()), np.nan)
    k[fit.cells] = fit.intensity_per_approach
    fitted = k[release.cells]
    return math.sqrt(float(np.nanmean(fitted**2))) / release.intensity_per_approach, release


def square_face_problem(N: int):
    """The square face of side 2 on an N-per-radius grid, its settings, cell coordinates about
    its centre and its half side (cells)."""
    settings = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), rtol=1e-12)
    problem = build_problem(
        cs.Scene(cs.Indenter(cs.Square(2.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0)), settings
    )
    rows, cols = np.nonzero(problem.face)
    i, j = np.mgrid[0 : problem.face.shape[0], 0 : problem.face.shape[1]].astype(float)
    x, y = i - (rows.min() + rows.max()) / 2, j - (cols.min() + cols.max()) / 2
    return problem, settings, x, y, (rows.max() - rows.min() + 1) / 2


def circle_fit_rows(grids=(40, 72, 144)) -> list[dict]:
    rows = []
    for N in grids:
        problem, settings, x, y, half = square_face_problem(N)
        depths = si.window_depths(N)
        for fraction in (0.6, 0.85):
            radius = fraction * half
            contact = problem.face & ((x + 0.21) ** 2 + (y + 0.37) ** 2 < radius**2)
            ratio, release = fitted_over_released(problem, settings, contact, depths)
            rows.append(
                {
                    "N": N,
                    "radius_cells": radius,
                    "s_in": depths[0],
                    "fitted_over_released": ratio,
                    "peel_over_add": release.peel_over_add,
                }
            )
    return rows


def rounded_corners(x, y, half_side, corner_radius):
    ax, ay = np.abs(x), np.abs(y)
    centre = half_side - corner_radius
    in_corner = (ax > centre) & (ay > centre)
    return ~in_corner | ((ax - centre) ** 2 + (ay - centre) ** 2 < corner_radius**2)


def corner_fit_rows(grids=(72, 144), windows=(0.15, 0.25, 0.35, 0.5, 0.65, 0.8, 1.0, 1.2, 1.5, 2.0, 3.0)) -> list[dict]:
    rows = []
    for N in grids:
        problem, settings, x, y, half = square_face_problem(N)
        depths = si.window_depths(N)
        for w in windows:
            radius = w * depths[2]
            if radius > 0.9 * half:
                continue
            contact = problem.face & rounded_corners(x, y, half, radius)
            ratio, release = fitted_over_released(problem, settings, contact, depths)
            small, _ = fitted_over_released(problem, settings, contact, (4.0, 12.0, 12.0))
            rows.append(
                {
                    "N": N,
                    "corner_radius_cells": radius,
                    "corner_radius_windows": w,
                    "s_in": depths[0],
                    "fitted_over_released": ratio,
                    "fitted_over_released_s_in_4": small,
                    "peel_over_add": release.peel_over_add,
                }
            )
    return rows


def snapshot_rows(face: str, N: int, fractions=(0.7, 0.75, 0.8, 0.85, 0.9, 0.92)) -> list[dict]:
    base = face_scene(face)
    area = base.indenter.shape.area
    upper_d = T.upper_bound_approach(E_star=1.0, work=1.0, area=area)
    upper_F = T.upper_bound_force(E_star=1.0, work=1.0, area=area)
    scene = cs.Scene(
        base.indenter,
        base.material,
        base.adhesion,
        base.loading,
        cs.Outputs(snapshots=tuple(f * upper_d for f in fractions)),
    )
    settings = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), rtol=1e-12)
    problem = build_problem(scene, settings)
    critical = math.sqrt(2.0)  # K_c = sqrt(2 E* w)
    rows = []
    for criterion in CRITERIA:
        result = bg.solve(scene, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), criterion=criterion))
        for snap in result.snapshots:
            solution = solve_contact_set(problem, snap.contact, settings, None, WorkCounters())
            release = si.free_front_release(problem, snap.contact, settings, solution=solution)
            row = {
                "face": face,
                "N": N,
                "criterion": criterion,
                "approach_over_upper": snap.approach / upper_d,
                "force_over_upper": -snap.force / upper_F,
                "area_fraction": float(snap.contact.sum() / problem.face.sum()),
            }
            if release is not None and release.cells.size >= 8:
                fit = si.fit_front(snap.contact, solution.pressure_per_approach, problem.spacing, si.window_depths(N))
                k = np.full(int(snap.contact.sum()), np.nan)
                k[fit.cells] = fit.intensity_per_approach
                fitted = k[release.cells]
                scale = abs(snap.approach) / critical
                row |= {
                    "free_front_cells": int(release.cells.size),
                    "released_K_over_Kc": release.intensity_per_approach * scale,
                    "fitted_K_over_Kc_mean": math.sqrt(float(np.nanmean(fitted**2))) * scale,
                    "fitted_K_over_Kc_max": float(np.nanmax(fitted)) * scale,
                    "peel_over_add": release.peel_over_add,
                }
            rows.append(row)
    return rows


def window_sweep_rows(face: str, N: int, depths_in=(4.0, 6.0, 8.0, 12.0)) -> list[dict]:
    scene = face_scene(face)
    area = scene.indenter.shape.area
    upper = T.upper_bound_force(E_star=1.0, work=1.0, area=area)
    rows = []
    default = si.window_depths
    try:
        for s_in in depths_in:
            si.window_depths = lambda n, s=s_in: (s, 3.0 * s, 3.0 * s)
            result = bg.solve(
                scene, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), criterion="stress_intensity")
            )
            scaled = T.force_at_nominal_area(result.pulloff_force, area=result.face_area, nominal_area=area)
            rows.append({"face": face, "N": N, "s_in": s_in, "force_ratio_scaled": scaled / upper})
            print(f"window sweep {face} N = {N} s_in = {s_in:g}: {scaled / upper:.5f}", flush=True)
    finally:
        si.window_depths = default
    rows.append({"face": face, "N": N, "s_in": default(N)[0], "default": True})
    return rows


def diagnose(data: dict, faces: list[str], sweep: list[tuple[str, int]]) -> None:
    diagnostics = data.setdefault("diagnostics", {})
    diagnostics["circle_fit"] = circle_fit_rows()
    print("circle calibration done", flush=True)
    diagnostics["corner_fit"] = corner_fit_rows()
    print("corner fits done", flush=True)
    snapshots = [r for r in diagnostics.get("pull_snapshots", []) if r["face"] not in faces]
    for face in faces:
        snapshots += snapshot_rows(face, 64)
        print(f"snapshots of the {face} done", flush=True)
    diagnostics["pull_snapshots"] = snapshots
    done = {(f, n) for f, n in sweep}
    rows = [r for r in diagnostics.get("window_sweep", []) if (r["face"], r["N"]) not in done]
    for face, N in sweep:
        rows += window_sweep_rows(face, N, (5.0, 6.0, 8.0, 12.0) if face == "triangle" else (4.0, 6.0, 8.0, 12.0))
    diagnostics["window_sweep"] = rows
    diagnostics["finding"] = finding(diagnostics)


def finding(diagnostics: dict) -> list[str]:
    """The measured statements the diagnostics support, one per line."""
    lines = []
    circle = [r["fitted_over_released"] - 1 for r in diagnostics.get("circle_fit", [])]
    if circle:
        lines.append(
            f"circles: the fit is {100 * min(circle):+.2f} to {100 * max(circle):+.2f} % off the solver's release"
        )
    corner = diagnostics.get("corner_fit", [])
    for low, high in ((0.0, 0.3), (0.3, 0.9), (0.9, 1.1), (1.1, 10.0)):
        picked = [r["fitted_over_released"] - 1 for r in corner if low <= r["corner_radius_windows"] < high]
        if picked:
            lines.append(
                f"corners rounded with {low:g}-{high:g} window radii: the fit is {100 * min(picked):+.2f} to "
                f"{100 * max(picked):+.2f} % off the release"
            )
    for face in sorted({r["face"] for r in diagnostics.get("pull_snapshots", [])}):
        for criterion in CRITERIA:
            pairs = [
                (r["approach_over_upper"], r["fitted_K_over_Kc_mean"] / r["released_K_over_Kc"] - 1)
                for r in diagnostics["pull_snapshots"]
                if r["face"] == face and r["criterion"] == criterion and "released_K_over_Kc" in r
            ]
            if pairs:
                worst = max(pairs, key=lambda p: abs(p[1]))
                lines.append(
                    f"{face}, {criterion}: along the pull the fit is {100 * min(p[1] for p in pairs):+.1f} to "
                    f"{100 * max(p[1] for p in pairs):+.1f} % off the release (largest at d = {worst[0]:.2f} d_up), "
                    f"{100 * pairs[-1][1]:+.1f} % at d = {pairs[-1][0]:.2f} d_up"
                )
    return lines


def diagnostics_report(diagnostics: dict) -> str:
    out = []
    out += diagnostics.get("finding", [])
    if diagnostics.get("circle_fit"):
        out.append("")
        out.append("Circular contacts in a square face: fitted K / released K (default window)")
        out.append(
            _timing.table(
                [
                    [
                        r["N"],
                        f"{r['radius_cells']:.1f}",
                        f"{r['fitted_over_released']:.4f}",
                        f"{r['peel_over_add']:.4f}",
                    ]
                    for r in diagnostics["circle_fit"]
                ],
                ["N", "radius (cells)", "fit / release", "peel / add"],
            )
        )
    if diagnostics.get("corner_fit"):
        out.append("")
        out.append("Square face, corners detached along tangent arcs: fitted K / released K on the free front")
        out.append(
            _timing.table(
                [
                    [
                        r["N"],
                        f"{r['corner_radius_cells']:.1f}",
                        f"{r['corner_radius_windows']:.2f}",
                        f"{r['fitted_over_released']:.4f}",
                        f"{r['fitted_over_released_s_in_4']:.4f}",
                        f"{r['peel_over_add']:.4f}",
                    ]
                    for r in diagnostics["corner_fit"]
                ],
                ["N", "corner radius (cells)", "(window radii)", "fit / release", "s_in = 4", "peel / add"],
            )
        )
    if diagnostics.get("pull_snapshots"):
        out.append("")
        out.append("Along the pull: the free front's released and fitted K / K_c (mean over its cells)")
        out.append(
            _timing.table(
                [
                    [
                        r["face"],
                        r["N"],
                        r["criterion"],
                        f"{r['approach_over_upper']:.3f}",
                        f"{r['force_over_upper']:.4f}",
                        f"{r['area_fraction']:.4f}",
                        r.get("free_front_cells", "-"),
                        f"{r['released_K_over_Kc']:.4f}" if "released_K_over_Kc" in r else "-",
                        f"{r['fitted_K_over_Kc_mean']:.4f}" if "fitted_K_over_Kc_mean" in r else "-",
                    ]
                    for r in diagnostics["pull_snapshots"]
                ],
                ["face", "N", "criterion", "d / d_up", "F / F_up", "area", "free front", "K_release/K_c", "K_fit/K_c"],
            )
        )
    if diagnostics.get("window_sweep"):
        out.append("")
        out.append("Stress-intensity pull-off F_A / F_A,upper (scaled) with the window depth s_in fixed")
        out.append(
            _timing.table(
                [
                    [r["face"], r["N"], f"{r['s_in']:g}", f"{r['force_ratio_scaled']:.5f}"]
                    for r in diagnostics["window_sweep"]
                    if not r.get("default")
                ],
                ["face", "N", "s_in", "F/Fup scaled"],
            )
        )
    return "\n".join(out)


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
    if data.get("diagnostics"):
        out.append("")
        out.append(diagnostics_report(data["diagnostics"]))
    return "\n".join(out)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--circle", type=int, nargs="*", help="circle grids (elements per radius)")
    parser.add_argument("--square", type=int, nargs="*", help="square grids (elements per radius)")
    parser.add_argument("--rotation", type=float, nargs="+", default=[0.0, 30.0], help="square rotations (degrees)")
    parser.add_argument("--criteria", nargs="+", default=list(CRITERIA), choices=CRITERIA)
    parser.add_argument("--report-only", action="store_true", help="print the stored table and exit")
    parser.add_argument("--diagnose", action="store_true", help="the fit against the solver's energy release (doc)")
    parser.add_argument("--diagnose-faces", nargs="+", default=["square"], help="faces followed along the pull")
    parser.add_argument(
        "--sweep", nargs="+", default=["square:64", "square:128"], help="face:N pull-offs with fixed windows"
    )
    args = parser.parse_args(argv)
    if args.circle is None and args.square is None and not args.report_only and not args.diagnose:
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
        if args.diagnose:
            sweep = [(face, int(n)) for face, n in (item.split(":") for item in args.sweep)]
            diagnose(data, args.diagnose_faces, sweep)
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
