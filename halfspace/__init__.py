"""The elastic half-space, shared by the boundary-element methods: Green's functions, the
influence coefficients of square elements (Love's homogeneous squares, the graded analogue,
the periodic image sum, the lattice symbol), a separately derived point-collocated kernel
(:mod:`halfspace.collocation`) and the FFT convolution operator u = C p.

Neither BEM imports the other; both take their discretisation of the half-space from here."""

from .collocation import collocated_graded_influence, collocated_influence, square_lattice_zeta
from .kernel import (
    MADELUNG_SQUARE,
    graded_influence,
    graded_square_integral,
    lattice_symbol,
    love_influence,
    love_influence_periodic,
    love_square_integral,
    padded_shape,
    point_kernel_transform,
    zero_mean_image_sum,
)
from .operator import HalfSpaceOperator, default_workers

__all__ = [
    "love_square_integral",
    "love_influence",
    "love_influence_periodic",
    "zero_mean_image_sum",
    "padded_shape",
    "graded_square_integral",
    "graded_influence",
    "lattice_symbol",
    "point_kernel_transform",
    "MADELUNG_SQUARE",
    "HalfSpaceOperator",
    "default_workers",
    "collocated_influence",
    "collocated_graded_influence",
    "square_lattice_zeta",
]
