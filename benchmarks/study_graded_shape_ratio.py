"""Does grading change a square's strength relative to a circle's the same way in both BEMs?

    python benchmarks/study_graded_shape_ratio.py [--quick | --full] [--update]

The calibrated graded criterion (``bem_griffith.criterion``) fixes one factor per k on the
circle; a square inherits it.  The Griffith solver's square/circle ratio does not depend on
that factor, so what can be checked independently is the ratio itself.  This script compares
the "double ratio" D(k) = [F_square / F_circle](k) / [F_square / F_circle](k = 0), equal
areas, forces scaled to the nominal area, between

* the Griffith BEM (Eq. 42's constant: the ratios do not depend on it) at 32 ... 181 elements
  per radius, and
* the energy BEM at finite process zones l_c / a = 0.32 ... 0.02 with 8 elements per l_c
  (the graded process zone l_c^(1-k) = c_k E_k rho^2 / w, ``bem_energy.potentials``; 8 per l_c
  is more than a graded zone needs, ``--resolution``),

at k = 0.5.  The energy method is not a converged reference here: its circle alone still
moves by percents per halving of l_c, so the table shows the trend, not a limit.  The default
stops the energy BEM at l_c / a = 0.08; ``--full`` adds 0.04 and 0.02 (8 elements per l_c:
400 per radius at 0.02, tens of minutes per face), ``--quick`` stops at 0.08 and 48 per
radius.  ``--update`` writes the table to docs/accuracy_graded_shape_ratio.json (rendered
into docs/accuracy.md by ``python benchmarks/docs_tables.py``).

    python benchmarks/study_graded_shape_ratio.py --zero-range [--ratios R ...] [--cache DIR] [--update]

runs the energy BEM's zero-range sequence instead (``bem_energy.ZeroRangeSettings``' grids: 2
elements per l_c, graded process zones; default l_c / a = 0.08 ... 0.01, ``--ratios`` for
another) on both faces at k = 0 and k = 0.5, each range cached in ``--cache`` (default
``.cache/graded_zero_range``) so that a finer range joins without redoing the others.  Each
sequence is extrapolated with ``bem_energy.richardson``; the circles' limits are checked
against the closed forms (Kendall at k = 0, Eq. 39 at k = 0.5), which says whether the
estimate bounds the error on a graded body too.  D's bar is the sum of the four forces'
relative estimates.  ``--update`` writes docs/accuracy_graded_zero_range.json.

    python benchmarks/study_graded_shape_ratio.py --resolution [--update]

measures how many elements per l_c a graded body needs (the flat circle at l_c = 0.08 a, k = 0,
0.25, 0.5, 0.75, 2 ... 16 elements per l_c; the source of
``bem_energy.potentials.GRADED_ZONE_ELEMENTS``); ``--update`` writes
docs/accuracy_graded_zone_resolution.json.
"""

from __future__ import annotations

import math
import sys
from dataclasses import replace
from pathlib import Path

import _timing
import numpy as np

import bem_energy as be
import bem_griffith as bg
import contact_scene as cs
from bem_energy.potentials import process_zone_modulus, range_for_process_zone
from bem_energy.zero_range import sequence_run, tail_bracket, tail_rates
from contact_scene import theory as T

FACES = {"circle": cs.Circle(1.0), "square": cs.Square(math.sqrt(math.pi))}  # both of area pi
K = 0.5


def griffith(N):
    out = {}
    for k in (0.0, K):
        for name, face in FACES.items():
            r = bg.solve(
                cs.Scene(cs.Indenter(face), cs.PowerLawGraded(1.0, 1.0, k), cs.Adhesion(1.0)),
                bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), graded_criterion="eq42"),
            )
            out[k, name] = T.force_at_nominal_area(
                r.pulloff_force, area=r.info["face_elements"] * r.grid_spacing**2, nominal_area=math.pi, k=k
            )
    return out


def energy(lc_over_a, per_zone=8.0, work=0.02):
    out = {}
    for k in (0.0, K):
        mat = cs.PowerLawGraded(1.0, 1.0, k)
        for name, face in FACES.items():
            h = min(lc_over_a / per_zone, 1 / 24)
            rho = range_for_process_zone(modulus=process_zone_modulus(mat), work=work, length=lc_over_a, exponent=k)
            r = be.pull_off(
                cs.Scene(cs.Indenter(face), mat, cs.Adhesion(work)),
                be.EnergySettings(grid=cs.Grid(spacing=h)),
                spacing=h,
                potential=be.Potential(work, rho),
            )
            out[k, name] = T.force_at_nominal_area(
                r.pulloff_force, area=cs.rasterise(face, h).area, nominal_area=math.pi, k=k
            )
    return out


def row(label, out):
    r0 = out[0.0, "square"] / out[0.0, "circle"]
    rk = out[K, "square"] / out[K, "circle"]
    return [label, f"{r0:.4f}", f"{rk:.4f}", f"{rk / r0:.4f}"]


