"""The zero-range extrapolation's error estimate covers its error (bem_energy.richardson).

Data only: the finite-range pull-off forces stored by ``benchmarks/study_energy_zero_range.py
--json`` (tests/data/zero_range_study.json; the command that wrote each sequence is in it).
Every window of three or more consecutive ranges of every stored sequence is extrapolated with
the fitted rate and with the rate fixed at 1/2 (the harness's coarse sequence), and the
estimate must cover the error.

References, in units of F_upper (Eq. 13), forces scaled to the nominal face area:
- circle: Kendall (Eq. 6) = F_upper exactly;
- square, triangle: no closed form.  The reference interval is the hull of the Griffith
  solver's 1/N extrapolations (its rotation means at 48, 64, 96, 128 per radius, README
  "Energy-minimisation BEM", from part 3 of the same study script; pairs 48/96, 64/128,
  96/128) and the energy method's own fitted-rate extrapolation of its finest window
  (0.04, 0.02, 0.01).  The error is measured from the interval's middle and may exceed the
  estimate by the interval's half-width (0.14 % of F_upper for both): below that the test
  cannot tell.

Measured (``pytest tests/test_zero_range_estimator.py -s`` prints every window): 78 windows,
estimate / error >= 1.09 (the square's 0.32 ... 0.01 at rate 1/2); the earlier spread between
fits left 52 of them uncovered (estimate / error down to 0.03), among them the issue's circle
windows (+3.5 % against 2.2 %, +8.7 % against 5.8 %, +1.27 % against 0.53 %).
"""

from __future__ import annotations

import importlib
import json
from pathlib import Path

import numpy as np
import pytest

zr = importlib.import_module("bem_energy.zero_range")

DATA = Path(__file__).parent / "data" / "zero_range_study.json"

#: Griffith BEM, F_A / F_upper scaled to the nominal area, mean over rotations 0, 15, 30, 45
#: degrees against the grid (spread within +-0.2 %), at N = 48, 64, 96, 128 per radius
GRIFFITH = {"square": (0.8945, 0.8894, 0.8858, 0.8831), "triangle": (0.8269, 0.8252, 0.8194, 0.8172)}
GRIFFITH_N = (48, 64, 96, 128)


def _griffith_limits(values):
    """1/N extrapolations F(inf) = (N2 F2 - N1 F1) / (N2 - N1) through the pairs 48/96, 64/128, 96/128."""
    F = dict(zip(GRIFFITH_N, values, strict=True))
    return [(n2 * F[n2] - n1 * F[n1]) / (n2 - n1) for n1, n2 in ((48, 96), (64, 128), (96, 128))]


def load():
    with open(DATA) as fh:
        return json.load(fh)["sequences"]


def reference(face, seqs):
    """(value, uncertainty) of the zero-range F_A / F_upper."""
    if face == "circle":
        return 1.0, 0.0
    fine = seqs[f"{face}-epz2"]
    h, F = np.array(fine["ratios"]), np.array(fine["area_scaled_over_upper"])
    sel = h <= 0.04 + 1e-12
    own = zr.richardson(h[sel], F[sel])[0]
    vals = _griffith_limits(GRIFFITH[face]) + [own]
    lo, hi = min(vals), max(vals)
    return 0.5 * (lo + hi), 0.5 * (hi - lo)


def windows(seqs, min_points=3):
    """(sequence, window label, procedure, F0, error, estimate, reference uncertainty) for every
    run of >= min_points consecutive ranges, fitted rate and rate 1/2."""
    rows = []
    for key, s in sorted(seqs.items()):
        h, F = np.array(s["ratios"]), np.array(s["area_scaled_over_upper"])
        ref, u = reference(s["face"], seqs)
        for i in range(len(h)):
            for j in range(i + min_points, len(h) + 1):
                for proc, rate in (("fitted", None), ("rate 1/2", 0.5)):
                    F0, _, est = zr.richardson(h[i:j], F[i:j], rate)
                    rows.append((key, f"{h[i]:g}..{h[j - 1]:g}", proc, F0, abs(F0 - ref), est, u))
    return rows


def tail_rates(h, F, limit):
    """The effective rate q of the shortfall beyond each range: limit - F_n = (F_n - F_(n-1)) / (t^q - 1)."""
    return np.log2(1 + (F[1:] - F[:-1]) / (limit - F[1:])) / np.log2(h[:-1] / h[1:])


@pytest.fixture(scope="module")
def seqs():
    return load()


@pytest.fixture(scope="module")
def rows(seqs):
    return windows(seqs)


