"""FEM reference: error against degrees of freedom and wall time, per material case.

    python benchmarks/study_fem.py             # convergence table
    python benchmarks/study_fem.py --locking   # displacement-only elements lock, the mixed form does not

For each case (homogeneous nu = 0.3 and 1/2, graded k = 0.25, 0.5, 0.75, 0.9) and mesh
grading g = 2, 1.5, 1 (element size / distance to the punch edge; for graded bodies the
tensor mesh's growth factor 1 + g), prints the unknowns, the wall time, the errors of K and
F_A against Eqs. 1/6 and 34/39, and the solver's own estimate.
"""
from __future__ import annotations

import time

import _timing  # noqa: F401

import contact_scene as cs
import fem_reference as fr
from contact_scene import theory as T

CASES = [("nu=0.3", cs.Homogeneous(1.0, 0.3)), ("nu=0.5", cs.Homogeneous(0.75, 0.5)),
         ("k=0.25", cs.PowerLawGraded(1.0, 1.0, 0.25)), ("k=0.5", cs.PowerLawGraded(1.0, 1.0, 0.5)),
         ("k=0.75", cs.PowerLawGraded(1.0, 1.0, 0.75)), ("k=0.9", cs.PowerLawGraded(1.0, 1.0, 0.9))]


def main(gradings=(2.0, 1.5, 1.0)):
    rows = []
    for name, mat in CASES:
        sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), mat, cs.Adhesion(1.0))
        if isinstance(mat, cs.Homogeneous):
            E = mat.effective_modulus
            K, F = T.kendall_stiffness(E_star=E, radius=1.0), T.kendall_adhesion_force(E_star=E, radius=1.0, work=1.0)
        else:
            k = mat.exponent
            K = T.graded_stiffness(E0=1.0, c0=1.0, k=k, radius=1.0)
            F = T.graded_adhesion_force(E0=1.0, c0=1.0, k=k, radius=1.0, work=1.0)
        for g in gradings:
            t = time.perf_counter()
            r = fr.solve(sc, fr.FemSettings(grading=g))
            wall = time.perf_counter() - t
            rows.append([name, g, r.info["dofs"], f"{wall:.2f}", f"{r.stiffness / K - 1:+.2e}",
                         f"{r.pulloff_force / F - 1:+.2e}", f"{r.accuracy_estimate:.1e}"])
            print(_timing.table(rows, ["case", "grading", "dofs", "wall s", "dK/K", "dF/F", "estimate"]), flush=True)


def locking(nus=(0.3, 0.49, 0.499, 0.4999, 0.5)):
    """Displacement-only P1 and P2 against the mixed Taylor-Hood form: K / (2 E* a) - 1."""
    from fem_reference.locking import displacement_only_stiffness

    rows = []
    for nu in nus:
        mixed = fr.solve(cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, nu), cs.Adhesion(1.0)),
                         fr.FemSettings(grading=1.0))
        K = T.kendall_stiffness(E_star=1.0 / (1 - nu**2), radius=1.0)
        p1 = f"{displacement_only_stiffness(nu, grading=0.5) - 1:+.2e}" if nu < 0.5 else "n/a"
        p2 = f"{displacement_only_stiffness(nu, order=2, grading=0.5) - 1:+.2e}" if nu < 0.5 else "n/a"
        rows.append([nu, p1, p2, f"{mixed.stiffness / K - 1:+.2e}"])
    print(_timing.table(rows, ["nu", "P1 displacement", "P2 displacement", "Taylor-Hood P4/P3"]))


if __name__ == "__main__":
    import sys

    if "--locking" in sys.argv:
        locking()
    else:
        main()
