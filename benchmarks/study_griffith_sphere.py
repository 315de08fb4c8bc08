"""JKR sphere: the Griffith BEM's pull-off force against resolution, raw and extrapolated.

    python benchmarks/study_griffith_sphere.py [--full] [--update]

The scene of ``crossval/scenes/jkr_sphere.toml`` (a paraboloid pressed without adhesion, then
pulled; JKR's pull-off 1.5 pi w R).  For each N (elements per face radius) prints
F_A / F_JKR - 1, that error times N (constant for a first-order error), the contact radius at
the pull-off over the face radius, the operator applications and the wall time; then the
Richardson extrapolation F = F_inf + c / N over the coarsest runs, the procedure
``tests/test_bem_griffith.py`` checks against JKR.  ``--full`` adds 112, 160 and 192 per face
radius (minutes each; 192 is where the slow test asks for the raw force within 1 %).
``--update`` writes the table to docs/accuracy_griffith_sphere.json (rendered into
docs/accuracy.md by ``python benchmarks/docs_tables.py``).
"""

from __future__ import annotations

import math
import sys
import time

import _timing
import numpy as np

import bem_griffith as bg
import contact_scene as cs
from contact_scene import theory as T
from crossval.suite import SCENE_DIR

DEFAULT = (16, 20, 24, 28, 32, 40, 56, 80)
FULL = (112, 160, 192)
EXTRAPOLATED = (16, 20, 24, 28, 32)  # the test's sweep
HEADERS = ["N/face radius", "F/F_JKR - 1", "(F/F_JKR - 1) N", "contact radius / face radius", "matvecs", "wall s"]


def main(Ns=DEFAULT, update=False):
    record = _timing.provenance_record()
    sc = cs.load_scene(SCENE_DIR / "jkr_sphere.toml")
    FJ = T.jkr_pulloff_force(work=sc.adhesion.work_of_adhesion, sphere_radius=sc.indenter.profile.radius)
    face = sc.indenter.shape.radius
    rows, err = [], {}
    for N in Ns:
        t = time.perf_counter()
        r = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)))
        wall = time.perf_counter() - t
        if not (r.converged and r.detached):
            raise RuntimeError(f"N = {N}: the pull-off did not converge or detach: {r.messages}")
        err[N] = r.pulloff_force / FJ - 1
        at = int(np.argmin(r.curve.force))  # the largest tension
        contact = math.sqrt(r.curve.contact_area[at] / math.pi) / face
        rows.append([N, f"{err[N]:+.4f}", f"{err[N] * N:+.3f}", f"{contact:.3f}", r.info["matvecs"], f"{wall:.1f}"])
        print(_timing.table(rows, HEADERS), flush=True)
    fit = [N for N in EXTRAPOLATED if N in err]
    if len(fit) >= 2:
        _, e_inf = np.polyfit(1 / np.array(fit, float), [err[N] for N in fit], 1)
        rows.append([f"c/N fit over {fit[0]}-{fit[-1]}", f"{e_inf:+.4f}", "", "", "", ""])
        print(_timing.table(rows, HEADERS))
    if update:
        _timing.write_doc_table("accuracy_griffith_sphere", HEADERS, rows, record)


if __name__ == "__main__":
    args = sys.argv[1:]
    main(DEFAULT + (FULL if "--full" in args else ()), update="--update" in args)
