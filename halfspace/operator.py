"""The half-space operator u = C p as an FFT convolution."""

from __future__ import annotations

import threading
import weakref
from dataclasses import dataclass, field

import numpy as np
import scipy.fft as sfft

from .kernel import padded_shape

# pocketfft's own entry points write into a given array (``out``), which scipy.fft's do not;
# None (scipy.fft's allocating path) where they are missing or differ
from .pocketfft import POCKETFFT as _pocketfft

__all__ = ["HalfSpaceOperator", "default_workers", "mirrors"]

#: each thread's transform buffers, per operator (kept out of the operator, which stays picklable)
_scratch = threading.local()


def default_workers() -> int:
    """FFT threads for one solve: 1.

    A second FFT thread did not speed up the pruned convolution on two cores at any size up to
    1080^2 padded and slowed small grids twofold (``benchmarks/bench_matvec.py``); the second core
    serves parallel sweeps instead.

    Returns
    -------
    int
        The number of FFT workers, 1.
    """
    return 1


def mirrors(grid: np.ndarray) -> bool:
    """Whether a grid array equals its mirror image about its middle row (rows i and
    n - 1 - i), exactly: the products of such a pressure take the half-size transforms.

    Parameters
    ----------
    grid : numpy.ndarray
        An (nx, ny) array (values or a mask).

    Returns
    -------
    bool
    """
    half = grid.shape[0] // 2  # the middle row of an odd grid is its own mirror
    return bool(np.array_equal(grid[:half], grid[::-1][:half]))


