"""A candidate detachment criterion for the Griffith BEM, measured and not adopted: the
crack-closure energy release of the contact front, smoothed along it.

    python benchmarks/study_griffith_closure.py [--faces circle square triangle]
        [--grids 32 45 64 90 128] [--circle-grids 181 256] [--circle-finest 362 510]
        [--widths 0.7 1 1.4]
        [--cache DIR] [--update]

Issue #22 asks for a detachment criterion that converges both on smooth fronts (where the
paper's cell-stress rule, Eq. 22, keeps a staircase bias) and at corners (where the fitted
stress-intensity rule of ``bem_griffith.stress_intensity`` lets go too early).  This script
measures one more candidate, built on the solver's own energy instead of a fitted field.

For a flat punch held at approach d on a contact set S, peeling a layer L of cells releases d^2
(K(S) - K(S minus L)) / 2 of elastic energy (K the stiffness, cell area times the sum of the
pressures per approach x1).  With g the gaps per approach at L once L is peeled, that
difference is exactly the sum of x1_i g_i over L (crack closure: the tractions that held L
close the gaps that open; tests/test_griffith_closure_study.py).  Each front cell's share,
smoothed by an isotropic Gaussian of width sigma = c sqrt(N) cells (N elements per equivalent
radius) over the cells of the layer and divided by the smoothed peeled area, estimates the
local release rate G over d^2 (variant "one layer": L the front layer, the contact cells with a
4-neighbour outside S; across a narrow detached region the Gaussian also reaches the front on
its far side).  A one-sided advance of one cell over-estimates G by a term of order Delta / a
(the mean of G over the advance); peeling two layers and taking 2 G_1 - G_2 removes it (variant
"two layers").  A front cell detaches where G >= w.  On a fixed set G is proportional to d^2,
so each event's approach is exact; the driver below solves every set to ``RTOL`` with the
package's contact solver (no early decisions, which the package's driver takes under the
paper's rule only), detaches at each pass every front cell whose release is within a relative
``TIE`` of the threshold w / d^2 (TIE / 2 in the approach, the release growing like d^2; the
package's ``tie_tolerance`` acts on the stress, which grows like d: without such a tie the
cells of a symmetric face go one by one in an order set by the solver's round-off, and the
pull-off moves with it), and stops once the force has fallen to half its largest value (a
heuristic end: the force only falls during a cascade at a fixed approach).

Each row: the face, the variant, c, N, the pull-off force scaled to the nominal area (F ~
A^(3/4)) over Kendall's force (circle) or Eq. 13's upper bound (the other faces), the
contact passes and the detachment events, and the CPU time.  Then, per series, the limit of
the least-squares q0 + c1 / N through its finest four grids (the reference table's Griffith
fit), with the note of the fits through the finest three and five and whether the finest four
values move monotonically; the rate 1/N is assumed, not verified for this criterion
(its smoothing width shrinks like 1/sqrt(N) of the face).  The faces are those of
``benchmarks/study_griffith_criterion.py``: the circle of radius 1 and the square of area pi,
and the built-in triangle (E* = 1, w = 1); the circle also at 181 and 256 per radius, and in
the one-layer variant at 362 and 510 (minutes each), where Eq. 22's error has settled (the
first table of docs/accuracy.md).  ``--update`` writes
docs/accuracy_griffith_closure.json (rendered into docs/accuracy.md by
``python benchmarks/docs_tables.py``); every pull-off is cached under ``--cache`` as it
finishes, so an interrupted run resumes.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import _timing
import numpy as np
from scipy import signal

import bem_griffith as bg
import contact_scene as cs
from bem_griffith.contact_set import ContactSolution, solve_contact_set
from bem_griffith.counters import WorkCounters
from bem_griffith.problem import Problem, build_problem
from bem_griffith.stress_intensity import front_cells
from contact_scene import theory as T

HEADERS = ["face", "variant", "c", "N/radius", "F_A ratio", "passes", "events", "cpu s", "note"]
RTOL = 1e-9
TIE = 1e-6
VARIANTS = ("one layer", "two layers")
CACHE = Path(__file__).resolve().parent / ".closure_cache"


def closure_shares(problem: Problem, solution: ContactSolution, layer: np.ndarray, settings) -> np.ndarray:
    """x1_i g_i times the cell area on ``layer`` (zero elsewhere): each cell's share of the
    stiffness lost when ``layer`` is peeled from ``solution.contact``, so that the shares sum
    to K(S) - K(S minus layer)."""
    peeled = solve_contact_set(problem, solution.contact & ~layer, settings, solution, WorkCounters())
    if not peeled.converged:
        raise RuntimeError(f"a peeled contact solve did not converge (residual {peeled.residual:.2e})")
    x1 = np.zeros(layer.shape)
    x1[solution.contact] = solution.pressure_per_approach
    gap = 1.0 - peeled.displacement_per_approach
    return np.where(layer, x1 * gap, 0.0) * problem.cell_area


def gaussian(sigma: float) -> np.ndarray:
    reach = int(math.ceil(3 * sigma))
    y, x = np.mgrid[-reach : reach + 1, -reach : reach + 1]
    return np.exp(-0.5 * (x**2 + y**2) / sigma**2)


def release_per_approach_squared(problem, solution, settings, sigma: float, variant: str) -> np.ndarray | None:
    """G / d^2 at each front cell of ``solution`` (zero elsewhere); None when peeling the front
    would leave no contact."""
    contact = solution.contact
    front = front_cells(contact)
    kernel = gaussian(sigma)

    def smoothed(layer):
        shares = closure_shares(problem, solution, layer, settings)
        area = layer * problem.cell_area
        return (
            0.5
            * signal.oaconvolve(shares, kernel, mode="same")
            / np.maximum(signal.oaconvolve(area, kernel, mode="same"), 1e-300)
        )

    if front.sum() == contact.sum():
        return None
    one = smoothed(front)
    if variant == "one layer":
        return np.where(front, one, 0.0)
    both = front | front_cells(contact & ~front)
    if both.sum() == contact.sum():
        return np.where(front, one, 0.0)
    return np.where(front, 2.0 * one - smoothed(both), 0.0)


def pull(scene: cs.Scene, N: int, c: float, variant: str) -> dict:
    """The pull-off of a flat face under the closure criterion (see the module docstring)."""
    settings = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), rtol=RTOL)
    problem = build_problem(scene, settings)
    sigma = c * math.sqrt(N)
    work = scene.adhesion.work_of_adhesion
    solution = solve_contact_set(problem, problem.face.copy(), settings, None, WorkCounters())
    approach, largest, passes, events = 0.0, 0.0, 0, 0
    while True:
        release = release_per_approach_squared(problem, solution, settings, sigma, variant)
        passes += 1
        if release is None:
            break
        stiffness = problem.cell_area * float(solution.pressure_per_approach.sum())
        if not release.max() > 0:
            raise RuntimeError(f"N = {N}: no front cell releases energy ({variant}, c = {c:g})")
        needed = -math.sqrt(work / release.max())  # where the most released front cell reaches w
        if needed < approach:  # the set holds until then: pull on to it
            approach = needed
            events += 1
            largest = max(largest, -approach * stiffness)
        leaving = release >= work / approach**2 * (1 - TIE)
        contact = solution.contact & ~leaving
        if not contact.any():
            break
        solution = solve_contact_set(problem, contact, settings, solution, WorkCounters())
        if not solution.converged:
            raise RuntimeError(f"N = {N}: a contact solve did not converge (residual {solution.residual:.2e})")
        # a heuristic end: the force only falls during a cascade at a fixed approach, and a face
        # whose force has halved since its largest is taken to be letting go
        if -approach * problem.cell_area * float(solution.pressure_per_approach.sum()) < 0.5 * largest:
            break
    return {
        "pulloff_force": largest,
        "face_area": float(problem.face.sum() * problem.cell_area),
        "passes": passes,
        "events": events,
    }


def first_order_limits(points) -> dict[str, float]:
    """q0 of the least-squares q0 + c1 / N through the finest three, four and five of
    ``points`` ((N, q) in increasing N): the reference table's Griffith fits."""
    n, q = np.array(points, float).T
    return {f"finest {k}": float(np.polyfit(1.0 / n[-k:], q[-k:], 1)[1]) for k in (3, 4, 5)}


