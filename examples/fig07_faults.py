"""
Fig. 7: a square with faults
============================

A square punch with faults (a V notch, straight line cuts) detaches almost like the plain
square, with a force scaled by the square root of the filling factor (Eq. 24).

The filling factor phi is the face area over the nominal (uncut) square.  Eq. 24 replaces w
by phi w in the upper bound, so F_max / F_max(plain square) should be close to sqrt(phi).
The panels show the force curves and each face's last stable contact; the cuts are white.

The short version runs 40 cells per side, the full version 96::

    python examples/fig07_faults.py        # full version, writes fig07_faults.png
    from examples.fig07_faults import run  # short version (used by the tests)
"""

from __future__ import annotations

import contact_scene as cs
from contact_scene import theory as T

try:  # imported as examples.<name> (tests) or run as a script
    from examples import _gallery
except ImportError:
    import _gallery

FAULTS = {
    "plain": dict(),
    "V notch": dict(v_cut_depth=0.3, v_cut_width=0.3),
    "3 line cuts": dict(line_cuts=3, line_cut_length=0.5, cut_width=0.05),
    "7 line cuts": dict(line_cuts=7, line_cut_length=0.6, cut_width=0.05),
    "V + 5 line cuts": dict(v_cut_depth=0.3, v_cut_width=0.3, line_cuts=5, line_cut_length=0.5, cut_width=0.05),
}


def run(cells_per_side: int = 40) -> dict:
    import bem_griffith as bg

    out = {}
    E = cs.Homogeneous(0.75, 0.5)  # E* = 1
    for name, kw in FAULTS.items():
        shape = cs.SquareWithFaults(side=1.0, **kw)
        sc = cs.Scene(cs.Indenter(shape), E, cs.Adhesion(1.0))
        r = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(spacing=1.0 / cells_per_side)))
        phi = shape.area / shape.nominal_area
        up = T.upper_bound_force(E_star=1.0, work=1.0, area=shape.nominal_area, filling_factor=phi)
        out[name] = {"result": r, "phi": phi, "F": r.pulloff_force, "F_over_upper": r.pulloff_force / up}
    plain = out["plain"]["F"]
    for o in out.values():
        o["F_over_plain"] = o["F"] / plain
        o["sqrt_phi"] = o["phi"] ** 0.5
    return out


def plot(out: dict, path=None):
    """The force-approach curves of the faces, and each face's last stable contact."""
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch
    from matplotlib.ticker import MaxNLocator

    ncols = 3
    nrows = -(-(len(out) + 1) // ncols)
    fig, axs = plt.subplots(nrows, ncols, figsize=(4.0 * ncols, 3.9 * nrows), layout="constrained")
    axs = axs.ravel()
    for ax, (name, o) in zip(axs[1:], out.items(), strict=False):
        r = o["result"]
        face = cs.rasterise(cs.SquareWithFaults(side=1.0, **FAULTS[name]), r.grid_spacing).mask
        _gallery.contact_map(
            ax,
            r.last_stable,
            face,
            title=f"{name}: last stable contact\nphi = {o['phi']:.3f}, "
            f"F_A / (F_A,plain sqrt(phi)) = {o['F_over_plain'] / o['sqrt_phi']:.3f}",
        )
    for ax in axs[len(out) + 1 :]:
        ax.set_visible(False)
    for name, o in out.items():
        axs[0].plot(o["result"].curve.approach, o["result"].curve.force, label=name)
    axs[0].set_xlabel("approach d")
    axs[0].set_ylabel("force F")
    axs[0].set_title("force against approach\n(square of side 1, E* = w = 1)", fontsize=9)
    axs[0].legend(fontsize=7, loc="lower right")
    axs[0].xaxis.set_major_locator(MaxNLocator(5))
    cuts = Patch(facecolor="white", edgecolor="0.5", lw=0.5, label="not part of the face (notch, cuts)")
    fig.legend(handles=_gallery.contact_handles([cuts]), loc="outside lower center", fontsize=8, ncols=3)
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def report(out: dict) -> None:
    for name, o in out.items():
        print(
            f"{name:>16}: phi = {o['phi']:.4f}  F/F_plain = {o['F_over_plain']:.4f}  sqrt(phi) = {o['sqrt_phi']:.4f}"
            f"  ratio = {o['F_over_plain'] / o['sqrt_phi']:.4f}  F/F_upper(phi) = {o['F_over_upper']:.4f}"
        )


def main(path=None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    out = run(cells_per_side=96)
    plot(out, path or _gallery.picture_path("fig07_faults"))
    report(out)


if __name__ == "__main__":
    if _gallery.short_run():
        out = run(cells_per_side=40)
        plot(out)
        report(out)
    else:
        main()