@dataclass(frozen=True, eq=False)
class HalfSpaceOperator:
    """The half-space operator u = C p as a zero-padded FFT convolution.

    Displacement u (nx x ny) from pressure p (nx x ny) by linear convolution with the element
    influence coefficients, zero-padded (to at least 2n - 1) so the grid does not wrap.  The
    transforms are pruned: the input occupies only nx of the Mx padded rows and only nx rows of
    the output are wanted, so the row transforms run on nx rows, not Mx (about 3/4 of the work
    of a plain padded rfft2/irfft2 pair; measured in ``benchmarks/bench_matvec.py``).  The
    transforms run in place in buffers each thread keeps per operator (pocketfft's own entry
    points, which take an output array), so that a product allocates and copies only its
    result; the numbers are those of scipy.fft's allocating transforms, bit for bit.  A masked
    product whose pressure mirrors exactly about the grid's middle row (with an even number of
    padded rows) runs the row-axis pair as cosine transforms over half the rows instead
    (``_mirrored``): the same product to round-off, mirrored exactly.

    Parameters
    ----------
    kernel : numpy.ndarray
        The influence coefficients, laid out as :func:`halfspace.love_influence` returns them,
        (Mx, My) with Mx >= 2 nx - 1 and My >= 2 ny - 1; for ``periodic``, the coefficients
        over the period, Mx >= nx and My >= ny (for a periodic array of faces, as
        :func:`halfspace.love_influence_periodic` returns them, with the grid's shape).
    shape : tuple of int
        (nx, ny), the grid of the pressure and the displacement.
    workers : int, optional
        FFT threads (:func:`default_workers`), >= 1.
    periodic : bool, optional
        Circular convolution over the kernel's shape (the period), whose first nx x ny cells
        hold the grid: the grid itself for a periodic array of faces, or a longer period over
        which the grid's values are zero-extended (a circulant approximation such as a
        preconditioner, which may wrap).

    Raises
    ------
    ValueError
        If the kernel's shape does not fit the grid.
    """

    kernel: np.ndarray
    shape: tuple[int, int]
    workers: int = 1
    periodic: bool = False  # circular convolution over the kernel's shape, >= the grid's
    _symbol: np.ndarray = field(init=False, repr=False)  # set once in __post_init__

    def __post_init__(self):
        nx, ny = self.shape
        Mx, My = self.kernel.shape
        if self.periodic:
            if Mx < nx or My < ny:
                raise ValueError(f"a periodic kernel's shape {self.kernel.shape} must hold the grid {self.shape}")
        elif Mx < 2 * nx - 1 or My < 2 * ny - 1:
            raise ValueError(f"kernel shape {self.kernel.shape} too small for grid {self.shape}")
        # the symbol of an even real kernel is real: multiply by the real part only
        khat = sfft.rfft2(self.kernel, workers=self.workers)
        object.__setattr__(self, "_symbol", np.ascontiguousarray(khat.real))

    def _buffers(self, dtype: np.dtype) -> tuple[np.ndarray, np.ndarray]:
        """This thread's zero-padded input rows (nx, My) and half spectrum (Mx, My // 2 + 1) in
        ``dtype``'s precision, allocated once: a product then allocates only its output."""
        if not hasattr(_scratch, "buffers"):
            _scratch.buffers = weakref.WeakKeyDictionary()
        mine = _scratch.buffers.setdefault(self, {})
        buffers = mine.get(dtype.char)
        if buffers is None:
            nx, _ = self.shape
            Mx, My = self.kernel.shape
            complex_type = np.complex64 if dtype == np.float32 else np.complex128
            buffers = mine[dtype.char] = (np.zeros((nx, My), dtype), np.zeros((Mx, My // 2 + 1), complex_type))
        return buffers

    def _pruned(self, rows: np.ndarray, s: np.ndarray) -> np.ndarray:
        """The pruned convolution of the padded input ``rows`` (nx, My) with the symbol ``s``,
        transformed in the half-spectrum buffer of ``rows``' precision; (nx, My) output."""
        nx, _ = self.shape
        Mx, My = self.kernel.shape
        _, spectrum = self._buffers(rows.dtype)
        workers = self.workers
        _pocketfft.r2c(rows, (1,), True, 0, spectrum[:nx], workers)
        spectrum[nx:] = 0.0
        _pocketfft.c2c(spectrum, (0,), True, 0, spectrum, workers)
        np.multiply(spectrum, s, out=spectrum)
        _pocketfft.c2c(spectrum, (0,), False, 2, spectrum, workers)
        return _pocketfft.c2r(spectrum[:nx], (1,), My, False, 2, None, workers)

    def _mirrored(self, rows: np.ndarray, s: np.ndarray) -> np.ndarray:
        """:meth:`_pruned` for input rows that mirror about the grid's middle row
        (rows[i] == rows[nx - 1 - i]); (nx, ny) output, mirror-symmetric exactly.

        Along the padded rows the input is then even about the middle, and so is the output
        (the kernel is even): the row-axis transform pair of period Mx is a cosine pair over
        half the rows (DCT-II and -III about a half-sample centre for even nx, DCT-I about the
        middle row for odd nx), and the column transforms run on half the rows too.  Equal to
        the full transform's product to round-off (``tests/test_halfspace.py``)."""
        nx, ny = self.shape
        _, My = self.kernel.shape
        dtype = rows.dtype
        centre = nx // 2  # rows centre .. nx - 1 carry the half (for odd nx, from the middle row)
        half_rows, spectrum, half_symbol = self._mirror_buffers(dtype, s)
        workers = self.workers
        view = spectrum.view(dtype)  # real and imaginary parts side by side, both transformed
        m = nx - centre
        _pocketfft.r2c(rows[centre:], (1,), True, 0, spectrum[:m], workers)
        spectrum[m:] = 0.0
        if nx % 2 == 0:
            _pocketfft.dct(view, 2, (0,), 0, view, workers)
            np.multiply(view, half_symbol, out=view)
            _pocketfft.dct(view, 3, (0,), 2, view, workers)  # over 2 N = Mx
        else:
            _pocketfft.dct(view, 1, (0,), 0, view, workers)
            np.multiply(view, half_symbol, out=view)
            _pocketfft.dct(view, 1, (0,), 2, view, workers)  # over 2 (N - 1) = Mx
        half = _pocketfft.c2r(spectrum[:m], (1,), My, False, 2, half_rows, workers)
        out = np.empty((nx, ny), dtype)
        out[centre:] = half[:, :ny]
        out[: nx - centre] = half[::-1, :ny]
        return out

    def _mirror_buffers(self, dtype: np.dtype, s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """This thread's buffers of :meth:`_mirrored` in ``dtype``: the half output rows, the
        half spectrum (N rows) and the symbol's first N rows, each entry twice (for the real
        view of the spectrum), kept per symbol array."""
        if not hasattr(_scratch, "mirror"):
            _scratch.mirror = weakref.WeakKeyDictionary()
        mine = _scratch.mirror.setdefault(self, {})
        nx, _ = self.shape
        Mx, My = self.kernel.shape
        N = Mx // 2 if nx % 2 == 0 else Mx // 2 + 1
        buffers = mine.get(dtype.char)
        if buffers is None:
            complex_type = np.complex64 if dtype == np.float32 else np.complex128
            buffers = mine[dtype.char] = (np.empty((nx - nx // 2, My), dtype), np.empty((N, My // 2 + 1), complex_type))
        symbols = mine.setdefault("symbols", {})
        known = symbols.get(id(s))
        if known is None or known[0]() is not s:
            known = symbols[id(s)] = (weakref.ref(s), np.repeat(s[:N], 2, axis=1).astype(dtype))
        return buffers[0], buffers[1], known[1]

    def _mirror_ready(self, grid: np.ndarray) -> bool:
        """Whether a product of ``grid`` (nx, ny) may take :meth:`_mirrored`: the transforms
        are at hand, the padded rows are even in number and the grid mirrors exactly."""
        return _pocketfft is not None and self.kernel.shape[0] % 2 == 0 and self.shape[0] >= 2 and mirrors(grid)

    @property
    def padded_shape(self) -> tuple[int, int]:
        """(Mx, My), the shape of the kernel and of the padded FFT grid."""
        return self.kernel.shape

    @property
    def symbol(self) -> np.ndarray:
        """The real Fourier symbol on the padded (Mx, My // 2 + 1) half-spectrum."""
        return self._symbol

    def convolve(self, p: np.ndarray, symbol: np.ndarray | None = None) -> np.ndarray:
        """Linear (or, for a periodic operator, circular) convolution of p with a symbol.

        Parameters
        ----------
        p : numpy.ndarray
            (nx, ny) array, any float dtype.
        symbol : numpy.ndarray or None, optional
            A real Fourier symbol in the layout of :attr:`symbol` (float32 or float64); this
            operator's own, C, by default.

        Returns
        -------
        numpy.ndarray
            (nx, ny) array, the convolution on the grid.
        """
        nx, ny = self.shape
        Mx, My = self.kernel.shape
        s = self._symbol if symbol is None else symbol
        if _pocketfft is not None and p.dtype in (np.float32, np.float64):
            rows, _ = self._buffers(p.dtype)
            rows[:, :ny] = p
            return self._pruned(rows, s)[:, :ny]
        a = sfft.rfft(p, n=My, axis=1, workers=self.workers)
        b = sfft.fft(a, n=Mx, axis=0, workers=self.workers, overwrite_x=True)
        b *= s
        c = sfft.ifft(b, axis=0, workers=self.workers, overwrite_x=True)[:nx]
        return sfft.irfft(c, n=My, axis=1, workers=self.workers)[:, :ny]

    def window(self, shape: tuple[int, int], *, even_rows: bool = False) -> HalfSpaceOperator:
        """The same operator on a smaller grid of wx x wy cells (wx <= nx, wy <= ny).

        Its coefficients are this kernel's for the offsets such a grid has, on the smaller padded
        grid :func:`~halfspace.padded_shape` gives.  A contact set that fits into the smaller grid
        then costs its FFTs instead of the whole face's, with the same C_SS.

        Parameters
        ----------
        shape : tuple of int
            (wx, wy), with 1 <= wx <= nx and 1 <= wy <= ny.
        even_rows : bool, optional
            An even number of padded rows (:func:`~halfspace.padded_shape`), for sets that
            mirror about the window's middle row.

        Returns
        -------
        HalfSpaceOperator
            The operator on the smaller grid.

        Raises
        ------
        ValueError
            If the window does not fit into the grid, or the operator is periodic (its images fill
            the whole cell).
        """
        if self.periodic:
            raise ValueError("a periodic operator has no smaller window: its images fill the whole cell")
        nx, ny = self.shape
        wx, wy = int(shape[0]), int(shape[1])
        if not (1 <= wx <= nx and 1 <= wy <= ny):
            raise ValueError(f"window {shape} must fit into the grid {self.shape}")
        Mx, My = self.kernel.shape
        Wx, Wy = padded_shape(wx, wy, even_rows=even_rows)

        def offsets(W, w, M):
            # the window's index -> offset -> this kernel's index, or -1 for an offset the window lacks
            o = np.arange(W)
            o = np.where(o < w, o, o - W)
            return np.where(np.abs(o) <= w - 1, o % M, -1)

        ix, iy = offsets(Wx, wx, Mx), offsets(Wy, wy, My)
        K = self.kernel[np.ix_(np.maximum(ix, 0), np.maximum(iy, 0))]
        K[ix < 0, :] = 0.0
        K[:, iy < 0] = 0.0
        return HalfSpaceOperator(K, (wx, wy), self.workers)

    def apply(self, p: np.ndarray) -> np.ndarray:
        """u = C p on the nx x ny grid.

        Parameters
        ----------
        p : numpy.ndarray
            (nx, ny) pressures on the elements.

        Returns
        -------
        numpy.ndarray
            (nx, ny) displacements at the element centres.
        """
        return self.convolve(np.asarray(p, float))

    def apply_masked(self, values: np.ndarray, mask: np.ndarray) -> np.ndarray:
        """u = C p on the whole grid, where p equals ``values`` on ``mask`` and 0 elsewhere.

        Parameters
        ----------
        values : numpy.ndarray
            Pressures of the elements in ``mask``, in the order of ``p[mask]``.
        mask : numpy.ndarray
            Boolean (nx, ny) array: the loaded elements.

        Returns
        -------
        numpy.ndarray
            (nx, ny) displacements at the element centres.
        """
        return self._masked(values, mask, self._symbol, np.dtype(np.float64))

    def apply_symbol(self, values: np.ndarray, mask: np.ndarray, symbol: np.ndarray) -> np.ndarray:
        """Like :meth:`apply_masked` with another Fourier symbol, restricted to ``mask``.

        Computed in the symbol's precision (float32 or float64), e.g. for a single-precision
        preconditioner.

        Parameters
        ----------
        values : numpy.ndarray
            Pressures of the elements in ``mask``, in the order of ``p[mask]``.
        mask : numpy.ndarray
            Boolean (nx, ny) array: the loaded elements, and those where the result is returned.
        symbol : numpy.ndarray
            A real Fourier symbol in the layout of :attr:`symbol`.

        Returns
        -------
        numpy.ndarray
            The convolution on ``mask`` (float64), in the order of ``u[mask]``.
        """
        return self._masked(values, mask, symbol, np.dtype(symbol.dtype))[mask].astype(float)

    def _masked(self, values: np.ndarray, mask: np.ndarray, symbol: np.ndarray, dtype: np.dtype) -> np.ndarray:
        """The convolution of ``values`` on ``mask`` (zero elsewhere) with ``symbol``, computed
        in ``dtype``'s precision, on the whole grid."""
        if _pocketfft is None or dtype not in (np.float32, np.float64):
            p = np.zeros(self.shape, dtype=dtype)
            p[mask] = values
            return self.convolve(p, symbol)
        _, ny = self.shape
        rows, _ = self._buffers(dtype)
        grid = rows[:, :ny]
        grid.fill(0.0)
        grid[mask] = values
        if self._mirror_ready(grid):
            return self._mirrored(rows, symbol)
        return self._pruned(rows, symbol)[:, :ny]