def scene_of(face: str) -> tuple[cs.Scene, float, float]:
    """The scene, its nominal area and the force the ratio is taken to."""
    if face == "circle":
        scene = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
        return scene, math.pi, T.kendall_adhesion_force(E_star=1.0, radius=1.0, work=1.0)
    if face == "square":
        scene = cs.Scene(cs.Indenter(cs.Square(math.sqrt(math.pi))), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
        return scene, math.pi, T.upper_bound_force(E_star=1.0, work=1.0, area=math.pi)
    from crossval.suite import load_scene_or_builtin

    scene = load_scene_or_builtin(face)
    area = scene.indenter.shape.area
    modulus, work = scene.material.effective_modulus, scene.adhesion.work_of_adhesion
    return scene, area, T.upper_bound_force(E_star=modulus, work=work, area=area)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--faces", nargs="+", default=["circle", "square", "triangle"])
    parser.add_argument("--grids", type=int, nargs="+", default=[32, 45, 64, 90, 128])
    parser.add_argument("--circle-grids", type=int, nargs="*", default=[181, 256], help="the circle's finer grids")
    parser.add_argument(
        "--circle-finest",
        type=int,
        nargs="*",
        default=[362, 510],
        help="the circle's finest grids, one-layer variant only (minutes each)",
    )
    parser.add_argument("--widths", type=float, nargs="+", default=[0.7, 1.0, 1.4], help="c in sigma = c sqrt(N)")
    parser.add_argument("--cache", type=Path, default=CACHE)
    parser.add_argument("--update", action="store_true")
    args = parser.parse_args(argv)
    record = _timing.provenance_record()
    rows, series, runs = [], {}, {}
    for face in args.faces:
        scene, nominal, reference = scene_of(face)
        plan = [(variant, c) for variant in VARIANTS for c in args.widths]
        for variant, c in plan:
            grids = args.grids
            if face == "circle":
                grids = grids + args.circle_grids + (args.circle_finest if variant == "one layer" else [])
            points, revisions = [], []
            for N in grids:
                key = (face, variant.replace(" ", "_"), f"{c:g}", N)
                run = _timing.cached(args.cache, key, lambda: pull(scene, N, c, variant))
                scaled = T.force_at_nominal_area(run["pulloff_force"], area=run["face_area"], nominal_area=nominal)
                ratio = scaled / reference
                points.append((N, ratio))
                rows.append(
                    [
                        face,
                        variant,
                        f"{c:g}",
                        N,
                        f"{ratio:.5f}",
                        run["passes"],
                        run["events"],
                        f"{run['cpu_s']:.1f}",
                        "",
                    ]
                )
                revisions.append((key, run["revision"]))
                print(_timing.table(rows[-1:], HEADERS), flush=True)
            if len(points) >= 5:
                limits = first_order_limits(points)
                series[f"{face}, {variant}, c = {c:g}"] = limits
                last = [q for _, q in points[-4:]]
                steps = np.diff(last)
                monotone = bool(np.all(steps > 0) or np.all(steps < 0))
                note = (
                    f"finest 3: {limits['finest 3']:.5f}, finest 5: {limits['finest 5']:.5f}; "
                    f"finest four {'monotone' if monotone else 'not monotone'}"
                )
                finest = ", ".join(str(n) for n, _ in points[-4:])
                rows.append(
                    [face, variant, f"{c:g}", f"q0 + c1/N over {finest}", f"{limits['finest 4']:.5f}", "", "", "", note]
                )
            runs.update({"__".join(str(k) for k in key): revision for key, revision in revisions})
    print(_timing.table(rows, HEADERS))
    if args.update:
        _timing.write_doc_table("accuracy_griffith_closure", HEADERS, rows, record, limits=series, runs=runs)


if __name__ == "__main__":
    main()
