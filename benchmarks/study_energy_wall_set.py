"""What the energy BEM's slowest continuation step waits for: the set of cells at the wall.

    python benchmarks/study_energy_wall_set.py [--face triangle] [--ratio 0.01]

Runs one range of the zero-range sequence (the triangle's finest default range, l_c = 0.01 a;
the range and the re-runs below take a few minutes on one core) and prints its pull-off force.
Of its pulling trials (``Equilibria.pulling_trial``: continuation steps and snap-off trials)
that were not stopped as peeling off, it keeps the one that took most iterations (on the
triangle an attached continuation step), prints its approach, iterations and force, and
minimises it again from the same start, stopped after k iterations for a list of k (the
minimiser is deterministic, so each run retraces the full one).  For each k it prints:

* the distance ||U_k - U*|| over the face cells relative to the start's, U* the converged state;
* the cosine between the distance vectors at k and at the k before (1: direction unchanged);
* the cells at the wall at k that are free at U* (they have to leave it) and those at the wall
  at U* that are not yet at k (they have to join it);
* in how many patches (8-connected groups of cells) the cells to leave lie;
* the share of the squared distance on cells whose gap at U* is below 5 rho (rho the
  potential's range), and the force.

Then two restarts from U_85 (a state in the stall): CG restarted from U_85 itself, and from the
lowest-energy of six multiples t = 0.5 ... 16 of U_85 - U_70 (the iterates' own progress),
projected onto the wall (U_85 itself if none is lower), with the iterations each needs to
converge.  Last, the trial started with the cells that are at the wall in the start but free at
U* lifted to their displacements at U* (an oracle that frees exactly the right cells), and
lifted by rho / 10 only.  Prints tables only; docs/performance.md quotes them.
"""

from __future__ import annotations

import argparse
import time
from typing import Any

import _timing
import numpy as np
from scipy import ndimage

import bem_energy as be
import contact_scene as cs
from bem_energy import equilibria
from bem_energy.minimisers import Minimum, minimise
from bem_energy.zero_range import sequence_run

FACES = {
    "triangle": lambda: cs.Triangle.equilateral(2.0),
    "square": lambda: cs.Square(2.0),
    "circle": lambda: cs.Circle(1.0),
}
STOPS = (10, 25, 40, 55, 70, 85, 100, 115, 130, 145, 160)


