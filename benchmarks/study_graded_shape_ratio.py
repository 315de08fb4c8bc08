"""Does grading change a square's strength relative to a circle's the same way in both BEMs?

    python benchmarks/study_graded_shape_ratio.py [--quick | --full] [--update]

The calibrated graded criterion (``bem_griffith.criterion``) fixes one factor per k on the
circle; a square inherits it.  The Griffith solver's square/circle ratio does not depend on
that factor, so what can be checked independently is the ratio itself.  This script compares
the "double ratio" D(k) = [F_square / F_circle](k) / [F_square / F_circle](k = 0), equal
areas, forces scaled to the nominal area, between

* the Griffith BEM (Eq. 42's constant: the ratios do not depend on it) at 32 ... 96 elements
  per radius, and
* the energy BEM at finite process zones l_c / a = 0.32 ... 0.02 with 8 elements per l_c
  (the graded process zone l_c^(1-k) = E_k rho^2 / w, ``bem_energy.potentials``),

at k = 0.5.  The energy method is not a converged reference here: its circle alone still
moves by percents per halving of l_c, so the table shows the trend, not a limit.  The default
stops the energy BEM at l_c / a = 0.08; ``--full`` adds 0.04 and 0.02 (8 elements per l_c:
400 per radius at 0.02, tens of minutes per face), ``--quick`` stops at 0.08 and 48 per
radius.  ``--update`` writes the table to docs/accuracy_graded_shape_ratio.json (rendered
into docs/accuracy.md by ``python benchmarks/docs_tables.py``).
"""

from __future__ import annotations

import math
import sys

import _timing  # noqa: F401

import bem_energy as be
import bem_griffith as bg
import contact_scene as cs
from bem_energy.potentials import process_zone_modulus, range_for_process_zone
from contact_scene import theory as T

FACES = {"circle": cs.Circle(1.0), "square": cs.Square(math.sqrt(math.pi))}  # both of area pi
K = 0.5


def griffith(N):
    out = {}
    for k in (0.0, K):
        for name, face in FACES.items():
            r = bg.solve(
                cs.Scene(cs.Indenter(face), cs.PowerLawGraded(1.0, 1.0, k), cs.Adhesion(1.0)),
                bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N), graded_criterion="eq42"),
            )
            out[k, name] = T.force_at_nominal_area(
                r.pulloff_force, area=r.info["face_elements"] * r.grid_spacing**2, nominal_area=math.pi, k=k
            )
    return out


def energy(lc_over_a, per_zone=8.0, work=0.02):
    out = {}
    for k in (0.0, K):
        mat = cs.PowerLawGraded(1.0, 1.0, k)
        for name, face in FACES.items():
            h = min(lc_over_a / per_zone, 1 / 24)
            rho = range_for_process_zone(modulus=process_zone_modulus(mat), work=work, length=lc_over_a, exponent=k)
            r = be.pull_off(
                cs.Scene(cs.Indenter(face), mat, cs.Adhesion(work)),
                be.EnergySettings(grid=cs.Grid(spacing=h)),
                spacing=h,
                potential=be.Potential(work, rho),
            )
            out[k, name] = T.force_at_nominal_area(
                r.pulloff_force, area=cs.rasterise(face, h).area, nominal_area=math.pi, k=k
            )
    return out


def row(label, out):
    r0 = out[0.0, "square"] / out[0.0, "circle"]
    rk = out[K, "square"] / out[K, "circle"]
    return [label, f"{r0:.4f}", f"{rk:.4f}", f"{rk / r0:.4f}"]


def main(Ns=(32, 48, 64, 96), lcs=(0.32, 0.16, 0.08), update=False):
    record = _timing.provenance_record()
    headers = ["method", "square/circle k=0", f"square/circle k={K}", "D"]
    rows = []
    for N in Ns:
        rows.append(row(f"Griffith, {N} per radius", griffith(N)))
        print(_timing.table(rows, headers), flush=True)
    for lc in lcs:
        rows.append(row(f"energy, l_c/a = {lc}", energy(lc)))
        print(_timing.table(rows, headers), flush=True)
    if update:
        _timing.write_doc_table("accuracy_graded_shape_ratio", headers, rows, record)


if __name__ == "__main__":
    update = "--update" in sys.argv
    if "--quick" in sys.argv:
        main(Ns=(32, 48), lcs=(0.32, 0.16, 0.08), update=update)
    elif "--full" in sys.argv:
        main(lcs=(0.32, 0.16, 0.08, 0.04, 0.02), update=update)
    else:
        main(update=update)
