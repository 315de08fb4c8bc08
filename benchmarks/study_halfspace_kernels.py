"""The two discretisations of the half-space in halfspace/: Love's uniformly loaded squares
(the Griffith solver's kernel) and the point-collocated Boussinesq kernel (the energy BEM's
default), each on its own: flat-punch stiffness against Eq. 1 / Eq. 34 at the raster's area,
the square's beta against Eq. 9's 1.021, and the same-grid difference between the two.

    python benchmarks/study_halfspace_kernels.py [--update]

Stiffness by a direct solve C_SS p = 1 (conjugate gradients to 1e-11), K = Delta^2 sum p,
E* = 1 (homogeneous), E0 = c0 = 1 (graded).  ``--update`` writes the three tables to
docs/accuracy_halfspace_kernels_{circle,square,same_grid}.json (rendered into docs/accuracy.md
by ``python benchmarks/docs_tables.py``)."""

import math
import sys

import _timing  # thread settings first
import numpy as np
from scipy.sparse.linalg import LinearOperator, cg

import contact_scene as cs
from contact_scene import theory as T
from halfspace import HalfSpaceOperator, graded_influence, love_influence, padded_shape
from halfspace.collocation import collocated_graded_influence, collocated_influence

KERNELS = {
    "love": (love_influence, graded_influence),
    "collocation": (collocated_influence, collocated_graded_influence),
}


def stiffness(shape, spacing, kernel, k=0.0):
    r = cs.rasterise(shape, spacing)
    nx, ny = r.shape
    P = padded_shape(nx, ny)
    homogeneous, graded = KERNELS[kernel]
    K = homogeneous(nx, ny, spacing, 1.0, P) if k == 0 else graded(nx, ny, spacing, 1.0, 1.0, k, P)
    op = HalfSpaceOperator(K, (nx, ny))
    m = r.mask
    n = int(m.sum())
    p, info = cg(
        LinearOperator((n, n), matvec=lambda v: op.apply_masked(v, m)[m], dtype=float),
        np.ones(n),
        rtol=1e-11,
        maxiter=20_000,
    )
    if info:
        raise RuntimeError(f"CG did not converge ({info})")
    return spacing**2 * float(p.sum()), r.area


def rate(Ns, errs):
    return -np.polyfit(np.log(Ns), np.log(np.abs(errs)), 1)[0]


def main(update=False):
    record = _timing.provenance_record()
    Ns = np.array([8, 16, 32, 64, 128])
    circle = []
    for k in (0.0, 0.5, 0.9):
        for kernel in KERNELS:
            errs = []
            for N in Ns:
                K, A = stiffness(cs.Circle(1.0), 1.0 / N, kernel, k)
                a = math.sqrt(A / math.pi)
                ref = (
                    T.graded_stiffness(E0=1.0, c0=1.0, k=k, radius=a)
                    if k
                    else T.kendall_stiffness(E_star=1.0, radius=a)
                )
                errs.append(K / ref - 1)
            circle.append(
                [
                    f"{k:g} (Eq. {34 if k else 1})",
                    kernel,
                    *(f"{e:+.5f}" for e in errs),
                    f"{errs[-1] * Ns[-1]:+.3f}",
                    f"{rate(Ns[1:], errs[1:]):.2f}",
                ]
            )
    circle_head = ["k", "kernel", *(f"N = {N}" for N in Ns), f"N err at {Ns[-1]}", "fitted rate (16-128)"]
    print("flat circle: K / Eq. 1 or 34 (raster area) - 1")
    print(_timing.table(circle, circle_head), flush=True)
    square = []
    for kernel in KERNELS:
        b = np.array([stiffness(cs.Square(2.0), 1.0 / N, kernel)[0] / (2 * math.sqrt(4 / math.pi)) for N in Ns])
        square.append([kernel, *(f"{x:.5f}" for x in b), f"{2 * b[-1] - b[-2]:.5f}"])
    square_head = ["kernel", *(f"N = {N}" for N in Ns), "first-order extrapolation"]
    print("flat square of side 2, N elements per half side: beta = K / (2 E* sqrt(A/pi)); Eq. 9: 1.021")
    print(_timing.table(square, square_head), flush=True)
    shapes = {
        "circle": cs.Circle(1.0),
        "square": cs.Square(2.0),
        "square 45 deg": cs.Square(2.0, rotation_deg=45.0),
        "triangle": cs.Triangle.equilateral(2.0),
        "rectangle 4:1": cs.Rectangle(4.0, 1.0),
        "star 5": cs.Star(5, 1.0, 0.5),
    }
    same = []
    for name, sh in shapes.items():
        row = []
        for N in Ns[:4]:
            h = sh.equivalent_radius / N
            row.append((stiffness(sh, h, "love")[0] / stiffness(sh, h, "collocation")[0] - 1) * N)
        same.append([name, *(f"{x:+.4f}" for x in row)])
    same_head = ["face", *(f"N = {N}" for N in Ns[:4])]
    print("same grid: (K_love / K_collocation - 1) * N, N per equivalent radius")
    print(_timing.table(same, same_head), flush=True)
    if update:
        _timing.write_doc_table("accuracy_halfspace_kernels_circle", circle_head, circle, record)
        _timing.write_doc_table("accuracy_halfspace_kernels_square", square_head, square, record)
        _timing.write_doc_table("accuracy_halfspace_kernels_same_grid", same_head, same, record)


if __name__ == "__main__":
    main(update="--update" in sys.argv)
