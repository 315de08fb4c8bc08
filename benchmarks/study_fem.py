"""FEM reference: error against degrees of freedom and wall time, and its error estimate.

    python benchmarks/study_fem.py             # convergence table and the estimate's sharpness
    python benchmarks/study_fem.py --quick     # gradings 2 (homogeneous) and 2, 4 (graded) only
    python benchmarks/study_fem.py --locking   # displacement-only elements lock, the mixed form does not
    python benchmarks/study_fem.py --update    # also write the docs table (with --locking: its table)

For each case (homogeneous nu = -0.5, 0, 0.3, 0.5; graded k = 0.25, 0.5, 0.75, 0.9) and mesh
grading g (element size / distance to the punch edge; for graded bodies the tensor mesh's
growth factor 1 + g), prints the unknowns, the wall time (solution and error estimate), the
relative errors of K, F_A and d_c against Eqs. 1/6/4 and 34/39/38, the solver's estimate
(accuracy_estimate, the largest of its three per-quantity bounds) and its ratio to the largest
error, which the estimator must keep within [1, 10], and the comparison solve's share of the
wall time.  The columns rho K and rho K' are the
error ratios between the comparison degree (3) and the solution's degree (4) on the same mesh,
the factor the estimator assumes (fem_reference.solver.order_ratio); rho x g for graded bodies.

``--update`` writes the table to docs/accuracy_fem.json (with ``--locking``:
docs/accuracy_fem_locking.json), rendered into docs/accuracy.md by
``python benchmarks/docs_tables.py``.
"""

from __future__ import annotations

import sys
import time

import _timing  # noqa: F401

import contact_scene as cs
import fem_reference as fr
from contact_scene import theory as T

HOMOGENEOUS = [(f"nu={nu}", cs.Homogeneous(1.0 - nu**2, nu)) for nu in (-0.5, 0.0, 0.3, 0.5)]
GRADED = [(f"k={k}", cs.PowerLawGraded(1.0, 1.0, k)) for k in (0.25, 0.5, 0.75, 0.9)]


def exact(mat, a=1.0, w=1.0):
    """(K, F_A, d_c) of Eqs. 1, 6, 4 or 34, 39, 38."""
    if isinstance(mat, cs.Homogeneous):
        E = mat.effective_modulus
        return (
            T.kendall_stiffness(E_star=E, radius=a),
            T.kendall_adhesion_force(E_star=E, radius=a, work=w),
            T.kendall_critical_approach(E_star=E, radius=a, work=w),
        )
    kw = dict(E0=mat.surface_modulus, c0=mat.reference_depth, k=mat.exponent, radius=a)
    return (T.graded_stiffness(**kw), T.graded_adhesion_force(**kw, work=w), T.graded_critical_approach(**kw, work=w))


def errors(r, mat, a=1.0, w=1.0):
    """Relative errors of (K, F_A, d_c) and of the comparison degree's K and K'."""
    K, F, d = exact(mat, a, w)
    k = 0.0 if isinstance(mat, cs.Homogeneous) else mat.exponent
    dK = (1 + k) * K / a
    return {
        "stiffness": r.stiffness / K - 1,
        "pulloff_force": r.pulloff_force / F - 1,
        "pulloff_approach": r.pulloff_approach / d - 1,
        "dK_da": r.info["dK_da_vce"] / dK - 1,
        "comparison_stiffness": r.info["comparison_stiffness"] / K - 1,
        "comparison_dK_da": r.info["comparison_dK_da"] / dK - 1,
    }


def main_time(r):
    """Wall time of the solution itself: everything but the error estimate's comparison solve."""
    return sum(v for key, v in r.timings.items() if key != "error_estimate")


def main(hom_gradings=(1.0, 2.0), graded_gradings=(1.0, 2.0, 4.0), update=False):
    record = _timing.provenance_record()
    rows = []
    head = [
        "case",
        "grading",
        "dofs",
        "wall s",
        "dK/K",
        "dF/F",
        "dd/d",
        "estimate",
        "est/err",
        "rho K",
        "rho K'",
        "rho g",
        "estimate time / main",
    ]
    for cases, gradings in ((HOMOGENEOUS, hom_gradings), (GRADED, graded_gradings)):
        for name, mat in cases:
            sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), mat, cs.Adhesion(1.0))
            for g in gradings:
                t = time.perf_counter()
                r = fr.solve(sc, fr.FemSettings(grading=g))
                wall = time.perf_counter() - t
                e = errors(r, mat)
                worst = max(abs(e[q]) for q in ("stiffness", "pulloff_force", "pulloff_approach"))
                rho_K = e["comparison_stiffness"] / e["stiffness"]
                rho_dK = e["comparison_dK_da"] / e["dK_da"]
                rows.append(
                    [
                        name,
                        g,
                        r.info["dofs"],
                        f"{wall:.1f}",
                        f"{e['stiffness']:+.2e}",
                        f"{e['pulloff_force']:+.2e}",
                        f"{e['pulloff_approach']:+.2e}",
                        f"{r.accuracy_estimate:.2e}",
                        f"{r.accuracy_estimate / worst:.2f}",
                        f"{rho_K:.1f}",
                        f"{rho_dK:.1f}",
                        "" if isinstance(mat, cs.Homogeneous) else f"{min(rho_K, rho_dK) * g:.1f}",
                        f"{r.timings['error_estimate'] / main_time(r):.2f}",
                    ]
                )
                print(*rows[-1], file=sys.stderr, flush=True)
    print(_timing.table(rows, head))
    if update:
        _timing.write_doc_table("accuracy_fem", head, rows, record)


def locking(nus=(0.3, 0.49, 0.499, 0.4999, 0.5), update=False):
    """Displacement-only P1 and P2 against the mixed Taylor-Hood form: K / (2 E* a) - 1."""
    from fem_reference.locking import displacement_only_stiffness

    record = _timing.provenance_record()
    rows = []
    for nu in nus:
        mixed = fr.solve(
            cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, nu), cs.Adhesion(1.0)),
            fr.FemSettings(grading=1.0),
        )
        K = T.kendall_stiffness(E_star=1.0 / (1 - nu**2), radius=1.0)
        p1 = f"{displacement_only_stiffness(nu, grading=0.5) - 1:+.2e}" if nu < 0.5 else "n/a"
        p2 = f"{displacement_only_stiffness(nu, order=2, grading=0.5) - 1:+.2e}" if nu < 0.5 else "n/a"
        rows.append([nu, p1, p2, f"{mixed.stiffness / K - 1:+.2e}"])
    head = ["nu", "P1 displacement", "P2 displacement", "Taylor-Hood P4/P3"]
    print(_timing.table(rows, head))
    if update:
        _timing.write_doc_table("accuracy_fem_locking", head, rows, record)


if __name__ == "__main__":
    update = "--update" in sys.argv
    if "--locking" in sys.argv:
        locking(update=update)
    elif "--quick" in sys.argv:
        main(hom_gradings=(2.0,), graded_gradings=(2.0, 4.0), update=update)
    else:
        main(update=update)
