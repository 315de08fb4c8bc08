"""Matvec cost of the Griffith BEM operator against the bare padded FFT convolution.

    python benchmarks/bench_matvec.py

Prints medians and ratios measured in one run: ours (pruned transforms) / bare
(scipy.fft rfft2 -> multiply -> irfft2 on the padded grid), for float64 and for the float32
preconditioner path, a pressure that mirrors about the grid's middle row through the solver's
masked product (its half-size cosine transforms, the scatter onto the grid and the mirror
check included), in double precision and, as the Fourier preconditioner takes it, in single
precision over the padded grid and over the compact period
(``bem_griffith.preconditioner.compact_period``, no zero padding), and pyfftw's bare
convolution when pyfftw is installed.
"""

from __future__ import annotations

import statistics
import sys
import time

import _timing  # sets thread counts before numpy loads
import numpy as np
import scipy.fft as sfft

from bem_griffith.preconditioner import compact_period, fourier_preconditioner
from halfspace.kernel import love_influence, padded_shape
from halfspace.operator import HalfSpaceOperator, default_workers

HEADERS = [
    "grid",
    "padded",
    "bare ms",
    "ours ms",
    "ours/bare",
    "f32/bare",
    "mirrored/bare",
    "mirrored f32/bare",
    "compact f32/bare",
    "2 workers/1",
    "pyfftw/bare",
]


def alternated(f, g, repeat=21):
    """Median of f's time over g's, timed in alternation."""
    f(), g()
    ratios = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        t1 = time.perf_counter()
        g()
        ratios.append((t1 - t0) / (time.perf_counter() - t1))
    return statistics.median(ratios)


def main(sizes=(64, 130, 258, 514), update=False):
    record = _timing.provenance_record()
    workers = default_workers()
    rows = []
    for n in sizes:
        P = padded_shape(n, n)
        op = HalfSpaceOperator(love_influence(n, n, 1.0, 1.0, P), (n, n), workers)
        rng = np.random.default_rng(0)
        p = rng.random((n, n))
        buf = np.zeros(P)
        khat = sfft.rfft2(op.kernel)

        def bare():
            buf[:n, :n] = p
            return sfft.irfft2(sfft.rfft2(buf, workers=workers) * khat, s=P, workers=workers)[:n, :n]

        def ours():
            return op.convolve(p)

        p32 = p.astype(np.float32)
        s32 = op.symbol.astype(np.float32)

        def ours32():
            return op.convolve(p32, s32)

        mirrored_p = p + p[::-1]
        everywhere = np.ones((n, n), bool)
        values = mirrored_p[everywhere]

        def mirrored():
            return op.apply_masked(values, everywhere)

        # the preconditioner's products (E* = 1, unit spacing: the point kernel 1 / (pi r))
        padded_m = fourier_preconditioner((n, n), P, 1.0, (1.0 / np.pi, 0.0), padded=True, workers=workers)
        compact_m = fourier_preconditioner(
            (n, n), compact_period((n, n)), 1.0, (1.0 / np.pi, 0.0), padded=False, workers=workers
        )

        assert np.allclose(ours(), bare(), rtol=1e-12, atol=1e-12 * np.abs(bare()).max())
        expected = op.convolve(mirrored_p)
        assert np.allclose(mirrored(), expected, rtol=0, atol=1e-13 * np.abs(expected).max())
        tb = _timing.median_time(bare)
        to = _timing.median_time(ours)
        t32 = _timing.median_time(ours32)
        tm = _timing.median_time(mirrored)
        tpm = _timing.median_time(lambda: padded_m.apply(values, everywhere))
        tcm = _timing.median_time(lambda: compact_m.apply(values, everywhere))
        one, two = HalfSpaceOperator(op.kernel, (n, n), 1), HalfSpaceOperator(op.kernel, (n, n), 2)
        w2 = alternated(lambda: two.convolve(p), lambda: one.convolve(p))
        row = [
            f"{n}x{n}",
            f"{P[0]}x{P[1]}",
            f"{tb * 1e3:.3f}",
            f"{to * 1e3:.3f}",
            f"{to / tb:.2f}",
            f"{t32 / tb:.2f}",
            f"{tm / tb:.2f}",
            f"{tpm / tb:.2f}",
            f"{tcm / tb:.2f}",
            f"{w2:.2f}",
        ]
        try:
            import pyfftw.interfaces.scipy_fft as pf

            tf = _timing.median_time(lambda: pf.irfft2(pf.rfft2(buf, workers=workers) * khat, s=P, workers=workers))
            row.append(f"{tf / tb:.2f}")
        except ImportError:
            row.append("n/a")
        rows.append(row)
    print(f"FFT workers = {workers}")
    print(_timing.table(rows, HEADERS))
    if update:
        _timing.write_doc_table("performance_matvec", HEADERS, rows, record, fft_workers=workers)


if __name__ == "__main__":
    main(update="--update" in sys.argv)
