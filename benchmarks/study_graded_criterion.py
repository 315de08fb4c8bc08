"""Why the graded Griffith BEM misses Eq. 39: the criterion constant of Eq. 42 against the
constant the discrete stress field implies.

    python benchmarks/study_graded_criterion.py [--update]

A flat circular punch detaches unstably (|d_c| grows with a, Eq. 38), so the pull-off is at or
shortly after the first detachment: the moment the most stressed staircase cell of the edge
reaches sigma_c.  (Not always the same moment: on some grids a few isolated cells go first
and the force still rises a little (study_griffith_graded.py prints the pull-offs), so the
prediction below is approximate.)
From the pressed, non-adhesive state (a linear problem) this script reads that cell's stress
in units of the continuum intensity, p ~ K_k s^((k-1)/2) with K_k from the exact pressure
P (a^2 - r^2)^((k-1)/2) (theory sheet, section 5), and so the constant kappa for which the
first detachment falls exactly at Eq. 39:  kappa_implied = g_max K_k,c / sqrt(E0 w / c0^k).
The ratio kappa(Eq. 42) / kappa_implied then predicts F_A / F_A(Eq. 39) of the pull-off.

Columns: the stress factor of a grid-aligned edge cell (top of the circle) and of the most
stressed edge cell, kappa implied, kappa of Eq. 42, and their ratio.  Measured pull-offs to
compare with: ``benchmarks/study_griffith_graded.py``.  ``--update`` writes the table to
docs/accuracy_graded_criterion.json (rendered into docs/accuracy.md by
``python benchmarks/docs_tables.py``).
"""

from __future__ import annotations

import math
import sys

import _timing  # noqa: F401
import numpy as np
import scipy.sparse.linalg as spla
from scipy import ndimage

import bem_griffith as bg
import contact_scene as cs
from bem_griffith.solver import build_problem
from contact_scene import theory as T


def stress_factors(k: float, per_radius: int) -> tuple[float, float]:
    """(aligned-edge, largest) edge-cell pressure / (K_k Delta^((k-1)/2)), pressed state."""
    h = 1.0 / per_radius
    mat = cs.Homogeneous(0.75, 0.5) if k == 0 else cs.PowerLawGraded(1.0, 1.0, k)
    prob = build_problem(
        cs.Scene(cs.Indenter(cs.Circle(1.0)), mat, cs.Adhesion(1.0)), bg.GriffithSettings(grid=cs.Grid(spacing=h))
    )
    S = prob.face
    n = int(S.sum())
    A = spla.LinearOperator((n, n), matvec=lambda v: prob.operator.apply_masked(v, S)[S])
    p, info = spla.cg(A, np.ones(n), rtol=1e-12, maxiter=20_000)
    if info:
        raise RuntimeError(f"CG did not converge (k = {k}, N = {per_radius})")
    P = np.zeros(S.shape)
    P[S] = p
    K = T.graded_stiffness(E0=1.0, c0=1.0, k=k, radius=1.0) if k else 2.0
    Kk = K * (k + 1) / (2 * math.pi) * 2.0 ** ((k - 1) / 2)  # intensity per unit approach, a = 1
    unit = Kk * h ** ((k - 1) / 2)
    x = prob.origin[0] + h * np.arange(S.shape[0])
    top = [P[c, np.flatnonzero(S[c])[-1]] for c in np.flatnonzero(np.abs(x) < h)]
    edge = S & ~ndimage.binary_erosion(S)
    return float(np.mean(top)) / unit, float(P[edge].max()) / unit


def main(ks=(-0.75, -0.5, -0.25, 0.0, 0.25, 0.5, 0.75), Ns=(32, 64), update=False):
    record = _timing.provenance_record()
    rows = []
    for k in ks:
        F = T.graded_adhesion_force(E0=1.0, c0=1.0, k=k, radius=1.0, work=1.0) if k else math.sqrt(8 * math.pi * 4 / 3)
        Kc = F * (k + 1) / (2 * math.pi) * 2.0 ** ((k - 1) / 2)  # critical intensity, E0 = w = c0 = 1
        kappa = T.graded_criterion_constant(k) if k else math.sqrt((4 / 3) / T.element_energy_constant())
        for N in Ns:
            aligned, largest = stress_factors(k, N)
            implied = largest * Kc
            rows.append(
                [
                    f"{k:+.2f}",
                    N,
                    f"{aligned:.4f}",
                    f"{largest:.4f}",
                    f"{implied:.4f}",
                    f"{kappa:.4f}",
                    f"{kappa / implied:.4f}",
                ]
            )
    head = ["k", "N/radius", "aligned cell", "largest cell", "kappa implied", "kappa Eq. 42", "predicted F/F39"]
    print(_timing.table(rows, head), flush=True)
    if update:
        _timing.write_doc_table("accuracy_graded_criterion", head, rows, record)


if __name__ == "__main__":
    main(update="--update" in sys.argv)
