"""Three ways to the same constrained minimum of the discrete energy (see ``problem``).

All take the padded displacement U0 as a warm start, the approach d and whether adhesion is
on, and return a :class:`Minimum`.  Convergence is judged the same way for all: the projected
gradient, in units of the pressure that displaces one element by the length scale L (the
range rho with adhesion, else |d|), must fall below ``gtol``.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np
from scipy import optimize
from threadpoolctl import ThreadpoolController

from .problem import EnergyProblem

__all__ = ["Minimum", "minimise", "projected_gradient", "face_matrix"]

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
    U: np.ndarray
    P: np.ndarray
    energy: float
    iterations: int
    evaluations: int
    converged: bool
    gradient: float          # scaled projected-gradient norm reached
    message: str = ""


def _length_scale(prob: EnergyProblem, d: float, adhesive: bool) -> float:
    if adhesive and prob.potential is not None:
        return prob.potential.range
    hmax = float(np.ptp(prob.height)) if prob.height.size else 0.0
    return max(abs(d), hmax, 1e-12 * prob.spacing)


def _lower_bound(prob: EnergyProblem, d: float) -> np.ndarray:
    return d - prob.height


def projected_gradient(prob: EnergyProblem, U: np.ndarray, G: np.ndarray, d: float, L: float) -> float:
    """max |projected gradient| / (cell * L / C_00): zero exactly at a KKT point."""
    pg = G.copy()
    lb = _lower_bound(prob, d)
    # L-BFGS-B and the projections put cells exactly on the wall; a state rebuilt through
    # C p (cvxpy) carries round-off of order 1e-13 L
    at_wall = U[prob.face] <= lb + 1e-9 * L
    gf = pg[prob.face]
    gf[at_wall] = np.minimum(gf[at_wall], 0.0)
    pg[prob.face] = gf
    return float(np.max(np.abs(pg))) * prob.self_compliance / (prob.cell * L)


def minimise(prob: EnergyProblem, U0: np.ndarray, d: float, adhesive: bool, *, method: str = "lbfgsb",
             gtol: float = 1e-6, max_iterations: int = 50_000, memory: int = 10) -> Minimum:
    # the vector work (L-BFGS-B's updates, the dot products here) goes through BLAS; threaded
    # BLAS on these vector sizes was measured 4x (L-BFGS-B) to 20x (dot products) slower on
    # this shared 2-core machine, so every minimisation runs with one BLAS thread
    with _one_blas_thread():
        if method == "lbfgsb":
            return _lbfgsb(prob, U0, d, adhesive, gtol, max_iterations, memory)
        if method == "pk":
            return _projected_cg(prob, U0, d, adhesive, gtol, max_iterations)
        if method == "cvxpy":
            return _cvxpy(prob, U0, d, adhesive, gtol, max_iterations)
    raise ValueError(f"unknown minimiser {method!r}")


# ---------------------------------------------------------------------------
# L-BFGS-B
# ---------------------------------------------------------------------------

def _lbfgsb(prob, U0, d, adhesive, gtol, max_iterations, memory) -> Minimum:
    L = _length_scale(prob, d, adhesive)
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
    res = optimize.minimize(fun, x0, jac=True, method="L-BFGS-B", bounds=bounds,
                            options=dict(maxcor=memory, ftol=0.0, gtol=0.1 * gtol, maxiter=max_iterations,
                                         maxfun=2 * max_iterations, maxls=40))
    U = res.x.reshape(M) * L
    E, G, P = prob.energy(U, d, adhesive)
    pg = projected_gradient(prob, U, G, d, L)
    # L-BFGS-B aims ten times lower on the same quantity; it may stop earlier on stagnation
    # (round-off in the energy), which is fine when the gradient is small enough
    ok = pg <= gtol
    return Minimum(U, P, E, int(res.nit), int(count[0]), bool(ok), pg, "" if ok else str(res.message))


# ---------------------------------------------------------------------------
# Polonsky-Keer / Rey style projected conjugate gradients
# ---------------------------------------------------------------------------

def _projected_cg(prob, U0, d, adhesive, gtol, max_iterations) -> Minimum:
    """Conjugate directions on the free set, preconditioned by C itself (which inverts the
    elastic Hessian C^-1 exactly away from the wall), step from the local quadratic model,
    projection onto the wall, restart whenever the set at the wall changes (as in
    Polonsky-Keer) or the direction is not a descent direction; Armijo backtracking keeps the
    energy decreasing on the concave adhesive part."""
    L = _length_scale(prob, d, adhesive)
    face = prob.face
    lb = _lower_bound(prob, d)
    U = U0.copy()
    U[face] = np.maximum(U[face], lb)
    E, G, P = prob.energy(U, d, adhesive)
    S = None
    Gf_old = None
    zg_old = None
    wall_old = None
    evals = 1
    pot = prob.potential if adhesive else None
    for it in range(1, max_iterations + 1):
        at_wall = np.zeros(prob.padded, bool)
        at_wall[face] = U[face] <= lb + 1e-13 * L
        fixed = at_wall & (G > 0)
        Gf = np.where(fixed, 0.0, G)
        pg = float(np.max(np.abs(Gf))) * prob.self_compliance / (prob.cell * L)
        if pg <= gtol:
            return Minimum(U, P, E, it - 1, evals, True, pg)
        Z = prob.displacement(Gf)
        Z[fixed] = 0.0
        zg = float(np.vdot(Z, Gf))
        if S is not None and np.array_equal(fixed, wall_old) and zg_old > 0:
            beta = max(0.0, float(np.vdot(Z, Gf - Gf_old)) / zg_old)
            S = -Z + beta * S
            S[fixed] = 0.0
            if float(np.vdot(S, Gf)) >= 0:
                S = -Z
        else:
            S = -Z
        wall_old, zg_old, Gf_old = fixed, zg, Gf
        KS = prob.pressure(S)
        sKs = float(np.vdot(S, KS))
        sHs = sKs
        if pot is not None:
            Sf = S[face]
            sHs += float(np.dot(pot.curvature(prob.gap(U, d)) * Sf, Sf))
        gs = float(np.vdot(Gf, S))
        # Newton step on the local quadratic model; where the adhesion makes the model concave
        # along S, the elastic curvature alone sets a first trial (backtracking follows)
        alpha = -gs / (prob.cell * (sHs if sHs > 0 else sKs))
        for halvings in range(60):
            Un = U + alpha * S
            clipped = Un[face] < lb
            if clipped.any():
                Un[face] = np.maximum(Un[face], lb)
                Pn = None
            else:
                Pn = P + alpha * KS
            En, Gn, Pn = prob.energy(Un, d, adhesive, Pn)
            evals += 1
            if En <= E + 1e-4 * alpha * gs:
                break
            if abs(En - E) <= 1e-12 * abs(E) and abs(float(np.vdot(Gn, S))) <= 0.9 * abs(gs):
                # the energy change is at round-off, where Armijo cannot decide; the slope
                # along S still can: accept a step that flattens it (a Wolfe-type condition)
                break
            alpha *= 0.5
        else:
            return Minimum(U, P, E, it, evals, False, pg, "line search failed")
        if halvings >= 40:
            # a decrease found only 2^-40 along the model step is round-off in the energy: the
            # iteration has stagnated (l_c ~ Delta near a snap took 50 evaluations per step and
            # 150,000 in one minimisation before this stop)
            return Minimum(Un, Pn, En, it, evals, pg <= gtol, pg, "stagnated at round-off in the energy")
        U, P, E, G = Un, Pn, En, Gn
        if it % 50 == 0:
            # refresh P from U: the incremental update accumulates round-off
            E, G, P = prob.energy(U, d, adhesive)
    return Minimum(U, P, E, max_iterations, evals, False, pg, "iteration limit")


# ---------------------------------------------------------------------------
# cvxpy: convex QP and the convex-concave procedure (small grids)
# ---------------------------------------------------------------------------

def face_matrix(prob: EnergyProblem) -> np.ndarray:
    """The dense influence matrix C_ff between face cells (u_f = C_ff p_f)."""
    import scipy.fft as sfft

    kernel = sfft.irfft2(prob.symbol, s=prob.padded)
    ix, iy = np.nonzero(prob.face)
    Mx, My = prob.padded
    return kernel[(ix[:, None] - ix[None, :]) % Mx, (iy[:, None] - iy[None, :]) % My]


def _cvxpy(prob, U0, d, adhesive, gtol, max_iterations) -> Minimum:
    import cvxpy as cp

    L = _length_scale(prob, d, adhesive)
    Cff = face_matrix(prob)
    Cff = 0.5 * (Cff + Cff.T)
    lb = _lower_bound(prob, d)
    n = Cff.shape[0]
    scale = prob.self_compliance
    pot = prob.potential if adhesive else None

    def to_grid(p_face):
        P = np.zeros(prob.padded)
        P[prob.face] = p_face
        return prob.displacement(P)

    if pot is None:
        # Kalker's complementary energy: min 1/2 p.C p - p.(d - h), p >= 0 (pressures in units L/C_00)
        p = cp.Variable(n)
        A = Cff / scale
        obj = 0.5 * cp.quad_form(p, cp.psd_wrap(A)) - (lb / L) @ p
        cp.Problem(cp.Minimize(obj), [p >= 0]).solve(solver="CLARABEL", tol_gap_abs=1e-12, tol_gap_rel=1e-12,
                                                      tol_feas=1e-12)
        U = to_grid(np.asarray(p.value) * L / scale)
        E, G, P = prob.energy(U, d, False)
        pg = projected_gradient(prob, U, G, d, L)
        return Minimum(U, P, E, 1, 1, pg <= max(gtol, 1e-6), pg, "")
    # convex-concave procedure on the face displacements: the elastic energy of the face with
    # free surroundings is 1/2 u.(C_ff^-1) u; the concave adhesion is replaced by its tangent
    Kff = np.linalg.inv(Cff / scale)
    Kff = 0.5 * (Kff + Kff.T)
    u_k = np.maximum(U0[prob.face], lb)
    x = cp.Variable(n)
    lin = cp.Parameter(n)
    w_scale = prob.cell * L**2 / scale      # energy unit
    obj = 0.5 * cp.quad_form(x, cp.psd_wrap(Kff)) + lin @ x
    problem = cp.Problem(cp.Minimize(obj), [x >= lb / L])
    it = 0
    for it in range(1, max_iterations + 1):
        lin.value = pot.stress(u_k - lb) * prob.cell * L / w_scale
        problem.solve(solver="CLARABEL", warm_start=True, tol_gap_abs=1e-12, tol_gap_rel=1e-12, tol_feas=1e-12)
        u_new = np.maximum(np.asarray(x.value) * L, lb)
        step = float(np.max(np.abs(u_new - u_k))) / L
        u_k = u_new
        if step <= gtol:
            break
    U = to_grid(np.linalg.solve(Cff, u_k))
    E, G, P = prob.energy(U, d, True)
    pg = projected_gradient(prob, U, G, d, L)
    ok = step <= gtol
    return Minimum(U, P, E, it, it, ok, pg, "" if ok else "convex-concave procedure did not settle")
