"""Speed of the energy-minimisation BEM, as ratios measured in one run.

1. One finite-range circle pull-off (l_c = 0.16 a, 32 elements per radius) with each
   minimiser: wall time, iterations, FFT-pair equivalents (wall / one padded FFT pair), and
   whether the answer changes.
2. Per-solve overhead at a 128 x 128 face grid: a minimisation started at its own minimum
   (set-up, one energy evaluation, the convergence test) against a continuation step.
3. The 256 x 256 circle (127 elements per radius) at rho = 0.05 a, l_c = 2 Delta.
4. The zero-range (JKR) limit of the circle with the default settings: time and error.
5. Why the padded grid is rounded up to an FFT-friendly size: one FFT pair at a size with a
   large prime factor against ``scipy.fft.next_fast_len`` of it.

    python benchmarks/bench_energy.py [--skip-large] [--update]

``--update`` writes docs/performance_energy_{minimisers,overhead,cases,fft_size}.json
(rendered into docs/performance.md by ``python benchmarks/docs_tables.py``).
"""

from __future__ import annotations

import math
import sys
import time

import _timing  # thread settings first
import numpy as np
import scipy.fft as sfft
from _timing import median_time, table

import bem_energy as be
import contact_scene as cs
from contact_scene import theory as T


def circle(work, range_=None):
    return cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(work, range_))


def fft_pair(M):
    x = np.random.default_rng(0).standard_normal(M)
    return median_time(lambda: sfft.irfft2(sfft.rfft2(x), s=M), repeat=9, number=5)


def minimisers():
    W = 0.02
    sc = circle(W, math.sqrt(0.16 * W))
    rows, ref, t_ref = [], None, None
    for name in ("pk", "lbfgsb"):
        st = be.EnergySettings(grid=cs.Grid(elements_per_radius=32), minimiser=name)
        t = time.perf_counter()
        r = be.solve(sc, st)
        dt = time.perf_counter() - t
        pair = fft_pair(tuple(r.info["padded_grid"]))
        ref = ref or r.pulloff_force
        t_ref = t_ref or dt
        rows.append(
            (
                name,
                f"{dt:.2f}",
                f"{dt / t_ref:.1f}",
                f"{dt / pair:.0f}",
                r.iterations,
                r.info["evaluations"],
                r.info["minimisations"],
                f"{r.pulloff_force:.8f}",
                f"{r.pulloff_force / ref - 1:+.1e}",
            )
        )
    head = ("minimiser", "wall s", "/ pk", "FFT pairs", "iterations", "evaluations", "minimisations", "F_A", "vs pk")
    print(f"1. circle pull-off, l_c = 0.16 a, 32 per radius (padded {r.info['padded_grid']})")
    print(table(rows, head), flush=True)
    return head, rows


def overhead():
    W = 0.02
    N = 63.0  # a 128 x 128 face raster
    sc = circle(W, math.sqrt(0.16 * W))
    h = 1.0 / N
    prob = be.build_problem(sc, h, be.Potential(W, math.sqrt(0.16 * W)))
    rows = []
    for name in ("pk", "lbfgsb"):
        U = np.zeros(prob.padded)
        m = be.minimise(prob, U, -0.1, True, method=name)
        t_step = median_time(lambda: be.minimise(prob, m.U, -0.105, True, method=name), repeat=3)
        t_over = median_time(lambda: be.minimise(prob, m.U, -0.1, True, method=name), repeat=7)
        t_setup = median_time(lambda: be.build_problem(sc, h, be.Potential(W, math.sqrt(0.16 * W))), repeat=5)
        rows.append(
            (name, f"{t_over * 1e3:.1f}", f"{t_step * 1e3:.1f}", f"{t_over / t_step:.1%}", f"{t_setup * 1e3:.1f}")
        )
    head = ("minimiser", "at minimum ms", "one step ms", "overhead share", "problem set-up ms")
    print(f"\n2. per-solve overhead, face grid {prob.n}, padded {prob.padded}")
    print(table(rows, head), flush=True)
    return head, rows


def large():
    a, rho = 1.0, 0.05
    N = 127.0
    lc = 2.0 / N
    W = rho**2 / lc  # E* = 1
    sc = circle(W, rho)
    t = time.perf_counter()
    r = be.solve(sc, be.EnergySettings(grid=cs.Grid(elements_per_radius=N)))
    dt = time.perf_counter() - t
    FK = T.kendall_adhesion_force(E_star=1.0, radius=a, work=W)
    print(
        f"\n3. circle {r.info['grid']} (padded {r.info['padded_grid']}), rho = 0.05 a, l_c/a = {lc:.4f}: "
        f"{dt:.1f} s wall, {r.iterations} iterations, F_A/F_K = {r.pulloff_force / FK:.4f}, converged {r.converged}",
        flush=True,
    )
    grid = "x".join(map(str, r.info["grid"]))
    return [f"circle {grid}, rho = 0.05 a, l_c = 2 Delta", f"{dt:.1f}", f"{r.pulloff_force / FK:.4f}", "", r.converged]


def zero_range():
    W = 0.02
    t = time.perf_counter()
    r = be.solve(circle(W))
    dt = time.perf_counter() - t
    FK = T.kendall_adhesion_force(E_star=1.0, radius=1.0, work=W)
    print(
        f"\n4. zero-range circle (default ratios {r.info['zero_range']['process_zone_ratios']}): {dt:.1f} s wall, "
        f"F_A/F_K - 1 = {r.pulloff_force / FK - 1:+.3%}, estimate {r.accuracy_estimate:.2%}, "
        f"runs {[round(f / FK, 4) for f in r.info['zero_range']['pulloff_forces']]}",
        flush=True,
    )
    ratios = ", ".join(f"{x:g}" for x in r.info["zero_range"]["process_zone_ratios"])
    return [
        f"zero-range circle, l_c/a = {ratios}",
        f"{dt:.1f}",
        f"{r.pulloff_force / FK:.4f}",
        f"{r.accuracy_estimate:.2%}",
        r.converged,
    ]


def fft_sizes(sizes=(202, 404, 808)):
    rows = []
    for n in sizes:
        fast = sfft.next_fast_len(n, real=True)
        t_n, t_fast = fft_pair((n, n)), fft_pair((fast, fast))
        rows.append([f"{n}^2", f"{fast}^2", f"{t_n * 1e3:.2f}", f"{t_fast * 1e3:.2f}", f"{t_n / t_fast:.1f}"])
    head = ("padded", "next fast", "ms per FFT pair", "next fast ms", "ratio")
    print("\n5. FFT pair at a size with a large prime factor against the next fast size")
    print(table(rows, head), flush=True)
    return head, rows


if __name__ == "__main__":
    record = _timing.provenance_record()
    tables = {"minimisers": minimisers(), "overhead": overhead()}
    cases = [zero_range()]
    if "--skip-large" not in sys.argv:
        cases.insert(0, large())
    tables["cases"] = (("case", "wall s", "F_A/F_K", "estimate", "converged"), cases)
    tables["fft_size"] = fft_sizes()
    if "--update" in sys.argv:
        for name, (head, rows) in tables.items():
            _timing.write_doc_table(f"performance_energy_{name}", head, rows, record)
