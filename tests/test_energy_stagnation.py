"""A zero-range sequence's minimisation whose single-precision direction pressures stall.

The sequences compute each search direction's pressure in single precision
(``EnergySettings.single_precision_directions``) and judge convergence on the double-precision
gradient.  On the square turned by 45 degrees at l_c = 0.08 a the line search of one pulling
step stalled at the directions' own round-off with the double-precision gradient at 1.2 gtol,
and the range was reported as not converged.  The minimiser now continues such a stall in
double precision; the range converges to the force of an all-double-precision run within the
minimisers' tolerance (the force agrees to 1e-6 relative at gtol = 1e-6, as in
tests/test_bem_energy.py).  That range no longer stalls on the present path, so a stall is
also forced on a small pull.
"""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

import contact_scene as cs
from bem_energy.potentials import Potential, process_zone_modulus, range_for_process_zone
from bem_energy.settings import ZeroRangeSettings
from bem_energy.solver import pull_off
from crossval.suite import scene as builtin_scene


def _square_45_range(single_precision: bool):
    sq = builtin_scene("square")
    shape = cs.Transformed(sq.indenter.shape, rotation_deg=45.0)
    scene = replace(sq, indenter=replace(sq.indenter, shape=shape))
    zs = ZeroRangeSettings()
    a = scene.indenter.shape.equivalent_radius
    lc = 0.08 * a
    w = scene.adhesion.work_of_adhesion
    rho = range_for_process_zone(modulus=process_zone_modulus(scene.material), work=w, length=lc)
    spacing = min(lc / zs.elements_per_process_zone, a / zs.minimum_elements_per_radius)
    settings = replace(zs.energy, grid=cs.Grid(spacing=spacing), single_precision_directions=single_precision)
    return pull_off(scene, settings, spacing=spacing, potential=Potential(w, rho, zs.potential))


def test_single_precision_directions_give_the_double_precision_force():
    """The range that once stalled (see the module's docstring) converges in either precision
    to the same force within the minimisers' tolerance.  Later changes of the path took that
    stall away; the next test forces one."""
    res = _square_45_range(single_precision=True)
    assert res.converged, res.messages
    ref = _square_45_range(single_precision=False)
    assert ref.converged, ref.messages
    assert res.pulloff_force == pytest.approx(ref.pulloff_force, rel=1e-6)


def test_a_single_precision_stall_continues_in_double_precision(monkeypatch):
    """A line search that finds its decrease only after 40 halvings (forced here on the first
    step: the first 41 energy changes it sees are infinite) is a stall.  In single precision
    the minimisation goes on from that step with double-precision directions, once, and
    converges to the all-double-precision minimum (forces within the tolerance's reach, as in
    the test above); a double-precision minimisation would stop there, unconverged."""
    import numpy as np

    import bem_energy.minimisers as mins
    from bem_energy.problem import build_problem

    w = 0.02
    rho = range_for_process_zone(modulus=1.0, work=w, length=0.08)
    scene = cs.Scene(cs.Indenter(cs.Triangle.equilateral(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(w, rho))
    prob = build_problem(scene, 1 / 16, Potential(w, rho))
    pressed = mins.minimise(prob, np.zeros(prob.padded), 0.05, True, method="pk")
    reference = mins.minimise(prob, pressed.U, -0.1, True, method="pk", gtol=1e-10)
    assert reference.converged

    precisions = []
    make_arrays = mins._DirectionArrays.__init__

    def recorded(self, shape, double):
        precisions.append("double" if double else "single")
        make_arrays(self, shape, double)

    monkeypatch.setattr(mins._DirectionArrays, "__init__", recorded)
    change = mins.step_energy_change
    calls = []

    def stalling(*args):
        calls.append(1)
        return math.inf if len(calls) <= 41 else change(*args)

    monkeypatch.setattr(mins, "step_energy_change", stalling)
    m = mins.minimise(prob, pressed.U, -0.1, True, method="pk", gtol=1e-10, single_precision_directions=True)
    assert m.converged, m.message
    assert precisions == ["single", "double"]
    assert prob.force(m.P) == pytest.approx(prob.force(reference.P), rel=1e-6)
    calls.clear()
    precisions.clear()
    stopped = mins.minimise(prob, pressed.U, -0.1, True, method="pk", gtol=1e-10)
    assert stopped.message == "stagnated at round-off in the energy" and not stopped.converged
    assert stopped.iterations == 1 and precisions == ["double"]


def _pulling_step(monkeypatch, flat_steps, flat_energy, single_precision):
    """One pulling step of the circle at l_c = 0.08 a (a peeling edge: several CG iterations)
    with the stagnation window's constants replaced."""
    import numpy as np

    import bem_energy.minimisers as mins
    from bem_energy.problem import build_problem

    monkeypatch.setattr(mins, "FLAT_STEPS", flat_steps)
    monkeypatch.setattr(mins, "FLAT_ENERGY", flat_energy)
    w = 0.02
    rho = range_for_process_zone(modulus=1.0, work=w, length=0.08)
    scene = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(w, rho))
    prob = build_problem(scene, 1 / 24, Potential(w, rho))
    attached = mins.minimise(prob, np.zeros(prob.padded), 0.05, True, method="pk")
    return mins.minimise(
        prob, attached.U, -0.3, True, method="pk", max_iterations=200, single_precision_directions=single_precision
    )


def test_a_stall_in_double_precision_ends_the_minimisation(monkeypatch):
    """With a window that calls every step a stall, a single-precision minimisation goes on in
    double precision after the first and stops, reporting the stagnation and not converged,
    at the second (a mode that is not recognised as double precision continues every stall,
    up to the iteration cap); a double-precision one stops at the first.  With the default
    window the same step converges."""
    for single, most in ((True, 2), (False, 1)):
        m = _pulling_step(monkeypatch, 1, math.inf, single)
        assert m.message.startswith("stagnated: the energy fell by less than") and m.iterations <= most
        assert not m.converged
    m = _pulling_step(monkeypatch, 20, 1e-10, True)
    assert m.converged and m.iterations > 2
