"""Cost of the graded half-space in the Griffith BEM against the homogeneous one, same grid.

Kernel set-up (closed-form 2F1 element integrals vs Love's asinh form) and a full circle
pull-off, as medians and ratios measured in one run.

    python benchmarks/bench_graded.py [--update]

``--update`` writes the table to docs/performance_graded.json (rendered into
docs/performance.md by ``python benchmarks/docs_tables.py``).
"""

from __future__ import annotations

import sys
import time

import _timing  # noqa: F401  (thread settings)
from _timing import median_time, table

import bem_griffith as bg
import contact_scene as cs
from halfspace.kernel import graded_influence, love_influence, padded_shape

HEADERS = ("what", "material", "time", "matvecs", "contact solves", "vs homogeneous")


def main(N: int = 48, update: bool = False):
    record = _timing.provenance_record()
    h = 1.0 / N
    n = 2 * N + 3
    P = padded_shape(n, n)
    t_love = median_time(lambda: love_influence(n, n, h, 1.0, P), repeat=5)
    rows = [[f"kernel set-up, {N} per radius", "homogeneous", f"{t_love * 1e3:.1f} ms", "", "", "1.00"]]
    for k in (0.5, -0.5):
        t = median_time(lambda: graded_influence(n, n, h, 1.0, 1.0, k, P), repeat=3)
        rows.append([f"kernel set-up, {N} per radius", f"k = {k:+g}", f"{t * 1e3:.1f} ms", "", "", f"{t / t_love:.1f}"])
    settings = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N))
    base = None
    for name, mat in (
        ("homogeneous", cs.Homogeneous(0.75, 0.5)),
        ("k = +0.5", cs.PowerLawGraded(1.0, 1.0, 0.5)),
        ("k = -0.5", cs.PowerLawGraded(1.0, 1.0, -0.5)),
    ):
        sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), mat, cs.Adhesion(1.0))
        t0 = time.perf_counter()
        r = bg.solve(sc, settings)
        wall = time.perf_counter() - t0
        base = base or wall
        rows.append(
            [
                f"circle pull-off, {N} per radius",
                name,
                f"{wall:.2f} s",
                r.info["matvecs"],
                r.info["solves"],
                f"{wall / base:.1f}",
            ]
        )
    print(f"Circle, {N} elements per radius ({n} x {n} grid, padded {P})")
    print(table(rows, HEADERS))
    if update:
        _timing.write_doc_table("performance_graded", HEADERS, rows, record)


if __name__ == "__main__":
    main(update="--update" in sys.argv)
