"""scipy.fft's own transforms, written into arrays the caller keeps.

scipy.fft allocates every result; its pocketfft backend takes an output array, which lets a
solver that transforms thousands of times reuse its buffers (fresh multi-megabyte arrays are
fresh pages, and their faults cost several per cent of a solve).  That backend is not public
API: it is checked here once, on small arrays, against scipy.fft's public transforms, and
:data:`POCKETFFT` is None when it is missing or does not give the same numbers bit for bit, in
which case the callers take scipy.fft's allocating path.
"""

from __future__ import annotations

import logging
from typing import Any

import numpy as np
import scipy.fft as sfft

__all__ = ["POCKETFFT", "norm_factor", "same_as_scipy_fft"]

log = logging.getLogger("halfspace")


def norm_factor(n: int, dtype: Any) -> Any:
    """The factor 1/n of an inverse transform of n points, rounded as pocketfft rounds it.

    pocketfft computes 1/n in long double and rounds it to the transform's precision, so an
    inverse run unnormalised and scaled afterwards by this factor is scipy.fft's, bit for bit
    (:func:`same_as_scipy_fft` checks that the unnormalised inverse one axis at a time
    behaves so before the in-place path is used).

    Parameters
    ----------
    n : int
        The number of points of the inverse transform (their product over its axes).
    dtype : numpy.dtype or type
        The real precision of the transform, float32 or float64.

    Returns
    -------
    numpy.floating
        1/n in ``dtype``.
    """
    return np.dtype(dtype).type(np.longdouble(1) / np.longdouble(n))


def same_as_scipy_fft(p: Any) -> bool:
    """Whether ``p``'s ``r2c``, ``c2c``, ``c2r`` and ``dct`` write into the arrays given and compute,
    bit for bit, what scipy.fft's public transforms do, in double and single precision.

    Parameters
    ----------
    p : module
        A module with pocketfft's entry points (scipy's ``pypocketfft``).

    Returns
    -------
    bool
        True when every check passes; False on a different number, a new array instead of the
        one given, or any error (a changed signature).
    """
    try:
        rng = np.random.default_rng(0)
        for dtype, complex_type in ((np.float64, np.complex128), (np.float32, np.complex64)):
            a: np.ndarray[Any, Any] = rng.standard_normal((6, 5)).astype(dtype)
            half = np.empty((6, 3), complex_type)
            if p.r2c(a, (0, 1), True, 0, half, 1) is not half or not np.array_equal(half, sfft.rfft2(a)):
                return False
            rows = np.empty((6, 3), complex_type)
            p.r2c(a, (1,), True, 0, rows, 1)
            p.c2c(rows, (0,), True, 0, rows, 1)
            if not np.array_equal(rows, half):
                return False
            p.c2c(rows, (0,), False, 2, rows, 1)
            back = np.empty((6, 5), dtype)
            if p.c2r(rows, (1,), 5, False, 2, back, 1) is not back:
                return False
            if not np.array_equal(back, sfft.irfft(sfft.ifft(half, axis=0), n=5, axis=1)):
                return False
            # the 2-D inverse one axis at a time, unnormalised, then scaled by norm_factor
            spectrum = half.copy()
            p.c2c(spectrum, (0,), False, 0, spectrum, 1)
            scaled = np.empty((6, 5), dtype)
            if p.c2r(spectrum, (1,), 5, False, 0, scaled, 1) is not scaled:
                return False
            scaled *= norm_factor(30, dtype)
            if not np.array_equal(scaled, sfft.irfft2(half, s=(6, 5))):
                return False
            whole = np.empty((6, 5), dtype)
            if p.c2r(half, (0, 1), 5, False, 2, whole, 1) is not whole:
                return False
            if not np.array_equal(whole, sfft.irfft2(half, s=(6, 5))):
                return False
            # the cosine transforms of the mirror-symmetric products, in place
            for kind in (1, 2, 3):
                column = a.copy()
                if p.dct(column, kind, (0,), 0, column, 1) is not column:
                    return False
                if not np.array_equal(column, sfft.dct(a, type=kind, axis=0)):
                    return False
        return True
    except Exception as exc:  # any change of the private API: the public path, never a wrong number
        log.debug("pocketfft's in-place transforms unusable (%s): scipy.fft allocates", exc)
        return False


def _load() -> Any:
    try:
        from scipy.fft._pocketfft import pypocketfft as p  # type: ignore[import-not-found]
    except ImportError:
        return None
    return p if same_as_scipy_fft(p) else None


#: scipy's pocketfft module (``r2c``, ``c2c``, ``c2r`` with ``out``) when it computes exactly
#: what scipy.fft does, else None
POCKETFFT = _load()
