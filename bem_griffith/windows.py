"""Sub-grid windows: a contact set that has shrunk into a small box of the face is solved
on that box's (smaller) padded grid, with the same coefficients C_SS."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import scipy.fft as sfft

from halfspace.kernel import padded_shape
from halfspace.operator import HalfSpaceOperator, mirrors

from .preconditioner import FourierPreconditioner, compact_period, fourier_preconditioner

if TYPE_CHECKING:
    from .problem import Problem

__all__ = [
    "ContactWindow",
    "WindowMemo",
    "window_for",
    "window_length",
    "windows_memory_bytes",
    "WINDOW_STEPS",
    "WINDOW_GAIN",
    "WINDOW_MEMO",
]

#: window extents are rounded up to multiples of n / WINDOW_STEPS, so that a shrinking
#: contact set reuses a few windows (each costs a kernel transform and a preconditioner symbol)
WINDOW_STEPS = 32
#: a window is used only when its padded grid has at most this share of the full one's cells
WINDOW_GAIN = 0.9
#: windows kept at a time (each holds a padded kernel, its transform and a preconditioner)
WINDOW_MEMO = 3


def windows_memory_bytes(padded_cells: int) -> float:
    """Bytes the remembered windows of a grid with ``padded_cells`` padded cells may hold:
    WINDOW_MEMO windows of at most WINDOW_GAIN of its cells, each a float64 kernel (8 bytes
    a cell), its real half-spectrum symbol (4), the transform buffers in both precisions (18:
    the input rows and a complex half spectrum; the single-precision ones the
    preconditioner's), and the preconditioner's circulant at most on the same padded grid: its
    float64 kernel and symbol (12) and its float32 inverse symbol (2)."""
    return padded_cells * (8 + 4 + 18 + 12 + 2) * WINDOW_MEMO * WINDOW_GAIN


@dataclass(frozen=True, eq=False)
class ContactWindow:
    """The box [rows, cols] of the face grid a contact set is solved on, its operator and
    its preconditioner (None when the problem has none; padded or compact as the problem's)."""

    rows: slice
    cols: slice
    operator: HalfSpaceOperator
    preconditioner: FourierPreconditioner | None


class WindowMemo:
    """The last few windows' operators and preconditioners, keyed by window shape and whether
    the window mirrors (its padded rows then even); contact sets mostly shrink, so the oldest
    are forgotten first."""

    def __init__(self, capacity: int = WINDOW_MEMO):
        self.capacity = capacity
        self._entries: dict[tuple, tuple[HalfSpaceOperator, FourierPreconditioner | None]] = {}

    def get(self, key: tuple, build):
        entry = self._entries.get(key)
        if entry is None:
            entry = self._entries[key] = build()
            while len(self._entries) > self.capacity:
                self._entries.pop(next(iter(self._entries)))
        return entry

    def __len__(self):
        return len(self._entries)


def window_length(n: int, extent: int) -> int:
    """The window length for a set spanning ``extent`` of ``n`` cells: rounded up to the
    quantum n / WINDOW_STEPS, then widened to the most that its FFT-friendly padded length
    can hold."""
    quantum = max(1, n // WINDOW_STEPS)
    length = min(n, quantum * math.ceil(extent / quantum))
    return min(n, (sfft.next_fast_len(2 * length - 1, real=True) + 1) // 2)


def window_for(problem: Problem, contact: np.ndarray) -> ContactWindow | None:
    """A box of the grid holding ``contact`` whose padded FFTs are markedly cheaper than the
    whole face's (at most WINDOW_GAIN of its cells), or None (windows off, or no gain)."""
    if problem.windows is None:
        return None
    rows, cols = np.flatnonzero(contact.any(axis=1)), np.flatnonzero(contact.any(axis=0))
    if rows.size == 0:
        return None
    nx, ny = contact.shape
    wx = window_length(nx, int(rows[-1] - rows[0] + 1))
    wy = window_length(ny, int(cols[-1] - cols[0] + 1))
    # a set that mirrors about the grid's middle row gets a window centred there, so that it
    # mirrors in the window too and its products take the half-size transforms; its extent has
    # the parity of nx, so a window one row shorter still holds it where the parity differs
    mirrored = int(rows[0] + rows[-1]) == nx - 1 and mirrors(contact)
    if mirrored and (nx - wx) % 2:
        wx -= 1
    if np.prod(padded_shape(wx, wy, even_rows=mirrored)) > WINDOW_GAIN * np.prod(problem.operator.padded_shape):
        return None

    def build():
        operator = problem.operator.window((wx, wy), even_rows=mirrored)
        whole = problem.preconditioner
        if whole is None or problem.point_kernel is None:
            return operator, None
        period = operator.padded_shape if whole.padded else compact_period((wx, wy))
        preconditioner = fourier_preconditioner(
            (wx, wy), period, problem.spacing, problem.point_kernel, padded=whole.padded, workers=operator.workers
        )
        return operator, preconditioner

    operator, preconditioner = problem.windows.get((wx, wy, mirrored), build)
    # the window starts at the set's first row/column unless that would run off the grid
    i0, j0 = (nx - wx) // 2 if mirrored else min(int(rows[0]), nx - wx), min(int(cols[0]), ny - wy)
    return ContactWindow(slice(i0, i0 + wx), slice(j0, j0 + wy), operator, preconditioner)
