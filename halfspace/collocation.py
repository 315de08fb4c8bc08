"""Point-collocated influence coefficients of the half-space: a second discretisation,
derived separately from the element integrals of :mod:`halfspace.kernel`.

The displacement at the centre of element i from uniform pressure on element j != i is taken
as that of the point load Delta^2 p_j at the centre of j (Boussinesq, or its graded analogue
w = A_k P / r^(1+k), theory sheet section 5):

    C_ij = A_k Delta^2 / abs(x_i - x_j)^(1+k)        (A_0 = 1 / (pi E*)).

The self term is where the point load is singular.  It is chosen so that the lattice sum
reproduces the continuum integral: for s = 1 + k in (0, 2),

    sum over lattice points R != 0 within L of Delta^2 abs(R)^-s
        = integral over abs(x) < L of abs(x)^-s dx + Z(s) Delta^(2-s) + o(1)    (L -> infinity),

where Z(s) = sum' abs(m)^-s over the unit square lattice, continued analytically to s < 2
(Epstein's zeta function; 4 zeta(s/2) beta(s/2), Dirichlet's beta; Z(1) = -3.90026...).  So

    C_ii = -Z(1 + k) A_k Delta^(1-k)    (k = 0: 3.90026 Delta / (pi E*))

makes sum_j C_ij p_j the integral of G p to leading order for a smooth pressure: the
zeta-corrected trapezoidal rule.  The other natural self term, the centre displacement of the
element itself (8 ln(1 + sqrt 2) b for k = 0, 3.52549 Delta / (pi E*)), leaves the sum short
of the integral by a fixed multiple of Delta^(1-k), a relative error of order (Delta/a)^(1-k):
the graded flat circle's stiffness then stayed 0.7-0.9 % (k = 0.5) and 1.0-1.1 % (k = 0.9)
above Eq. 34 (at the raster's area) from 16 to 64 elements per radius, while with this self
term it converges like 1/N for every k tried (benchmarks/study_halfspace_kernels.py,
tests/test_halfspace.py).

Off the diagonal the point value differs from the element average by the square's second
moment, (Delta^2 / 24) laplacian(r^-(1+k)) Delta^2, a relative (1+k)^2 Delta^2 / (24 r^2):
4 % at the nearest neighbours for k = 0.  On the same grid this kernel and Love's squares
give different stiffnesses, each converging to the continuum, so agreement between solvers
using different ones checks both.
"""

from __future__ import annotations

import math

import numpy as np

from .kernel import _offset_layout

__all__ = ["square_lattice_zeta", "collocated_influence", "collocated_graded_influence"]


def _dirichlet_beta(s: float) -> float:
    """beta(s) = sum_n (-1)^n / (2n + 1)^s for s > 0, from its Mellin integral
    beta(s) = 1/Gamma(s) integral_0^inf t^(s-1) / (2 cosh t) dt."""
    from scipy.integrate import quad
    from scipy.special import gamma

    def f(t):
        return math.exp(-t) / (1.0 + math.exp(-2.0 * t))

    near, _ = quad(f, 0.0, 1.0, weight="alg", wvar=(s - 1.0, 0.0), epsabs=0.0, epsrel=1e-13)
    far, _ = quad(lambda t: t ** (s - 1.0) * f(t), 1.0, 60.0, epsabs=0.0, epsrel=1e-13, limit=200)
    return (near + far) / gamma(s)


def square_lattice_zeta(s: float) -> float:
    """Epstein zeta Z(s) of the unit square lattice, continued to 0 < s < 2.

    Z(s) = sum over the lattice points m != 0 of abs(m)^-s, equal to 4 zeta(s/2) beta(s/2)
    (the lattice's theta function factorises; beta is Dirichlet's); Z(1) = -3.90026...

    Parameters
    ----------
    s : float
        Exponent, 0 < s < 2 (s = 1 + k for the graded kernel).

    Returns
    -------
    float
        Z(s).

    Raises
    ------
    ValueError
        If s is outside (0, 2).
    """
    from scipy.special import zeta

    if not 0.0 < s < 2.0:
        raise ValueError(f"s must be in (0, 2) (got {s})")
    return 4.0 * float(zeta(s / 2.0)) * _dirichlet_beta(s / 2.0)


