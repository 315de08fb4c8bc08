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


def _snapshot(approach, fields):
    contact = np.zeros((5, 4), bool)
    contact[1:4, 1:3] = True
    contact[0, 0] = True  # a run at the very start, to exercise the leading empty run
    p = np.where(contact, 1.0, 0.0) if fields else None
    u = np.full(contact.shape, approach) if fields else None
    return cs.Snapshot(approach, -2.0, contact, 0.5, (-1.0, -0.75), p, u)


def test_to_json_carries_the_snapshots_and_says_what_it_leaves_out():
    """``crossval solve --json`` once dropped snapshots and last_stable whole, while the
    docstring promised every field: each snapshot's scalars and contact map are in, and the
    fields it holds are named under ``left_out`` with where to read them."""
    import json

    from crossval.jsonio import dumps

    r = _result(snapshots=(_snapshot(-0.25, True), _snapshot(-0.5, True)), last_stable=_snapshot(-0.75, False))
    out = json.loads(dumps(r.to_json()))
    for s, got in zip((*r.snapshots, r.last_stable), (*out["snapshots"], out["last_stable"]), strict=True):
        assert got["approach"] == s.approach and got["force"] == s.force
        assert got["contact_area"] == pytest.approx(s.contact_area) == 7 * 0.25
        assert got["spacing"] == 0.5 and got["origin"] == [-1.0, -0.75]
        assert np.array_equal(cs.Snapshot.decode_contact(got["contact"]), s.contact)
        assert got["contact"]["elements"] == 7 and got["contact"]["runs"][0] == 0
    assert out["snapshots"][0]["fields"]["left_out"] == ["pressure", "displacement"]
    assert out["last_stable"]["fields"] is None
    assert len(out["left_out"]) == 1 and "Result.snapshots[i].pressure" in out["left_out"][0]
    # nothing held, nothing left out
    bare = json.loads(dumps(_result().to_json()))
    assert bare["snapshots"] == [] and bare["last_stable"] is None and bare["left_out"] == []
    with pytest.raises(ValueError, match="the runs cover"):
        cs.Snapshot.decode_contact({"shape": [2, 2], "runs": [1, 2]})


def test_unrecorded_snapshots_are_named_with_their_reason():
    from contact_scene.result import unrecorded_snapshots

    kw = dict(start=0.0, highest=0.5, lowest=-2.0, end="where the punch detached", method="bem_test")
    assert unrecorded_snapshots((-1.0,), (-1.0,), **kw) is None
    msg = unrecorded_snapshots((1.0, -1.0, -3.0), (-1.0,), **kw)
    assert msg is not None and msg.startswith("bem_test recorded no snapshot at 2 of the approaches")
    assert "d = 1 lies above d = 0.5, the highest approach" in msg
    assert "d = -3 lies below d = -2, where the punch detached" in msg
    assert "d = -1 " not in msg
    msg = unrecorded_snapshots((1.0,), (), **{**kw, "highest": 0.0})
    assert msg is not None and "where the pull starts" in msg
