"""Three ways to the same constrained minimum of the discrete energy (see ``problem``).

All take the padded displacement U0 as a warm start, the approach d and whether adhesion is
on, and return a :class:`Minimum`.  Convergence is judged the same way for all: the projected
gradient, in units of the pressure that displaces one element by the length scale L (the
range rho with adhesion, else |d|), must fall below ``gtol``; with adhesion that unit is at
most ``ADHESIVE_UNIT`` times the potential's peak stress w / rho (:func:`unit_ratio`).
"""

from __future__ import annotations

import logging
import math
import warnings
import weakref
from dataclasses import dataclass

import numpy as np
from scipy import optimize
from threadpoolctl import ThreadpoolController

from .problem import EnergyProblem

__all__ = ["Minimum", "minimise", "projected_gradient", "face_matrix", "step_energy_change"]

log = logging.getLogger("bem_energy")

_THREADPOOLS = None


def _one_blas_thread():
    # inspecting the loaded libraries costs about 1 ms; do it once, not per minimisation
    global _THREADPOOLS
    if _THREADPOOLS is None:
        _THREADPOOLS = ThreadpoolController()
    return _THREADPOOLS.limit(limits=1, user_api="blas")


@dataclass(frozen=True, eq=False)
class Minimum:
    """A constrained minimum of the energy, as :func:`bem_energy.minimise` returns it.

    Attributes
    ----------
    U : numpy.ndarray
        Surface displacements on the padded grid.
    P : numpy.ndarray
        Pressures C^-1 U on the padded grid.
    energy : float
        The energy Pi(U).
    iterations : int
        Iterations of the minimiser.
    evaluations : int
        Energy and gradient evaluations.
    converged : bool
        Whether the scaled projected gradient reached the tolerance.
    gradient : float
        The scaled projected-gradient norm reached.
    message : str
        The minimiser's own message, if any.
    peeled : bool
        Stopped because the contact fell (``peel_fraction``): detaching.
    """

    U: np.ndarray
    P: np.ndarray
    energy: float
    iterations: int
    evaluations: int
    converged: bool
    gradient: float  # scaled projected-gradient norm reached
    message: str = ""
    peeled: bool = False  # stopped because the contact fell (``peel_fraction``): detaching


def _length_scale(prob: EnergyProblem, d: float, adhesive: bool) -> float:
    if adhesive and prob.potential is not None:
        return prob.potential.range
    hmax = float(np.ptp(prob.height)) if prob.height.size else 0.0
    return max(abs(d), hmax, 1e-12 * prob.spacing)


#: with adhesion, the pressure unit of the convergence measure is at most this multiple of the
#: potential's peak stress w / rho.  The element's own unit, rho / C_00, grows with the
#: elements per process zone l_c: about 0.8 l_c / h times w / rho on a homogeneous body, so
#: 1.6 w / rho at the exponential potential's two per l_c, 12.9 at Maugis-Dugdale's sixteen,
#: less on graded bodies.  The cap leaves the zero-range sequences and every grid of up to
#: about 20 elements per l_c as they were; it acts on longer zones (a finite range with l_c
#: above about 0.6 a on the default 32 per radius; long ranges, stiff bodies, weak adhesion),
#: where the element unit outgrows the adhesive stress until a minimum accepted at ``gtol``
#: leaves the adhesive tractions unresolved (the pull-off force then comes out at a fraction
#: of its value, or zero).  There it costs iterations; L-BFGS-B, whose objective (the adhesive
#: energy, about -w A, plus changes of relative size a / l_c) loses those changes to round-off,
#: can stall short of the tolerance at l_c >> a and then says so (not converged); the default
#: projected CG sums its steps' energy changes cell by cell and converges
ADHESIVE_UNIT = 16.0


def unit_ratio(prob: EnergyProblem, L: float, adhesive: bool) -> float:
    """The convergence measure's pressure unit over the element's own, L / C_00: 1, or less
    where ``ADHESIVE_UNIT`` w / rho is the smaller (the measure is then divided by it, and a
    minimiser's internal tolerance on the element-unit gradient multiplied by it)."""
    pot = prob.potential
    if not adhesive or pot is None or pot.work <= 0:
        return 1.0
    return min(1.0, ADHESIVE_UNIT * (pot.work / pot.range) * prob.self_compliance / L)


def _lower_bound(prob: EnergyProblem, d: float) -> np.ndarray:
    return d - prob.height


def projected_gradient(
    prob: EnergyProblem, U: np.ndarray, G: np.ndarray, d: float, L: float, adhesive: bool = True
) -> float:
    """max |projected gradient| / (cell * L / C_00), divided by :func:`unit_ratio` where the
    adhesive stress sets the unit: zero exactly at a KKT point."""
    pg = G.copy()
    lb = _lower_bound(prob, d)
    # L-BFGS-B and the projections put cells exactly on the wall; a state rebuilt through
    # C p (cvxpy) carries round-off of order 1e-13 L
    at_wall = U[prob.face] <= lb + 1e-9 * L
    gf = pg[prob.face]
    gf[at_wall] = np.minimum(gf[at_wall], 0.0)
    pg[prob.face] = gf
    measure = float(np.max(np.abs(pg))) * prob.self_compliance / (prob.cell * L)
    ratio = unit_ratio(prob, L, adhesive)
    return measure if ratio == 1.0 else measure / ratio