def test_the_study_data_are_complete(seqs):
    for face in ("circle", "square", "triangle"):
        s = seqs[f"{face}-epz2"]
        assert s["ratios"][:6] == [0.32, 0.16, 0.08, 0.04, 0.02, 0.01] and all(s["converged"])
        assert s["command"].startswith("python benchmarks/study_energy_zero_range.py")
        # the stored scaled forces are the raw ones at the nominal area, F ~ A^(3/4)
        raw, area = np.array(s["raw_pulloff_forces"]), np.array(s["raster_areas"])
        np.testing.assert_allclose(
            s["area_scaled_pulloff_forces"], raw * (s["nominal_area"] / area) ** 0.75, rtol=1e-12
        )
        np.testing.assert_allclose(
            s["area_scaled_over_upper"], np.array(s["area_scaled_pulloff_forces"]) / s["upper_bound_force"], rtol=1e-12
        )
    assert seqs["circle-epz2"]["kendall_force"] == pytest.approx(seqs["circle-epz2"]["upper_bound_force"], rel=1e-12)


def _report(rows, scale=1.0):
    lines, fails = [], []
    for key, win, proc, F0, err, est, u in rows:
        ok = err <= scale * est + u
        lines.append(
            f"{key:13s} {win:11s} {proc:8s} F0 = {F0:.4f}  error {err:.4f}  estimate {scale * est:.4f}"
            f"  (+ ref. {u:.4f})  estimate/error {scale * est / err if err else float('inf'):7.2f}"
            + ("" if ok else "  NOT COVERED")
        )
        if not ok:
            fails.append(lines[-1])
    return lines, fails


def test_the_estimate_covers_the_error_in_every_window(rows, record_property):
    lines, fails = _report(rows)
    print("\n" + "\n".join(lines))
    ratios = [est / err for *_, err, est, _ in rows if err > 0]
    record_property("min_estimate_over_error", min(ratios))
    record_property("windows", len(rows))
    assert len(rows) >= 2 * 3 * 10
    assert not fails, "\n".join(fails)


def test_half_the_estimate_does_not_cover_it(rows):
    """The bound is not loose by an arbitrary factor: half of it leaves the error uncovered in
    at least half of the windows (43 of 78 on the stored study, mostly the cornered faces')."""
    _, fails = _report(rows, scale=0.5)
    assert 2 * len(fails) >= len(rows), (len(fails), len(rows))


def test_the_circles_tail_rate_lies_in_the_bracket(seqs):
    """The assumption behind the bound, checked where the limit is exact: the circle's effective
    tail rate q, F(0) - F_n = (F_n - F_(n-1)) / (t^q - 1), at every range a window can end on."""
    lo, hi = zr.RATE_BRACKET
    for key in ("circle-epz2", "circle-epz1"):
        s = seqs[key]
        h, F = np.array(s["ratios"]), np.array(s["area_scaled_over_upper"])
        q = tail_rates(h, F, 1.0)
        fine = h[1:] <= zr.VALIDATED_FINEST_RATIO + 1e-12
        print(key, dict(zip(h[1:], q.round(3), strict=False)))
        assert np.all((lo <= q[fine]) & (q[fine] <= hi)), (key, q)


@pytest.mark.parametrize(
    "terms",
    [
        [(0.6, 0.5)],
        [(0.6, 0.7)],
        [(0.6, 1.0)],
        [(0.6, 1.5)],
        [(0.5, 0.5), (0.3, 1.0)],
        [(0.5, 0.5), (0.5, 1.5)],
        [(0.2, 1.0), (0.6, 1.5)],
    ],
)
def test_a_tail_with_rates_in_the_bracket_is_covered(terms):
    """Shortfalls sum c_i l_c^q_i of one sign with q_i in the bracket: the limit is covered
    whichever procedure extrapolates."""
    h = np.array([0.08, 0.04, 0.02, 0.01])
    F = 1.0 - sum(c * h**q for c, q in terms)
    for rate in (None, 0.5, 1.0):
        F0, _, est = zr.richardson(h, F, rate)
        assert abs(F0 - 1.0) <= est * (1 + 1e-9) + 1e-12


def test_a_tail_slower_than_the_bracket_is_not():
    """Outside the assumption there is no bound: a shortfall like l_c^(1/4) beats it."""
    h = np.array([0.08, 0.04, 0.02])
    F0, _, est = zr.richardson(h, 1.0 - 0.6 * h**0.25, 0.5)
    assert abs(F0 - 1.0) > est
