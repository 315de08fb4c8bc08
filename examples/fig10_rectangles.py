"""Figs. 10-11 of Popov, Pohrt & Li (2017): rectangles of aspect ratio 1 to 20.  The last
stable contact is the rectangle with rounded corners, not its incircle.

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


def main(path: str = "fig10.png") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from crossval.plotting import plot_contact

    out = run()
    fig, axs = plt.subplots(len(out), 1, figsize=(8, 2 * len(out)))
    for ax, (ar, o) in zip(axs, out.items()):
        plot_contact(o["result"].last_stable, ax)
        ax.set_title(f"{ar}:1  last stable {o['last_stable_fraction']:.2f} of the face "
                     f"(incircle {o['incircle_fraction']:.2f}); F_max/F_up = {o['max']:.3f}", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    for ar, o in out.items():
        print(f"{ar}:1  F_max/F_up = {o['max']:.4f}  last stable / face = {o['last_stable_fraction']:.3f}")


if __name__ == "__main__":
    main()