def minimise(
    prob: EnergyProblem,
    U0: np.ndarray,
    d: float,
    adhesive: bool,
    *,
    method: str = "lbfgsb",
    gtol: float = 1e-6,
    max_iterations: int = 50_000,
    memory: int = 10,
    peel_fraction: float | None = None,
    restart_on_wall_change: bool = False,
    single_precision_directions: bool = False,
) -> Minimum:
    """The constrained minimum of the energy from the warm start ``U0``.

    Minimises Pi(U) under the hard wall g >= 0 on the face at approach d.

    Parameters
    ----------
    prob : bem_energy.EnergyProblem
        The discrete problem.
    U0 : numpy.ndarray
        Warm start on the padded grid (projected onto the wall).
    d : float
        Approach of the punch.
    adhesive : bool
        Whether the adhesive potential is switched on.
    method : str, optional
        ``"lbfgsb"`` (scipy's L-BFGS-B), ``"pk"`` (projected conjugate gradients) or ``"cvxpy"``
        (small grids).
    gtol : float, optional
        Tolerance on the scaled projected gradient, > 0.
    max_iterations : int, optional
        Most iterations, >= 1.
    memory : int, optional
        L-BFGS-B correction pairs, >= 1.
    peel_fraction : float or None, optional
        s, projected CG only: stop, not converged and ``peeled``, once the face cells at the wall
        have fallen below (1 - s) of the most this minimisation had, i.e. the state is peeling
        off toward the detached branch (see :meth:`bem_energy.equilibria.Equilibria.pulling_trial`).
    restart_on_wall_change : bool, optional
        Projected CG only: restart from steepest descent whenever the set of face cells held at
        the wall changes (Polonsky-Keer's rule).  False (the default) keeps the conjugate
        direction, projected onto the new free set: a detaching or peeling state changes that
        set at about every iteration, and restarting there made half of all iterations steepest
        descent.  Either converges to the same projected-gradient tolerance.
    single_precision_directions : bool, optional
        Projected CG only: compute the pressure of each search direction with single-precision
        FFTs.  The pressure is updated by it along the steps and recomputed in double precision
        every 50 iterations and before convergence is declared, so the minimum is judged on
        the double-precision gradient either way.

    Returns
    -------
    bem_energy.Minimum
        The minimum reached, with ``converged`` False (and a message) when the tolerance was not
        reached.

    Raises
    ------
    ValueError
        If ``method`` is unknown.
    """
    # the vector work (L-BFGS-B's updates, the dot products here) goes through BLAS; threaded
    # BLAS on these vector sizes was measured 4x (L-BFGS-B) to 20x (dot products) slower on
    # a shared 2-core machine, so every minimisation runs with one BLAS thread
    with _one_blas_thread():
        if method == "lbfgsb":
            return _lbfgsb(prob, U0, d, adhesive, gtol, max_iterations, memory)
        if method == "pk":
            return _projected_cg(
                prob,
                U0,
                d,
                adhesive,
                gtol,
                max_iterations,
                peel_fraction,
                restart_on_wall_change,
                single_precision_directions,
            )
        if method == "cvxpy":
            return _cvxpy(prob, U0, d, adhesive, gtol, max_iterations)
    raise ValueError(f"unknown minimiser {method!r}")


# ---------------------------------------------------------------------------
# L-BFGS-B
# ---------------------------------------------------------------------------


def _lbfgsb(prob, U0, d, adhesive, gtol, max_iterations, memory) -> Minimum:
    L = _length_scale(prob, d, adhesive)
    ratio = unit_ratio(prob, L, adhesive)
    # energy unit: one element displaced by L; gradients are then O(1) at the scale of interest
    e = prob.cell * L**2 / prob.self_compliance
    M = prob.padded
    lb = np.full(M, -np.inf)
    lb[prob.face] = _lower_bound(prob, d)
    x0 = np.maximum(U0, lb).ravel() / L
    count = [0]

    def fun(x):
        count[0] += 1
        E, G, _ = prob.energy(x.reshape(M) * L, d, adhesive)
        return E / e, G.ravel() * (L / e)

    bounds = optimize.Bounds((lb / L).ravel(), np.inf)
    res = optimize.minimize(
        fun,
        x0,
        jac=True,
        method="L-BFGS-B",
        bounds=bounds,
        options=dict(
            maxcor=memory,
            ftol=0.0,
            gtol=0.1 * gtol * ratio,
            maxiter=max_iterations,
            maxfun=2 * max_iterations,
            maxls=40,
        ),
    )
    U = res.x.reshape(M) * L
    E, G, P = prob.energy(U, d, adhesive)
    pg = projected_gradient(prob, U, G, d, L, adhesive)
    # L-BFGS-B aims ten times lower on the same quantity; it may stop earlier on stagnation
    # (round-off in the energy), which is fine when the gradient is small enough
    ok = pg <= gtol
    return Minimum(U, P, E, int(res.nit), int(count[0]), bool(ok), pg, "" if ok else str(res.message))


