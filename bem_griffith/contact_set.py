"""The linear state on a fixed contact set.

With the contact set S fixed, the pressure on S is linear in the approach d:
p = d x1 - xh, where C_SS x1 = 1 (the pressure per unit approach) and C_SS xh = h (the
pressure that holds the profile h flat).  The displacement of the whole grid is then
u = d C x1 - C xh.  One solve of the two systems gives the state at every approach, until
an element detaches or a gap closes.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from halfspace.operator import mirrors

from .counters import WorkCounters
from .linear import CGResult, conjugate_gradient
from .problem import SAMPLING_MARGIN, Problem
from .settings import GriffithSettings
from .windows import window_for

__all__ = ["ContactSolution", "Decision", "solve_contact_set", "no_contact"]

#: cells of a changed contact set around each cell that left or joined it, whose residual the
#: local warm start (``GriffithSettings.local_warm_start``) solves exactly before CG
LOCAL_REACH = 3
#: changes beyond which the local warm start is skipped (its dense solve would grow too large)
LOCAL_CHANGES = 16

#: ``decide(contact, x1, displacement, error, displacement_error)``: whether a caller has learnt
#: all it needs from an unfinished flat-face solve on ``contact`` with pressures per approach
#: ``x1`` (each within ``error`` of the exact ones); ``displacement()`` gives C x1 on the whole
#: grid (it may cost an operator application, so it is asked for only when the pressures have
#: decided), each value within ``displacement_error`` of the exact one at the free cells
Decision = Callable[[np.ndarray, np.ndarray, Callable[[], np.ndarray], float, float], bool]


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
        C x1 on the whole grid (on the solve's window only where ``displacement_in_window``).
    profile_displacement
        C xh on the whole grid.
    iterations, residual, converged
        CG iterations of the solve, the larger relative residual of its runs, and whether both
        reached the tolerance.
    displacement_in_window
        True when ``displacement_per_approach`` holds C x1 only inside the window the set was
        solved on (zeros beyond it): a windowed solve stopped early by a decision that needed no
        gaps, because every free gap is known to be open while pulling under the walk property
        (``bem_griffith.driver.early_decision``) or the face has no free cell.  Such a state only
        passes on to the next set of its cascade, whose cells lie in the window; a cascade never
        returns one (``gap_coefficients`` refuses it).
    at_approach
        The approach d at which a curved face's passing set was decided (None otherwise):
        ``pressure_per_approach`` then holds p / d and the profile parts are zero, so that
        :meth:`pressure`, :meth:`displacement` and the gaps are exact at d only.  Such a state
        only passes on to the next set of its cascade at d; a cascade never returns one.
    """

    contact: np.ndarray
    pressure_per_approach: np.ndarray
    profile_pressure: np.ndarray
    displacement_per_approach: np.ndarray
    profile_displacement: np.ndarray
    iterations: int
    residual: float
    converged: bool
    displacement_in_window: bool = False
    at_approach: float | None = None

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
    decide: Decision | None = None,
    approach: float | None = None,
) -> ContactSolution:
    """Solve C_SS x1 = 1 and (curved faces) C_SS xh = h on the contact set by preconditioned
    CG, warm-started from a neighbouring set's solution; on a smaller window of the grid when
    the set fits into one (``bem_griffith.windows``).  Never raises on non-convergence: the
    solution and the counters say so.

    With ``decide`` (flat faces, with the problem's eigenvalue floor), CG stops as soon as
    ``decide`` accepts an iterate, given bounds on its pressures' and displacements' errors: from
    the energy norm of the error (``Problem.inverse_diagonal``, ``Problem.self_influence``) with
    the Fourier preconditioner, else ||r||_2 / eigenvalue_floor (``Problem.eigenvalue_floor``,
    ``Problem.kernel_norm``).  The solution is then exact only to those bounds, and counted as
    decided, not as converged to rtol.

    On a curved face ``decide`` needs the cascade's ``approach`` d: the pressure there,
    p = d x1 - xh, is one solve, C_SS y = 1 - h / d with p = d y, and ``decide`` reads y as it
    reads x1 on a flat face.  A decided set is returned as y with no profile part, exact at
    d only, which is all a passing set of a cascade at d is used for; otherwise x1 and xh are
    solved as without ``decide``, xh warm-started from d (x1 - y).  x1 and xh never start from
    such a decided state (its y grows like h / |d|, and CG started from it stops on a recursive
    residual whose round-off, near d = 0, far exceeds rtol)."""
    window = window_for(problem, contact)
    if window is None:
        operator, contact_in_window, preconditioner = problem.operator, contact, problem.preconditioner
    else:
        operator, preconditioner = window.operator, window.preconditioner
        counters.windowed_solves += 1
        # the set lies inside the window, so its row-major order there is its order on the grid
        contact_in_window = contact[window.rows, window.cols]

    def apply_operator(v):
        counters.operator_applications += 1
        return operator.apply_masked(v, contact_in_window)

    precondition = None
    if preconditioner is not None:

        def precondition(residual):
            counters.operator_applications += 1
            return preconditioner.apply(residual, contact_in_window)

    def initial_guess(
        pressures_on_previous_set: np.ndarray | None, image_of_previous: np.ndarray, rhs_on_grid: np.ndarray | float
    ) -> np.ndarray | None:
        if warm_start is None or not warm_start.contact.any():
            return None
        full = np.zeros(problem.face.shape)
        full[warm_start.contact] = pressures_on_previous_set
        if settings.local_warm_start:
            local_correction(full, warm_start.contact, image_of_previous, rhs_on_grid)
        if mirrors(contact) and mirrors(warm_start.contact) and mirrors(problem.face) and mirrors(problem.height):
            # on a face and profile that mirror about the grid's middle row, a mirrored start on
            # a mirrored set keeps every CG iterate mirrored, and each product then takes the
            # half-size transforms (``HalfSpaceOperator``); the dense solve of the local
            # correction leaves round-off asymmetry, averaged out here
            full = 0.5 * (full + full[::-1])
        return full[contact]

    def local_correction(
        full: np.ndarray, previous: np.ndarray, image_of_previous: np.ndarray, rhs_on_grid: np.ndarray | float
    ) -> None:
        # the previous pressures on the new set leave a residual concentrated around the cells
        # that left (their pressure is missing) or joined; solving it exactly on the cells
        # within LOCAL_REACH of them removes most of it before CG starts
        changed = np.argwhere(previous != contact)
        if len(changed) == 0 or len(changed) > LOCAL_CHANGES:
            return
        near = np.zeros(contact.shape, bool)
        for i, j in changed:
            near[max(i - LOCAL_REACH, 0) : i + LOCAL_REACH + 1, max(j - LOCAL_REACH, 0) : j + LOCAL_REACH + 1] = True
        near &= contact
        left = previous & ~contact
        if not near.any():
            return
        kernel = problem.operator.kernel
        Mx, My = kernel.shape
        Pi, Pj = np.nonzero(near)
        Ri, Rj = np.nonzero(left)
        # residual on the patch: b - C (previous pressures on the new set) = b - u_prev + C_PR x_R
        rhs = rhs_on_grid[near] if isinstance(rhs_on_grid, np.ndarray) else np.full(len(Pi), rhs_on_grid)
        residual = rhs - image_of_previous[near] + kernel[(Pi[:, None] - Ri) % Mx, (Pj[:, None] - Rj) % My] @ full[left]
        full[near] += np.linalg.solve(kernel[(Pi[:, None] - Pi) % Mx, (Pj[:, None] - Pj) % My], residual)

    def image_on_grid(cg: CGResult) -> np.ndarray:
        if window is None:
            assert cg.image is not None  # CG is restricted to the contact set, so it returns C x
            return cg.image
        # the gaps of the whole face need C x beyond the window: one operator application
        counters.operator_applications += 1
        return problem.operator.apply_masked(cg.x, contact)

    n = int(contact.sum())

    early_stop = None
    decided_image: list[np.ndarray] = []
    floor = problem.eigenvalue_floor
    # a curved face's passing sets are decided on their pressure at the cascade's approach
    combined = decide is not None and not problem.flat and approach is not None and approach != 0.0
    # the largest right-hand side entry (1 on a flat face, 1 - h / d on a curved one): the
    # recursive residual's drift from b - A x, never trusted below, grows with it
    rhs_size, rhs_on_grid = 1.0, None
    if combined:
        assert approach is not None
        rhs_on_grid = 1.0 - problem.height / approach
        rhs_size = max(1.0, float(np.abs(rhs_on_grid[contact]).max()))
    if decide is not None and (problem.flat or combined) and floor is not None:
        tried_displacements = False
        # with the lattice's inverse symbol on the padded grid as the preconditioner, r.M r bounds
        # the energy norm of the error (below), a bound markedly tighter than ||r||_2 / floor
        inverse_diagonal = problem.inverse_diagonal
        energy_bounds = preconditioner is not None and preconditioner.padded and inverse_diagonal is not None

        # where the lattice's C^-1 is a random walk's (``Problem.walk_bounds``) the residual's
        # largest entry bounds the errors too, often more tightly than its energy
        walk_diagonal = inverse_diagonal if problem.walk_bounds else None

        def early_stop(
            x: np.ndarray, image: np.ndarray | None, residual_norm: float, residual_energy: float, residual_max: float
        ) -> bool:
            nonlocal tried_displacements
            if tried_displacements:  # a windowed solve's displacements left it undecided: finish it
                return False

            def displacement() -> np.ndarray:
                nonlocal tried_displacements
                tried_displacements = window is not None  # a full-grid product: try it once
                if not decided_image:
                    decided_image.append(image_on_grid(CGResult(x, 0, 0.0, False, image)))
                return decided_image[0]

            # the recursive residual drifts from b - A x by round-off: never trust it below that
            error = max(residual_norm, 1e-13 * rhs_size * math.sqrt(n)) / floor
            displacement_error = problem.kernel_norm * error
            if energy_bounds and inverse_diagonal is not None:
                # ||x - x*||_C^2 = r.C_SS^-1 r <= r.(T^-1)_SS r (T the element lattice's Toeplitz
                # operator, of which C_SS is a section), which the preconditioner's r.M r gives to
                # its sampling, covered by SAMPLING_MARGIN; by Cauchy-Schwarz in the energy inner
                # product each pressure's error is at most sqrt((C_SS^-1)_ii) times that norm, and
                # each free cell's displacement error at most sqrt(C_00) times it
                energy_error = max(
                    math.sqrt(SAMPLING_MARGIN * max(residual_energy, 0.0)), 1e-13 * rhs_size * math.sqrt(n / floor)
                )
                error = min(error, math.sqrt(inverse_diagonal) * energy_error)
                displacement_error = min(displacement_error, math.sqrt(problem.self_influence) * energy_error)
            if walk_diagonal is not None:
                # |e_i| <= sum_j |(C_SS^-1)_ij| max|r| <= 2 (C_SS^-1)_ii max|r|, and a free cell's
                # displacement error is a sub-probability average of r (``Problem.walk_bounds``)
                largest = max(residual_max, 1e-13 * rhs_size * math.sqrt(n))
                error = min(error, 2.0 * walk_diagonal * largest)
                displacement_error = min(displacement_error, largest)
            if decide(contact, x, displacement, error, displacement_error):
                return True
            decided_image.clear()
            return False

    def solve(rhs: np.ndarray, x0: np.ndarray | None, stop=early_stop) -> CGResult:
        return conjugate_gradient(
            apply_operator,
            rhs,
            x0,
            rtol=settings.rtol,
            maxiter=settings.maxiter,
            precondition=precondition,
            restrict=contact_in_window,
            early_stop=stop,
        )

    def unit_start() -> np.ndarray | None:
        # x1 from the previous set's x1; a state decided at one approach holds y = x1 - xh / d
        # instead, whose entries grow like h / |d|: started from it, CG's recursive residual
        # drifts from b - A x by round-off of that size (near d = 0 far above rtol, while it
        # reports convergence), so x1 starts afresh after a decided set
        if warm_start is None or warm_start.at_approach is not None:
            return None
        return initial_guess(warm_start.pressure_per_approach, warm_start.displacement_per_approach, 1.0)

    at_approach: CGResult | None = None
    if combined and early_stop is not None:
        assert approach is not None and rhs_on_grid is not None
        at_approach = solve(
            rhs_on_grid[contact],
            None
            if warm_start is None
            else initial_guess(
                warm_start.pressure_per_approach - warm_start.profile_pressure / approach,
                warm_start.displacement_per_approach - warm_start.profile_displacement / approach,
                rhs_on_grid,
            ),
        )
        unit = at_approach
    else:
        unit = solve(np.ones(n), unit_start())
    if unit.stopped_early:
        counters.record_decided(unit.iterations)
        in_window = not decided_image and window is not None
        if decided_image:
            image = decided_image[0]
        elif in_window:
            # the decision asked for no gaps: C x1 on the window, not a whole-grid product
            assert unit.image is not None and window is not None
            image = np.zeros(problem.face.shape)
            image[window.rows, window.cols] = unit.image
        else:
            image = image_on_grid(unit)
        return ContactSolution(
            contact.copy(),
            unit.x,
            np.zeros(n),
            image,
            np.zeros(problem.face.shape),
            unit.iterations,
            unit.residual,
            True,
            displacement_in_window=in_window,
            at_approach=approach if at_approach is not None else None,
        )
    spent = 0
    if at_approach is not None:
        # undecided (this set may hold): its linear state needs x1 and xh themselves
        spent = at_approach.iterations
        unit = solve(np.ones(n), unit_start(), None)
    iterations, residual, converged = unit.iterations + spent, unit.residual, unit.converged
    if problem.flat:
        profile_pressure, profile_displacement = np.zeros(n), np.zeros(problem.face.shape)
    else:
        if at_approach is not None and at_approach.converged:
            assert approach is not None
            profile_start: np.ndarray | None = approach * (unit.x - at_approach.x)  # xh = d x1 - p
        else:
            profile_start = (
                None
                if warm_start is None or warm_start.at_approach is not None
                else initial_guess(warm_start.profile_pressure, warm_start.profile_displacement, problem.height)
            )
        profile = solve(problem.height[contact], profile_start, None)
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
