"""Kendall circle: the Griffith BEM's error against resolution and run time.

    python benchmarks/study_griffith_circle.py [--full] [--update] [N ...]

Prints, for each N (elements per radius): F_A / F_Kendall - 1 against the nominal radius and
against the rasterised area's equivalent radius, the force of the first detachment event over
Kendall's (the staircase cell that reaches the criterion first; the pull-off follows a few
events later), d_c / d_Kendall - 1, the stiffness error against the rasterised radius, the
first-order envelope 0.5/N of the theory sheet, the operator applications and the wall time;
then a fitted rate of the stiffness error.  ``--full`` adds 362 and 510 per radius (a
1022 x 1022 grid: minutes each).  ``--update`` writes docs/accuracy_griffith_circle.json, the
table of docs/accuracy.md (``python benchmarks/docs_tables.py`` renders it).
"""

from __future__ import annotations

import math
import sys
import time

import _timing
import numpy as np

import bem_griffith as bg
import contact_scene as cs
from contact_scene import theory as T

DEFAULT = (16, 24, 32, 48, 64, 96, 128, 181, 256)
FULL = (362, 510)
HEADERS = [
    "N/radius",
    "dF/F nominal",
    "dF/F raster",
    "first detachment F/F_K",
    "dd/d",
    "dK/K raster",
    "0.5/N",
    "matvecs",
    "wall s",
]


def first_detachment_force(r) -> float:
    """|force| at the first event that shrinks the contact: the most stressed cell letting go."""
    area = r.curve.contact_area
    i = int(np.flatnonzero(area[1:] < area[:-1])[0])
    return abs(float(r.curve.force[i]))


def main(Ns=DEFAULT, update=False):
    record = _timing.provenance_record()
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    FK = T.kendall_adhesion_force(E_star=1.0, radius=1.0, work=1.0)
    dK = T.kendall_critical_approach(E_star=1.0, radius=1.0, work=1.0)
    rows, kerr = [], []
    for N in Ns:
        t = time.perf_counter()
        r = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)))
        wall = time.perf_counter() - t
        if not r.converged:
            raise RuntimeError(f"N = {N}: the solve did not converge: {r.messages}")
        a_r = math.sqrt(cs.rasterise(sc.indenter.shape, 1.0 / N).area / math.pi)
        Fr = T.kendall_adhesion_force(E_star=1.0, radius=a_r, work=1.0)
        ke = r.stiffness / (2 * a_r) - 1
        kerr.append(abs(ke))
        rows.append(
            [
                N,
                f"{r.pulloff_force / FK - 1:+.5f}",
                f"{r.pulloff_force / Fr - 1:+.5f}",
                f"{first_detachment_force(r) / FK:.4f}",
                f"{r.pulloff_approach / dK - 1:+.5f}",
                f"{ke:+.5f}",
                f"{0.5 / N:.5f}",
                r.info["matvecs"],
                f"{wall:.2f}",
            ]
        )
        print(_timing.table(rows, HEADERS), flush=True)
    rate = -np.polyfit(np.log(Ns), np.log(kerr), 1)[0] if len(Ns) > 2 else float("nan")
    print(f"stiffness error ~ N^-{rate:.2f}")
    if update:
        _timing.write_doc_table("accuracy_griffith_circle", HEADERS, rows, record, stiffness_rate=rate)


if __name__ == "__main__":
    args = sys.argv[1:]
    Ns = tuple(int(a) for a in args if not a.startswith("--")) or DEFAULT + (FULL if "--full" in args else ())
    main(Ns, update="--update" in args)
