"""Conjugate gradients for the symmetric positive definite contact systems C_SS x = b."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["CGResult", "conjugate_gradient"]


def _dot(a: np.ndarray, b: np.ndarray) -> float:
    # numpy's own pairwise sum, not a threaded BLAS reduction whose rounding depends on the
    # thread count: results are bit-identical serially, in worker processes and on a cluster
    return float(np.add.reduce(a * b))


@dataclass(frozen=True, eq=False)
class CGResult:
    """The solution x, the iterations taken, the relative residual ||b - A x|| / ||b||
    reached, whether it is within the tolerance, and (with ``restrict``) the full-grid C x."""

    x: np.ndarray
    iterations: int
    residual: float
    converged: bool
    image: np.ndarray | None = None
    stopped_early: bool = False


def conjugate_gradient(
    matvec: Callable,
    b: np.ndarray,
    x0: np.ndarray | None = None,
    *,
    rtol: float = 1e-10,
    maxiter: int = 1000,
    precondition: Callable[[np.ndarray], np.ndarray] | None = None,
    restrict: np.ndarray | None = None,
    early_stop: Callable[[np.ndarray, np.ndarray | None, float, float, float], bool] | None = None,
    early_stop_below: float = 1e-3,
) -> CGResult:
    """(Preconditioned) CG for A x = b, warm-started from ``x0``.

    With ``restrict`` (a boolean mask), ``matvec`` returns the operator's image on the whole
    grid, the system is its restriction to the mask, and the full-grid image C x of the
    solution is accumulated alongside at no extra operator cost.  Never raises on
    non-convergence: the result says so, with the relative residual reached.

    ``early_stop(x, full_image, residual_norm, residual_energy, residual_max)`` is asked after
    every step whose relative residual is at most ``early_stop_below``, with the absolute
    residual norm ||b - A x||, r.M r (M the preconditioner; ||r||^2 without one) and the
    residual's largest magnitude max |r_i|; when it returns True, CG
    stops there (``stopped_early``): the caller has learnt what it needed from an iterate whose
    error it can bound by the residual."""

    def apply(v):
        full = matvec(v)
        return (full[restrict], full) if restrict is not None else (full, None)

    b_norm = math.sqrt(_dot(b, b))
    if x0 is None:
        x = np.zeros_like(b)
        residual = b.copy()  # r = b - A x
        full_image = None if restrict is None else np.zeros(restrict.shape)
    else:
        x = x0.copy()
        image_of_x, full_image = apply(x)
        residual = b - image_of_x
        full_image = None if full_image is None else full_image.copy()
    if b_norm == 0.0:
        return CGResult(np.zeros_like(b), 0, 0.0, True, None if restrict is None else np.zeros(restrict.shape))
    preconditioned = precondition(residual) if precondition else residual  # z = M r
    direction = preconditioned.copy()  # p
    r_dot_z = _dot(residual, preconditioned)
    relative_residual = math.sqrt(_dot(residual, residual)) / b_norm
    iterations = 0
    while relative_residual > rtol and iterations < maxiter:
        image_of_direction, full_image_of_direction = apply(direction)  # A p
        curvature = _dot(direction, image_of_direction)  # p.A p
        if not curvature > 0.0:  # loss of positive definiteness: stop and report, never NaN
            break
        step = r_dot_z / curvature  # alpha
        x += step * direction
        residual -= step * image_of_direction
        if full_image is not None:
            full_image += step * full_image_of_direction
        iterations += 1
        relative_residual = math.sqrt(_dot(residual, residual)) / b_norm
        if relative_residual <= rtol:
            break
        preconditioned = precondition(residual) if precondition else residual
        r_dot_z_new = _dot(residual, preconditioned)
        if early_stop is not None and relative_residual <= early_stop_below:
            if early_stop(x, full_image, relative_residual * b_norm, r_dot_z_new, float(np.abs(residual).max())):
                return CGResult(x, iterations, relative_residual, False, full_image, stopped_early=True)
        direction *= r_dot_z_new / r_dot_z  # beta
        direction += preconditioned
        r_dot_z = r_dot_z_new
    return CGResult(x, iterations, relative_residual, relative_residual <= rtol, full_image)
