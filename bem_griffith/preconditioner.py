"""The Fourier preconditioner of the contact systems C_SS x = b."""

from __future__ import annotations

import numpy as np

from halfspace.kernel import lattice_symbol, point_kernel_transform

__all__ = [
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
    return (1.0 / symbol).astype(np.float32)


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
