"""
Fig. 9: a star designed for a constant force
============================================

A star whose rays thin like phi(r) = (r0/r)^3 pulls off at a nearly constant force.

Eq. 28 gives F = sqrt(8 pi E* a^3 phi(a) w) for a contact of outer radius a and ring filling
factor phi(a); with phi = (r0/a)^3 (Eq. 29) a drops out, F = F0 = sqrt(8 pi E* w r0^3).  For
comparison, a full disc's Kendall force grows like a^(3/2): a factor 1.84 between a = 0.6 and
0.9 of the outer radius.  The outer radius a of the remaining contact is read off its area,
A(a) = 3 pi r0^2 - 2 pi r0^3 / a for the designed face.  The right panel draws the full
disc's Kendall force, (a / r0)^(3/2) in units of F0, and the same power scaled to the
plateau at the window's smallest a, a guide to compare the slopes.

The level of the plateau is not F0: Eq. 28 takes the stiffness of the full disc of radius a,
while the star's stiffness grows more slowly with a (thin rays add little), and
F = K d with d^2 = 4 pi w a phi / K'(a) rises when K' falls.

The short version runs 24 elements per core radius, the full version 48::

    python examples/fig09_constant_force.py        # full version, writes fig09_constant_force.png
    from examples.fig09_constant_force import run  # short version (used by the tests)
"""

from __future__ import annotations

import math

import numpy as np

import contact_scene as cs

try:  # imported as examples.<name> (tests) or run as a script
    from examples import _gallery
except ImportError:
    import _gallery

R0 = 0.5  # core radius; the rays follow Eq. 29 out to OUTER


def run(resolution: float = 16, *, n_rays: int = 8, outer: float = 1.0, window=(0.6, 0.9)) -> dict:
    """Pull the star off with ``resolution`` elements per core radius.

    ``window`` is the range of a / outer over which the plateau is measured (away from the
    core, where the face is a full disc, and from the tips, a few cells wide).
    """
    import bem_griffith as bg

    star = cs.PowerLawStar(n_rays=n_rays, core_radius=R0, outer_radius=outer, samples=128)
    scene = cs.Scene(cs.Indenter(star), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    r = bg.solve(scene, bg.GriffithSettings(grid=cs.Grid(spacing=R0 / resolution)))
    F0 = math.sqrt(8 * math.pi * R0**3)
    c = r.curve
    a = contact_radius(c.contact_area)
    pulling = np.arange(len(a)) >= int(np.argmax(c.contact_area < c.contact_area[0]))  # detachment under way
    m = pulling & (a > window[0] * outer) & (a < window[1] * outer)
    F = -c.force[m] / F0
    return {
        "result": r,
        "shape": star,
        "F0": F0,
        "radius": a[m],
        "force": F,
        "plateau_spread": float(F.max() / F.min()),
        "plateau_level": float(np.median(F)),
        "disc_spread": (window[1] / window[0]) ** 1.5,
    }


def contact_radius(area):
    """Invert A(a) = pi r0^2 + int_r0^a 2 pi r (r0/r)^3 dr = 3 pi r0^2 - 2 pi r0^3 / a."""
    return 2 * math.pi * R0**3 / np.maximum(3 * math.pi * R0**2 - np.asarray(area), 1e-300)


def plot(out: dict, path=None):
    """The last stable contact, the force curve, and the force against the contact's outer radius."""
    import matplotlib.pyplot as plt

    r = out["result"]
    fig, axs = plt.subplots(1, 3, figsize=(12.5, 4.3), layout="constrained")
    _gallery.contact_map(
        axs[0],
        r.last_stable,
        cs.rasterise(out["shape"], r.grid_spacing).mask,
        title=f"last stable contact (core radius r0 = {R0:g})\n"
        f"Griffith BEM, {R0 / r.grid_spacing:.0f} elements per core radius",
    )
    _gallery.contact_legend(axs[0], loc="lower left", fontsize=6, framealpha=0.9)
    c = r.curve
    axs[1].plot(-c.approach, -c.force / out["F0"], label="BEM (Griffith)")
    a = contact_radius(c.contact_area)
    pulling = np.arange(len(a)) >= int(np.argmax(c.contact_area < c.contact_area[0]))
    inside = pulling & (a >= out["radius"].min()) & (a <= out["radius"].max())  # the points of the right panel
    axs[1].plot(
        -c.approach[inside],
        -c.force[inside] / out["F0"],
        ".",
        ms=3,
        color="C1",
        label=f"right panel: a = {out['radius'].min():.2f} ... {out['radius'].max():.2f}",
    )
    axs[1].set_xlabel("pull-off distance -d")
    axs[1].set_ylabel("-F / F0,  F0 = sqrt(8 pi E* w r0^3)  (Eq. 29)")
    axs[1].set_title("force against pull-off distance (E* = w = 1)", fontsize=9)
    axs[1].legend(fontsize=7, loc="lower center")
    axs[2].plot(out["radius"], out["force"], ".", color="C1", label="BEM, detachment under way")
    a = np.linspace(out["radius"].min(), out["radius"].max(), 50)
    axs[2].plot(a, (a / R0) ** 1.5, "-", color="0.4", label="a full disc of radius a: Kendall (Eq. 6), (a / r0)^(3/2)")
    axs[2].plot(
        a,
        out["plateau_level"] * (a / a[0]) ** 1.5,
        "--",
        color="C2",
        label="slope guide ~ a^(3/2), scaled to the plateau's\nmedian at the window's smallest a",
    )
    axs[2].set_xlabel("outer radius a of the contact (from the contact\narea through the designed A(a); the face's: 1)")
    axs[2].set_ylabel("-F / F0")
    axs[2].set_title(f"plateau: max / min = {out['plateau_spread']:.3f} (a disc: {out['disc_spread']:.2f})", fontsize=9)
    axs[2].legend(fontsize=7, loc="lower right")
    axs[2].set_ylim(bottom=0)
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def report(out: dict) -> None:
    print(
        f"plateau over a = {out['radius'].min():.3f} .. {out['radius'].max():.3f}: F/F0 = "
        f"{out['force'].min():.4f} .. {out['force'].max():.4f} (max/min {out['plateau_spread']:.4f}; "
        f"a disc: {out['disc_spread']:.3f}), median {out['plateau_level']:.4f}"
    )


def main(path=None, resolution: float = 48) -> None:
    import matplotlib

    matplotlib.use("Agg")
    out = run(resolution)
    plot(out, path or _gallery.picture_path("fig09_constant_force"))
    report(out)


if __name__ == "__main__":
    if _gallery.short_run():
        out = run(24)
        plot(out)
        report(out)
    else:
        main()
