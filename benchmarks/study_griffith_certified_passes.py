"""How many of a cascade's next leavers a lower bound from the element lattice's random walk
certifies without solving their contact set: the evidence for a Griffith BEM lever that issue
#21's 512^2 row needs (fewer passes per event), measured and not yet built.

    python benchmarks/study_griffith_certified_passes.py [--cells 128 256] [--reach 2 4 8]
        [--outer 16] [--update]

Where the lattice's C^-1 is a random walk's (``Problem.walk_bounds``), C^-1 = D0 (I - P) with P
the step matrix of a transient walk, and for a contact set S the pressures per approach are
x1_i(S) = D0 Esc_S(i), the chance that the walk, leaving i, never returns to S.  A cascade's pass
removes the leavers R from S; a cell q of T = S \\ R leaves at the next pass if x1_q(T) reaches
sigma_c / |d|, and then it is outside the largest set that holds at d (tensions only grow as cells
leave), so it could go with R without solving T.  The walk gives a lower bound from S's own
solution: x1_q(T) - x1_q(S) = D0 P_q(the walk's first return to S lands in R, and it never visits
T afterwards); counting only the paths from q to R through the free cells (on and off the face)
within ``reach`` cells of R, and bounding the chance of never visiting T from r in R by the
larger of Esc_S(r) = x1_r(S) / D0 and a local system on those free cells whose own escape is at
least 1 - u1 (u1 = C x1, the hitting chance of S) on the free cells within ``outer`` cells,
gives a lower bound that needs only dense solves on the patch.  P comes from the lattice's
inverse symbol sampled on the padded grid (its aliasing neglected here).

For every pass of the star's pull-off whose next pass detaches cells too, the script solves S
and T to rtol (an idealisation: the package decides passing sets early, with error bounds the
certificate would have to subtract) and reports how many of the next leavers the bound
certifies, how many passes would be skipped (all their leavers certified), the bound over the
true x1 at those cells, and the dense work per pass.  ``--update`` writes
docs/performance_griffith_certified.json (docs/performance.md).
"""

from __future__ import annotations

import argparse
import time

import _timing  # noqa: F401  (thread counts first)
import numpy as np
import scipy.fft as sfft

import bem_griffith as bg
import bem_griffith.driver as driver
import contact_scene as cs
from bem_griffith.counters import WorkCounters
from halfspace.kernel import lattice_symbol, point_kernel_transform

HEADERS = [
    "case",
    "reach (cells)",
    "passes followed by a pass",
    "next leavers",
    "certified",
    "passes all certified",
    "bound / true x1, median",
    "bound / true x1, least",
    "dense ms / pass",
]


def walk_steps(problem) -> tuple[float, np.ndarray]:
    """(D0, P): the lattice inverse's diagonal and the walk's step chances by offset, on the
    padded grid (periodic in it), from the inverse of the lattice symbol (zero mode 0)."""
    Mx, My = problem.operator.padded_shape
    A, k = problem.point_kernel
    transform = point_kernel_transform(k)
    symbol = lattice_symbol((Mx, My), problem.spacing, lambda q: A * transform(q))
    inverse = 1.0 / symbol
    inverse[0, 0] = 0.0
    T = sfft.irfft2(inverse, s=(Mx, My))
    D0 = float(T[0, 0])
    P = -T / D0
    P[0, 0] = 0.0
    return D0, P


def box(mask: np.ndarray, reach: int) -> np.ndarray:
    out = np.zeros(mask.shape, bool)
    for i, j in np.argwhere(mask):
        out[max(i - reach, 0) : i + reach + 1, max(j - reach, 0) : j + reach + 1] = True
    return out


