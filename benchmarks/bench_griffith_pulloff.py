"""Cost of a full Pohrt-Popov pull-off, in matvec-equivalents measured in the same run.

    python benchmarks/bench_griffith_pulloff.py [--star512] [--update]
    python benchmarks/bench_griffith_pulloff.py --ties [--update]
    python benchmarks/bench_griffith_pulloff.py --curved [--update]
    python benchmarks/bench_griffith_pulloff.py --profile [--star512] [--update]

For each case: median wall and CPU time of the pull-off, the median time of one bare padded
FFT convolution (scipy.fft rfft2 -> multiply -> irfft2) at the same padded size, the ratio of
the CPU time to it (the "matvec-equivalents"; the CPU time, because on a shared machine the
wall time also counts other processes) and the operator applications actually counted.  A second
table shows which solver choices change the answer and what they cost, with the CG
iterations per contact solve (the speed-ups must not change the answer; a looser CG tolerance
moves it at its own level, and a larger tie tolerance tau within the factor [1 - tau, 1] that
``GriffithSettings.tie_tolerance`` states, under its conditions): on a circle, a 4:1 rectangle (whose padded window's
symbol has negative modes, so the preconditioner must be the lattice's) and a star, whose tips
detach first so that its later solves fit into smaller windows (the rows "every set to rtol"
and "plain warm start" switch off the early decisions and the local warm start, "neither" both
of them).  ``--star512`` adds the paper's size, the five-ray star on a 512^2 grid over its
bounding box (long), as it is and with tie tolerances 1e-3 and 1e-2.  A third table pulls seven
of the suite's flat faces with the default tie tolerance and with 1e-3, alternated: the CPU time
and the work of each and how far F_A, the approach at F_A and the detachment approach moved
(``--ties``: that table alone).  ``--update`` writes docs/performance_griffith_pulloff.json,
docs/performance_griffith_choices.json and docs/performance_griffith_ties.json (rendered into
docs/performance.md by ``python benchmarks/docs_tables.py``).  ``--curved`` pulls the JKR
sphere (homogeneous and graded) with the cascade's early decisions and with every contact set
solved to rtol, alternated: CPU times, work and whether the answer moved; ``--update`` writes
docs/performance_griffith_curved.json.  ``--profile`` splits the star's pull-off at 128^2 and
256^2 (and 512^2 with ``--star512``) into the solves of passing and of holding contact sets and
into double-precision operator products and single-precision preconditioner applications
(their CPU shares); ``--update`` writes docs/performance_griffith_profile.json.

    python benchmarks/bench_griffith_pulloff.py --baseline [REV] [--star512] [--update]

compares the solver with its state at git revision REV (``bem_griffith`` and ``halfspace``
extracted with ``git archive``; default BASELINE) on the star at 128^2 and 256^2 (and 512^2 with
``--star512``, once each) and the circle at 128 per radius: each case runs in fresh
subprocesses, old and new alternated, and the table shows their CPU times, the ratio of the
medians, the work counted and whether the answer moved (same contact areas along the curve,
F_A to how many digits).  ``--update`` writes
docs/performance_griffith_baseline.json.
"""

from __future__ import annotations

import hashlib
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import _timing  # noqa: F401  (thread counts first)
import numpy as np
import scipy.fft as sfft

import bem_griffith as bg
import contact_scene as cs
from halfspace.kernel import padded_shape


def bare_conv_time(nx, ny) -> float:
    P = padded_shape(nx, ny)
    buf = np.zeros(P)
    buf[:nx, :ny] = np.random.default_rng(0).random((nx, ny))
    khat = sfft.rfft2(np.random.default_rng(1).random(P))
    return _timing.median_time(lambda: sfft.irfft2(sfft.rfft2(buf) * khat, s=P), repeat=15, number=3)


