"""The process zone of a graded body (``bem_energy.potentials``): defined where the zero-range
edge field reaches the potential's strength, as at k = 0, and resolved by its default grid.

The definition is checked against the closed-form graded punch (Eqs. 34 and 39); the grid
against a run with twice the elements per l_c, with the tolerance of the homogeneous default
(2 elements per l_c are within 0.2 % of converged, ``PROCESS_ZONE_ELEMENTS``); the zero-range
extrapolation's tail bracket against the graded circle's closed form.  Each check keeps its
mutant: the definition without c_k, the graded body on the homogeneous count, the
homogeneous tail rates.
"""

from __future__ import annotations

import importlib
import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import bem_energy as be
import contact_scene as cs
from bem_energy import potentials
from bem_energy.potentials import process_zone_exponent, process_zone_modulus, range_for_process_zone
from contact_scene import theory as T

zr = importlib.import_module("bem_energy.zero_range")


def edge_distance(k: float, E0: float, c0: float, a: float, w: float, rho: float) -> float:
    """Where the exact pull-off pressure P0 (a^2 - r^2)^((k-1)/2) of the circular punch on a
    graded body (force F_A of Eq. 39) equals w / rho: its distance from the edge."""
    F = T.graded_adhesion_force(E0=E0, c0=c0, k=k, radius=a, work=w)
    P0 = F * (1 + k) / (2 * math.pi * a ** (1 + k))
    x = (P0 * rho / w) ** (2 / (1 - k))  # a^2 - r^2 there
    return a - math.sqrt(a * a - x) if x < a * a else a


def range_at(s: float, k: float, E0: float, c0: float, a: float, w: float) -> float:
    """The range whose edge distance (:func:`edge_distance`) is ``s``, by bisection in log."""
    lo, hi = 1e-12, 10.0
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if edge_distance(k, E0, c0, a, w, mid) < s else (lo, mid)
    return math.sqrt(lo * hi)


@pytest.mark.parametrize("k", [-0.5, 0.0, 0.25, 0.5, 0.75, 0.9])
def test_process_zone_is_pi_times_where_the_edge_field_reaches_the_strength(k):
    """l_c = pi s_k for every k (E* rho^2 / w at k = 0), in the limit rho -> 0 where the edge
    field is the whole story: the offset falls like s_k / a."""
    E0, c0, a, w = 2.0, 1.3, 1.7, 0.3
    mat = cs.PowerLawGraded(E0, c0, k)
    E, kk = process_zone_modulus(mat), process_zone_exponent(mat)
    for s_over_a in (1e-3, 1e-4):
        rho = range_at(s_over_a * a, k, E0, c0, a, w)
        s = edge_distance(k, E0, c0, a, w, rho)
        lc = be.process_zone_length(modulus=E, work=w, range=rho, exponent=kk)
        assert lc / (math.pi * s) == pytest.approx(1.0, abs=2 * s_over_a)


def test_the_definition_without_its_constant_is_caught(monkeypatch):
    """Mutant: l_c^(1-k) = E_k rho^2 / w without c_k puts the zone pi^(k/(1-k)) off (pi at k = 0.5)."""
    monkeypatch.setattr(potentials, "process_zone_factor", lambda k: 1.0)
    E0, c0, a, w, k = 2.0, 1.3, 1.7, 0.3, 0.5
    E = process_zone_modulus(cs.PowerLawGraded(E0, c0, k))
    rho = range_at(1e-4 * a, k, E0, c0, a, w)
    lc = be.process_zone_length(modulus=E, work=w, range=rho, exponent=k)
    assert lc / (math.pi * edge_distance(k, E0, c0, a, w, rho)) == pytest.approx(math.pi, rel=1e-2)


RATIO = 0.08  # l_c / a of the grid check: the study's (benchmarks/study_graded_shape_ratio.py --resolution)


def _pull_off(k: float, spacing: float) -> float:
    scene = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.PowerLawGraded(1.0, 1.0, k), cs.Adhesion(1.0))
    rho = range_for_process_zone(modulus=process_zone_modulus(scene.material), work=1.0, length=RATIO, exponent=k)
    res = be.pull_off(
        scene,
        replace(be.ZeroRangeSettings().energy, grid=cs.Grid(spacing=spacing)),
        spacing=spacing,
        potential=be.Potential(1.0, rho),
    )
    assert res.converged and res.detached
    return T.force_at_nominal_area(
        res.pulloff_force, area=cs.rasterise(scene.indenter.shape, spacing).area, nominal_area=math.pi, k=k
    )