def study(cells: int, reaches, outer: int) -> list[list]:
    star = cs.Scene(cs.Indenter(cs.Star(5, 1.0, 0.45)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    N = cells * star.indenter.shape.equivalent_radius / 2.0
    settings = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N))
    problem = bg.solver.build_problem(star, settings)
    assert problem.walk_bounds and problem.flat
    D0, P = walk_steps(problem)
    Mx, My = P.shape
    threshold = problem.critical_stress * (1 - settings.tie_tolerance)

    def steps(a, b):
        return P[(b[None, :, 0] - a[:, None, 0]) % Mx, (b[None, :, 1] - a[:, None, 1]) % My]

    # the passes of the package's own pull-off: (set before, set after, approach)
    solve = driver.solve_contact_set
    passes = []

    def recording(problem_, contact, settings_, previous, counters, *args, **kwargs):
        if len(args) >= 2 and args[1] is not None:
            passes.append((previous.contact.copy(), contact.copy(), args[1]))
        return solve(problem_, contact, settings_, previous, counters, *args, **kwargs)

    driver.solve_contact_set = recording
    try:
        bg.solve(star, settings)
    finally:
        driver.solve_contact_set = solve

    def exact(S):
        state = solve(problem, S, settings, None, WorkCounters())
        return state.pressure_per_approach, state.displacement_per_approach

    chains = []
    for (S, T, d), (T2, after, d2) in zip(passes, passes[1:], strict=False):
        if d2 == d and np.array_equal(T, T2) and (S & ~T).any() and (T & ~after).any():
            x1S, u1S = exact(S)
            x = np.zeros(S.shape)
            x[S] = x1S
            xT = np.zeros(S.shape)
            xT[T] = exact(T)[0]
            chains.append((S, T, T & ~after, d, x, u1S, xT))
    rows = []
    for reach in reaches:
        certified = candidates = full = 0
        ratios, dense = [], 0.0
        for S, T, leaving, d, x, u1S, xT in chains:
            start = time.process_time()
            R = S & ~T
            local = box(R, reach) & ~T  # free cells near R, R itself among them
            rim = box(R, outer) & ~T & ~local
            Lc, Wc, Qc, Rc = np.argwhere(local), np.argwhere(rim), np.argwhere(leaving), np.argwhere(R)
            escape_rim = np.clip(1.0 - u1S[rim], 0.0, 1.0)
            E = np.zeros(S.shape)
            E[local] = np.linalg.solve(np.eye(len(Lc)) - steps(Lc, Lc), steps(Lc, Wc) @ escape_rim)
            never_T = np.maximum(x[R] / D0, E[R])
            free = np.argwhere(local & ~R)
            first = steps(Qc, Rc)
            if len(free):
                through = np.linalg.solve(np.eye(len(free)) - steps(free, free), steps(free, Rc))
                first = first + steps(Qc, free) @ through
            bound = x[leaving] + D0 * (first @ never_T)
            dense += time.process_time() - start
            ok = -d * bound >= threshold
            certified += int(ok.sum())
            candidates += len(Qc)
            full += int(ok.all())
            ratios += list(bound / xT[leaving])
        rows.append(
            [
                f"star {cells}^2",
                reach,
                len(chains),
                candidates,
                f"{certified} ({certified / max(candidates, 1):.0%})",
                f"{full} ({full / max(len(chains), 1):.0%})",
                f"{np.median(ratios):.3f}",
                f"{np.min(ratios):.3f}",
                f"{1e3 * dense / max(len(chains), 1):.1f}",
            ]
        )
        print(_timing.table(rows, HEADERS), flush=True)
    return rows


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cells", type=int, nargs="+", default=[128, 256], help="grid cells across the star")
    parser.add_argument("--reach", type=int, nargs="+", default=[2, 4, 8], help="free patch around the leavers")
    parser.add_argument("--outer", type=int, default=16, help="free cells whose escape 1 - u1 is counted")
    parser.add_argument("--update", action="store_true", help="write docs/performance_griffith_certified.json")
    args = parser.parse_args(argv)
    record = _timing.provenance_record()
    rows = []
    for cells in args.cells:
        rows += study(cells, args.reach if cells == min(args.cells) else [4], args.outer)
    if args.update:
        _timing.write_doc_table("performance_griffith_certified", HEADERS, rows, record)


if __name__ == "__main__":
    main()
