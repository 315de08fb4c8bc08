"""The work a Griffith solve does, counted as it goes and reported as ``SolverStats``."""

from __future__ import annotations

from dataclasses import dataclass

from contact_scene import SolverStats

__all__ = ["WorkCounters"]


@dataclass
class WorkCounters:
    """Mutable tallies shared by the contact-set solves, the press and the pull.

    operator_applications
        FFT convolutions: products C v inside CG, preconditioner applications (one FFT pair
        each) and the full-grid products that follow a windowed solve.
    cg_iterations
        Conjugate-gradient steps over all contact-set solves.
    contact_solves
        Contact-set solves (one or two CG runs each: the unit approach, and the profile when
        the face is curved).
    worst_residual
        The largest relative CG residual any contact-set solve ended with.
    unconverged_solves
        Contact-set solves whose CG stopped above its tolerance.
    unsettled_cascades
        Cascades that did not reach a stable contact set within their pass limit, or that came
        back to a contact set they had already left.
    cycled_cascades
        Of those, the cascades that came back to a set (the pull stops there: every later pass
        would repeat the cycle).
    detached_elements
        Face elements that left the contact set, summed over all cascades.
    cascades_cut
        Cascades ended early because the remaining area cannot hold (Eq. 14).
    windowed_solves
        Contact-set solves that ran on a smaller window of the grid.
    decided_solves
        Contact-set solves of a cascade's passing sets stopped once their error bound showed
        which elements leave next (``GriffithSettings.decide_early``); counted in
        ``contact_solves``, not in ``worst_residual``.
    """

    operator_applications: int = 0
    cg_iterations: int = 0
    contact_solves: int = 0
    worst_residual: float = 0.0
    unconverged_solves: int = 0
    unsettled_cascades: int = 0
    cycled_cascades: int = 0
    detached_elements: int = 0
    cascades_cut: int = 0
    windowed_solves: int = 0
    decided_solves: int = 0

    def record_solve(self, iterations: int, residual: float, converged: bool) -> None:
        """Account for one contact-set solve (its CG runs together)."""
        self.cg_iterations += iterations
        self.contact_solves += 1
        self.worst_residual = max(self.worst_residual, residual)
        if not converged:
            self.unconverged_solves += 1

    def record_decided(self, iterations: int) -> None:
        """Account for a solve stopped once it had decided the next pass of its cascade."""
        self.cg_iterations += iterations
        self.contact_solves += 1
        self.decided_solves += 1

    def stats(self, *, events: int, face_elements: int) -> SolverStats:
        """The method-neutral counters of a finished solve: an unsettled cascade counts as an
        unconverged sub-solve, like a CG run that stopped above its tolerance."""
        return SolverStats(
            linear_solves=self.contact_solves,
            linear_iterations=self.cg_iterations,
            operator_applications=self.operator_applications,
            events=events,
            unconverged=self.unconverged_solves + self.unsettled_cascades,
            unknowns=face_elements,
        )