def time_solve(scene, settings, repeat):
    """Median wall and CPU seconds of ``repeat`` solves, and the last result.  The CPU time is
    what the ratios use: on a shared machine the wall time also counts other processes."""
    ts, cpu, res = [], [], None
    for _ in range(repeat):
        t, c = time.perf_counter(), time.process_time()
        res = bg.solve(scene, settings)
        ts.append(time.perf_counter() - t)
        cpu.append(time.process_time() - c)
    return float(np.median(ts)), float(np.median(cpu)), res


COST_HEADERS = [
    "case",
    "N/radius",
    "grid",
    "wall s",
    "cpu s",
    "bare conv ms",
    "matvec-eq",
    "matvecs",
    "solves",
    "events",
    "F_A",
]
CHOICE_HEADERS = [
    "case",
    "choice",
    "wall s",
    "cpu s",
    "cpu / default",
    "matvecs",
    "CG it/solve",
    "F_A",
    "|dF_A|/F_A",
    "|d det| rel",
    "same areas",
]


def main(star512=False, update=False):
    record = _timing.provenance_record()
    E = cs.Homogeneous(0.75, 0.5)
    circle = cs.Scene(cs.Indenter(cs.Circle(1.0)), E, cs.Adhesion(1.0))
    star = cs.Scene(cs.Indenter(cs.Star(5, 1.0, 0.45)), E, cs.Adhesion(1.0))
    rectangle = cs.Scene(cs.Indenter(cs.Rectangle(4.0, 1.0)), E, cs.Adhesion(1.0))
    cases = [("circle", circle, 32, 3, {}), ("circle", circle, 64, 3, {}), ("circle", circle, 128, 3, {})]
    if star512:
        # the paper's 512 x 512 grid over the star's 2.0 x 2.0 bounding box (takes long), and the
        # same with near-simultaneous events batched (F_A within a factor [1 - tau, 1]) at two tau
        N512 = 512 * star.indenter.shape.equivalent_radius / 2.0
        cases.append(("star 512^2", star, N512, 1, {}))
        cases.append(("star 512^2, tie tolerance 1e-3", star, N512, 1, {"tie_tolerance": 1e-3}))
        cases.append(("star 512^2, tie tolerance 1e-2", star, N512, 1, {"tie_tolerance": 1e-2}))
    rows, precise = [], []
    for name, sc, N, rep, kw in cases:
        st = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), **kw)
        wall, cpu, r = time_solve(sc, st, rep)
        nx, ny = r.info["grid"]
        tb = bare_conv_time(nx, ny)
        rows.append(
            [
                name,
                f"{N:.0f}",
                f"{nx}x{ny}",
                f"{wall:.2f}",
                f"{cpu:.2f}",
                f"{tb * 1e3:.2f}",
                f"{cpu / tb:.0f}",
                r.info["matvecs"],
                r.info["solves"],
                r.info["events"],
                f"{r.pulloff_force:.6g}",
            ]
        )
        precise.append(
            {
                "case": name,
                "grid": [nx, ny],
                "pulloff_force": r.pulloff_force,
                "detachment_approach": r.detachment_approach,
                "cg_iterations": r.iterations,
            }
        )
        print(_timing.table(rows, COST_HEADERS), flush=True)
    if update:  # each table as soon as it is complete: the star at 512^2 alone takes a quarter of an hour
        _timing.write_doc_table("performance_griffith_pulloff", COST_HEADERS, rows, record, precise=precise)
    print()
    # which choices change the answer: a circle, an elongated face, and a star, whose tips
    # detach first so that its later solves fit into smaller windows
    choices = []
    for name, sc, N in [
        ("circle", circle, 48),
        ("rectangle 4:1", rectangle, 32),
        ("star 128^2", star, 128 * star.indenter.shape.equivalent_radius / 2.0),
    ]:
        rows, ref = [], None
        for label, kw in [
            ("default (fourier, cut cascade, window, early decisions)", {}),
            ("no preconditioner", {"preconditioner": "none"}),
            ("full cascade", {"stop_when_certainly_detached": False}),
            ("every set to rtol", {"decide_early": False}),
            ("plain warm start", {"local_warm_start": False}),
            ("neither (full solves, plain warm start)", {"decide_early": False, "local_warm_start": False}),
            ("whole-grid FFTs", {"shrink_window": False}),
            ("rtol 1e-8", {"rtol": 1e-8}),
            ("tie tolerance 1e-3", {"tie_tolerance": 1e-3}),
            ("tie tolerance 1e-2", {"tie_tolerance": 1e-2}),
        ]:
            wall, cpu, r = time_solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), **kw), 3)
            if ref is None:
                ref, ref_cpu = r, cpu
            same = np.array_equal(r.curve.contact_area, ref.curve.contact_area)
            rows.append(
                [
                    f"{name}, {N:.0f} per radius",
                    label,
                    f"{wall:.2f}",
                    f"{cpu:.2f}",
                    f"{cpu / ref_cpu:.2f}",
                    r.info["matvecs"],
                    f"{r.iterations / max(r.info['solves'], 1):.1f}",
                    f"{r.pulloff_force:.10g}",
                    f"{abs(r.pulloff_force / ref.pulloff_force - 1):.1e}",
                    f"{abs(r.detachment_approach / ref.detachment_approach - 1):.1e}",
                    "yes" if same else "no",
                ]
            )
        print(_timing.table(rows, CHOICE_HEADERS), flush=True)
        print()
        choices += rows
    if update:
        _timing.write_doc_table("performance_griffith_choices", CHOICE_HEADERS, choices, record)
    print()
    ties(update, record)


