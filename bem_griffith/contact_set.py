"""The linear state on a fixed contact set.

With the contact set S fixed, the pressure on S is linear in the approach d:
p = d x1 - xh, where C_SS x1 = 1 (the pressure per unit approach) and C_SS xh = h (the
pressure that holds the profile h flat).  The displacement of the whole grid is then
u = d C x1 - C xh.  One solve of the two systems gives the state at every approach, until
an element detaches or a gap closes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .counters import WorkCounters
from .linear import CGResult, conjugate_gradient
from .problem import Problem
from .settings import GriffithSettings
from .windows import window_for

__all__ = ["ContactSolution", "solve_contact_set", "no_contact"]


@dataclass(frozen=True, eq=False)
class ContactSolution:
    """The solved contact set S, linear in the approach d.

    contact
        Boolean mask of S on the grid.
    pressure_per_approach
        x1 on S (row-major order of the mask): C_SS x1 = 1.
    profile_pressure
        xh on S: C_SS xh = h (zeros on a flat face).
    displacement_per_approach
        C x1 on the whole grid.
    profile_displacement
        C xh on the whole grid.
    iterations, residual, converged
        CG iterations of the solve, the larger relative residual of its runs, and whether both
        reached the tolerance.
    """

    contact: np.ndarray
    pressure_per_approach: np.ndarray
    profile_pressure: np.ndarray
    displacement_per_approach: np.ndarray
    profile_displacement: np.ndarray
    iterations: int
    residual: float
    converged: bool

    def pressure(self, approach: float) -> np.ndarray:
        """p = d x1 - xh on S (compressive > 0)."""
        return approach * self.pressure_per_approach - self.profile_pressure

    def displacement(self, approach: float) -> np.ndarray:
        """u = d C x1 - C xh on the whole grid."""
        return approach * self.displacement_per_approach - self.profile_displacement

    def force(self, approach: float, cell_area: float) -> float:
        """The normal force: the pressures summed over S times the element area."""
        return float(cell_area * (approach * self.pressure_per_approach.sum() - self.profile_pressure.sum()))

    def stiffness(self, cell_area: float) -> float:
        """dF/dd with S held fixed."""
        return float(cell_area * self.pressure_per_approach.sum())

    @property
    def attached(self) -> bool:
        return bool(self.contact.any())


def no_contact(problem: Problem) -> ContactSolution:
    """The detached state: no contact, no pressure, no displacement."""
    zero = np.zeros(problem.face.shape)
    return ContactSolution(np.zeros(problem.face.shape, bool), np.zeros(0), np.zeros(0), zero, zero, 0, 0.0, True)


def solve_contact_set(
    problem: Problem,
    contact: np.ndarray,
    settings: GriffithSettings,
    warm_start: ContactSolution | None,
    counters: WorkCounters,
) -> ContactSolution:
    """Solve C_SS x1 = 1 and (curved faces) C_SS xh = h on the contact set by preconditioned
    CG, warm-started from a neighbouring set's solution; on a smaller window of the grid when
    the set fits into one (``bem_griffith.windows``).  Never raises on non-convergence: the
    solution and the counters say so."""
    window = window_for(problem, contact)
    if window is None:
        operator, contact_in_window, inverse = problem.operator, contact, problem.inverse_symbol
    else:
        operator, inverse = window.operator, window.inverse_symbol
        counters.windowed_solves += 1
        # the set lies inside the window, so its row-major order there is its order on the grid
        contact_in_window = contact[window.rows, window.cols]

    def apply_operator(v):
        counters.operator_applications += 1
        return operator.apply_masked(v, contact_in_window)

    precondition = None
    if inverse is not None:

        def precondition(residual):
            counters.operator_applications += 1
            return operator.apply_symbol(residual, contact_in_window, inverse)

    def initial_guess(pressures_on_previous_set: np.ndarray | None) -> np.ndarray | None:
        if warm_start is None or not warm_start.contact.any():
            return None
        full = np.zeros(problem.face.shape)
        full[warm_start.contact] = pressures_on_previous_set
        return full[contact]

    def image_on_grid(cg: CGResult) -> np.ndarray:
        if window is None:
            assert cg.image is not None  # CG is restricted to the contact set, so it returns C x
            return cg.image
        # the gaps of the whole face need C x beyond the window: one operator application
        counters.operator_applications += 1
        return problem.operator.apply_masked(cg.x, contact)

    n = int(contact.sum())

    def solve(rhs: np.ndarray, x0: np.ndarray | None) -> CGResult:
        return conjugate_gradient(
            apply_operator,
            rhs,
            x0,
            rtol=settings.rtol,
            maxiter=settings.maxiter,
            precondition=precondition,
            restrict=contact_in_window,
        )

    unit = solve(np.ones(n), initial_guess(None if warm_start is None else warm_start.pressure_per_approach))
    iterations, residual, converged = unit.iterations, unit.residual, unit.converged
    if problem.flat:
        profile_pressure, profile_displacement = np.zeros(n), np.zeros(problem.face.shape)
    else:
        profile = solve(
            problem.height[contact], initial_guess(None if warm_start is None else warm_start.profile_pressure)
        )
        profile_pressure, profile_displacement = profile.x, image_on_grid(profile)
        iterations += profile.iterations
        residual = max(residual, profile.residual)
        converged = converged and profile.converged
    counters.record_solve(iterations, residual, converged)
    return ContactSolution(
        contact.copy(),
        unit.x,
        profile_pressure,
        image_on_grid(unit),
        profile_displacement,
        iterations,
        residual,
        converged,
    )
