"""
Fig. 8: brushes
===============

Brushes of flat-ended columns in a square (regular, random, and mixed circular and square
columns) detach like the continuous square, and their adhesion forces collapse onto one
master curve linear in sqrt(phi) (Eq. 24).

phi is the filling factor, the columns' area over the square's.  Forces are normalised by
F_A,lower of the whole square (Eq. 18 with the incircle radius L/2), as in the paper.  Eq. 24
is the upper bound applied to the nominal area with w -> phi w, i.e.
F / F_A,lower = (4/pi)^(3/4) sqrt(phi) = 1.198 sqrt(phi); the continuous square itself
reaches about 0.88 of its bound (Fig. 4), so the master curve's slope is expected near that
square's own F / F_A,lower.

The short version runs 64 cells per side, the full version 128::

    python examples/fig08_brushes.py        # full version, writes fig08_brushes.png
    from examples.fig08_brushes import run  # short version (used by the tests)
"""

from __future__ import annotations

import math

import numpy as np

import contact_scene as cs
from contact_scene import theory as T

try:  # imported as examples.<name> (tests) or run as a script
    from examples import _gallery
except ImportError:
    import _gallery

SIDE = 1.0
BRUSHES = {
    "square": cs.Square(SIDE),
    "regular r=.04 p=.1": cs.Brush(SIDE, 0.04, pitch=0.1),
    "regular r=.05 p=.2": cs.Brush(SIDE, 0.05, pitch=0.2),
    "regular r=.08 p=.2": cs.Brush(SIDE, 0.08, pitch=0.2),
    "regular r=.1 p=.25": cs.Brush(SIDE, 0.1, pitch=0.25),
    "random 30 r=.05": cs.Brush(SIDE, 0.05, layout="random", count=30, seed=0),
    "random 45 r=.05": cs.Brush(SIDE, 0.05, layout="random", count=45, seed=0),
    "mixed 30 r<=.07": cs.Brush(SIDE, 0.07, layout="mixed", count=30, seed=1),
}


def run(cells_per_side: int = 64, names=None) -> dict:
    """Pull every brush off; return phi, F / F_A,lower, the master-curve slope and scatter."""
    import bem_griffith as bg

    E = cs.Homogeneous(0.75, 0.5)  # E* = 1, w = 1
    F_low = T.lower_bound_force(E_star=1.0, work=1.0, incircle_radius=SIDE / 2)
    out = {}
    for name in names or BRUSHES:
        shape = BRUSHES[name]
        scene = cs.Scene(cs.Indenter(shape), E, cs.Adhesion(1.0))
        r = bg.solve(scene, bg.GriffithSettings(grid=cs.Grid(spacing=SIDE / cells_per_side)))
        phi = shape.area / SIDE**2
        ls = r.last_stable
        out[name] = {
            "result": r,
            "phi": phi,
            "F_over_lower": r.pulloff_force / F_low,
            "last_stable_reach": _reach(ls) / (SIDE / 2),
        }
    s = np.sqrt([o["phi"] for o in out.values()])
    f = np.array([o["F_over_lower"] for o in out.values()])
    slope = float(s @ f / (s @ s))  # least squares through the origin
    return {
        "brushes": out,
        "slope": slope,
        "scatter": float(np.max(np.abs(f / (slope * s) - 1))),
        "eq24_slope": (4 / math.pi) ** 0.75,
    }


def _reach(snapshot) -> float:
    """Largest distance of a contact cell centre from the face centre."""
    c = snapshot.contact
    X, Y = snapshot.centres()
    return float(np.hypot(X[c], Y[c]).max()) if c.any() else 0.0


def plot(out: dict, path=None):
    """Three brushes' last stable contacts and every brush's force against sqrt(phi)."""
    import matplotlib.pyplot as plt

    b = out["brushes"]
    fig, axs = plt.subplots(
        1, 4, figsize=(15, 4.0), layout="constrained", gridspec_kw={"width_ratios": [1, 1, 1, 1.25]}
    )
    for ax, name in zip(axs[:3], ("regular r=.05 p=.2", "random 45 r=.05", "mixed 30 r<=.07"), strict=False):
        res = b[name]["result"]
        _gallery.contact_map(
            ax,
            res.last_stable,
            cs.rasterise(BRUSHES[name], res.grid_spacing).mask,
            title=f"{name}: last stable\nphi = {b[name]['phi']:.3f}  (square side L = 1)",
        )
    fig.legend(handles=_gallery.contact_handles(), loc="outside lower left", fontsize=7, ncols=2)
    ax = axs[3]
    markers = {"square": "*", "regular": "o", "random": "^", "mixed": "s"}
    for i, (name, o) in enumerate(b.items()):
        ax.plot(
            o["phi"] ** 0.5,
            o["F_over_lower"],
            markers[name.split()[0]],
            color=f"C{i}",
            ms=6,
            ls="none",
            label=name if name != "square" else "plain square",
        )
    t = np.linspace(0, 1, 2)
    ax.plot(t, out["slope"] * t, "-", color="k", lw=1, label=f"fit: {out['slope']:.3f} sqrt(phi)")
    ax.plot(
        t,
        out["eq24_slope"] * t,
        "--",
        color="grey",
        lw=1,
        label=f"Eq. 24 (upper bound): {out['eq24_slope']:.3f} sqrt(phi)",
    )
    ax.set_xlabel("sqrt(phi)  (phi: columns' area / square's)")
    ax.set_ylabel("F_A / F_A,lower(square)  (Eq. 18)")
    ax.set_title(f"master curve: largest deviation {out['scatter']:.1%}", fontsize=9)
    ax.legend(fontsize=6.5, loc="upper left")
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def report(out: dict) -> None:
    for name, o in out["brushes"].items():
        print(
            f"{name:>20}: phi = {o['phi']:.4f}  F/F_lower = {o['F_over_lower']:.4f}"
            f"  / sqrt(phi) = {o['F_over_lower'] / o['phi'] ** 0.5:.4f}"
            f"  last stable reach = {o['last_stable_reach']:.3f} L/2"
        )
    print(f"master slope {out['slope']:.4f} (Eq. 24: {out['eq24_slope']:.4f}), largest deviation {out['scatter']:.3%}")


def main(path=None, cells_per_side: int = 128) -> None:
    import matplotlib

    matplotlib.use("Agg")
    out = run(cells_per_side)
    plot(out, path or _gallery.picture_path("fig08_brushes"))
    report(out)


if __name__ == "__main__":
    if _gallery.short_run():
        out = run(64)
        plot(out)
        report(out)
    else:
        main()
