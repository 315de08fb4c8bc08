"""Convergence of the energy-minimisation BEM on the flat circle (Kendall), as tables.

1. Fixed range (l_c = 0.16 a): F_A against elements per radius; error against the finest.
2. Zero-range limit: F_A / F_Kendall against l_c / a at two elements per l_c (at least 16 per
   radius), with (1 - F/F_K) / sqrt(l_c / a): constant means the rate 1/2 that
   the harness's coarse sequence assumes.  Then sqrt-law extrapolations over consecutive
   ratios, with the rate a free fit finds (the default procedure and the cornered faces:
   benchmarks/study_energy_zero_range.py).

    python benchmarks/study_energy.py [--quick] [--update]

``--update`` writes table 1 to docs/accuracy_energy_fixed_range.json (rendered into
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


def circle(range_=None):
    return cs.Scene(cs.Indenter(cs.Circle(A)), cs.Homogeneous(E, 0.0), cs.Adhesion(W, range_))


def fixed_range(Ns, update=False):
    record = _timing.provenance_record()
    sc = circle(math.sqrt(0.16 * A * W / E))
    rows = []
    res = []
    for N in Ns:
        t = time.perf_counter()
        r = be.solve(sc, be.EnergySettings(grid=cs.Grid(elements_per_radius=N)))
        res.append((N, r, time.perf_counter() - t))
    Fref = res[-1][1].pulloff_force
    for N, r, dt in res:
        rows.append(
            (
                N,
                f"{r.pulloff_force:.6f}",
                f"{r.pulloff_force / Fref - 1:+.2e}",
                f"{(r.pulloff_force / Fref - 1) * N:+.3f}",
                r.info["peak"],
                r.iterations,
                f"{dt:.1f}",
            )
        )
    head = ("N/radius", "F_A", "rel. err", "err x N", "peak", "iterations", "wall s")
    print("Fixed range l_c = 0.16 a: F_A against N (error against the finest run)")
    print(table(rows, head), flush=True)
    if update:
        _timing.write_doc_table("accuracy_energy_fixed_range", head, rows, record)


def zero_range(ratios, epz=2.0):
    FK = T.kendall_adhesion_force(E_star=E, radius=A, work=W)
    rows, data = [], []
    for r in ratios:
        lc = r * A
        h = min(lc / epz, A / 16)
        t = time.perf_counter()
        res = be.pull_off(
            circle(),
            be.EnergySettings(grid=cs.Grid(spacing=h)),
            spacing=h,
            potential=be.Potential(W, math.sqrt(lc * W / E)),
        )
        dt = time.perf_counter() - t
        f = res.pulloff_force / FK
        data.append((r, res.pulloff_force))
        rows.append((r, f"{A / h:.1f}", f"{f:.5f}", f"{(1 - f) / math.sqrt(r):.4f}", res.converged, f"{dt:.1f}"))
    print(f"\nZero-range sequence, {epz:g} elements per l_c (>= 16 per radius): F_A / F_Kendall")
    print(table(rows, ("l_c/a", "N/radius", "F/F_K", "(1-F/F_K)/sqrt", "converged", "wall s")))
    import numpy as np

    lc = np.array([x[0] for x in data])
    F = np.array([x[1] for x in data])
    out = []
    for k in range(len(lc) - 1):
        for j in range(k + 2, len(lc) + 1):
            F0, _, est = be.richardson(lc[k:j], F[k:j], rate=0.5)
            free = be.richardson(lc[k:j], F[k:j])[1] if j - k >= 3 else None
            out.append(
                (
                    ",".join(f"{x:g}" for x in lc[k:j]),
                    f"{F0 / FK - 1:+.3%}",
                    f"{est / F0:.2%}",
                    "-" if free is None else f"{free:.2f}",
                )
            )
    print("\nRichardson (rate 1/2, least squares) over consecutive ratios")
    print(table(out, ("ratios", "F0/F_K - 1", "estimate", "free rate")))


if __name__ == "__main__":
    quick = "--quick" in sys.argv
    fixed_range((8, 12, 16, 24, 32) if quick else (8, 12, 16, 24, 32, 48, 64, 96, 128), update="--update" in sys.argv)
    zero_range((0.32, 0.16, 0.08) if quick else (0.32, 0.16, 0.08, 0.04, 0.02))
