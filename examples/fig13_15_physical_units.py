"""
Figs. 13-15: triangle, star and two circles in physical units
=============================================================

The simulation side of Figs. 13-15: a triangle, a star and two circles with the moduli and
works of adhesion the paper fitted to its gelatin experiments.

The paper gives E* and w for each face but not the faces' dimensions; the sizes below are
assumed (laser-cut faces of a few centimetres), so the forces are of the right order, not a
reproduction of the measured curves.  What the example checks is what the paper says of the
simulations: F first rises linearly with the stiffness of the whole face (drawn as its Holm
radius, Eqs. 15-17), detachment starts at the corners and tips, the triangle and the star pass
a force maximum before the last stable state, and the two circles give two maxima: the first
when the small lobe goes, the second the large circle's own Kendall force (Eq. 6).

Everything is in SI units (m, Pa, N/m); a solve of the same scene in scaled units (E* = w = 1,
lengths / L) gives the same numbers after scaling by sqrt(E* w L^3) and sqrt(w L / E*).

The short version runs 24 elements per equivalent radius, the full version 48::

    python examples/fig13_15_physical_units.py        # full version, writes fig13_15_physical_units.png
    from examples.fig13_15_physical_units import run  # short version (used by the tests)
"""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.signal import find_peaks

import contact_scene as cs
from contact_scene import theory as T

try:  # imported as examples.<name> (tests) or run as a script
    from examples import _gallery
except ImportError:
    import _gallery

MM = 1e-3
# face, E* [Pa], w [N/m]: the paper's fits (Figs. 13, 14, 15); face sizes assumed
FACES = {
    "triangle": (cs.Triangle.equilateral(30 * MM), 6.02e3, 0.062),
    "star": (cs.Star(5, 15 * MM, 7 * MM), 7.60e3, 0.060),
    "two circles": (cs.TwoCircles(10 * MM, 5 * MM, 13.5 * MM), 9.28e3, 0.030),
}


def scene(name: str) -> cs.Scene:
    face, E_star, w = FACES[name]
    return cs.Scene(cs.Indenter(face), cs.Homogeneous(0.75 * E_star, 0.5), cs.Adhesion(w))


def run(resolution: float = 16, names=None, *, prominence: float = 0.02) -> dict:
    """Pull each face off with ``resolution`` elements per equivalent radius sqrt(A/pi).

    A force maximum counts when it stands out by ``prominence`` of the largest force (the
    event-driven curve has steps of a few per mille from single elements)."""
    import bem_griffith as bg

    out = {}
    for name in names or FACES:
        face, E_star, w = FACES[name]
        r = bg.solve(scene(name), bg.GriffithSettings(grid=cs.Grid(elements_per_radius=resolution)))
        tension = -r.curve.force
        peaks, _ = find_peaks(np.r_[0.0, tension, 0.0], prominence=prominence * tension.max())
        peaks = peaks - 1
        inc = face.incircle().radius
        out[name] = {
            "result": r,
            "E_star": E_star,
            "work": w,
            "maxima": [(float(tension[i]), float(r.curve.approach[i])) for i in peaks],
            "holm_radius": T.holm_radius(stiffness=r.stiffness, E_star=E_star),
            "F_over_upper": r.pulloff_force / T.upper_bound_force(E_star=E_star, work=w, area=face.area),
            "last_force_over_max": -r.last_stable.force / r.pulloff_force,
            "last_area_over_incircle": r.last_stable.contact_area / (np.pi * inc**2),
        }
    return out


def scaled(name: str, length: float) -> cs.Scene:
    """The same scene in units where E* = w = 1 and lengths are divided by ``length``."""
    face, _, _ = FACES[name]
    sc = scene(name)
    return dataclasses.replace(
        sc,
        indenter=cs.Indenter(cs.Transformed(face, scale=1 / length)),
        material=cs.Homogeneous(0.75, 0.5),
        adhesion=cs.Adhesion(1.0),
    )


def plot(out: dict, path=None):
    """Curves (top) and last stable contacts (bottom), every length in mm, every force in mN."""
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    fig, axs = plt.subplots(2, 3, figsize=(12, 7.8), layout="constrained")
    for col, (name, o) in enumerate(out.items()):
        r = o["result"]
        ax = axs[0, col]
        ax.plot(-r.curve.approach / MM, -r.curve.force * 1e3, "r-", label="BEM (Griffith)")
        ax.plot([-d / MM for _, d in o["maxima"]], [F * 1e3 for F, _ in o["maxima"]], "ko", ms=4, label="force maxima")
        ls = r.last_stable
        ax.plot(-ls.approach / MM, -ls.force * 1e3, "bs", ms=4, mfc="none", label="last stable state")
        ax.set_xlabel("pull-off distance -d [mm]")
        ax.set_ylabel("attracting force -F [mN]")
        ax.set_title(f"{name}: E* = {o['E_star'] / 1e3:.2f} kPa, w = {o['work']:.3f} N/m", fontsize=9)
        ax.legend(fontsize=7, loc="upper left")
        ax = axs[1, col]
        face = FACES[name][0]
        cx, cy = face.centroid
        R = o["holm_radius"]
        _gallery.contact_map(
            ax,
            ls,
            cs.rasterise(face, r.grid_spacing).mask,
            scale=MM,
            unit="mm",
            title=f"{name}: last stable contact, -d = {-ls.approach / MM:.3f} mm\nHolm radius {R / MM:.1f} mm",
        )
        ax.add_patch(plt.Circle((cx / MM, cy / MM), R / MM, fill=False, color="g"))
        # show the whole Holm circle: it can reach beyond the face
        x0, x1 = ax.get_xlim()
        y0, y1 = ax.get_ylim()
        pad = 0.5
        ax.set_xlim(min(x0, (cx - R) / MM - pad), max(x1, (cx + R) / MM + pad))
        ax.set_ylim(min(y0, (cy - R) / MM - pad), max(y1, (cy + R) / MM + pad))
    holm = Line2D([], [], color="g", label="Holm radius: the circle of the face's computed stiffness (Eqs. 15-17)")
    fig.legend(handles=_gallery.contact_handles([holm]), loc="outside lower center", fontsize=8, ncols=3)
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def report(out: dict) -> None:
    for name, o in out.items():
        r = o["result"]
        maxima = ", ".join(f"{F * 1e3:.2f} mN at {d / MM:.3f} mm" for F, d in o["maxima"])
        print(
            f"{name:>12}: F_A = {r.pulloff_force * 1e3:.2f} mN at d = {r.pulloff_approach / MM:.3f} mm"
            f" (F/F_upper = {o['F_over_upper']:.3f}); maxima: {maxima}; Holm radius {o['holm_radius'] / MM:.2f} mm;"
            f" last stable: F/F_max = {o['last_force_over_max']:.3f},"
            f" area/incircle = {o['last_area_over_incircle']:.3f}"
        )


def main(path=None, resolution: float = 48) -> None:
    import matplotlib

    matplotlib.use("Agg")
    out = run(resolution)
    plot(out, path or _gallery.picture_path("fig13_15_physical_units"))
    report(out)


if __name__ == "__main__":
    if _gallery.short_run():
        out = run(24)
        plot(out)
        report(out)
    else:
        main()
