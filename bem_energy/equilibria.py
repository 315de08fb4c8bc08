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
    peeled: int = 0
    worst_gradient: float = 0.0
    failures: list[str] = field(default_factory=list)

    def add(self, m: Minimum, d: float):
        self.minimisations += 1
        self.iterations += m.iterations
        self.evaluations += m.evaluations
        if m.peeled:
            self.peeled += 1  # stopped on purpose: the state is known to be detaching
            return
        self.worst_gradient = max(self.worst_gradient, m.gradient)
        if not m.converged:
            self.unconverged += 1
            if len(self.failures) < NOTED_FAILURES:
                self.failures.append(
                    f"minimisation at d = {d:.6g} did not converge (projected gradient {m.gradient:.3g}; {m.message})"
                )

    def messages(self) -> list[str]:
        out = list(self.failures)
        if self.unconverged > len(self.failures):
            out.append(f"{self.unconverged} minimisations did not converge in all")
        return out

    def solver_stats(self, *, events: int, unknowns: int) -> SolverStats:
        return SolverStats(
            linear_solves=self.minimisations,
            linear_iterations=self.iterations,
            operator_applications=self.evaluations,
            events=events,
            unconverged=self.unconverged,
            unknowns=unknowns,
        )


#: the least fall of the contact (a fraction of its most) that marks a trial as peeling off
PEEL_FRACTION_MIN = 0.1

#: the fall of the contact, in units of l_c / a, that marks a trial as peeling off: an attached
#: step near the maximum opens an edge zone of width about l_c, i.e. loses about 2 l_c / a of
#: a circle's contact, five times less than this
PEEL_FRACTION_PER_PROCESS_ZONE = 10.0


class Equilibria:
    """Minimisations of one problem with one settings object, counted in :attr:`work`.

    ``adhesive`` says whether the potential is on (the press runs without it); ``face_radius``
    (sqrt(A/pi)) sets the scale against which the process zone is small."""

    def __init__(self, prob: EnergyProblem, settings: EnergySettings, face_radius: float):
        self.prob = prob
        self.settings = settings
        self.work = WorkCount()
        self.peel_fraction = None
        if settings.stop_peeling_trials and settings.minimiser == "pk" and prob.potential is not None:
            self.peel_fraction = max(
                PEEL_FRACTION_MIN, PEEL_FRACTION_PER_PROCESS_ZONE * prob.process_zone / face_radius
            )

    def minimum(self, U0: np.ndarray, d: float, adhesive: bool) -> Minimum:
        """The equilibrium at approach ``d`` reached from the warm start ``U0``."""
        s = self.settings
        m = minimise(
            self.prob,
            U0,
            d,
            adhesive,
            method=s.minimiser,
            gtol=s.gtol,
            max_iterations=s.max_iterations,
            memory=s.memory,
            restart_on_wall_change=s.restart_on_wall_change,
            single_precision_directions=s.single_precision_directions,
        )
        self.work.add(m, d)
        return m

    def pulling_trial(self, U0: np.ndarray, d: float, adhesive: bool) -> Minimum:
        """The equilibrium at ``d`` reached from an attached warm start while pulling, where
        the state may detach.  A detaching minimisation peels the face about one ring of
        cells per iteration after a long creep, so it is stopped once its contact has fallen
        below (1 - s) of its most, s = max(0.1, 10 l_c / a), and the detached state is
        converged from U = 0 instead (a cold start falls onto the detached branch).  Should
        that start end attached, the trial is re-run in full from ``U0``, so that the path is
        that of the full minimisation either way."""
        if self.peel_fraction is None or not adhesive:
            return self.minimum(U0, d, adhesive)
        s = self.settings
        m = minimise(
            self.prob,
            U0,
            d,
            adhesive,
            method=s.minimiser,
            gtol=s.gtol,
            max_iterations=s.max_iterations,
            memory=s.memory,
            peel_fraction=self.peel_fraction,
            restart_on_wall_change=s.restart_on_wall_change,
            single_precision_directions=s.single_precision_directions,
        )
        self.work.add(m, d)
        if not m.peeled:
            return m
        cold = self.minimum(np.zeros_like(U0), d, adhesive)
        if not self.attached(cold, d, adhesive):
            return cold
        return self.minimum(U0, d, adhesive)

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
