"""A zero-range sequence's minimisation whose single-precision direction pressures stall.

The sequences compute each search direction's pressure in single precision
(``EnergySettings.single_precision_directions``) and judge convergence on the double-precision
gradient.  On the square turned by 45 degrees at l_c = 0.08 a the line search of one pulling
step stalled at the directions' own round-off with the double-precision gradient at 1.2 gtol,
and the range was reported as not converged.  The minimiser now continues such a stall in
double precision; the range converges to the force of an all-double-precision run within the
minimisers' tolerance (the force agrees to 1e-6 relative at gtol = 1e-6, as in
tests/test_bem_energy.py).
"""

from __future__ import annotations

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


def test_single_precision_stall_continues_in_double_precision():
    res = _square_45_range(single_precision=True)
    assert res.converged, res.messages
    ref = _square_45_range(single_precision=False)
    assert ref.converged, ref.messages
    assert res.pulloff_force == pytest.approx(ref.pulloff_force, rel=1e-6)
