"""Influence coefficients of square elements on an elastic half-space."""

from __future__ import annotations

import math

import numpy as np

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
]


def _f(X, Y):
    # an antiderivative of 1/sqrt(X^2 + Y^2) in both variables, valid in every quadrant
    X = np.asarray(X, float)
    Y = np.asarray(Y, float)
    ax, ay = np.abs(X), np.abs(Y)
    with np.errstate(divide="ignore", invalid="ignore"):
        t1 = np.where(ax > 0, X * np.arcsinh(Y / np.where(ax > 0, ax, 1.0)), 0.0)
        t2 = np.where(ay > 0, Y * np.arcsinh(X / np.where(ay > 0, ay, 1.0)), 0.0)
    return t1 + t2


def love_square_integral(x, y, half_width: float):
    """Integral of 1/abs(r - r') over the square abs(x'), abs(y') <= b, seen from (x, y).

    Love's closed asinh form; the displacement at (x, y) under unit pressure on the square is this
    divided by pi E* (formula sheet, section 3).  At the centre it is 8 b asinh(1).

    Parameters
    ----------
    x, y : float or array_like
        Field point relative to the square's centre (broadcast together).
    half_width : float
        Half the side of the square, b > 0.

    Returns
    -------
    float or numpy.ndarray
        The integral at each field point (length units), of the broadcast shape of x and y.

    References
    ----------
    - Love, A.E.H., "The stress produced in a semi-infinite solid by pressure on part of the boundary",
      Phil. Trans. R. Soc. Lond. A 228:377-420 (1929).
    """
    b = half_width
    return _f(x + b, y + b) - _f(x + b, y - b) - _f(x - b, y + b) + _f(x - b, y - b)


def _offset_layout(integral, nx: int, ny: int, spacing: float, padded: tuple[int, int] | None) -> np.ndarray:
    """``integral(X, Y, half_width)`` at every cell offset, laid out for a linear (zero-padded)
    FFT convolution on a ``padded`` grid (default (2 nx) x (2 ny); any size >= 2n - 1 works):
    entry [i, j] holds offset (i, j) for i < nx and (i - Mx, j) for i > Mx - nx (likewise j);
    entries for offsets no pair of cells can have are zero."""
    Mx, My = padded if padded is not None else (2 * nx, 2 * ny)
    if Mx < 2 * nx - 1 or My < 2 * ny - 1:
        raise ValueError(f"padded size {(Mx, My)} too small for a linear convolution of {(nx, ny)}")
    ix = np.arange(Mx)
    iy = np.arange(My)
    ox = np.where(ix < nx, ix, ix - Mx).astype(float)
    oy = np.where(iy < ny, iy, iy - My).astype(float)
    X, Y = np.meshgrid(ox * spacing, oy * spacing, indexing="ij")
    K = integral(X, Y, spacing / 2)
    K[(ix >= nx) & (ix <= Mx - nx), :] = 0.0
    K[:, (iy >= ny) & (iy <= My - ny)] = 0.0
    return K


def love_influence(
    nx: int, ny: int, spacing: float, E_star: float, padded: tuple[int, int] | None = None
) -> np.ndarray:
    """Influence coefficients of square elements on a homogeneous half-space (u = C p).

    The displacement at the centre of one element from unit pressure on another, Love's
    integral (:func:`love_square_integral`) over pi E*, laid out for
    :class:`~halfspace.HalfSpaceOperator`.

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

    References
    ----------
    - Love, A.E.H., "The stress produced in a semi-infinite solid by pressure on part of the boundary",
      Phil. Trans. R. Soc. Lond. A 228:377-420 (1929).
    """
    return _offset_layout(love_square_integral, nx, ny, spacing, padded) / (math.pi * E_star)


#: the zero-mean lattice sum of 1/abs(R) over the unit square lattice, sum' 1/abs(R) "minus" the
#: neutralising background: 4 zeta(1/2) beta(1/2) (Glasser & Zucker); the periodic
#: zero-mean Green's function of 1/r is 1/abs(x) + MADELUNG_SQUARE / L + O(abs(x)^2 / L^3)
MADELUNG_SQUARE = -3.900264920001956


def love_influence_periodic(n: int, spacing: float, E_star: float, *, images: int = 16) -> np.ndarray:
    """Influence coefficients of a half-space periodic over an n x n cell of side L = n Delta.

    The image sum of Love's coefficients diverges like the number of images (1/r in 2-D), but
    by a constant: the displacement is defined up to the mean plane, and the coefficients are
    made zero-mean over the cell.  Truncated to the cells within M of the home cell, the
    zero-mean sum still errs by an abs(x)^2 / M term (the far cells' quadratic term does not
    average out) and a 1/M^2 term; sums to M, 2M and 4M (``images`` = 4M) and two Richardson
    steps remove both (measured: the coefficients change by 5e-6 and 1e-6 of the largest from
    16 to 32 at n = 8 and 32; the error then falls like M^-3).

    Parameters
    ----------
    n : int
        Cells per side of the periodic cell, >= 1.
    spacing : float
        Side Delta of the square elements, > 0.
    E_star : float
        Effective modulus E* = E / (1 - nu^2), > 0.
    images : int, optional
        4M, four times the largest ring of image cells summed; a multiple of 4, >= 4.

    Returns
    -------
    numpy.ndarray
        (n, n) array for a circular FFT convolution: entry [i, j] is the coefficient of the
        offset (i, j) modulo n.

    Raises
    ------
    ValueError
        If ``images`` is not a positive multiple of 4.
    """
    return zero_mean_image_sum(lambda X, Y: love_square_integral(X, Y, spacing / 2), n, spacing, images=images) / (
        math.pi * E_star
    )


