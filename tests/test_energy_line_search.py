"""The projected CG's line search judges a step by the energy change summed from the cells'
changes (``bem_energy.minimisers.step_energy_change``), not by the difference of two totals.

Each total is a sum over the padded grid whose elastic and adhesive parts are several times the
energy and of opposite sign; on a graded circle at 800 elements per radius (3200^2 padded) its
round-off is about 1e-11 of the energy, above the decrease of a step near the minimum, so a
line search comparing totals lets round-off decide which steps pass and the minimisation
stagnates with its projected gradient above the tolerance.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import bem_energy.minimisers as mins
import contact_scene as cs
from bem_energy.potentials import Potential, range_for_process_zone
from bem_energy.problem import EnergyProblem, build_problem

W = 0.02
D = -0.1  # a pulling approach where the circle at l_c = 0.08 a peels (cells leave the wall)


@pytest.fixture(scope="module")
def attached():
    rho = range_for_process_zone(modulus=1.0, work=W, length=0.08)
    scene = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(W, rho))
    prob = build_problem(scene, 1 / 24, Potential(W, rho))
    return prob, mins.minimise(prob, np.zeros(prob.padded), 0.05, True, method="pk")


@pytest.fixture(scope="module")
def pulled(attached):
    """The equilibrium at D, with most face cells held at the wall."""
    prob, m = attached
    return prob, mins.minimise(prob, m.U, D, True, method="pk")


def _exact_change(prob, U, P, Un, d):
    """Pi(Un) - Pi(U) summed exactly (math.fsum) in the form dU.C^-1 U + 1/2 dU.C^-1 dU + the
    cells' phi changes, dU = Un - U: exact to the round-off of the step itself (the difference
    of two exactly summed totals is rounded to 1e-16 of the energy)."""
    dU = Un - U
    dP = prob.pressure(dU)
    phi = prob.potential.evaluate(prob.gap(U, d))[0]
    phi_n = prob.potential.evaluate(prob.gap(Un, d))[0]
    elastic = math.fsum((dU * P).ravel()) + 0.5 * math.fsum((dU * dP).ravel())
    return prob.cell * (elastic + math.fsum(phi_n - phi))


@pytest.mark.parametrize("projected", [False, True])
@pytest.mark.parametrize("alpha", [1e-2, 1e-4, 1e-6])
def test_step_energy_change_is_the_exact_change(pulled, alpha, projected):
    """From the equilibrium at D, along the preconditioned gradient (with cells at the wall
    pushed into it: the step projects them back), the line search's change agrees with the
    exactly summed change within its round-off budget (below) and 1e-8 of itself.  (On a grid
    this small the totals' own round-off is within that budget too: the test below, with the
    totals' round-off of a large grid injected, is the one that tells the two rules apart.)"""
    prob, m = pulled
    corner = (slice(0, prob.n[0]), slice(0, prob.n[1]))
    wall = D - prob.height
    U = m.U.copy()
    U[corner][prob.face_block] = np.maximum(prob.on_face(U), wall)
    _, G, P, _, phi = prob.energy_terms(U, D, True)
    direction = -prob.displacement(G)
    at_wall = prob.on_face(U) <= wall
    assert at_wall.sum() > 100
    if projected:  # push every seventh cell at the wall into it: the step projects them back
        push = np.zeros(prob.face_block.sum())
        push[np.flatnonzero(at_wall)[::7]] = -np.abs(direction).max()
        face = np.zeros(prob.face_block.shape)
        face[prob.face_block] = push
        direction[corner] += face
    else:  # cells at the wall stay there, as the minimiser's fixed cells
        face = np.zeros(prob.face_block.shape, bool)
        face[prob.face_block] = at_wall
        direction[corner][face] = 0.0
    direction_pressure = prob.pressure(direction)
    Un = U + alpha * direction
    Un_face = prob.on_face(Un)
    clipped = None
    if projected:
        clipped = np.maximum(Un_face, wall)
        Un[corner][prob.face_block] = clipped
        clipped -= Un_face
        assert np.count_nonzero(clipped) > 0
        Pn = None
    else:
        assert (Un_face >= wall).all()
        Pn = P + alpha * direction_pressure
    _, _, Pn, _, phi_n = prob.energy_terms(Un, D, True, Pn)
    change = mins.step_energy_change(
        prob,
        alpha,
        direction,
        float(np.vdot(direction, P)),
        float(np.vdot(direction, direction_pressure)),
        P,
        Pn,
        clipped,
        phi,
        phi_n,
    )
    exact = _exact_change(prob, U, P, Un, D)
    # the change's round-off budget: alpha direction stands for the stored Un - U, which is
    # rounded to eps |Un| per cell; a recomputed Pn (projected step) carries the transform's
    # round-off, eps log2(cells) max|P| per cell; both weighted by the pressures they meet
    eps = np.finfo(float).eps
    cells = prob.face.size
    budget = eps * float(np.sum(np.abs(Un) * (np.abs(P) + np.abs(Pn))))
    if projected:
        budget += eps * math.log2(cells) * float(np.abs(P).max()) * float(np.abs(Un - U).sum())
    budget *= prob.cell
    assert abs(change - exact) <= budget + 1e-8 * abs(exact)


@pytest.mark.parametrize("single_precision", [False, True])
def test_round_off_in_the_total_energy_does_not_reach_the_line_search(monkeypatch, attached, single_precision):
    """A pulling step of the circle at l_c = 0.08 a takes the same iterates, bit for bit, when
    every total energy carries a random error of 1e-10 of itself (ten times the round-off
    measured on the 3200^2 grid): no decision reads the totals but for a scale.  A line search
    on En - E stops there with "line search failed"."""
    prob, m = attached
    clean = mins.minimise(prob, m.U, D, True, method="pk", gtol=1e-8, single_precision_directions=single_precision)
    assert clean.converged
    state = EnergyProblem.energy_state
    rng = np.random.default_rng(0)
    calls = []

    def with_round_off(self, *args, **kwargs):
        exact = state(self, *args, **kwargs)
        calls.append(1)
        return exact._replace(energy=exact.energy + 1e-10 * abs(exact.energy) * rng.uniform(-1.0, 1.0))

    monkeypatch.setattr(EnergyProblem, "energy_state", with_round_off)
    noisy = mins.minimise(
        prob, m.U, D, True, method="pk", gtol=1e-8, max_iterations=2000, single_precision_directions=single_precision
    )
    assert noisy.converged, noisy.message
    assert calls  # the totals the minimiser summed its steps' changes onto carried the error
    assert noisy.iterations == clean.iterations
    assert np.array_equal(noisy.U, clean.U)


@pytest.mark.parametrize("single_precision", [False, True])
@pytest.mark.parametrize(
    "shape, material",
    [(cs.Triangle.equilateral(1.0), cs.Homogeneous(1.0, 0.0)), (cs.Circle(1.0), cs.PowerLawGraded(1.0, 1.0, 0.5))],
    ids=["triangle", "graded circle"],
)
def test_steps_below_the_energy_resolution_still_converge(shape, material, single_precision):
    """A far pull (d = -0.25) converged to gtol = 1e-13: the last steps' energy changes fall
    below what the totals resolve (1e-12 of E), where the line search accepts a step that
    flattens the slope along the direction, judged at the trial state (the direction's load
    plus alpha times its curvature, and the trial's adhesive stress).  Judged at the current
    state instead, or with its stress, the step never qualifies and the minimisation ends in
    "line search failed" short of the tolerance."""
    w = 0.02
    rho = range_for_process_zone(modulus=1.0, work=w, length=0.08)
    sc = cs.Scene(cs.Indenter(shape), material, cs.Adhesion(w, rho))
    prob = build_problem(sc, 1.0 / 16, Potential(w, rho))
    options = dict(method="pk", single_precision_directions=single_precision)
    pressed = mins.minimise(prob, np.zeros(prob.padded), 0.05, True, **options)
    pulled = mins.minimise(prob, pressed.U, -0.25, True, gtol=1e-13, max_iterations=3000, **options)
    assert pulled.converged, pulled.message
    assert pulled.gradient <= 1e-13


@pytest.mark.parametrize("single_precision", [False, True])
def test_an_unfinished_minimisation_says_so(monkeypatch, attached, single_precision):
    """A minimisation that stops short of gtol returns the state it reached, finite, marked not
    converged with the reason: at the iteration cap, or when no step along a direction
    lowers the energy (here every trial's energy change is made infinite)."""
    prob, m = attached
    options = dict(method="pk", gtol=1e-10, single_precision_directions=single_precision)
    capped = mins.minimise(prob, m.U, D, True, max_iterations=2, **options)
    assert capped.message == "iteration limit" and not capped.converged
    assert capped.iterations == 2 and capped.gradient > 1e-10
    assert np.isfinite(capped.energy) and np.all(np.isfinite(capped.U)) and np.all(np.isfinite(capped.P))
    # the first iterate at D, where the line search then fails: the state it stopped at is
    # the start projected onto the wall, with its exact pressure
    monkeypatch.setattr(mins, "step_energy_change", lambda *args: math.inf)
    failed = mins.minimise(prob, m.U, D, True, **options)
    assert failed.message == "line search failed" and not failed.converged and failed.iterations == 1
    start = m.U.copy()
    start[prob.face] = np.maximum(start[prob.face], D - prob.height)
    assert np.array_equal(failed.U, start)
    assert np.array_equal(failed.P, prob.pressure(start))


def test_an_unknown_minimiser_is_named(attached):
    prob, m = attached
    with pytest.raises(ValueError, match="'newton'"):
        mins.minimise(prob, m.U, D, True, method="newton")
