"""Figs. 10-11 of Popov, Pohrt & Li (2017): rectangles of aspect ratio 1 to 20.  The last
stable contact is the rectangle with rounded corners, not its incircle.

An inclined (tapered) strip detaches continuously: a rectangle is the degenerate case where
every shortened state is critical (stiffness ~ length, filling ~ 1/length, so Eq. 30 never
holds) and the whole strip goes at once, while a strip that widens along its length can
shorten stably from its narrow end (``run_tapered``).

    python examples/fig10_rectangles.py            # aspect 1, 2, 5, 10, 20; writes fig10.png
    from examples.fig10_rectangles import run      # short version (the tests use 1, 4, 8)
"""
from __future__ import annotations

import math

import contact_scene as cs
from contact_scene import theory as T


def run(aspects=(1, 2, 5, 10, 20), cells_across: int = 12) -> dict:
    import bem_griffith as bg

    out = {}
    for ar in aspects:
        shape = cs.Rectangle(float(ar), 1.0)
        sc = cs.Scene(cs.Indenter(shape), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0), name=f"rectangle {ar}:1")
        r = bg.solve(sc, bg.Settings(grid=cs.Grid(spacing=1.0 / cells_across)))
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
        r = bg.solve(sc, bg.Settings(grid=cs.Grid(spacing=1.0 / cells_across)))
        ls = r.last_stable
        X, _ = ls.centres()
        out[name] = {"result": r, "last_stable_fraction": ls.contact_area / face.area,
                     "last_stable_centre": float(X[ls.contact].mean()) / (x1 - x0)}
    return out


def main(path: str = "fig10.png") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from crossval.plotting import plot_contact

    out = run()
    tap = run_tapered(cells_across=16)
    fig, axs = plt.subplots(len(out) + 1, 1, figsize=(8, 2 * (len(out) + 1)))
    for ax, (ar, o) in zip(axs, out.items()):
        plot_contact(o["result"].last_stable, ax)
        ax.set_title(f"{ar}:1  last stable {o['last_stable_fraction']:.2f} of the face "
                     f"(incircle {o['incircle_fraction']:.2f}); F_max/F_up = {o['max']:.3f}", fontsize=9)
    t = tap["tapered"]
    plot_contact(t["result"].last_stable, axs[-1],
                 face=cs.rasterise(tapered_strip(), t["result"].grid_spacing).mask)
    axs[-1].set_title(f"tapered 10:1 strip: last stable {t['last_stable_fraction']:.2f} of the face", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    for ar, o in out.items():
        print(f"{ar}:1  F_max/F_up = {o['max']:.4f}  last stable / face = {o['last_stable_fraction']:.3f}")
    for name, o in tap.items():
        print(f"{name} strip (16 cells across): last stable / face = {o['last_stable_fraction']:.3f}, "
              f"its centre at x / length = {o['last_stable_centre']:+.3f}")


if __name__ == "__main__":
    main()
