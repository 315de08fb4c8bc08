"""Displacement-only axisymmetric elements, kept to show why the reference is mixed.

The pure-displacement weak form carries lambda (div u)(div v); as nu -> 1/2, lambda -> inf and
low-order elements cannot represent the near-incompressible displacement fields: the punch
stiffness "locks" (grows far above Eq. 1).  The Taylor-Hood form of :mod:`fem_reference.model`
replaces lambda div u by a pressure and stays on Eq. 1 up to nu = 1/2 exactly.
``benchmarks/study_fem.py --locking`` prints both side by side.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse.linalg as spla
from skfem import Basis, BilinearForm, ElementTriP1, ElementTriP2, ElementVector, asm

from contact_scene import SceneError

from .model import build_mesh

__all__ = ["displacement_only_stiffness"]


def displacement_only_stiffness(
    nu: float, *, order: int = 1, grading: float = 1.0, domain: float = 2.0**10, h_min: float = 1e-4
) -> float:
    """Punch stiffness K / (2 E* a) of a homogeneous body with displacement-only elements of
    ``order`` 1 or 2 (E = 1, a = 1); 1 means exact (up to mesh and domain truncation)."""
    if not 0.0 <= nu < 0.5:
        raise SceneError("material.poisson_ratio", f"displacement-only elements need 0 <= nu < 1/2 (got {nu:g})")
    el = {1: ElementTriP1, 2: ElementTriP2}.get(order)
    if el is None:
        raise SceneError("order", f"must be 1 or 2 (got {order})")
    mesh = build_mesh(domain=domain, grading=grading, h_min=h_min, h_max_near=grading)
    ub = Basis(mesh, ElementVector(el()), intorder=2 * order + 2)
    mu = 1.0 / (2 * (1 + nu))
    lam = nu / ((1 + nu) * (1 - 2 * nu))

    @BilinearForm
    def a(u, v, w):
        r = w.x[0]
        du, dv = u.grad, v.grad
        eu = (du[0][0], du[1][1], u[0] / r, du[0][1] + du[1][0])
        ev = (dv[0][0], dv[1][1], v[0] / r, dv[0][1] + dv[1][0])
        dev = 2 * mu * (eu[0] * ev[0] + eu[1] * ev[1] + eu[2] * ev[2]) + mu * eu[3] * ev[3]
        return (dev + lam * (eu[0] + eu[1] + eu[2]) * (ev[0] + ev[1] + ev[2])) * r

    A = asm(a, ub).tocsr()
    L, Z = mesh.p[0].max(), mesh.p[1].max()
    tol = 1e-12 * L
    axis = ub.get_dofs(lambda x: x[0] < tol).all("u^1")
    far = ub.get_dofs(lambda x: (x[0] > L - tol * L) | (x[1] > Z * (1 - 1e-12))).all()
    face = np.setdiff1d(ub.get_dofs(lambda x: (x[1] < tol) & (x[0] < 1 + 1e-12)).all("u^2"), far)
    fixed = np.unique(np.concatenate([axis, far, face]))
    x = np.zeros(A.shape[0])
    x[face] = 1.0
    free = np.setdiff1d(np.arange(A.shape[0]), fixed)
    x[free] = spla.spsolve(A[free][:, free].tocsc(), -(A[free][:, fixed] @ x[fixed]))
    K = 2 * math.pi * float(x @ (A @ x))
    E_star = 1.0 / (1 - nu**2)
    return K / (2 * E_star)
