"""Mirror-symmetric pulls: a face that mirrors about its grid's middle row keeps every contact set
and every CG iterate mirrored, so the products take the half-size transforms
(``HalfSpaceOperator._mirrored``) without changing the pull beyond the CG tolerance."""

import numpy as np
import pytest

import bem_griffith as bg
import contact_scene as cs
import halfspace.operator as ho
from bem_griffith.windows import window_for


def scene(shape):
    return cs.Scene(cs.Indenter(shape), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))


@pytest.mark.parametrize(
    "shape, N",
    [(cs.Star(5, 1.0, 0.45), 40), (cs.Triangle.equilateral(2.0), 32), (cs.Rectangle(4.0, 1.0), 16)],
    ids=["star", "triangle", "rectangle"],
)
def test_a_mirrored_pull_is_the_pull_with_full_transforms(shape, N, monkeypatch, count_calls):
    """Star, triangle and 4:1 rectangle (each mirrors about the grid's middle row): the same
    events and contact areas along the curve as with the full transforms only, the forces and
    the detachment approach to the CG tolerance, the last stable set mirrored, and most
    products on the half transforms."""
    sc = scene(shape)
    st = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N))
    problem = bg.solver.build_problem(sc, st)
    assert np.array_equal(problem.face, problem.face[::-1])
    calls = count_calls(ho.HalfSpaceOperator, "_mirrored", "_pruned")
    a = bg.solve(sc, st)
    assert calls["_mirrored"] > 3 * calls["_pruned"]
    monkeypatch.setattr(ho.HalfSpaceOperator, "_mirror_ready", lambda self, grid: False)
    b = bg.solve(sc, st)
    assert a.converged and b.converged
    assert a.info["events"] == b.info["events"]
    assert np.array_equal(a.curve.contact_area, b.curve.contact_area)
    assert np.array_equal(a.last_stable.contact, b.last_stable.contact)
    assert np.array_equal(a.last_stable.contact, a.last_stable.contact[::-1])
    assert a.pulloff_force == pytest.approx(b.pulloff_force, rel=1e-8)
    assert a.detachment_approach == pytest.approx(b.detachment_approach, rel=1e-8)
    assert np.allclose(a.curve.force, b.curve.force, rtol=1e-8, atol=1e-8 * b.pulloff_force)


def test_a_mirrored_set_gets_a_window_centred_on_the_mirror():
    """A mirrored set whose window is narrower than the grid lies in a window centred on the
    grid's middle row (so it mirrors there too), one row shorter where the parities differ;
    a set off the mirror keeps a window starting at its first row."""
    sc = scene(cs.Rectangle(4.0, 1.0))
    problem = bg.solver.build_problem(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=16)))
    nx, ny = problem.face.shape
    checked = 0
    for half in range(2, nx // 4):
        contact = np.zeros((nx, ny), bool)
        contact[nx // 2 - half : nx - nx // 2 + half] = problem.face[nx // 2 - half : nx - nx // 2 + half]
        window = window_for(problem, contact)
        if window is None:
            continue
        checked += 1
        i0, i1 = window.rows.start, window.rows.stop
        assert i0 == nx - i1 and contact[:i0].sum() == 0 and contact[i1:].sum() == 0
        inside = contact[window.rows, window.cols]
        assert np.array_equal(inside, inside[::-1])
        shifted = np.roll(contact, 1, axis=0)
        other = window_for(problem, shifted)
        first_row = int(np.flatnonzero(shifted.any(axis=1))[0])
        assert other is not None and other.rows.start == min(first_row, nx - (other.rows.stop - other.rows.start))
    assert checked >= 3
