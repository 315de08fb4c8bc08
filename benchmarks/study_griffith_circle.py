"""Kendall circle: the Griffith BEM's error against resolution and run time.

    python benchmarks/study_griffith_circle.py [N ...]

Prints, for each N (elements per radius): F_A / F_Kendall - 1 against the nominal radius and
against the rasterised area's equivalent radius, d_c / d_Kendall - 1, the stiffness error
against the rasterised radius, the wall time, and a fitted rate of the stiffness error.
"""

from __future__ import annotations

import math
import sys
import time

import _timing  # noqa: F401
import numpy as np

import bem_griffith as bg
import contact_scene as cs
from contact_scene import theory as T


def main(Ns=(16, 24, 32, 48, 64, 96, 128)):
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    FK = T.kendall_adhesion_force(E_star=1.0, radius=1.0, work=1.0)
    dK = T.kendall_critical_approach(E_star=1.0, radius=1.0, work=1.0)
    rows, kerr = [], []
    for N in Ns:
        t = time.perf_counter()
        r = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)))
        wall = time.perf_counter() - t
        a_r = math.sqrt(cs.rasterise(sc.indenter.shape, 1.0 / N).area / math.pi)
        Fr = T.kendall_adhesion_force(E_star=1.0, radius=a_r, work=1.0)
        ke = r.stiffness / (2 * a_r) - 1
        kerr.append(abs(ke))
        rows.append(
            [
                N,
                f"{r.pulloff_force / FK - 1:+.5f}",
                f"{r.pulloff_force / Fr - 1:+.5f}",
                f"{r.pulloff_approach / dK - 1:+.5f}",
                f"{ke:+.5f}",
                f"{0.5 / N:.5f}",
                f"{wall:.2f}",
            ]
        )
        print(
            _timing.table(rows, ["N", "dF/F nominal", "dF/F raster", "dd/d", "dK/K raster", "0.5/N", "wall s"]),
            flush=True,
        )
    if len(Ns) > 2:
        print(f"stiffness error ~ N^-{-np.polyfit(np.log(Ns), np.log(kerr), 1)[0]:.2f}")


if __name__ == "__main__":
    main(tuple(int(a) for a in sys.argv[1:]) or (16, 24, 32, 48, 64, 96, 128))