def main(Ns=(32, 48, 64, 96, 128, 181), lcs=(0.32, 0.16, 0.08), update=False):
    record = _timing.provenance_record()
    headers = ["method", "square/circle k=0", f"square/circle k={K}", "D"]
    rows = []
    for N in Ns:
        rows.append(row(f"Griffith, {N} per radius", griffith(N)))
        print(_timing.table(rows, headers), flush=True)
    for lc in lcs:
        rows.append(row(f"energy, l_c/a = {lc}", energy(lc)))
        print(_timing.table(rows, headers), flush=True)
    if update:
        _timing.write_doc_table("accuracy_graded_shape_ratio", headers, rows, record)


# -- the zero-range sequence ----------------------------------------------------------------------

ZERO_RANGE_WORK = 1.0


def graded_scene(name: str, k: float) -> cs.Scene:
    return cs.Scene(cs.Indenter(FACES[name]), cs.PowerLawGraded(1.0, 1.0, k), cs.Adhesion(ZERO_RANGE_WORK))


def zero_range_run(name: str, k: float, ratio: float, cache: Path) -> dict:
    """One range of the zero-range sequence, as ``bem_energy.zero_range`` runs it, cached."""

    def compute() -> dict:
        rho, res = sequence_run(graded_scene(name, k), ratio, be.ZeroRangeSettings())
        return {
            "face": name,
            "k": k,
            "ratio": ratio,
            "range": rho,
            "spacing": res.grid_spacing,
            "pulloff_force": res.pulloff_force,
            "face_area": res.face_area,
            "converged": bool(res.converged and res.detached),
            "messages": list(res.messages) if not res.converged else [],
        }

    return _timing.cached(cache, (name, f"k{k:g}", ratio), compute)


def zero_range_limit(name: str, k: float, ratios, cache: Path) -> dict:
    """The sequence's forces over the equal-area circle's closed form (Eq. 39; Kendall at k = 0),
    scaled to the nominal area, and their limit with its estimate."""
    exact = T.graded_adhesion_force(E0=1.0, c0=1.0, k=k, radius=1.0, work=ZERO_RANGE_WORK)
    runs = []
    for r in ratios:
        row = zero_range_run(name, k, r, cache)
        print(
            f"{name:6s} k = {k:g}, l_c/a = {r:g}: F = {row['pulloff_force']:.6g} ({row['cpu_s']:.0f} s CPU)", flush=True
        )
        runs.append(row)
    F = np.array(
        [
            T.force_at_nominal_area(x["pulloff_force"], area=x["face_area"], nominal_area=math.pi, k=k) / exact
            for x in runs
        ]
    )
    F0, rate, est = be.richardson(np.array(ratios, float), F, None, tail_rates(k))
    return {
        "face": name,
        "k": k,
        "ratios": list(ratios),
        "forces": F.tolist(),
        "limit": F0,
        "relative_estimate": est / F0,
        "fitted_rate": rate,
        "converged": all(x["converged"] for x in runs),
        "cpu_s": sum(x["cpu_s"] for x in runs),
        # the ranges come from a cache and may be older than the revision assembling the table
        "range_revisions": [x.get("revision") for x in runs],
    }


def zero_range_main(ratios, cache: Path, update: bool) -> None:
    record = _timing.provenance_record()
    seqs = {(name, k): zero_range_limit(name, k, ratios, cache) for k in (0.0, K) for name in FACES}
    headers = ["face", "k", *[f"l_c/a = {r:g}" for r in ratios], "limit", "estimate", "rate", "circle error", "covered"]
    rows = []
    for (name, k), q in seqs.items():
        err = q["limit"] - 1.0 if name == "circle" else None
        rows.append(
            [
                name,
                f"{k:g}",
                *[f"{f:.4f}" for f in q["forces"]],
                f"{q['limit']:.4f}",
                f"{100 * q['relative_estimate']:.2f} %",
            ]
            + ["none" if q["fitted_rate"] is None else f"{q['fitted_rate']:.2f}"]
            + (
                ["", ""]
                if err is None
                else [f"{100 * err:+.2f} %", str(abs(err) <= q["relative_estimate"] * q["limit"])]
            )
        )
    r0 = seqs["square", 0.0]["limit"] / seqs["circle", 0.0]["limit"]
    rk = seqs["square", K]["limit"] / seqs["circle", K]["limit"]
    D = rk / r0
    bar = sum(q["relative_estimate"] for q in seqs.values())
    rows.append(["D of the limits", f"{K:g}", *["" for _ in ratios], f"{D:.4f}", f"{100 * bar:.2f} %", "", "", ""])
    # D at each range, and its own extrapolation (the graded tail bracket: the slower of the two)
    Dseq = np.array(
        [
            (seqs["square", K]["forces"][i] / seqs["circle", K]["forces"][i])
            / (seqs["square", 0.0]["forces"][i] / seqs["circle", 0.0]["forces"][i])
            for i in range(len(ratios))
        ]
    )
    h = np.array(ratios, float)
    D0, Drate, Dest = be.richardson(h, Dseq, None, tail_rates(K))
    Dlow, Dhigh = sorted(tail_bracket(h, Dseq, tail_rates(K)))
    rate = "none" if Drate is None else f"{Drate:.2f}"
    rows.append(
        ["D per range", f"{K:g}", *[f"{x:.4f}" for x in Dseq], f"{D0:.4f}", f"{100 * Dest / D0:.2f} %", rate, "", ""]
    )
    print(_timing.table(rows, headers), flush=True)
    print(
        f"square/circle: k = 0 {r0:.4f}, k = {K:g} {rk:.4f}; D of the limits = {D:.4f} +- {D * bar:.4f}; "
        f"D per range extrapolated {D0:.4f} +- {Dest:.4f} (tail bracket {Dlow:.4f} ... {Dhigh:.4f})",
        flush=True,
    )
    if update:
        _timing.write_doc_table(
            "accuracy_graded_zero_range",
            headers,
            rows,
            record,
            sequences=list(seqs.values()),
            double_ratio={
                "of_the_limits": {"value": D, "relative_bar": bar, "square_over_circle": {"0": r0, str(K): rk}},
                "per_range": {
                    "values": Dseq.tolist(),
                    "limit": D0,
                    "estimate": Dest,
                    "fitted_rate": Drate,
                    "tail_bracket": [Dlow, Dhigh],
                },
            },
        )


