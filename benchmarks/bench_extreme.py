"""Stiff and extreme cases: converged or not, error against theory, iterations, time.

    python benchmarks/bench_extreme.py
"""
from __future__ import annotations

import time

import _timing  # noqa: F401

import bem_energy as be
import bem_griffith as bg
import contact_scene as cs
import fem_reference as fr
from contact_scene import theory as T


def _row(case, method, r, ref, wall):
    err = f"{r.stiffness / ref - 1:+.2e}" if ref else "n/a"
    return [case, method, r.converged, err, r.iterations, f"{wall:.2f}", (r.messages[-1][:50] if r.messages else "")]


def main():
    rows = []
    circle = lambda m, w=1.0, **kw: cs.Scene(cs.Indenter(cs.Circle(1.0)), m, cs.Adhesion(w), **kw)
    for nu in (0.49, 0.499, 0.4999, 0.5):
        m = cs.Homogeneous(1.0, nu)
        K = T.kendall_stiffness(E_star=m.effective_modulus, radius=1.0)
        for name, fn in (("bem_griffith", lambda s: bg.solve(s, bg.Settings(grid=cs.Grid(elements_per_radius=32)))),
                         ("bem_energy", lambda s: be.solve(s)),
                         ("fem_reference", lambda s: fr.solve(s, fr.FemSettings(grading=2.0)))):
            t = time.perf_counter()
            r = fn(circle(m))
            rows.append(_row(f"nu = {nu}", name, r, K, time.perf_counter() - t))
    for k in (0.9, 0.95, -0.9, -0.95):
        m = cs.PowerLawGraded(1.0, 1.0, k)
        K = T.graded_stiffness(E0=1.0, c0=1.0, k=k, radius=1.0)
        t = time.perf_counter()
        r = bg.solve(circle(m), bg.Settings(grid=cs.Grid(elements_per_radius=32)))
        rows.append(_row(f"k = {k}", "bem_griffith", r, K, time.perf_counter() - t))
        if k > 0:
            t = time.perf_counter()
            r = fr.solve(circle(m), fr.FemSettings(grading=2.0))
            rows.append(_row(f"k = {k}", "fem_reference", r, K, time.perf_counter() - t) + [])
            rows[-1][-1] = f"accuracy estimate {r.accuracy_estimate:.1e}"
    E = cs.Homogeneous(0.75, 0.5)
    for w in (1e-12, 1e6):
        t = time.perf_counter()
        r = bg.solve(circle(E, w, loading=cs.Loading(pull_limit=-10.0)), bg.Settings(grid=cs.Grid(elements_per_radius=32)))
        rows.append(_row(f"w = {w:g}", "bem_griffith", r, 2.0, time.perf_counter() - t))
        t = time.perf_counter()
        # the energy method at a finite range: l_c = 0.16 a (rho scales with sqrt(w))
        sc = circle(cs.Homogeneous(0.75, 0.5), w, loading=cs.Loading(pull_limit=-10.0))
        sc = cs.Scene(sc.indenter, sc.material, cs.Adhesion(w, (0.16 * w) ** 0.5), sc.loading)
        r = be.solve(sc, be.EnergySettings(grid=cs.Grid(elements_per_radius=16)))
        rows.append(_row(f"w = {w:g}, l_c = 0.16 a", "bem_energy", r, 2.0, time.perf_counter() - t))
    for ar in (10, 20, 50):
        t = time.perf_counter()
        sc = cs.Scene(cs.Indenter(cs.Rectangle(float(ar), 1.0)), E, cs.Adhesion(1.0))
        r = bg.solve(sc, bg.Settings(grid=cs.Grid(spacing=1 / 8)))
        rows.append(_row(f"rectangle {ar}:1", "bem_griffith", r, None, time.perf_counter() - t))
        if ar <= 20:
            t = time.perf_counter()
            r = be.solve(cs.Scene(cs.Indenter(cs.Rectangle(float(ar), 1.0)), E, cs.Adhesion(1.0, 0.16 ** 0.5)),
                         be.EnergySettings(grid=cs.Grid(spacing=1 / 8)))
            rows.append(_row(f"rectangle {ar}:1, l_c = 0.16 b", "bem_energy", r, None, time.perf_counter() - t))
    print(_timing.table(rows, ["case", "method", "converged", "stiffness err", "CG its", "wall s", "note"]))


if __name__ == "__main__":
    main()