def _point_layout(nx: int, ny: int, spacing: float, k: float, padded: tuple[int, int] | None) -> np.ndarray:
    """Delta^2 / r^(1+k) at every non-zero cell offset and -Z(1+k) Delta^(1-k) at offset zero,
    in the zero-padded layout of the FFT operators (:func:`halfspace.kernel.love_influence`)."""
    self_term = -square_lattice_zeta(1.0 + k) * spacing ** (1.0 - k)

    def point(X, Y, _half_width):
        r = np.hypot(X, Y)
        value = spacing**2 / np.where(r > 0, r, 1.0) ** (1.0 + k)
        return np.where(r > 0, value, self_term)

    return _offset_layout(point, nx, ny, spacing, padded)


def collocated_influence(
    nx: int, ny: int, spacing: float, E_star: float, padded: tuple[int, int] | None = None
) -> np.ndarray:
    """Point-collocated Boussinesq coefficients of a homogeneous half-space (u = C p).

    C_ij = Delta^2 / (pi E* abs(x_i - x_j)) off the diagonal and the zeta-corrected self term
    -Z(1) Delta / (pi E*) (see the module), laid out like :func:`halfspace.love_influence`.

    Parameters
    ----------
    nx, ny : int
        Cells of the grid along x and y, >= 1.
    spacing : float
        Side Delta of the square elements, > 0.
    E_star : float
        Effective modulus E* = E / (1 - nu^2), > 0.
    padded : tuple of int, optional
        (Mx, My), the zero-padded size of the FFT convolution, each >= 2n - 1 (:func:`padded_shape`
        gives an FFT-friendly one); (2 nx, 2 ny) by default.

    Returns
    -------
    numpy.ndarray
        (Mx, My) array for a linear (zero-padded) FFT convolution: entry [i, j] holds the
        coefficient of cell offset (i, j) for i < nx and (i - Mx, j) for i > Mx - nx (likewise j);
        the entries of offsets no pair of cells can have are zero.

    Raises
    ------
    ValueError
        If ``padded`` is smaller than 2n - 1 in either direction.
    """
    return _point_layout(nx, ny, spacing, 0.0, padded) / (math.pi * E_star)


def collocated_graded_influence(
    nx: int, ny: int, spacing: float, E0: float, c0: float, k: float, padded: tuple[int, int] | None = None
) -> np.ndarray:
    """Point-collocated coefficients of a power-law graded half-space.

    C_ij = A_k Delta^2 / abs(x_i - x_j)^(1+k) off the diagonal (w = A_k P / r^(1+k)) and the
    self term -Z(1+k) A_k Delta^(1-k) (see the module), laid out like
    :func:`halfspace.graded_influence`.

    Parameters
    ----------
    nx, ny : int
        Cells of the grid along x and y, >= 1.
    spacing : float
        Side Delta of the square elements, > 0.
    E0 : float
        Modulus at the reference depth of E(z) = E0 (z/c0)^k, > 0.
    c0 : float
        Reference depth c0, > 0.
    k : float
        Exponent of the grading, -1 < k < 1.
    padded : tuple of int, optional
        (Mx, My), the zero-padded size of the FFT convolution, each >= 2n - 1 (:func:`padded_shape`
        gives an FFT-friendly one); (2 nx, 2 ny) by default.

    Returns
    -------
    numpy.ndarray
        (Mx, My) array for a linear (zero-padded) FFT convolution: entry [i, j] holds the
        coefficient of cell offset (i, j) for i < nx and (i - Mx, j) for i > Mx - nx (likewise j);
        the entries of offsets no pair of cells can have are zero.

    Raises
    ------
    ValueError
        If k is outside (-1, 1) or ``padded`` is smaller than 2n - 1.
    """
    from contact_scene.theory import graded_green_coefficient

    if not -1.0 < k < 1.0:
        raise ValueError(f"k must be in (-1, 1) (got {k})")
    return _point_layout(nx, ny, spacing, k, padded) * graded_green_coefficient(E0=E0, c0=c0, k=k)