def ties(update: bool, record: dict | None = None) -> None:
    """The tie table, written to docs/performance_griffith_ties.json with ``update``."""
    rows = tie_table()
    if update:
        _timing.write_doc_table("performance_griffith_ties", TIE_HEADERS, rows, record or _timing.provenance_record())


#: the tie tolerance of the merged runs: F_A and the detachment approach within a relative tau
#: below the exact pull's (the bound), tau far below the faces' discretisation errors
MERGED_TIES = 1e-3
#: seven of the suite's flat faces (the bound's premises hold on each: flat, pulled without turning
#: points, homogeneous or 0 <= k <= 0.95, not periodic) and the resolutions of the tie table: the
#: star at about the finest-but-one of its reference sweep, the others at 64 per radius, the
#: circles at 128
TIE_FACES = [
    ("kendall_circle", 128),
    ("graded_circle_k0.5", 128),
    ("square", 64),
    ("triangle", 64),
    ("rectangle", 64),
    ("two_circles", 64),
    ("star", 90),
]
#: alternated pairs of runs per face (the CPU times are their medians): short runs vary more
TIE_ROUNDS = 3


def _tau(value: float) -> str:
    return np.format_float_scientific(value, trim="-", exp_digits=1)


TIE_HEADERS = [
    "face",
    "N/radius",
    f"cpu s, tau {_tau(bg.GriffithSettings().tie_tolerance)} (default)",
    f"cpu s, tau {_tau(MERGED_TIES)}",
    "cpu merged / default",
    "matvecs default / merged",
    "events default / merged",
    "F_A change",
    "d(F_A) change",
    "detachment approach change",
]


def tie_table() -> list[list]:
    """Seven of the suite's flat faces pulled with ties at round-off (the default) and merged
    within ``MERGED_TIES``: the CPU time of each (median of ``TIE_ROUNDS`` alternated pairs), the
    operator applications and events (which do not vary between runs), and how far F_A, the
    approach at F_A and the detachment approach moved (merged / default - 1; the bound covers F_A
    and the detachment approach, from below, not the approach at F_A)."""
    from crossval.suite import scene as builtin_scene

    rows = []
    for face, N in TIE_FACES:
        sc = builtin_scene(face)
        settings = {
            "default": bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)),
            "merged": bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), tie_tolerance=MERGED_TIES),
        }
        cpu: dict[str, list[float]] = {"default": [], "merged": []}
        result = {}
        for i in range(TIE_ROUNDS):
            for tag in ("default", "merged") if i % 2 == 0 else ("merged", "default"):
                _, seconds, result[tag] = time_solve(sc, settings[tag], 1)
                cpu[tag].append(seconds)
        exact, merged = result["default"], result["merged"]
        t0, t1 = float(np.median(cpu["default"])), float(np.median(cpu["merged"]))
        rows.append(
            [
                face,
                N,
                f"{t0:.2f}",
                f"{t1:.2f}",
                f"{t1 / t0:.2f}",
                f"{exact.info['matvecs']} / {merged.info['matvecs']}",
                f"{exact.info['events']} / {merged.info['events']}",
                f"{merged.pulloff_force / exact.pulloff_force - 1:+.1e}",
                f"{merged.pulloff_approach / exact.pulloff_approach - 1:+.1e}",
                f"{merged.detachment_approach / exact.detachment_approach - 1:+.1e}",
            ]
        )
        print(_timing.table(rows, TIE_HEADERS), flush=True)
    return rows


