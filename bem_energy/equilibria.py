"""The equilibria of one pull-off: counted minimisations and what a state is (in contact,
attached).

Every minimisation of a pull-off goes through :class:`Equilibria`, so that the work done
(minimisations, iterations, energy evaluations) and the ones that stopped short are counted in
one place, and the definitions of contact and attachment are the same for the loading path,
the snap-off search and the result.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from contact_scene import SolverStats

from .minimisers import Minimum, minimise
from .problem import EnergyProblem
from .settings import EnergySettings

__all__ = ["Equilibria", "WorkCount"]

#: how many unconverged minimisations are described one by one in the messages
NOTED_FAILURES = 5


@dataclass
class WorkCount:
    """What the minimisations of a pull-off cost, and which of them stopped short."""

    minimisations: int = 0
    iterations: int = 0
    evaluations: int = 0
    unconverged: int = 0
    worst_gradient: float = 0.0
    failures: list[str] = field(default_factory=list)

    def add(self, m: Minimum, d: float):
        self.minimisations += 1
        self.iterations += m.iterations
        self.evaluations += m.evaluations
        self.worst_gradient = max(self.worst_gradient, m.gradient)
        if not m.converged:
            self.unconverged += 1
            if len(self.failures) < NOTED_FAILURES:
                self.failures.append(f"minimisation at d = {d:.6g} did not converge "
                                     f"(projected gradient {m.gradient:.3g}; {m.message})")

    def messages(self) -> list[str]:
        out = list(self.failures)
        if self.unconverged > len(self.failures):
            out.append(f"{self.unconverged} minimisations did not converge in all")
        return out

    def solver_stats(self, *, events: int, unknowns: int) -> SolverStats:
        return SolverStats(linear_solves=self.minimisations, linear_iterations=self.iterations,
                           operator_applications=self.evaluations, events=events,
                           unconverged=self.unconverged, unknowns=unknowns)


class Equilibria:
    """Minimisations of one problem with one settings object, counted in :attr:`work`.

    ``adhesive`` says whether the potential is on (the press runs without it)."""

    def __init__(self, prob: EnergyProblem, settings: EnergySettings):
        self.prob = prob
        self.settings = settings
        self.work = WorkCount()

    def minimum(self, U0: np.ndarray, d: float, adhesive: bool) -> Minimum:
        """The equilibrium at approach ``d`` reached from the warm start ``U0``."""
        s = self.settings
        m = minimise(self.prob, U0, d, adhesive, method=s.minimiser, gtol=s.gtol,
                     max_iterations=s.max_iterations, memory=s.memory)
        self.work.add(m, d)
        return m

    def force(self, m: Minimum) -> float:
        return self.prob.force(m.P)

    def contact(self, m: Minimum, d: float) -> np.ndarray:
        """Face cells at the wall, on the padded grid (within round-off of the length scale:
        the range with adhesion, else the approach or one element)."""
        prob = self.prob
        length = prob.potential.range if prob.potential is not None else max(abs(d), prob.spacing)
        at_wall = np.zeros(prob.padded, bool)
        at_wall[prob.face] = prob.gap(m.U, d) <= 1e-9 * length
        return at_wall

    def contact_area(self, m: Minimum, d: float) -> float:
        return float(self.contact(m, d).sum()) * self.prob.cell

    def attached(self, m: Minimum, d: float, adhesive: bool) -> bool:
        """Some face cell within the range of the potential, or (without adhesion) at the wall."""
        prob = self.prob
        if adhesive and prob.potential is not None:
            return bool(prob.gap(m.U, d).min() < prob.potential.range)
        return bool(self.contact(m, d).any())