def slowest_pulling_step(scene: cs.Scene, ratio: float, settings: be.ZeroRangeSettings) -> dict[str, Any]:
    """Run the range, recording every pulling trial's problem, warm start and iterations."""
    seen: list[dict[str, Any]] = []
    original = equilibria.Equilibria.pulling_trial

    def recording(self, U0, d, adhesive):
        m = original(self, U0, d, adhesive)
        if not m.peeled:
            seen.append(
                {"prob": self.prob, "settings": self.settings, "U0": U0.copy(), "d": d, "iterations": m.iterations}
            )
        return m

    equilibria.Equilibria.pulling_trial = recording  # type: ignore[method-assign]
    try:
        t = time.process_time()
        _, result = sequence_run(scene, ratio, settings)
        print(f"range l_c = {ratio} a: F_A = {result.pulloff_force:.6f}, {time.process_time() - t:.0f} CPU s")
    finally:
        equilibria.Equilibria.pulling_trial = original  # type: ignore[method-assign]
    return max(seen, key=lambda s: s["iterations"])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--face", choices=sorted(FACES), default="triangle")
    parser.add_argument("--ratio", type=float, default=0.01, help="l_c / a of the range")
    args = parser.parse_args()
    scene = cs.Scene(cs.Indenter(FACES[args.face]()), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.02))
    settings = be.ZeroRangeSettings()
    step = slowest_pulling_step(scene, args.ratio, settings)
    prob, es, U0, d = step["prob"], step["settings"], step["U0"], step["d"]
    options = dict(
        method=es.minimiser,
        gtol=es.gtol,
        memory=es.memory,
        restart_on_wall_change=es.restart_on_wall_change,
        single_precision_directions=es.single_precision_directions,
    )

    def run(start: np.ndarray, iterations: int = es.max_iterations) -> Minimum:
        return minimise(prob, start, d, True, max_iterations=iterations, **options)

    full = run(U0)
    rho = prob.potential.range
    wall = d - prob.height
    gap_min = prob.on_face(full.U) - wall
    at_wall_min = gap_min <= 1e-13 * rho
    near = gap_min < 5 * rho
    e0 = prob.on_face(U0) - prob.on_face(full.U)
    print(f"slowest pulling trial: d = {d:.6g}, {full.iterations} iterations, F = {prob.force(full.P):.9f}\n")
    rows, previous = [], e0
    for k in (k for k in STOPS if k < full.iterations):
        m = run(U0, k)
        e = prob.on_face(m.U) - prob.on_face(full.U)
        at_wall = prob.on_face(m.U) - wall <= 1e-13 * rho
        cosine = float(e @ previous / (np.linalg.norm(e) * np.linalg.norm(previous)))
        to_leave = at_wall & ~at_wall_min
        on_grid = np.zeros(prob.face_block.shape, bool)
        on_grid[prob.face_block] = to_leave
        patches = ndimage.label(on_grid, np.ones((3, 3), bool))[1]
        rows.append(
            [
                k,
                f"{np.linalg.norm(e) / np.linalg.norm(e0):.2e}",
                f"{cosine:.3f}",
                int(to_leave.sum()),
                int((~at_wall & at_wall_min).sum()),
                patches,
                f"{float(np.sum(e[near] ** 2) / np.sum(e**2)):.2f}",
                f"{prob.force(m.P):.6f}",
            ]
        )
        previous = e
    headers = ["k", "|e_k|/|e_0|", "cos(e_k, e_prev)", "to leave", "to join", "patches", "share within 5 rho", "F"]
    print(_timing.table(rows, headers))

    m70, m85 = run(U0, 70), run(U0, 85)
    plain = run(m85.U)
    progress = m85.U - m70.U
    face = (slice(0, prob.n[0]), slice(0, prob.n[1]))

    def projected(U: np.ndarray) -> np.ndarray:
        out = U.copy()
        out[face][prob.face_block] = np.maximum(prob.on_face(U), wall)
        return out

    energy_85 = prob.energy_state(m85.U, d, True).energy
    trials = [(t, prob.energy_state(projected(m85.U + t * progress), d, True).energy) for t in (0.5, 1, 2, 4, 8, 16)]
    best, energy = min(trials, key=lambda te: te[1])
    start = projected(m85.U + best * progress) if energy < energy_85 else m85.U
    extrapolated = run(start)
    print(
        "\nfrom U_85: restarted as it is, "
        f"{plain.iterations} more iterations ({85 + plain.iterations} in all, F = {prob.force(plain.P):.9f}); "
        f"after the line search along U_85 - U_70 (best t = {best}, energy change {energy - energy_85:.2e}), "
        f"{extrapolated.iterations} more ({85 + extrapolated.iterations} in all, "
        f"F = {prob.force(extrapolated.P):.9f}); "
        f"uninterrupted: {full.iterations}"
    )

    at_wall_start = prob.on_face(U0) - wall <= 1e-13 * rho
    leaving = at_wall_start & ~at_wall_min
    for name, lifted in (
        ("to their displacements at the minimum", prob.on_face(full.U)),
        ("by rho / 10", prob.on_face(U0) + 0.1 * rho),
    ):
        start = U0.copy()
        on_face = prob.on_face(start).copy()
        on_face[leaving] = lifted[leaving]
        start[face][prob.face_block] = on_face
        m = run(start)
        print(
            f"the {int(leaving.sum())} cells at the wall in the start that leave it, lifted {name}: "
            f"{m.iterations} iterations (converged: {m.converged}, F = {prob.force(m.P):.9f}, "
            f"largest change of U from the minimum {np.abs(m.U - full.U).max():.2e})"
        )


if __name__ == "__main__":
    main()