# -- how many elements per l_c a graded body needs -------------------------------------------------

RESOLUTION_KS = (0.0, 0.25, 0.5, 0.75)
RESOLUTION_COUNTS = (2.0, 4.0, 8.0, 16.0)


def resolution_main(ratio: float, update: bool) -> None:
    """The flat circle at l_c = ``ratio`` a on bodies of grading k, on grids of 2 ... 16 elements
    per l_c (the source of ``bem_energy.potentials.GRADED_ZONE_ELEMENTS``): F_A over Eq. 39 and
    its excess over the finest grid's."""
    record = _timing.provenance_record()
    headers = [
        "k",
        *[f"{n:g} per l_c" for n in RESOLUTION_COUNTS],
        *[f"excess at {n:g}" for n in RESOLUTION_COUNTS[:-1]],
    ]
    rows, raw = [], []
    zs = be.ZeroRangeSettings()
    for k in RESOLUTION_KS:
        scene = graded_scene("circle", k)
        exact = T.graded_adhesion_force(E0=1.0, c0=1.0, k=k, radius=1.0, work=ZERO_RANGE_WORK)
        rho = range_for_process_zone(
            modulus=process_zone_modulus(scene.material), work=ZERO_RANGE_WORK, length=ratio, exponent=k
        )
        Fs = []
        for n in RESOLUTION_COUNTS:
            h = min(ratio / n, 1.0 / zs.minimum_elements_per_radius)
            res = be.pull_off(
                scene,
                replace(zs.energy, grid=cs.Grid(spacing=h)),
                spacing=h,
                potential=be.Potential(ZERO_RANGE_WORK, rho),
            )
            F = T.force_at_nominal_area(
                res.pulloff_force, area=cs.rasterise(scene.indenter.shape, h).area, nominal_area=math.pi, k=k
            )
            Fs.append(F / exact)
            raw.append(
                {
                    "k": k,
                    "elements_per_process_zone": n,
                    "spacing": h,
                    "force_over_eq39": F / exact,
                    "converged": bool(res.converged),
                }
            )
            print(f"k = {k:g}, {n:g} per l_c (h = {h:.4g}): F / Eq. 39 = {F / exact:.5f}", flush=True)
        rows.append([f"{k:g}", *[f"{f:.5f}" for f in Fs], *[f"{100 * (f / Fs[-1] - 1):+.2f} %" for f in Fs[:-1]]])
    print(_timing.table(rows, headers), flush=True)
    if update:
        _timing.write_doc_table("accuracy_graded_zone_resolution", headers, rows, record, runs=raw)


def option(name: str, default):
    if name not in sys.argv:
        return default
    i = sys.argv.index(name) + 1
    vals = []
    while i < len(sys.argv) and not sys.argv[i].startswith("--"):
        vals.append(sys.argv[i])
        i += 1
    return vals


if __name__ == "__main__":
    update = "--update" in sys.argv
    if "--resolution" in sys.argv:
        resolution_main(0.08, update)
    elif "--zero-range" in sys.argv:
        ratios = tuple(float(x) for x in option("--ratios", be.ZeroRangeSettings().ratios))
        cache = Path(option("--cache", [str(Path(_timing.ROOT) / ".cache" / "graded_zero_range")])[0])
        zero_range_main(ratios, cache, update)
    elif "--quick" in sys.argv:
        main(Ns=(32, 48), lcs=(0.32, 0.16, 0.08), update=update)
    elif "--full" in sys.argv:
        main(lcs=(0.32, 0.16, 0.08, 0.04, 0.02), update=update)
    else:
        main(update=update)
