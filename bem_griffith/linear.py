"""Conjugate gradients for the symmetric positive definite contact systems C_SS x = b."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

__all__ = ["CGResult", "conjugate_gradient"]


def _dot(a: np.ndarray, b: np.ndarray) -> float:
    # numpy's own pairwise sum, not a threaded BLAS reduction whose rounding depends on the
    # thread count: results are bit-identical serially, in worker processes and on a cluster
    return float(np.add.reduce(a * b))


@dataclass(frozen=True, eq=False)
class CGResult:
    x: np.ndarray
    iterations: int
    residual: float          # ||b - A x|| / ||b||
    converged: bool
    image: np.ndarray | None = None   # the full-grid C x, when the matvec provides it


def conjugate_gradient(matvec: Callable, b: np.ndarray, x0: np.ndarray | None = None,
                       *, rtol: float = 1e-10, maxiter: int = 1000,
                       precondition: Callable[[np.ndarray], np.ndarray] | None = None,
                       restrict: np.ndarray | None = None) -> CGResult:
    """(Preconditioned) CG, warm-started from ``x0``.

    With ``restrict`` (a boolean mask), ``matvec`` returns the operator's image on the whole
    grid, the system is its restriction to the mask, and the full-grid image C x of the
    solution is accumulated alongside at no extra operator cost.  Never raises on
    non-convergence: the result says so, with the relative residual reached."""
    def A(v):
        full = matvec(v)
        return (full[restrict], full) if restrict is not None else (full, None)

    bnorm = math.sqrt(_dot(b, b))
    if x0 is None:
        x = np.zeros_like(b)
        r = b.copy()
        img = None if restrict is None else np.zeros(restrict.shape)
    else:
        x = x0.copy()
        ax, img = A(x)
        r = b - ax
        img = None if img is None else img.copy()
    if bnorm == 0.0:
        return CGResult(np.zeros_like(b), 0, 0.0, True, None if restrict is None else np.zeros(restrict.shape))
    z = precondition(r) if precondition else r
    p = z.copy()
    rz = _dot(r, z)
    res = math.sqrt(_dot(r, r)) / bnorm
    it = 0
    while res > rtol and it < maxiter:
        Ap, Ap_full = A(p)
        pAp = _dot(p, Ap)
        if not pAp > 0.0:  # loss of positive definiteness: stop and report, never NaN
            break
        alpha = rz / pAp
        x += alpha * p
        r -= alpha * Ap
        if img is not None:
            img += alpha * Ap_full
        it += 1
        res = math.sqrt(_dot(r, r)) / bnorm
        if res <= rtol:
            break
        z = precondition(r) if precondition else r
        rz_new = _dot(r, z)
        p *= rz_new / rz
        p += z
        rz = rz_new
    return CGResult(x, it, res, res <= rtol, img)
