"""Cost of a full Pohrt-Popov pull-off, in matvec-equivalents measured in the same run.

    python benchmarks/bench_griffith_pulloff.py [--star512] [--update]

For each case: median wall and CPU time of the pull-off, the median time of one bare padded
FFT convolution (scipy.fft rfft2 -> multiply -> irfft2) at the same padded size, the ratio of
the CPU time to it (the "matvec-equivalents"; the CPU time, because on a shared machine the
wall time also counts other processes) and the operator applications actually counted.  A second
table shows which solver choices change the answer (they must not) and what they cost, with
the CG iterations per contact solve: on a circle, a 4:1 rectangle (whose padded window's
symbol has negative modes, so the preconditioner must be the lattice's) and a star, whose tips
detach first so that its later solves fit into smaller windows (the rows "every set to rtol"
and "plain warm start" switch off the early decisions and the local warm start, "both" is the
solver before them).  ``--star512`` adds the
paper's size, the five-ray star on a 512^2 grid over its bounding box (a quarter of an hour or
more).  ``--update`` writes docs/performance_griffith_pulloff.json and
docs/performance_griffith_choices.json (rendered into docs/performance.md by
``python benchmarks/docs_tables.py``).
"""

from __future__ import annotations

import sys
import time

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
    cases = [("circle", circle, 32, 3), ("circle", circle, 64, 3), ("circle", circle, 128, 3)]
    if star512:
        # the paper's 512 x 512 grid over the star's 2.0 x 2.0 bounding box (takes long)
        cases.append(("star 512^2", star, 512 * star.indenter.shape.equivalent_radius / 2.0, 1))
    rows, precise = [], []
    for name, sc, N, rep in cases:
        st = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N))
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
            ("both (the previous solver)", {"decide_early": False, "local_warm_start": False}),
            ("whole-grid FFTs", {"shrink_window": False}),
            ("rtol 1e-8", {"rtol": 1e-8}),
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


if __name__ == "__main__":
    main(star512="--star512" in sys.argv, update="--update" in sys.argv)
