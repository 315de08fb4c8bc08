"""How many elements per process zone a finite-range pull-off needs (bem_energy), as tables.

The flat circle (Kendall) at fixed ranges, l_c = E* rho^2 / w a fixed fraction of a, on grids
of n elements per l_c: F_A / F_Kendall raw and scaled to the nominal face area (each grid's
staircase face differs in area), and the change against the finest grid.  Below some n the
cohesive zone is trapped by the mesh and F_A overshoots; this sets
``bem_energy.potentials.PROCESS_ZONE_ELEMENTS`` (the fewest for a converged result, and the
default grid's count) per potential.

    python benchmarks/study_energy_process_zone.py [--quick | --full] [--update]

The default stops at 75 elements per radius (minutes); ``--full`` runs the finer sweeps,
up to 200 per radius (exponential to 16 per l_c at 0.16 a and at 0.02 a, Maugis-Dugdale to 32
per l_c at 0.32 a and 0.16 a, and at 0.08 a).
``--update`` writes the table to docs/accuracy_energy_process_zone.json (rendered into
docs/accuracy.md by ``python benchmarks/docs_tables.py``).
"""

from __future__ import annotations

import math
import sys
import time

import _timing  # thread settings first
from _timing import table

import bem_energy as be
import contact_scene as cs
from contact_scene import theory as T

W, E, A = 0.02, 1.0, 1.0


def sweep(kind, ratio, per_lc):
    FK = T.kendall_adhesion_force(E_star=E, radius=A, work=W)
    lc = ratio * A
    sc = cs.Scene(cs.Indenter(cs.Circle(A)), cs.Homogeneous(E, 0.0), cs.Adhesion(W, math.sqrt(lc * W / E), kind))
    res = []
    for n in per_lc:
        h = lc / n
        t = time.perf_counter()
        r = be.pull_off(sc, be.EnergySettings(grid=cs.Grid(spacing=h)))
        dt = time.perf_counter() - t
        area = cs.rasterise(sc.indenter.shape, h).area
        Fn = T.force_at_nominal_area(r.pulloff_force, area=area, nominal_area=sc.indenter.shape.area, k=0.0)
        res.append((n, A / h, r.pulloff_force / FK, Fn / FK, dt))
    ref = res[-1][3]
    rows = [
        [kind, f"{ratio:g}", f"{n:g}", f"{N:.1f}", f"{f:.5f}", f"{fn:.5f}", f"{fn / ref - 1:+.2%}", f"{dt:.1f}"]
        for n, N, f, fn, dt in res
    ]
    print(f"\n{kind}, l_c = {ratio:g} a: F_A / F_Kendall against elements per l_c (change against the finest)")
    print(table(rows, HEADERS), flush=True)
    return rows


HEADERS = ("potential", "l_c/a", "per l_c", "N/radius", "F/F_K", "scaled", "vs finest", "wall s")
QUICK = [("exponential", 0.16, (0.5, 1, 2, 4, 8)), ("maugis_dugdale", 0.32, (2, 4, 8, 16))]
DEFAULT = [
    ("exponential", 0.16, (0.5, 1, 2, 4, 8)),
    ("exponential", 0.04, (0.5, 1, 2, 3)),
    ("maugis_dugdale", 0.32, (2, 4, 8, 16)),
]
FULL = [
    ("exponential", 0.16, (0.5, 1, 2, 4, 8, 16)),
    ("exponential", 0.04, (0.5, 1, 2, 3, 4)),
    ("exponential", 0.02, (0.5, 1, 2, 4)),
    ("maugis_dugdale", 0.32, (2, 4, 8, 16, 32)),
    ("maugis_dugdale", 0.16, (0.5, 1, 2, 4, 8, 16, 32)),
    ("maugis_dugdale", 0.08, (2, 4, 8, 16)),
]


if __name__ == "__main__":
    record = _timing.provenance_record()
    sweeps = QUICK if "--quick" in sys.argv else FULL if "--full" in sys.argv else DEFAULT
    rows = [row for kind, ratio, per_lc in sweeps for row in sweep(kind, ratio, per_lc)]
    if "--update" in sys.argv:
        _timing.write_doc_table("accuracy_energy_process_zone", HEADERS, rows, record)
