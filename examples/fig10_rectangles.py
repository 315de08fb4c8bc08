"""
Figs. 10-11: rectangles and a tapered strip
===========================================

Rectangles of aspect ratio 1 to 20: the last stable contact is the rectangle with rounded
corners, not its incircle.

An inclined (tapered) strip detaches continuously: a rectangle is the degenerate case where
every shortened state is critical (stiffness ~ length, filling ~ 1/length, so Eq. 30 never
holds) and the whole strip goes at once, while a strip that widens along its length can
shorten stably from its narrow end (``run_tapered``).

The short version runs the aspect ratios 1, 4, 8 at 16 cells across the short side, the full
version 1, 2, 5, 10, 20 at 12; the tapered strip runs at 16 cells per unit width in both::

    python examples/fig10_rectangles.py            # full version, writes fig10_rectangles.png
    from examples.fig10_rectangles import run      # short version (the tests use 1, 4, 8)
"""

from __future__ import annotations

import math

import contact_scene as cs
from contact_scene import theory as T

try:  # imported as examples.<name> (tests) or run as a script
    from examples import _gallery
except ImportError:
    import _gallery


def run(aspects=(1, 2, 5, 10, 20), cells_across: int = 12) -> dict:
    import bem_griffith as bg

    out = {}
    for ar in aspects:
        shape = cs.Rectangle(float(ar), 1.0)
        sc = cs.Scene(cs.Indenter(shape), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0), name=f"rectangle {ar}:1")
        r = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(spacing=1.0 / cells_across)))
        out[ar] = {
            "result": r,
            "max": r.pulloff_force / T.upper_bound_force(E_star=1.0, work=1.0, area=shape.area),
            "last_stable_fraction": r.last_stable.contact_area / shape.area,
            "incircle_fraction": math.pi * 0.25 / shape.area,
        }
    return out


def tapered_strip(length: float = 10.0, narrow: float = 0.3, wide: float = 1.7) -> cs.Polygon:
    """A trapezoid: width ``narrow`` at x = -length/2 growing linearly to ``wide`` at +length/2."""
    h = length / 2
    return cs.Polygon(((-h, -narrow / 2), (h, -wide / 2), (h, wide / 2), (-h, narrow / 2)))


def run_tapered(cells_across: int = 12, **shape) -> dict:
    """A tapered strip and the rectangle of the same length and area, pulled off alike: the
    fraction of the face still attached in the last stable state, and where it sits."""
    import bem_griffith as bg

    strip = tapered_strip(**shape)
    x0, _, x1, _ = strip.bounds
    rect = cs.Rectangle(x1 - x0, strip.area / (x1 - x0))
    out = {}
    for name, face in (("tapered", strip), ("rectangle", rect)):
        sc = cs.Scene(cs.Indenter(face), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
        r = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(spacing=1.0 / cells_across)))
        ls = r.last_stable
        X, _ = ls.centres()
        out[name] = {
            "result": r,
            "last_stable_fraction": ls.contact_area / face.area,
            "last_stable_centre": float(X[ls.contact].mean()) / (x1 - x0),
        }
    return out


def plot(outs: dict, path=None):
    """``outs``: {"rectangles": run(), "tapered": run_tapered()}; the last stable contact of
    every face, each panel to its own scale (lengths in units of the short side)."""
    import matplotlib.pyplot as plt
    from matplotlib.ticker import MultipleLocator

    out, tap = outs["rectangles"], outs["tapered"]
    # axes heights follow the faces' shapes (capped for the squat ones) so no panel is mostly blank
    heights = [min(2.2, 8.0 / ar) for ar in out] + [8.0 * 1.7 / 10]
    fig, axs = plt.subplots(
        len(heights),
        1,
        figsize=(8.8, sum(heights) + 0.75 * len(heights)),
        layout="constrained",
        gridspec_kw={"height_ratios": heights},
    )
    for ax, (ar, o) in zip(axs, out.items(), strict=False):
        r = o["result"]
        _gallery.contact_map(
            ax,
            r.last_stable,
            cs.rasterise(cs.Rectangle(float(ar), 1.0), r.grid_spacing).mask,
            title=f"{ar}:1 rectangle: last stable contact keeps {o['last_stable_fraction']:.2f} of the "
            f"face (incircle {o['incircle_fraction']:.2f});  F_max / F_A,upper = {o['max']:.3f}",
        )
        if ar <= 2:  # a narrow panel: fewer ticks, none touching
            ax.xaxis.set_major_locator(MultipleLocator(0.5))
    t = tap["tapered"]
    _gallery.contact_map(
        axs[-1],
        t["result"].last_stable,
        cs.rasterise(tapered_strip(), t["result"].grid_spacing).mask,
        title=f"tapered 10:1 strip (width 0.3 to 1.7): last stable contact keeps "
        f"{t['last_stable_fraction']:.2f} of the face, centred {t['last_stable_centre']:+.2f} "
        f"of its length from the middle",
    )
    fig.legend(handles=_gallery.contact_handles(), loc="outside lower center", fontsize=8, ncols=2)
    if path is not None:
        fig.savefig(path, dpi=110)
    return fig


def report(outs: dict) -> None:
    for ar, o in outs["rectangles"].items():
        print(f"{ar}:1  F_max/F_up = {o['max']:.4f}  last stable / face = {o['last_stable_fraction']:.3f}")
    for name, o in outs["tapered"].items():
        print(
            f"{name} strip (16 cells across): last stable / face = {o['last_stable_fraction']:.3f}, "
            f"its centre at x / length = {o['last_stable_centre']:+.3f}"
        )


def main(path=None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    outs = {"rectangles": run(), "tapered": run_tapered(cells_across=16)}
    plot(outs, path or _gallery.picture_path("fig10_rectangles"))
    report(outs)


if __name__ == "__main__":
    if _gallery.short_run():
        outs = {"rectangles": run(aspects=(1, 4, 8), cells_across=16), "tapered": run_tapered(cells_across=16)}
        plot(outs)
        report(outs)
    else:
        main()
