"""Graded circle: the Griffith BEM's pull-off force against Eq. 39 over a resolution sweep.

    python benchmarks/study_griffith_graded.py

Prints F_A / F_A(Eq. 39) - 1 and d_c / d_c(Eq. 38) - 1 for k in -0.75 .. 0.75 and
N = 16, 32, 64 elements per radius, with the criterion constant kappa(k) of Eq. 42.
"""
from __future__ import annotations

import _timing  # noqa: F401
import bem_griffith as bg
import contact_scene as cs
from contact_scene import theory as T


def main(ks=(-0.75, -0.5, -0.25, 0.0, 0.25, 0.5, 0.75), Ns=(16, 32, 64)):
    rows = []
    for k in ks:
        sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.PowerLawGraded(1.0, 1.0, k), cs.Adhesion(1.0))
        F = T.graded_adhesion_force(E0=1.0, c0=1.0, k=k, radius=1.0, work=1.0)
        d = T.graded_critical_approach(E0=1.0, c0=1.0, k=k, radius=1.0, work=1.0)
        row = [f"{k:+.2f}", f"{T.graded_criterion_constant(k):.4f}"]
        for N in Ns:
            r = bg.solve(sc, bg.Settings(grid=cs.Grid(elements_per_radius=N)))
            row.append(f"{r.pulloff_force / F - 1:+.4f} / {r.pulloff_approach / d - 1:+.4f}")
        rows.append(row)
        print(_timing.table(rows, ["k", "kappa", *[f"N={N}: dF/F / dd/d" for N in Ns]]), flush=True)


if __name__ == "__main__":
    main()
