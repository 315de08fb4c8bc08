"""The energy BEM's own noise: how much F_A moves when only the loading path changes.

Near the force maximum of a finite range F(d) is jagged: different minimiser paths end in
different peeled states at the same approach, so an algorithmic change that alters the path
(step count, tolerances, warm starts) moves F_A even though the physics is the same.  This
measures that spread directly: one range of the zero-range sequence (l_c / a given, two
elements per l_c, at least 24 per radius, as ``ZeroRangeSettings()`` runs it) solved with
continuation step counts around the default 40, with the full snap-off bisection at the
default tolerance.  Printed per face: F_A for each step count and the spread (max - min) / mean.
A change of the algorithm that moves a range's F_A by less than this spread is within the
method's noise.

    python benchmarks/study_energy_noise.py [--ratio 0.04] [--steps 36,38,40,42,44]
        [--faces circle,square,triangle] [--json PATH] [--update]

``--update`` writes the table to docs/performance_energy_noise.json (rendered into
docs/performance.md by ``python benchmarks/docs_tables.py``).
"""

from __future__ import annotations

import argparse
import json
import math
import time

import _timing  # thread settings first
from _timing import table

import bem_energy as be
import contact_scene as cs

W = 0.02
FACES = {
    "circle": lambda: cs.Circle(1.0),
    "square": lambda: cs.Square(2.0),
    "triangle": lambda: cs.Triangle.equilateral(2.0),
}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--ratio", type=float, default=0.04, help="l_c / a of the range")
    ap.add_argument("--steps", default="36,38,40,42,44")
    ap.add_argument("--faces", default="circle,square,triangle")
    ap.add_argument("--json", default=None)
    ap.add_argument("--update", action="store_true", help="write docs/performance_energy_noise.json")
    args = ap.parse_args(argv)
    record = _timing.provenance_record()
    steps = [int(s) for s in args.steps.split(",")]
    zs = be.ZeroRangeSettings()
    rows, out = [], {}
    for name in args.faces.split(","):
        shape = FACES[name]()
        a = shape.equivalent_radius
        lc = args.ratio * a
        rho = math.sqrt(W * lc)
        h = min(lc / zs.elements_per_process_zone, a / zs.minimum_elements_per_radius)
        sc = cs.Scene(cs.Indenter(shape), cs.Homogeneous(1.0, 0.0), cs.Adhesion(W, rho))
        forces = []
        for n in steps:
            t = time.perf_counter()
            r = be.pull_off(sc, be.EnergySettings(grid=cs.Grid(spacing=h), steps=n), spacing=h)
            forces.append(r.pulloff_force)
            print(
                f"  {name} steps {n}: F_A = {r.pulloff_force:.8f} ({r.info['peak']}, {time.perf_counter() - t:.1f} s)",
                flush=True,
            )
        mean = sum(forces) / len(forces)
        spread = (max(forces) - min(forces)) / mean
        rows.append((name, f"{args.ratio:g}", round(a / h), *[f"{f:.6f}" for f in forces], f"{spread:.1e}"))
        out[name] = {
            "ratio": args.ratio,
            "elements_per_radius": a / h,
            "steps": steps,
            "forces": forces,
            "spread": spread,
        }
    head = ("face", "l_c/a", "per radius", *[f"steps {n}" for n in steps], "spread")
    print(table(rows, head))
    if args.update:
        _timing.write_doc_table("performance_energy_noise", head, rows, record)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh, indent=1)


if __name__ == "__main__":
    main()