#: the curved table's cases: the suite's JKR sphere (elements per face radius) and the same
#: sphere on a graded body, each pulled with early decisions and without, alternated
CURVED_CASES = [
    ("jkr_sphere", None, 32),
    ("jkr_sphere", None, 56),
    ("jkr_sphere", None, 80),
    ("jkr_sphere, graded k = 0.5", cs.PowerLawGraded(1.0, 0.5, 0.5), 32),
]
CURVED_ROUNDS = 2
CURVED_HEADERS = [
    "case",
    "N/face radius",
    "cpu s, every set to rtol",
    "cpu s, early decisions (default)",
    "full / early",
    "CG it full / early",
    "matvecs full / early",
    "solves",
    "decided",
    "|dF_A|/F_A",
    "same areas",
]


def curved(update: bool) -> None:
    """Curved faces: a cascade's passing sets decided on their pressure at the cascade's
    approach (``GriffithSettings.decide_early``, the default) against every set solved to
    rtol for x1 and xh, alternated in one process; written to
    docs/performance_griffith_curved.json with ``update``."""
    import dataclasses

    from crossval.suite import SUITE

    record = _timing.provenance_record()
    rows = []
    for name, material, N in CURVED_CASES:
        sc = SUITE["jkr_sphere"] if material is None else dataclasses.replace(SUITE["jkr_sphere"], material=material)
        runs: dict[bool, list] = {True: [], False: []}
        for i in range(CURVED_ROUNDS):
            for early in (False, True) if i % 2 == 0 else (True, False):
                cpu = time.process_time()
                r = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), decide_early=early))
                runs[early].append((time.process_time() - cpu, r))
        full, early = runs[False], runs[True]
        t_full = float(np.median([t for t, _ in full]))
        t_early = float(np.median([t for t, _ in early]))
        a, b = full[0][1], early[0][1]
        rows.append(
            [
                name,
                N,
                f"{t_full:.2f}",
                f"{t_early:.2f}",
                f"{t_full / t_early:.2f}",
                f"{a.iterations} / {b.iterations}",
                f"{a.info['matvecs']} / {b.info['matvecs']}",
                f"{b.info['solves']}",
                f"{b.info['decided_solves']}",
                f"{abs(b.pulloff_force / a.pulloff_force - 1):.1e}",
                "yes" if np.array_equal(a.curve.contact_area, b.curve.contact_area) else "no",
            ]
        )
        print(_timing.table(rows, CURVED_HEADERS), flush=True)
    if update:
        _timing.write_doc_table("performance_griffith_curved", CURVED_HEADERS, rows, record)


PROFILE_HEADERS = [
    "case",
    "grid",
    "cpu s",
    "events",
    "solves / event",
    "passing solves",
    "their cpu share",
    "products / passing solve",
    "holding solves",
    "their cpu share",
    "products / holding solve",
    "operator products (double)",
    "their cpu share",
    "preconditioner (single)",
    "their cpu share",
]


