"""The shared result type refuses what no solver may return: a NaN or infinite number (a
solver that does not converge says so in ``converged`` and ``messages``, never with a silent
NaN), a face area that is not positive, and malformed error bars or statistics."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import contact_scene as cs


def _result(**changes):
    base = dict(
        method="bem_test",
        pulloff_force=1.0,
        pulloff_approach=-0.5,
        stiffness=2.0,
        converged=True,
        grid_spacing=0.1,
        curve=cs.Curve(np.array([0.0, -0.5]), np.array([0.0, -1.0]), np.array([3.1, 3.0])),
        face_area=3.1,
    )
    base.update(changes)
    return cs.Result(**base)


def test_a_well_formed_result_is_accepted():
    r = _result(error_bars={"pulloff_force": cs.ErrorBar(0.01, "a study", interval=(0.98, 1.01))})
    assert r.converged and r.curve is not None


@pytest.mark.parametrize("name", ["pulloff_force", "pulloff_approach", "stiffness", "grid_spacing", "residual"])
@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf])
def test_a_number_that_is_not_finite_is_a_solver_bug(name, value):
    with pytest.raises(FloatingPointError, match=f"bem_test: {name} is not finite"):
        _result(**{name: value})


@pytest.mark.parametrize("column", ["approach", "force", "contact_area"])
def test_a_curve_with_nan_or_inf_is_a_solver_bug(column):
    curve = _result().curve
    assert curve is not None
    for bad in (math.nan, math.inf):
        values = getattr(curve, column).copy()
        values[-1] = bad
        with pytest.raises(FloatingPointError, match="the curve contains NaN or inf"):
            _result(curve=dataclasses.replace(curve, **{column: values}))


@pytest.mark.parametrize("area", [0.0, -1.0, math.nan])
def test_a_face_area_must_be_positive(area):
    with pytest.raises(FloatingPointError, match="face_area is not a positive number"):
        _result(face_area=area)


@pytest.mark.parametrize(
    "build, message",
    [
        (lambda: cs.ErrorBar(-0.01, "s"), "ErrorBar.relative"),
        (lambda: cs.ErrorBar(math.nan, "s"), "ErrorBar.relative"),
        (lambda: cs.ErrorBar(0.01, "s", role="guess"), "ErrorBar.role"),
        (lambda: cs.ErrorBar(0.01, "s", interval=(1.0, 0.9)), "ErrorBar.interval"),
        (lambda: cs.ErrorBar(0.01, "s", interval=(0.9, math.inf)), "ErrorBar.interval"),
        (lambda: _result(discretisation="voxels"), "discretisation"),
        (lambda: _result(error_bars={"adhesion": cs.ErrorBar(0.01, "s")}), "Result.error_bars"),
        (lambda: _result(error_bars={"pulloff_force": 0.01}), "Result.error_bars"),
        (lambda: cs.SolverStats(linear_solves=-1), "SolverStats.linear_solves"),
        (lambda: cs.SolverStats(events=1.5), "SolverStats.events"),
        (lambda: cs.SolverStats(unknowns=True), "SolverStats.unknowns"),
    ],
)
def test_malformed_bars_and_statistics_are_refused(build, message):
    with pytest.raises(ValueError, match=message):
        build()
