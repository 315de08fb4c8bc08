"""The Fourier preconditioner of the contact systems C_SS x = b."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.fft as sfft

from contact_scene import SceneError
from halfspace.kernel import lattice_symbol, point_kernel_transform
from halfspace.operator import HalfSpaceOperator

__all__ = [
    "FourierPreconditioner",
    "fourier_preconditioner",
    "compact_period",
    "inverse_lattice_symbol",
    "lattice_inverse_diagonal",
    "DIAGONAL_SAMPLES",
    "DIAGONAL_ALIASES",
    "DIAGONAL_MARGIN",
]

#: the Brillouin zone is sampled on DIAGONAL_SAMPLES^2 frequencies for the diagonal bound: the
#: integrand 1 / symbol is periodic and vanishes like |q|^(1-k) at the origin, so the sampled
#: mean lies within about 1e-6 of 128^2 samples' (-0.99 <= k <= 0.99)
DIAGONAL_SAMPLES = 64
#: aliases summed on each side for the diagonal bound: the symbol's sinc factors alternate in
#: sign from alias to alias, and so does the mean's error; with six it lies 0.05 % (k = 0) to
#: 0.27 % (k = 0.99) above the mean over 40 aliases, with five 0.08-0.44 % below
DIAGONAL_ALIASES = 6
#: the factor on the sampled mean, which covers the aliases left out (either parity) and the
#: sampling: the bound then lies 1.0-1.3 % above the diagonal computed from the solver's own
#: coefficients on tori (``tests/test_bem_griffith_ties.py``)
DIAGONAL_MARGIN = 1.01


def inverse_lattice_symbol(
    padded_shape: tuple[int, int], spacing: float, point_kernel: tuple[float, float]
) -> np.ndarray:
    """1 / (the element lattice's Fourier symbol) on ``padded_shape``, in single precision.

    ``point_kernel`` is (coefficient A, exponent k) of the point Green's function
    g(r) = A / r^(1 + k).  The inverse symbol approximates (C_SS)^-1 away from the contact
    edge.  It is taken on the infinite lattice, not from the padded window, whose truncated
    kernel has near-zero and negative modes when the window is elongated (a 4:1 rectangle
    then needed 49 CG iterations per solve instead of 10).  Single precision suffices for a
    preconditioner and halves its FFT cost.  The zero mode, infinite in the continuum, takes
    the value of its nearest neighbour."""
    coefficient, exponent = point_kernel
    transform = point_kernel_transform(exponent)
    symbol = lattice_symbol(padded_shape, spacing, lambda q: coefficient * transform(q))
    symbol[0, 0] = np.max(symbol[[1, 0], [0, 1]]) if min(symbol.shape) > 1 else np.inf
    inverse = 1.0 / symbol
    finite = inverse[np.isfinite(symbol)]
    single = np.finfo(np.float32)
    # the inverse symbol ~ E* / h, carried in single precision: lengths and moduli whose ratio
    # leaves its normal range would overflow, or lose its digits to underflow
    if finite.size and not (single.tiny <= finite.min() and finite.max() <= single.max):
        raise SceneError(
            "material",
            f"the preconditioner's inverse symbol ({finite.min():.3g} ... {finite.max():.3g}) leaves the "
            "single-precision range in these units: rescale lengths and moduli, e.g. to the face's radius and E*",
        )
    return inverse.astype(np.float32)


def lattice_inverse_diagonal(spacing: float, point_kernel: tuple[float, float]) -> float:
    """An upper bound on the diagonal coefficient D0 of the infinite element lattice's C^-1,
    the mean of 1 / (its Fourier symbol) over the Brillouin zone, which bounds every diagonal
    entry of every C_SS^-1 from above (the Schur complement of C^-1 on S).

    The mean is sampled on DIAGONAL_SAMPLES^2 frequencies with DIAGONAL_ALIASES aliases on each
    side and widened by DIAGONAL_MARGIN (module constants): 1.0-1.3 % above D0, where the mean
    sampled on a coarse padded grid with the preconditioner's three aliases falls short of it.
    It depends on the lattice alone (spacing and point kernel), not on the grid or the face."""
    coefficient, exponent = point_kernel
    transform = point_kernel_transform(exponent)
    n = DIAGONAL_SAMPLES
    symbol = lattice_symbol((n, n), spacing, lambda q: coefficient * transform(q), terms=DIAGONAL_ALIASES)
    inverse = 1.0 / symbol  # 0 at the origin, where the continuum's symbol is infinite
    weights = np.full(symbol.shape[1], 2.0)  # the half spectrum of an even n: columns 1..n/2-1 stand for two
    weights[[0, -1]] = 1.0
    return DIAGONAL_MARGIN * float(np.sum(inverse * weights) / (n * n))


@dataclass(frozen=True, eq=False)
class FourierPreconditioner:
    """M, an approximation of C_SS^-1: the element lattice's inverse symbol applied to a
    residual on the contact set as a circular convolution over ``operator``'s period, the
    result taken on the set.

    operator
        The circulant M on the contact grid (``HalfSpaceOperator`` with ``periodic``): its
        kernel is the inverse symbol's, over a period at least the grid's.
    inverse_symbol
        The inverse symbol on the period's half spectrum, in single precision (the products
        are computed in it: a preconditioner needs no more, and it halves their cost).
    padded
        Whether the period holds the grid zero-padded to at least 2 n - 1 in both directions,
        so that M restricted to the grid is a section of the infinite lattice's inverse, as
        sampled: then r.M r bounds the energy norm of a CG error (``SAMPLING_MARGIN``).  Over a
        compact period (:func:`compact_period`) M wraps and is no such section, so that argument
        does not apply (dense checks on a few faces found r.M r within SAMPLING_MARGIN all the
        same, but nothing guarantees it): the early decisions then take no energy bound."""

    operator: HalfSpaceOperator
    inverse_symbol: np.ndarray
    padded: bool

    @property
    def period(self) -> tuple[int, int]:
        return self.operator.padded_shape

    def apply(self, residual: np.ndarray, mask: np.ndarray) -> np.ndarray:
        """M r on ``mask`` (row-major order of ``mask``), for r given there."""
        return self.operator.apply_symbol(residual, mask, self.inverse_symbol)


def compact_period(shape: tuple[int, int]) -> tuple[int, int]:
    """The smallest FFT-friendly period holding a grid of ``shape`` without padding, with an
    even number of rows (for the mirrored products of ``HalfSpaceOperator``)."""
    nx, ny = shape
    rows = sfft.next_fast_len(nx, real=True)
    while rows % 2:
        rows = sfft.next_fast_len(rows + 1, real=True)
    return rows, sfft.next_fast_len(ny, real=True)


def fourier_preconditioner(
    shape: tuple[int, int],
    period: tuple[int, int],
    spacing: float,
    point_kernel: tuple[float, float],
    *,
    padded: bool,
    workers: int = 1,
    inverse: np.ndarray | None = None,
) -> FourierPreconditioner:
    """The Fourier preconditioner of contact sets on a grid of ``shape``, over ``period``:
    the padded FFT grid of the half-space operator (``padded``), or
    :func:`compact_period` (``padded=False``); ``inverse``, if given, is
    :func:`inverse_lattice_symbol` on ``period``, already computed."""
    if inverse is None:
        inverse = inverse_lattice_symbol(period, spacing, point_kernel)
    kernel = sfft.irfft2(inverse.astype(float), s=period)
    return FourierPreconditioner(HalfSpaceOperator(kernel, shape, workers, periodic=True), inverse, padded)