def profile(star512: bool, update: bool) -> None:
    """Where a star's pull-off spends its time: the contact solves of a cascade's passing sets
    (decided early, ``GriffithSettings.decide_early``) against those of the sets that hold
    (solved to rtol), and the double-precision operator products against the single-precision
    preconditioner's, each timed (CPU) around the solver's own calls in one run; written to
    docs/performance_griffith_profile.json with ``update``.  The instrumentation costs a few
    microseconds a call, so the shares, not the totals, are the measure."""
    import bem_griffith.driver as driver
    from halfspace.operator import HalfSpaceOperator

    star = cs.Scene(cs.Indenter(cs.Star(5, 1.0, 0.45)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    cells = [128, 256] + ([512] if star512 else [])
    record = _timing.provenance_record()
    rows = []
    tally: dict = {}

    def account(key, start, products):
        entry = tally.setdefault(key, [0, 0.0, 0])
        entry[0] += 1
        entry[1] += time.process_time() - start
        entry[2] += tally["products"] - products

    def counted(key, fn):
        def wrapper(*args, **kwargs):
            start = time.process_time()
            tally["products"] += 1
            try:
                return fn(*args, **kwargs)
            finally:
                account(key, start, tally["products"])

        return wrapper

    originals = (driver.solve_contact_set, HalfSpaceOperator.apply_masked, HalfSpaceOperator.apply_symbol)

    def solve(problem, contact, settings, warm_start, counters, *args):
        decided = counters.decided_solves
        start, products = time.process_time(), tally["products"]
        state = originals[0](problem, contact, settings, warm_start, counters, *args)
        account("passing" if counters.decided_solves > decided else "holding", start, products)
        return state

    try:
        driver.solve_contact_set = solve
        HalfSpaceOperator.apply_masked = counted("operator", originals[1])
        HalfSpaceOperator.apply_symbol = counted("preconditioner", originals[2])
        for n in cells:
            tally.clear()
            tally["products"] = 0
            N = n * star.indenter.shape.equivalent_radius / 2.0
            cpu = time.process_time()
            r = bg.solve(star, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)))
            cpu = time.process_time() - cpu
            nx, ny = r.info["grid"]

            def share(key, cpu=cpu):
                return f"{tally.get(key, [0, 0.0])[1] / cpu:.2f}"

            def per_solve(key):
                count, _, products = tally.get(key, [0, 0.0, 0])
                return f"{products / max(count, 1):.1f}"

            rows.append(
                [
                    f"star {n}^2",
                    f"{nx}x{ny}",
                    f"{cpu:.1f}",
                    r.info["events"],
                    f"{r.info['solves'] / max(r.info['events'], 1):.2f}",
                    tally.get("passing", [0])[0],
                    share("passing"),
                    per_solve("passing"),
                    tally.get("holding", [0])[0],
                    share("holding"),
                    per_solve("holding"),
                    tally.get("operator", [0])[0],
                    share("operator"),
                    tally.get("preconditioner", [0])[0],
                    share("preconditioner"),
                ]
            )
            print(_timing.table(rows, PROFILE_HEADERS), flush=True)
    finally:
        driver.solve_contact_set, HalfSpaceOperator.apply_masked, HalfSpaceOperator.apply_symbol = originals
    if update:
        _timing.write_doc_table("performance_griffith_profile", PROFILE_HEADERS, rows, record)


ROOT = Path(__file__).resolve().parent.parent
#: the solver before the in-place transforms and the energy-norm decision bounds
BASELINE = "b5fc263"
BASELINE_HEADERS = [
    "case",
    "grid",
    "old cpu s",
    "new cpu s",
    "old/new",
    "CG it old/new",
    "matvecs old/new",
    "|dF_A|/F_A",
    "same areas",
]


def baseline_case(name: str):
    """The scene and elements per radius of a baseline case."""
    E = cs.Homogeneous(0.75, 0.5)
    if name.startswith("star"):
        star = cs.Scene(cs.Indenter(cs.Star(5, 1.0, 0.45)), E, cs.Adhesion(1.0))
        cells = int(name.split()[1].split("^")[0])
        return star, cells * star.indenter.shape.equivalent_radius / 2.0
    return cs.Scene(cs.Indenter(cs.Circle(1.0)), E, cs.Adhesion(1.0)), 128


