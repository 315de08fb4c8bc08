"""The finite-range pull-off against a peer: ContactMechanics with Adhesion's exponential potential.

With ``kernel="love"`` ours and the peer solve the same discrete problem (the same raster, Love's
uniformly loaded squares, a zero padding of at least 2n - 1 that makes both the exact
non-periodic half-space, phi = -w exp(-g / rho) under a hard wall): benchmarks/bench_energy_peer.py
sets the peer up and drives it along our loading path.  Their answers may then differ only by
what each minimisation leaves undone.  Both stop at the same scaled projected gradient, a
residual pressure of at most gtol rho / C_00 on every cell of the padded grid.  Taken as a load
left over on each cell, it moves the force on the punch by at most that pressure times the
padded grid's area A_pad, for each solver: the tolerance is twice A_pad gtol rho / C_00 (an
estimate rather than a bound; the agreement found is some thirty times tighter, at 16 elements
per radius).  A different discretisation (the collocated kernel, 0.05/N to 0.07/N in stiffness)
or a range 1 % wider misses it by more than ten times.

Skipped without the ``peers`` extra (ContactMechanics, Adhesion).
"""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("ContactMechanics")
pytest.importorskip("Adhesion")

import bem_energy as be  # noqa: E402
import contact_scene as cs  # noqa: E402
from bem_energy.problem import build_problem  # noqa: E402

BENCHMARKS = Path(__file__).resolve().parents[1] / "benchmarks"

#: 16 elements per radius, l_c = E* rho^2 / w = 2 elements: the grid the exponential potential
#: needs for a converged pull-off (bem_energy.potentials.PROCESS_ZONE_ELEMENTS), seconds for the peer
N = 16.0
WORK = 1.0 / (2.0 * math.pi)
RANGE = math.sqrt(2.0 / N * WORK)


def _bench():
    sys.path.insert(0, str(BENCHMARKS))  # for its _timing
    try:
        spec = importlib.util.spec_from_file_location("bench_energy_peer", BENCHMARKS / "bench_energy_peer.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = module  # its dataclass looks its module up there
        spec.loader.exec_module(module)
    finally:
        sys.path.remove(str(BENCHMARKS))
    return module


bench = _bench()


def _scene(rho=RANGE):
    return cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(WORK, rho))


def _settings(kernel="love"):
    return be.EnergySettings(grid=cs.Grid(elements_per_radius=N), kernel=kernel)


def _force_bound(prob, st):
    """Each solver's bound on the force error: A_pad gtol rho / C_00 (the module)."""
    padded_area = 4 * prob.n[0] * prob.n[1] * prob.cell
    return padded_area * st.gtol * prob.potential.range / prob.self_compliance


def _problem(scene, st):
    potential = be.Potential(scene.adhesion.work_of_adhesion, scene.adhesion.range)
    return build_problem(scene, st.grid.spacing_for(scene.indenter.shape), potential, kernel=st.kernel)


def test_one_equilibrium_agrees_with_the_peer():
    # a pulled, attached state from a cold start (the edge zone opens under the tension)
    scene, st = _scene(), _settings()
    prob = _problem(scene, st)
    peer = bench.PeerSystem(prob, gtol=st.gtol, memory=st.memory, max_iterations=st.max_iterations)
    d = -0.5 * bench.critical_approach_scale(scene)
    ours = be.minimise(prob, np.zeros(prob.padded), d, True, method="pk", gtol=st.gtol)
    theirs = peer.minimum(np.zeros(peer.shape), d)
    assert ours.converged and theirs.converged, theirs.message
    F_ours, F_peer = prob.force(ours.P), peer.force(theirs)
    assert F_ours < 0 and peer.gap(theirs, d).max() > 0  # tensile, with cells off the wall
    assert abs(F_ours - F_peer) <= 2 * _force_bound(prob, st), (F_ours, F_peer, _force_bound(prob, st))


def test_one_equilibrium_of_another_discretisation_disagrees():
    # the bound sees a different discrete problem: the collocated kernel on the same grid
    scene, st = _scene(), _settings()
    prob = _problem(scene, st)
    d = -0.5 * bench.critical_approach_scale(scene)
    peer = bench.PeerSystem(prob, gtol=st.gtol, memory=st.memory, max_iterations=st.max_iterations)
    F_peer = peer.force(peer.minimum(np.zeros(peer.shape), d))
    colloc = _problem(scene, _settings("collocation"))
    F_colloc = colloc.force(be.minimise(colloc, np.zeros(colloc.padded), d, True, method="pk").P)
    assert abs(F_colloc - F_peer) > 10 * 2 * _force_bound(prob, st)


def test_pulloff_force_agrees_with_the_peer():
    # the whole pull along the same loading path; near the force maximum the potential sets
    # the answer, so a range 1 % wider (F_A ~ sqrt(w rho) per unit of l_c) misses the bound
    scene, st = _scene(), _settings()
    ours = be.solve(scene, st)
    theirs = bench.peer_pull_off(scene, st)
    assert ours.converged and theirs.unconverged == 0
    bound = 2 * _force_bound(_problem(scene, st), st)
    assert abs(ours.pulloff_force - theirs.force) <= bound, (ours.pulloff_force, theirs, bound)
    wider = be.solve(_scene(1.01 * RANGE), st)
    assert abs(wider.pulloff_force - theirs.force) > 10 * bound, (wider.pulloff_force, theirs.force, bound)