def zero_mean_image_sum(integral, n: int, spacing: float, *, images: int = 16, k: float = 0.0) -> np.ndarray:
    """The zero-mean sum of an element integral over the periodic images of an n x n cell.

    The sum over images of a kernel r^-(1+k) diverges, but by a constant over the cell, which the
    zero mean removes.  Truncated to the cells within M of the home cell, the zero-mean sum
    still errs by an M^-(1+k) term (the far cells' quadratic term does not average out) and an
    M^-(2+k) term; sums to M, 2M and 4M (``images`` = 4M) and two Richardson steps remove both
    (:func:`love_influence_periodic` is this sum of Love's integrals, at k = 0).

    Parameters
    ----------
    integral : callable
        (X, Y) -> the element integral of the kernel seen from the offsets (X, Y), e.g.
        ``lambda X, Y: love_square_integral(X, Y, spacing / 2)``.
    n : int
        Cells per side of the periodic cell, >= 1.
    spacing : float
        Side Delta of the square elements, > 0.
    images : int, optional
        4M, four times the largest ring of image cells summed; a multiple of 4, >= 4.
    k : float, optional
        The kernel's exponent, r^-(1+k), -1 < k < 1; 0 by default.

    Returns
    -------
    numpy.ndarray
        (n, n) array: entry [i, j] is the sum for the offset (i, j) modulo n.

    Raises
    ------
    ValueError
        If ``images`` is not a positive multiple of 4.
    """
    if images < 4 or images % 4:
        raise ValueError(f"images must be a multiple of 4, >= 4 (got {images})")
    L = n * spacing
    idx = np.arange(n)
    o = np.where(idx <= n // 2, idx, idx - n).astype(float) * spacing
    X, Y = np.meshgrid(o, o, indexing="ij")
    levels = (images // 4, images // 2, images)
    sums, total, done = [], np.zeros((n, n)), -1
    for M in levels:
        for a in range(-M, M + 1):
            for b in range(-M, M + 1):
                if max(abs(a), abs(b)) > done:
                    total += integral(X + a * L, Y + b * L)
        done = M
        sums.append(total - total.mean())
    first, second = 2.0 ** (1.0 + k), 2.0 ** (2.0 + k)
    r1 = (first * sums[1] - sums[0]) / (first - 1.0)  # C + b/M^(2+k) (times a constant)
    r2 = (first * sums[2] - sums[1]) / (first - 1.0)
    return (second * r2 - r1) / (second - 1.0)


def padded_shape(nx: int, ny: int, *, even_rows: bool = False) -> tuple[int, int]:
    """Smallest FFT-friendly padded size that holds a linear convolution of an nx x ny grid.

    Parameters
    ----------
    nx, ny : int
        Cells of the grid along x and y, >= 1.
    even_rows : bool, optional
        Mx even (twice a fast length), as the half-size transforms of a mirror-symmetric
        product need (``HalfSpaceOperator``).

    Returns
    -------
    tuple of int
        (Mx, My), each the smallest fast real-FFT length >= 2n - 1 (Mx the smallest even one
        with ``even_rows``).
    """
    import scipy.fft as sfft

    Mx = 2 * sfft.next_fast_len(nx, real=True) if even_rows else sfft.next_fast_len(2 * nx - 1, real=True)
    return (Mx, sfft.next_fast_len(2 * ny - 1, real=True))


def graded_square_integral(x, y, half_width: float, k: float):
    """Integral of abs(r - r')^-(1+k) over the square abs(x'), abs(y') <= b, seen from (x, y).

    The closed form of the formula sheet (section 5): 1/(1-k) times the sum over the four edges
    of sgn(h) abs(h)^(1-k) [G(s2/abs(h)) - G(s1/abs(h))], G(t) = t 2F1(1/2, (1+k)/2; 3/2; -t^2).
    k = 0 gives Love's asinh form (:func:`love_square_integral`).

    Parameters
    ----------
    x, y : float or array_like
        Field point relative to the square's centre (broadcast together).
    half_width : float
        Half the side of the square, b > 0.
    k : float
        Exponent of the point kernel r^-(1+k), -1 < k < 1.

    Returns
    -------
    float or numpy.ndarray
        The integral at each field point, of the broadcast shape of x and y.

    Raises
    ------
    ValueError
        If k is outside (-1, 1).

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    from scipy.special import hyp2f1

    if not -1.0 < k < 1.0:
        raise ValueError(f"k must be in (-1, 1) (got {k})")
    b = half_width
    x = np.asarray(x, float)
    y = np.asarray(y, float)

    def G(t):
        return t * hyp2f1(0.5, 0.5 * (1 + k), 1.5, -t * t)

    total = np.zeros(np.broadcast(x, y).shape)
    for h, s1, s2 in ((b - x, -b - y, b - y), (b + x, -b - y, b - y), (b - y, -b - x, b - x), (b + y, -b - x, b - x)):
        h = np.broadcast_to(h, total.shape)
        ah = np.abs(h)
        safe = np.where(ah > 0, ah, 1.0)
        term = np.sign(h) * safe ** (1 - k) * (G(s2 / safe) - G(s1 / safe))
        total += np.where(ah > 0, term, 0.0)  # the edge through the field point contributes nothing
    return total / (1 - k)


def graded_influence(
    nx: int, ny: int, spacing: float, E0: float, c0: float, k: float, padded: tuple[int, int] | None = None
) -> np.ndarray:
    """Influence coefficients of square elements on a power-law graded half-space.

    The point-force displacement w = A_k P / r^(1+k) (:func:`contact_scene.theory.graded_green_coefficient`)
    integrated over each element (:func:`graded_square_integral`), laid out like
    :func:`love_influence`.

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

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    from contact_scene.theory import graded_green_coefficient

    K = _offset_layout(lambda X, Y, b: graded_square_integral(X, Y, b, k), nx, ny, spacing, padded)
    return K * graded_green_coefficient(E0=E0, c0=c0, k=k)


def point_kernel_transform(k: float = 0.0):
    """2-D Fourier transform of the point kernel r^-(1+k), as a function of abs(q).

    2^(1-k) pi Gamma((1-k)/2) / Gamma((1+k)/2) abs(q)^(k-1) (angular frequency q); 2 pi / abs(q)
    at k = 0.

    Parameters
    ----------
    k : float, optional
        Exponent of the kernel, -1 < k < 1; 0 (homogeneous) by default.

    Returns
    -------
    callable
        q -> the transform at abs(q) = q > 0 (float or array).

    Raises
    ------
    ValueError
        If k is outside (-1, 1).
    """
    from scipy.special import gamma

    if not -1.0 < k < 1.0:
        raise ValueError(f"k must be in (-1, 1) (got {k})")
    c = 2.0 ** (1.0 - k) * math.pi * gamma((1.0 - k) / 2.0) / gamma((1.0 + k) / 2.0)
    return lambda q: c * q ** (k - 1.0)


def lattice_symbol(padded: tuple[int, int], spacing: float, transform, *, terms: int = 3) -> np.ndarray:
    """Fourier symbol of square-element influence coefficients on the infinite lattice.

    Sampled at the frequencies of a ``padded`` grid (rfft2 half-spectrum layout).  By Poisson
    summation the symbol is the sum over the aliases q + 2 pi m / Delta of transform(abs(q))
    sinc(q_x Delta/2) sinc(q_y Delta/2), here over abs(m_x), abs(m_y) <= ``terms``.  Unlike the
    transform of the coefficients truncated to the padded window, which for an elongated window
    has near-zero and negative modes, it is positive, as the element energy p^T C p is (the
    truncated alias sum was positive in every case tested).

    Parameters
    ----------
    padded : tuple of int
        (Mx, My), the padded grid whose frequencies are sampled.
    spacing : float
        Side Delta of the square elements, > 0.
    transform : callable
        The point kernel's 2-D Fourier transform as a function of abs(q) > 0 (e.g. 2/(E* abs(q))
        for a homogeneous body, or a multiple of :func:`point_kernel_transform`).
    terms : int, optional
        Aliases summed in each direction on each side, >= 0.

    Returns
    -------
    numpy.ndarray
        (Mx, My // 2 + 1) real array; entry [0, 0] (the continuum's 1/abs(q) singularity) is inf.
    """
    Mx, My = padded
    h = float(spacing)
    kx = 2.0 * math.pi * np.fft.fftfreq(Mx, d=h)[:, None]
    ky = 2.0 * math.pi * np.fft.rfftfreq(My, d=h)[None, :]
    total = np.zeros((Mx, My // 2 + 1))
    shifted_y = [ky + 2.0 * math.pi * my / h for my in range(-terms, terms + 1)]
    sinc_y = [np.sinc(qy * h / (2.0 * math.pi)) for qy in shifted_y]
    # abs(q) vanishes only at the zero frequency's own alias, entry [0, 0], set to inf below
    with np.errstate(divide="ignore", invalid="ignore"):
        for mx in range(-terms, terms + 1):
            qx = kx + 2.0 * math.pi * mx / h
            sx = np.sinc(qx * h / (2.0 * math.pi))
            for qy, sy in zip(shifted_y, sinc_y, strict=True):
                total += transform(np.hypot(qx, qy)) * sx * sy
    total[0, 0] = np.inf
    return total