def child(name: str) -> None:
    """Run one baseline case with whichever ``bem_griffith`` is importable; print one JSON line."""
    scene, N = baseline_case(name)
    cpu = time.process_time()
    r = bg.solve(scene, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)))
    cpu = time.process_time() - cpu
    areas = hashlib.sha1(np.asarray(r.curve.contact_area, float).tobytes()).hexdigest()
    print(
        json.dumps(
            {
                "cpu": cpu,
                "pulloff_force": r.pulloff_force,
                "iterations": r.iterations,
                "matvecs": r.info["matvecs"],
                "grid": list(r.info["grid"]),
                "areas": areas,
                "module": bg.__file__,
            }
        )
    )


def against_baseline(rev: str, update: bool, star512: bool = False) -> None:
    """The table against revision ``rev``, old and new alternated in fresh subprocesses (with
    ``star512`` the paper's 512^2 star too, once each)."""
    record = _timing.provenance_record()
    cases = [("circle 128", 3), ("star 128^2", 3), ("star 256^2", 2)] + ([("star 512^2", 1)] if star512 else [])
    rows, precise = [], []
    with tempfile.TemporaryDirectory() as tmp:
        _timing.extract_revision(rev, ["bem_griffith", "halfspace"], tmp)
        paths = {"old": f"{tmp}{os.pathsep}{ROOT}", "new": str(ROOT)}

        def run(tag: str, name: str) -> dict:
            env = dict(os.environ, PYTHONPATH=paths[tag])
            out = subprocess.run(
                [sys.executable, __file__, "--child", name], env=env, check=True, capture_output=True, text=True
            ).stdout
            result = json.loads(out.strip().splitlines()[-1])
            expected = tmp if tag == "old" else str(ROOT)
            assert result["module"].startswith(expected), f"{tag} imported {result['module']}"
            return result

        for name, repeat in cases:
            runs: dict[str, list[dict]] = {"old": [], "new": []}
            for i in range(repeat):  # alternated, each order as often as possible
                for tag in ("old", "new") if i % 2 == 0 else ("new", "old"):
                    runs[tag].append(run(tag, name))
            old, new = runs["old"], runs["new"]
            old_cpu = float(np.median([r["cpu"] for r in old]))
            new_cpu = float(np.median([r["cpu"] for r in new]))
            nx, ny = new[0]["grid"]
            rows.append(
                [
                    name,
                    f"{nx}x{ny}",
                    " ".join(f"{r['cpu']:.2f}" for r in old),
                    " ".join(f"{r['cpu']:.2f}" for r in new),
                    f"{old_cpu / new_cpu:.2f}",
                    f"{old[0]['iterations']}/{new[0]['iterations']}",
                    f"{old[0]['matvecs']}/{new[0]['matvecs']}",
                    f"{abs(new[0]['pulloff_force'] / old[0]['pulloff_force'] - 1):.1e}",
                    "yes" if old[0]["areas"] == new[0]["areas"] else "no",
                ]
            )
            precise.append({"case": name, "old": old, "new": new})
            print(_timing.table(rows, BASELINE_HEADERS), flush=True)
    if update:
        _timing.write_doc_table(
            "performance_griffith_baseline", BASELINE_HEADERS, rows, record, baseline=rev, precise=precise
        )


if __name__ == "__main__":
    if "--child" in sys.argv:
        child(sys.argv[sys.argv.index("--child") + 1])
    elif "--baseline" in sys.argv:
        following = sys.argv[sys.argv.index("--baseline") + 1 :]
        revision = following[0] if following and not following[0].startswith("--") else BASELINE
        against_baseline(revision, update="--update" in sys.argv, star512="--star512" in sys.argv)
    elif "--ties" in sys.argv:
        ties(update="--update" in sys.argv)
    elif "--curved" in sys.argv:
        curved(update="--update" in sys.argv)
    elif "--profile" in sys.argv:
        profile(star512="--star512" in sys.argv, update="--update" in sys.argv)
    else:
        main(star512="--star512" in sys.argv, update="--update" in sys.argv)