def _largest_magnitude(A: np.ndarray) -> float:
    """max |A| without the temporary array of abs(A)."""
    return float(max(A.max(), -A.min()))


def _power_of_two_near_inverse(x: float) -> float:
    """2^-e with x = m 2^e, 1/2 <= m < 1 (so that x 2^-e lies in [1/2, 1)); 1 for x zero or not
    finite.  Multiplying by it is exact in any binary precision."""
    if not (x > 0 and math.isfinite(x)):
        return 1.0
    return math.ldexp(1.0, -math.frexp(x)[1])


# ---------------------------------------------------------------------------
# Polonsky-Keer / Rey style projected conjugate gradients
# ---------------------------------------------------------------------------


def step_energy_change(
    prob: EnergyProblem,
    alpha: float,
    direction: np.ndarray,
    direction_load: float,
    direction_curvature: float,
    P: np.ndarray,
    Pn: np.ndarray | None,
    clipped: np.ndarray | None,
    phi: np.ndarray | None,
    phi_n: np.ndarray | None,
) -> float:
    """The energy change of a projected CG step, summed from the cells' changes.

    Each total energy is a sum over the padded grid whose elastic and adhesive parts are several
    times the energy and of opposite sign: its round-off can exceed the decrease of a step near
    the minimum.  The elastic change is 1/2 (Un - U).(Pn + P) (C^-1 symmetric), with
    Un - U = alpha direction plus the wall projection's move on the face; without a projection
    Pn - P = alpha C^-1 direction, and the change is alpha (direction.P + alpha/2 direction.C^-1
    direction).  The adhesive change is the sum of the cells' phi_n - phi.  All are sums of the
    step's own size.

    Parameters
    ----------
    prob : bem_energy.EnergyProblem
        The discrete problem.
    alpha : float
        The step along ``direction``.
    direction : numpy.ndarray
        The search direction on the padded grid.
    direction_load : float
        direction . P.
    direction_curvature : float
        direction . C^-1 direction, as the pressure that formed Pn (used without a projection).
    P, Pn : numpy.ndarray
        The pressures before and after the step (``Pn`` is read only with a projection, and
        may be None without one).
    clipped : numpy.ndarray or None
        The projection's move of the face cells (face order), None when no cell was projected
        (then Pn = P + alpha C^-1 direction).
    phi, phi_n : numpy.ndarray or None
        The face cells' potential energies before and after (``EnergyProblem.energy_state``);
        None without the adhesive term.

    Returns
    -------
    float
        Pi(Un) - Pi(U), in physical units.
    """
    if clipped is None:
        change = alpha * (direction_load + 0.5 * alpha * direction_curvature)
    else:
        assert Pn is not None  # a projection's change reads the pressure after it
        change = 0.5 * alpha * (direction_load + float(np.vdot(direction, Pn)))
        change += 0.5 * float(np.dot(clipped, prob.on_face(Pn) + prob.on_face(P)))
    if phi is not None and phi_n is not None:
        change += float(np.sum(phi_n - phi))
    return prob.cell * change


#: the projected CG is stalled when its projected gradient has not halved in FLAT_STEPS steps
#: and the energy fell by less than FLAT_ENERGY of itself over them (summed step by step,
#: :func:`step_energy_change`): a converging iteration halves its gradient in a few steps
FLAT_STEPS, FLAT_ENERGY = 20, 1e-10