def _default_against_twice(k: float) -> float:
    per = be.ZeroRangeSettings().elements_per_process_zone * potentials.graded_zone_elements(k)
    return _pull_off(k, RATIO / per) / _pull_off(k, RATIO / (2 * per)) - 1.0


#: the homogeneous default's distance from converged (0.18 % at l_c = 0.08 a), with room for
#: the graded one's (0.15 % at k = 0.5 against 16 per l_c)
RESOLVED = 3e-3


def test_graded_zone_is_resolved_like_a_homogeneous_one():
    """At k = 0.5 the sequence's grid (2 x 2 elements per l_c) is as close to converged as the
    homogeneous one: doubling the elements moves F_A by less than RESOLVED."""
    assert abs(_default_against_twice(0.5)) < RESOLVED


def test_the_homogeneous_count_on_a_graded_body_is_caught(monkeypatch):
    """Mutant: the graded body on 2 elements per l_c overshoots by about 2 % (the zone is
    trapped by the mesh)."""
    monkeypatch.setattr(potentials, "graded_zone_elements", lambda k: 1.0)
    assert _default_against_twice(0.5) > 3 * RESOLVED


# -- the zero-range extrapolation on a graded body ------------------------------------------------

GRADED_STUDY = Path(__file__).resolve().parents[1] / "docs" / "accuracy_graded_zero_range.json"


def _circle_sequence(k: float):
    doc = json.loads(GRADED_STUDY.read_text())
    (seq,) = [q for q in doc["sequences"] if q["face"] == "circle" and q["k"] == k]
    assert seq["converged"]
    return np.array(seq["ratios"], float), np.array(seq["forces"])


@pytest.mark.parametrize("k", [0.0, 0.5])
def test_graded_tail_bracket_contains_the_closed_form(k):
    """The flat circle's zero-range sequence (``study_graded_shape_ratio.py --zero-range``:
    l_c / a = 0.08 ... 0.01, forces over Eq. 39): the limits the finest step allows for the
    body's tail rates (:func:`tail_rates`) contain the exact 1, and the estimate covers the
    extrapolation's error."""
    h, F = _circle_sequence(k)
    lo, hi = sorted(zr.tail_bracket(h, F, zr.tail_rates(k)))
    assert lo <= 1.0 <= hi
    F0, _, est = zr.richardson(h, F, None, zr.tail_rates(k))
    assert abs(F0 - 1.0) <= est


def test_the_homogeneous_tail_rates_on_a_graded_body_are_caught():
    """Mutant: at k = 0.5 the shortfall goes like l_c^0.25 ... (steps shrink by 2^0.25 ... 2^0.34
    per halving), and the homogeneous bracket (0.5 ... 1.5) ends below the exact value."""
    h, F = _circle_sequence(0.5)
    assert max(zr.tail_bracket(h, F, zr.RATE_BRACKET)) < 1.0


def test_zero_range_on_a_graded_body_uses_its_tail_rates():
    """``bem_energy.zero_range`` on a graded circle (coarse ranges, seconds): its force bar's
    interval is the graded tail bracket of its own sequence, not the homogeneous one, and its
    messages say how far that bracket is checked."""
    scene = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.PowerLawGraded(1.0, 1.0, 0.5), cs.Adhesion(1.0))
    res = be.zero_range(scene, be.ZeroRangeSettings(ratios=(0.32, 0.16, 0.08)))
    assert res.converged
    seq = res.info["zero_range"]
    h, F = np.array(seq["process_zone_ratios"]), np.array(seq["pulloff_forces"])
    graded = sorted(zr.tail_bracket(h, F, zr.tail_rates(0.5)))
    homogeneous = sorted(zr.tail_bracket(h, F))
    assert graded != pytest.approx(homogeneous, rel=1e-3)
    assert res.error_bars["pulloff_force"].interval == pytest.approx(tuple(graded), rel=1e-12)
    assert any("graded body (k = 0.5)" in m for m in res.messages)