class _DirectionArrays:
    """The projected CG's search-direction arrays of the padded grid, allocated once per
    minimisation and precision: the free gradient (two, the previous one is needed for the
    conjugate direction), its preconditioned image, their difference, the direction and its
    pressure.

    With single-precision directions they are float32: the preconditioner and the direction's
    pressure are single-precision transforms anyway, and besides those two transforms an
    iteration streams these arrays through memory about a dozen times, in half the bytes.  The
    direction and its pressure are copied to double precision once per iteration
    (:meth:`double`), for the step, its slope and its energy change, which stay in double
    precision; the products of two single-precision arrays (numpy's vdot, accumulated in their
    precision) only weigh the conjugate directions."""

    def __init__(self, shape: tuple[int, int], double: bool):
        dtype = np.float64 if double else np.float32
        self.gradients = (np.empty(shape, dtype), np.empty(shape, dtype))
        self.preconditioned = np.empty(shape, dtype)
        self.difference = np.empty(shape, dtype)
        self.direction = np.empty(shape, dtype)
        self.direction_pressure = None if double else np.empty(shape, dtype)
        self.direction_double = None if double else np.empty(shape)
        self.direction_pressure_double = None if double else np.empty(shape)

    def double(self, A: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        """``A`` in double precision: itself, or copied into ``out`` (by default the direction's
        double-precision array)."""
        if A.dtype == np.float64:
            return A
        target = self.direction_double if out is None else out
        assert target is not None  # single-precision arrays come with double-precision copies
        np.copyto(target, A)
        return target


def _projected_cg(
    prob,
    U0,
    d,
    adhesive,
    gtol,
    max_iterations,
    peel_fraction=None,
    restart_on_wall_change=False,
    single_precision_directions=False,
) -> Minimum:
    """Conjugate directions on the free set, preconditioned by C itself (which inverts the
    elastic Hessian C^-1 exactly away from the wall), step from the local quadratic model,
    projection onto the wall.  The direction restarts from steepest descent when it is not a
    descent direction, and with ``restart_on_wall_change`` also whenever the set at the wall
    changes (as in Polonsky-Keer); otherwise the previous direction is kept, projected onto
    the new free set (Polak-Ribiere's beta, clipped at zero, from the projected gradients).
    Armijo backtracking keeps the energy decreasing on the concave adhesive part, judged on
    the step's energy change summed from the cells' changes (:func:`step_energy_change`),
    not on the difference of two totals, whose round-off can exceed a late step's decrease.  The
    pressure is updated along each step from the direction's pressure (in single precision
    with ``single_precision_directions``, and so is a projected step's, plus the pressure of
    the projection's move) and recomputed from U every 50 iterations and, in single
    precision, before a minimum is accepted; the energy is summed from the steps' changes
    between those evaluations.  A minimisation that has stagnated (40
    halvings for a decrease, or a projected gradient that has not halved in ``FLAT_STEPS``
    steps while the energy fell by less than ``FLAT_ENERGY`` of itself) goes on in double
    precision if its directions were in single precision, and otherwise stops with a message
    that says which ("stagnated at round-off in the energy" or "stagnated: ..."), converged
    only if the projected gradient is below ``gtol``."""
    L = _length_scale(prob, d, adhesive)
    ratio = unit_ratio(prob, L, adhesive)
    # the face lies in the raster's corner of the padded grid: its cells are read and written
    # there (``face_block``), a quarter of the grid
    corner = (slice(0, prob.n[0]), slice(0, prob.n[1]))
    face_block = prob.face_block
    wall = _lower_bound(prob, d)
    U = U0.copy()
    # the face's displacements are carried beside U (the projection and the trial step form
    # them anyway), and the gradient as its face entries beside P: off the face it is cell P
    U_face = np.maximum(prob.on_face(U), wall)
    U[corner][face_block] = U_face
    E, P, P_face, G_face, stress, curvature_face, phi = prob.energy_state(U, d, adhesive, U_face=U_face)
    direction = None
    Gf_previous = None
    zg_previous = 0.0  # no previous step: the first direction is steepest descent
    fixed_previous = np.zeros(0, bool)
    evals = 1
    potential = prob.potential if adhesive else None
    most_in_contact = 0
    window_steps, window_pg, window_fall = 0, math.inf, 0.0  # the stagnation window (below)
    # the directions' pressures in double precision: from the start, or after a stall in
    # single precision (one flag decides both which transform runs and whether a stall ends)
    double_directions = not single_precision_directions
    # work arrays of the padded grid, reused across the iterations: a fresh array of a few
    # megabytes is fresh pages from the system, whose faults cost system time.  A projected
    # trial goes into the spare U and P, which are the previous ones once it is accepted (an
    # unprojected one is accepted in place, through them)
    spare_U, spare_P = np.empty(prob.padded), np.empty(prob.padded)
    # a projection's move (zero off the face, where it is never written) and its pressure
    move = None if double_directions else np.zeros(prob.padded)
    move_pressure = None if double_directions else np.empty(prob.padded)
    work = _DirectionArrays(prob.padded, double_directions)
    # the directions carry the gradient times a power of two that brings the products of two
    # single-precision arrays (zg and beta's, about C_00 times the gradient squared) and the
    # single-precision preconditioner's image (C_00 times the gradient) near 1 at the start: in
    # small units (nanometres and gigapascals) they would otherwise fall below float32's range
    # (even with double-precision directions the preconditioner is a single-precision
    # transform, and an image that underflowed to zero left no direction).  The direction is
    # then that power of two times the unscaled one, which the step length alpha undoes exactly
    # (its slope and curvatures scale with it), so the iterates are those of the unscaled
    # directions bit for bit wherever nothing underflows
    gradient_scale = _power_of_two_near_inverse(
        _largest_magnitude(prob.gradient(P, G_face)) * math.sqrt(prob.self_compliance)
    )
    # P carries incremental updates since it was last computed from U (E always does: it is
    # summed from the steps' changes between evaluations from U)
    updated = False

    def free_gradient(P, G_face, at_wall_face):
        # cells held at the wall (pressed onto it), on the raster's corner; the gradient without
        # them, times gradient_scale in the directions' precision (the power of two makes the
        # scaled single-precision entries those of the unscaled ones times it, bit for bit), and
        # its scaled largest magnitude, the projected-gradient measure of convergence
        fixed_face = at_wall_face & (G_face > 0)
        fixed = np.zeros(face_block.shape, bool)
        fixed[face_block] = fixed_face
        Gf = work.gradients[0] if work.gradients[0] is not Gf_previous else work.gradients[1]
        prob.gradient(P, np.where(fixed_face, 0.0, G_face), out=Gf, scale=gradient_scale)
        largest = _largest_magnitude(Gf) / gradient_scale
        measure = largest * prob.self_compliance / (prob.cell * L)
        return fixed, Gf, measure if ratio == 1.0 else measure / ratio

    def slope_from(load, stress, direction_face):
        # the energy's slope along a direction (zero on the fixed cells), from the elastic
        # energy's (direction . P, the direction's load) and the face's adhesive stress
        if stress is None:
            return prob.cell * load
        return prob.cell * (load + float(np.dot(direction_face, stress)))

    def slope(direction_double, P, stress):
        # the slope, the direction's load and its face entries (the adhesive terms read them)
        load = float(np.vdot(direction_double, P))
        direction_face = None if stress is None else prob.on_face(direction_double)
        return slope_from(load, stress, direction_face), load, direction_face

    for it in range(1, max_iterations + 1):
        at_wall_face = U_face <= wall + 1e-13 * L
        if peel_fraction is not None:
            in_contact = int(np.count_nonzero(at_wall_face))
            most_in_contact = max(most_in_contact, in_contact)
            if in_contact < (1.0 - peel_fraction) * most_in_contact:
                return Minimum(U, P, E, it - 1, evals, False, math.inf, "peeling off", peeled=True)
        fixed, Gf, pg = free_gradient(P, G_face, at_wall_face)
        if pg <= gtol and updated and single_precision_directions:
            # judge the minimum on the gradient computed from U in double precision (its largest
            # free entry read after rounding to the directions' precision, 6e-8 relative)
            E, P, P_face, G_face, stress, curvature_face, phi = prob.energy_state(U, d, adhesive, U_face=U_face)
            evals += 1
            updated = False
            fixed, Gf, pg = free_gradient(P, G_face, at_wall_face)
        if pg <= gtol:
            return Minimum(U, P, E, it - 1, evals, True, pg)
        preconditioned = prob.preconditioned(Gf, out=work.preconditioned)
        preconditioned[corner][fixed] = 0.0
        zg = float(np.vdot(preconditioned, Gf))
        same_set = not restart_on_wall_change or np.array_equal(fixed, fixed_previous)
        gs = 0.0
        if direction is not None and Gf_previous is not None and same_set and zg_previous > 0:
            change_of_gradient = np.subtract(Gf, Gf_previous, out=work.difference)
            beta = max(0.0, float(np.vdot(preconditioned, change_of_gradient)) / zg_previous)
            # in place (the previous direction is not needed again): beta d - z
            direction *= beta
            direction -= preconditioned
            direction[corner][fixed] = 0.0
            # the slope and the step in double precision (the direction is zero on the fixed
            # cells, the only ones where the free gradient differs from the gradient)
            direction_double = work.double(direction)
            gs, direction_load, direction_face = slope(direction_double, P, stress)
            if gs >= 0:
                direction = np.negative(preconditioned, out=work.direction)
                direction_double = work.double(direction)
                gs, direction_load, direction_face = slope(direction_double, P, stress)
        else:
            direction = np.negative(preconditioned, out=work.direction)
            direction_double = work.double(direction)
            gs, direction_load, direction_face = slope(direction_double, P, stress)
        fixed_previous, zg_previous, Gf_previous = fixed, zg, Gf
        if double_directions:
            direction_pressure = prob.pressure(direction)
        else:
            direction_pressure = work.double(
                prob.pressure_single(direction, out=work.direction_pressure), work.direction_pressure_double
            )
        elastic_curvature = float(np.vdot(direction_double, direction_pressure))
        curvature = elastic_curvature
        if potential is not None and curvature_face is not None and direction_face is not None:
            # phi'' at U, from the evaluation that produced U's energy (one exponential per evaluation)
            curvature += float(np.dot(curvature_face * direction_face, direction_face))
        # Newton step on the local quadratic model; where the adhesion makes the model concave along
        # the direction, the elastic curvature alone sets a first trial (backtracking follows)
        alpha = -gs / (prob.cell * (curvature if curvature > 0 else elastic_curvature))
        if direction_face is None:
            direction_face = prob.on_face(direction_double)
        pressure_face = prob.on_face(direction_pressure)
        for halvings in range(60):  # noqa: B007  (the count is read after the loop)
            # the trial on the face cells first: a step that projects nothing is formed on the
            # padded grid only once it is accepted, in place (U += alpha direction, P += alpha
            # direction's pressure, whose face entries come out as the trial's, rounded the
            # same way), which saves two arrays' writes and reads per iteration over forming the
            # trial beside U and P
            Un_face = np.multiply(direction_face, alpha)
            Un_face += U_face
            clipped = None
            if (Un_face < wall).any():
                Un = np.multiply(direction_double, alpha, out=spare_U)
                Un += U
                projected_face = np.maximum(Un_face, wall)
                Un[corner][face_block] = projected_face
                clipped = projected_face - Un_face  # the projection's move, on the face cells
                Un_face = projected_face
                if double_directions or move is None:
                    Pn = None
                else:
                    # the projection moves a few cells onto the wall: their pressure from a
                    # single-precision transform, added to the step's like a direction's (one
                    # cheaper transform than a double-precision P, and round-off relative to
                    # the step rather than to P)
                    move[corner][face_block] = clipped
                    Pn = np.multiply(direction_pressure, alpha, out=spare_P)
                    Pn += P
                    Pn += prob.pressure_single(move, out=move_pressure)
                # a pressure carried along the step, not computed from Un by energy_state, is
                # recomputed from U before a minimum is accepted
                Pn_updated = Pn is not None
                _, Pn, Pn_face, Gn_face, stress_n, curvature_face_n, phi_n = prob.energy_state(
                    Un, d, adhesive, Pn, Un_face, total=False
                )
            else:
                Un = Pn = None
                Pn_updated = True
                Pn_face = np.multiply(pressure_face, alpha)
                Pn_face += P_face
                Gn_face, stress_n, curvature_face_n, phi_n = prob.face_terms(Un_face, Pn_face, d, adhesive)
            evals += 1
            # the step's change from the cells' changes, not the difference of two totals: they
            # carry round-off (about 1e-11 of E on a 3200^2 grid) above the decrease of a step
            # near the minimum, where comparing them would let round-off decide which steps
            # pass.  The trial's energy is E plus this change (no pass over Un.Pn for a total)
            change = step_energy_change(
                prob, alpha, direction_double, direction_load, elastic_curvature, P, Pn, clipped, phi, phi_n
            )
            if change <= 1e-4 * alpha * gs:
                break
            if abs(change) <= 1e-12 * abs(E):
                # a change below what the totals could resolve: accept a step that flattens the
                # slope along the direction (a Wolfe-type condition), as the totals' comparison
                # did; it may raise the energy by at most that much
                trial_load = (
                    direction_load + alpha * elastic_curvature if Pn is None else float(np.vdot(direction_double, Pn))
                )
                if abs(slope_from(trial_load, stress_n, direction_face)) <= 0.9 * abs(gs):
                    break
            alpha *= 0.5
        else:
            return Minimum(U, P, E, it, evals, False, pg, "line search failed")
        En = E + change
        if Un is None or Pn is None:
            # the accepted step projected nothing: U and P move in place, through the spare
            # arrays (the same two roundings as the trial's face entries; BLAS axpy's single
            # fused rounding would save a pass but change the iterates at round-off, which near
            # a snap-off moves a range's pull-off by its path noise)
            U += np.multiply(direction_double, alpha, out=spare_U)
            P += np.multiply(direction_pressure, alpha, out=spare_P)
            Un, Pn = U, P
        else:
            spare_U, spare_P = U, P
        # a decrease found only 2^-40 along the model step is round-off in the energy: the
        # iteration has stagnated (l_c ~ Delta near a snap took 50 evaluations per step and
        # 150,000 in one minimisation before this stop).  So has one whose projected gradient
        # has not halved in FLAT_STEPS steps while the energy fell by less than FLAT_ENERGY of
        # itself: a guard against progress too slow to reach gtol in any useful time
        if window_steps == 0 or pg < 0.5 * window_pg:
            window_steps, window_pg, window_fall = 0, pg, 0.0
        window_steps += 1
        window_fall -= change
        flat = False
        if window_steps >= FLAT_STEPS:
            flat = window_fall <= FLAT_ENERGY * abs(En)
            window_steps = 0
        stalled = halvings >= 40 or flat
        if stalled and (pg <= gtol or double_directions):
            why = (
                "stagnated at round-off in the energy"
                if halvings >= 40
                else f"stagnated: the energy fell by less than {FLAT_ENERGY:g} of itself in {FLAT_STEPS} steps "
                "while the projected gradient did not halve"
            )
            return Minimum(Un, Pn, En, it, evals, pg <= gtol, pg, why)
        U, U_face, P, P_face, E = Un, Un_face, Pn, Pn_face, En
        G_face, stress, curvature_face, phi = Gn_face, stress_n, curvature_face_n, phi_n
        updated = Pn_updated
        if stalled:
            # the directions' single-precision pressures can stall the line search at their own
            # round-off while the double-precision gradient is still above gtol: go on in double
            # precision from a fresh evaluation (a stall there ends the minimisation as above)
            double_directions = True
            direction = None
            work = _DirectionArrays(prob.padded, double_directions)
            Gf_previous = None
            E, P, P_face, G_face, stress, curvature_face, phi = prob.energy_state(U, d, adhesive, U_face=U_face)
            evals += 1
            updated = False
            window_steps = 0
            continue
        if it % 50 == 0:
            # refresh P from U: the incremental update accumulates round-off
            E, P, P_face, G_face, stress, curvature_face, phi = prob.energy_state(U, d, adhesive, U_face=U_face)
            updated = False
    return Minimum(U, P, E, max_iterations, evals, False, pg, "iteration limit")


# ---------------------------------------------------------------------------
# cvxpy: sequential convex QPs on the face (small grids)
# ---------------------------------------------------------------------------


def face_matrix(prob: EnergyProblem) -> np.ndarray:
    """The dense influence matrix C_ff between face cells (u_f = C_ff p_f)."""
    import scipy.fft as sfft

    kernel = sfft.irfft2(prob.symbol, s=prob.padded)
    ix, iy = np.nonzero(prob.face)
    Mx, My = prob.padded
    return kernel[(ix[:, None] - ix[None, :]) % Mx, (iy[:, None] - iy[None, :]) % My]


class _FaceQP:
    """The face's dense matrices and the compiled contact QP of one problem:
    min 1/2 s.K s + g.s subject to s >= lower, with g and lower cvxpy parameters, so that the
    canonicalisation (most of a fresh 112-variable solve) is done once per problem."""

    def __init__(self, prob: EnergyProblem):
        import cvxpy as cp

        scale = prob.self_compliance
        Cff = face_matrix(prob)
        self.Cff = 0.5 * (Cff + Cff.T)
        K = np.linalg.inv(self.Cff / scale)  # stiffness in units of 1 / C_00
        self.K = 0.5 * (K + K.T)
        n = self.K.shape[0]
        self.s = cp.Variable(n)
        self.g, self.lower = cp.Parameter(n), cp.Parameter(n)
        self.qp = cp.Problem(
            cp.Minimize(0.5 * cp.quad_form(self.s, cp.psd_wrap(self.K)) + self.g @ self.s), [self.s >= self.lower]
        )

    def step(self, g: np.ndarray, lower: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
        """The QP's solution and its set of cells at the bound (None if the solver fails).  Clarabel finds the solution
        to its tolerance and, above all, which cells stay at the wall; that set is then
        solved exactly.  An interior point stops short of the bound by its tolerance and, at
        a degenerate minimum (a flat face at d = 0: every cell at the wall under zero
        pressure), about 1e-4 of the scale away whatever the scale, which the projected
        gradient reports as not converged."""
        import cvxpy as cp

        K = self.K
        self.g.value, self.lower.value = g, lower
        with warnings.catch_warnings():
            # "solution may be inaccurate" at a degenerate minimum: the active-set solve below
            # and the projected gradient of the iteration judge the step
            warnings.simplefilter("ignore", UserWarning)
            try:
                self.qp.solve(solver="CLARABEL")
            except cp.error.SolverError:
                return None
        if self.s.value is None:
            return None
        s0 = np.maximum(np.asarray(self.s.value, float), lower)
        active = K @ s0 + g > s0 - lower  # multiplier larger than the slack
        s1 = _on_active_set(K, g, lower, active)
        if _solves_qp(K, g, lower, s1, active):
            return np.maximum(s1, lower), active
        return s0, s0 <= lower


def _on_active_set(H, g, lower, active):
    """Minimiser of 1/2 s.H s + g.s with s = lower on ``active`` and free elsewhere."""
    s = lower.copy()
    free = ~active
    if free.any():
        s[free] = np.linalg.solve(H[np.ix_(free, free)], -g[free] - H[np.ix_(free, active)] @ lower[active])
    return s


def _solves_qp(H, g, lower, s, active) -> bool:
    """KKT of min 1/2 s.H s + g.s, s >= lower for s from :func:`_on_active_set`: the free cells
    feasible, the held ones pressed (non-negative multipliers), to round-off."""
    tol = 1e-9 * max(1.0, float(np.max(np.abs(g), initial=0.0)))
    return bool(np.all(s[~active] >= lower[~active] - tol) and np.all((H @ s + g)[active] >= -tol))


_FACE_QPS: weakref.WeakKeyDictionary[EnergyProblem, _FaceQP] = weakref.WeakKeyDictionary()


def _cvxpy(prob, U0, d, adhesive, gtol, max_iterations) -> Minimum:
    """Newton's method on the face displacements u under the hard wall, with the surface off
    the face relaxed exactly (elastic energy 1/2 u.K u, K = C_ff^-1), in units of L and of
    the cell energy cell L^2 / C_00.  Each iteration takes Newton's step (Hessian
    K + diag phi''(g), positive definite on the stable attached branch) with some cells held
    at the wall: those pressed onto it, when the step then satisfies the model's optimality
    conditions; else the cells that the contact QP (cvxpy, the adhesion replaced by its
    tangent) leaves at the wall.  Where Newton's Hessian is not positive definite or its step
    does not lower the energy, that QP's own step is taken (the convex-concave procedure's,
    which never raises the energy).  The convex-concave procedure alone converges linearly
    with a rate that tends to one at the snap-off fold: stopped on its step length, it left
    pull-off forces 5e-4 from the other minimisers on a 52-cell face.  Newton's steps reach
    the shared projected-gradient criterion.  Without adhesion the model is exact and one
    step is the minimum."""
    face_qp = _FACE_QPS.get(prob)
    if face_qp is None:
        face_qp = _FACE_QPS[prob] = _FaceQP(prob)
    K = face_qp.K
    L = _length_scale(prob, d, adhesive)
    # the loop's measure is in the element's unit; the shared one may be the adhesive stress's
    inner_tolerance = gtol * unit_ratio(prob, L, adhesive)
    pot = prob.potential if adhesive else None
    a = prob.self_compliance / L**2  # one cell's adhesive energy in the energy unit
    wall = _lower_bound(prob, d) / L
    x = np.maximum(U0[prob.face] / L, wall)
    elastic = float(np.dot(x, K @ x))

    def gradient(x):
        gx = K @ x
        if pot is not None:
            gx = gx + pot.stress((x - wall) * L) * (a * L)
        return gx

    def projected(x, gx):
        return float(np.max(np.abs(np.where(x <= wall, np.minimum(gx, 0.0), gx)), initial=0.0))

    def change(x, xn):
        """E(xn) - E(x) without the cancellation of two large energies."""
        s = xn - x
        dE = float(np.dot(K @ x, s) + 0.5 * np.dot(s, K @ s))
        if pot is not None:
            dE += a * float(np.sum(pot.energy((xn - wall) * L) - pot.energy((x - wall) * L)))
        return dE

    def search(x, gx, pg, s, halvings):
        """Backtracking along s (cells pushed through the wall are put on it): (x, g) or None."""
        t = 1.0
        slope = float(np.dot(gx, s))
        for _ in range(halvings):
            xn = x + t * s
            # x + (wall - x) misses wall by round-off: cells the step puts at the wall go exactly there
            xn = np.where(xn <= wall + 1e-12 * (1.0 + np.abs(wall)), wall, xn)
            dE = change(x, xn)
            gn = gradient(xn)
            if dE <= 1e-4 * min(float(np.dot(gx, xn - x)), t * slope, 0.0) and dE < 0:
                return xn, gn
            # an energy change at round-off (a step of the size of the gradient): the gradient decides
            if abs(dE) <= 1e-13 * (1.0 + elastic) and projected(xn, gn) < pg:
                return xn, gn
            t *= 0.5
        return None

    def newton(H, gx, lower, active):
        """Newton's step with the cells of ``active`` held at the wall, or None where the
        Hessian on the free cells is not positive definite (past a fold)."""
        free = ~active
        try:
            np.linalg.cholesky(H[np.ix_(free, free)])
        except np.linalg.LinAlgError:
            return None
        return _on_active_set(H, gx, lower, active)

    gx = gradient(x)
    pg = projected(x, gx)
    it, evals, message = 0, 1, ""
    while pg > inner_tolerance:
        if it >= max_iterations:
            message = "iteration limit"
            break
        it += 1
        lower = wall - x
        H = K if pot is None else K + np.diag(pot.curvature((x - wall) * L) * (a * L**2))
        # the cells pressed onto the wall now usually stay there: when Newton's step with
        # them held satisfies the model's optimality conditions, it is that model's solution
        # and the QP is not needed
        held = (x <= wall) & (gx > 0)
        s = newton(H, gx, lower, held)
        nxt = None
        if s is not None and _solves_qp(H, gx, lower, s, held):
            nxt = search(x, gx, pg, s, 8)
            evals += 1
        if nxt is None:
            qp = face_qp.step(gx, lower)
            if qp is None:
                message = "the cvxpy contact QP failed"
                break
            s_cc, active = qp
            if pot is not None:
                s = newton(H, gx, lower, active)
                if s is not None:
                    nxt = search(x, gx, pg, s, 8)
                    evals += 1
            if nxt is None:
                nxt = search(x, gx, pg, s_cc, 60)
                evals += 1
        if nxt is None:
            message = "line search failed"
            break
        x, gx = nxt
        pg = projected(x, gx)
        elastic = float(np.dot(x, K @ x))
    P = np.zeros(prob.padded)
    P[prob.face] = np.linalg.solve(face_qp.Cff, x * L)
    U = prob.displacement(P)
    E, G, P = prob.energy(U, d, pot is not None, P)
    pgf = projected_gradient(prob, U, G, d, L, adhesive)
    ok = pgf <= gtol
    return Minimum(U, P, E, it, evals, bool(ok), pgf, "" if ok else (message or "not converged"))
