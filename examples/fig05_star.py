"""
Figs. 5-6: a star and complicated shapes
========================================

A star punch detaches from the tips inward and ends close to its incircle.  Normalised by the
incircle's Kendall force and approach (the lower bound, Eqs. 18-19), its last stable state
lies at d / d_lower = 1.04-1.08 and F / F_lower = 1.16-1.35 (measured at 12, 16, 24, 32, 48
elements per radius sqrt(A/pi): d / d_lower = 1.079, 1.067, 1.055, 1.051, 1.042 and
F / F_lower = 1.174, 1.351, 1.225, 1.200, 1.158).  The approach is the incircle's within a
few per cent and moves toward it; the force, above the lower bound, is not converged: the
short version's star (16 per radius) shows the largest, 1.35.

Fig. 6's "complicated shapes" (here a cross and an irregular concave polygon) also lose
their first cells at convex corners and end at an approach near the incircle's, but keep
more than the incircle: a cross's arms behave like short strips (Figs. 10-11), so its last
stable force is 2.2-2.5 times the lower bound.

Top row: the star when its first cells go (circled in red), half-way, and in its last stable
state, and a 3-D view of the surface half-way through the detachment; bottom row: the cross
and the irregular polygon.  The short version runs the star at 16 and the other two at 12
elements per radius, the full version all three at 48::

    python examples/fig05_star.py        # full version, writes fig05_star.png
    from examples.fig05_star import run  # short version (used by the tests)
"""

from __future__ import annotations

import dataclasses

import numpy as np

import contact_scene as cs
from contact_scene import theory as T

try:  # imported as examples.<name> (tests) or run as a script
    from examples import _gallery
except ImportError:
    import _gallery

STAR = cs.Star(5, 1.0, 0.45)
#: the full version's elements per radius
FULL_N = 48
#: Fig. 6's "complicated shapes": a cross and an irregular concave polygon
CROSS = cs.Polygon(
    (
        (-0.3, -1.0),
        (0.3, -1.0),
        (0.3, -0.3),
        (1.0, -0.3),
        (1.0, 0.3),
        (0.3, 0.3),
        (0.3, 1.0),
        (-0.3, 1.0),
        (-0.3, 0.3),
        (-1.0, 0.3),
        (-1.0, -0.3),
        (-0.3, -0.3),
    )
)
IRREGULAR = cs.Polygon(
    ((-1.0, -0.6), (0.2, -0.9), (0.5, -0.3), (1.1, -0.5), (0.9, 0.4), (0.3, 0.5), (0.1, 1.0), (-0.6, 0.7), (-0.4, 0.1))
)


def run(resolution: float = 16, *, fields: bool = False, shape=STAR) -> dict:
    """Pull ``shape`` off; where the first cells were lost, and the last stable state
    normalised by the incircle's Kendall force and approach (Eqs. 18-19)."""
    import bem_griffith as bg

    scene = cs.Scene(cs.Indenter(shape), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    st = bg.GriffithSettings(grid=cs.Grid(elements_per_radius=resolution))
    r = bg.solve(scene, st)
    c = r.curve
    A0 = c.contact_area[0]
    first = int(np.argmax(c.contact_area < A0))  # the first recorded loss of contact
    # snapshots record the contact at the approach before that approach's detachment cascade,
    # so look just past the first event
    d_first = float(c.approach[first]) * (1 + 1e-9)
    d_mid = 0.5 * (d_first + r.last_stable.approach)
    outputs = cs.Outputs(snapshots=(d_first, d_mid), fields=fields)
    r2 = bg.solve(dataclasses.replace(scene, outputs=outputs), st)
    snaps = {s.approach: s for s in r2.snapshots}
    s_first = snaps[d_first]
    # where the first cells left: their distance from the centre, against the tips' radius
    X, Y = s_first.centres()
    lost = _face_mask(r2, shape) & ~s_first.contact
    cx, cy = shape.centroid
    r_lost = np.hypot(X[lost] - cx, Y[lost] - cy)
    # convex corners: vertices where the boundary turns the way the polygon winds
    v = np.asarray(shape.vertices, float)
    e1, e2 = v - np.roll(v, 1, axis=0), np.roll(v, -1, axis=0) - v
    turn = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    winding = np.sign(np.sum(v[:, 0] * np.roll(v[:, 1], -1) - np.roll(v[:, 0], -1) * v[:, 1]))
    corners = v[np.sign(turn) == winding]
    to_corner = np.hypot(X[lost][:, None] - corners[:, 0], Y[lost][:, None] - corners[:, 1]).min(axis=1)
    inc = shape.incircle().radius
    F_lo = T.lower_bound_force(E_star=1.0, work=1.0, incircle_radius=inc)
    d_lo = T.lower_bound_approach(E_star=1.0, work=1.0, incircle_radius=inc)
    ls = r.last_stable
    return {
        "result": r,
        "snapshots": r2.snapshots,
        "first_lost_radius": float(r_lost.min()) if r_lost.size else np.nan,
        "tip_radius": float(np.hypot(v[:, 0] - cx, v[:, 1] - cy).max()),
        "first_lost_to_corner": float(to_corner.max() / r.grid_spacing) if r_lost.size else np.nan,
        "last_stable_normalised": (ls.approach / d_lo, ls.force / -F_lo),
        "last_area_over_incircle": ls.contact_area / (np.pi * inc**2),
        "mid": snaps[d_mid],
        "shape": shape,
    }


def _face_mask(result, shape=STAR):
    from contact_scene import rasterise

    return rasterise(shape, result.grid_spacing).mask


def plot(outs: dict, path=None):
    """``outs``: {"star": run(fields=True), "cross": run(shape=CROSS), "irregular": run(shape=IRREGULAR)}
    (any of the last two may be left out).  Top: the star when its first cells go, half-way, in
    its last stable state, and the surface half-way in 3-D; bottom: first loss and last stable
    state of the other two faces.  The first cells lost are a few cells at the tips: circled."""
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    from crossval.plotting import plot_surface

    fig = plt.figure(figsize=(14, 8.8), layout="constrained")

    def first_loss(ax, s, face, name):
        _gallery.contact_map(ax, s, face, title=f"{name}: first cells lost (circled)\nd = {s.approach:.3f}")
        X, Y = s.centres()
        lost = face & ~s.contact
        ax.plot(X[lost], Y[lost], "o", mfc="none", mec="r", ms=9, mew=1.2, clip_on=False)

    star = outs["star"]
    face = _face_mask(star["result"])
    first_loss(fig.add_subplot(2, 4, 1), star["snapshots"][0], face, "star")
    for i, (s, what) in enumerate(
        ((star["snapshots"][1], "half-way"), (star["result"].last_stable, "last stable state"))
    ):
        title = f"star: {what}\nd = {s.approach:.3f}"
        if i == 1:
            d, F = star["last_stable_normalised"]
            title += f"\nd/d_lower = {d:.3f}, F/F_lower = {F:.2f}"
        _gallery.contact_map(fig.add_subplot(2, 4, i + 2), s, face, title=title)
    ax3 = fig.add_subplot(2, 4, 4, projection="3d")
    plot_surface(star["mid"], ax3, stride=2)
    ax3.set_title(
        f"star half-way: surface displacement\n-u in sqrt(w R / E*) (dark: in contact)\nd = {star['mid'].approach:.3f}",
        fontsize=9,
    )
    ax3.set_zlabel("-u / sqrt(w R / E*)")
    ax3.set_box_aspect(None, zoom=0.85)
    col = 5
    for name, shape in (("cross", CROSS), ("irregular", IRREGULAR)):
        if name not in outs:
            continue
        o = outs[name]
        f = _face_mask(o["result"], shape)
        first_loss(fig.add_subplot(2, 4, col), o["snapshots"][0], f, name)
        ls = o["result"].last_stable
        d, F = o["last_stable_normalised"]
        _gallery.contact_map(
            fig.add_subplot(2, 4, col + 1),
            ls,
            f,
            title=f"{name}: last stable state\nd = {ls.approach:.3f}\nd/d_lower = {d:.3f}, F/F_lower = {F:.2f}",
        )
        col += 2
    lost = Line2D([], [], ls="none", marker="o", mfc="none", mec="r", ms=9, label="first cells lost")
    fig.legend(handles=_gallery.contact_handles([lost]), loc="outside lower center", fontsize=8, ncols=3)
    per_radius = {n: o["shape"].equivalent_radius / o["result"].grid_spacing for n, o in outs.items()}
    grids = ", ".join(f"{n} {N:.0f}" for n, N in per_radius.items())
    converged = (
        ""
        if min(per_radius.values()) >= FULL_N
        else f"\nshort version, not converged (the full version: {FULL_N} per radius; the docstring gives both)"
    )
    fig.suptitle(
        "Figs. 5-6: contact (black) on the face (grey); R = 1 the length unit (the star's tip radius), E* = w = 1:"
        " lengths in R, approach d and displacement u in sqrt(w R / E*)\n"
        f"Griffith BEM, elements per radius sqrt(A/pi): {grids}" + converged,
        fontsize=10,
    )
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def report(outs: dict) -> None:
    for name, o in outs.items():
        d, F = o["last_stable_normalised"]
        print(
            f"{name}: first cells lost at r >= {o['first_lost_radius']:.3f} "
            f"(farthest vertex at {o['tip_radius']:.3f}), "
            f"within {o['first_lost_to_corner']:.2f} cells of a convex corner; last stable state at "
            f"d/d_lower = {d:.3f}, F/F_lower = {F:.3f}, area / incircle area = {o['last_area_over_incircle']:.3f}"
        )


def main(path=None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    outs = {
        "star": run(resolution=FULL_N, fields=True),
        **{name: run(resolution=FULL_N, shape=shape) for name, shape in (("cross", CROSS), ("irregular", IRREGULAR))},
    }
    plot(outs, path or _gallery.picture_path("fig05_star"))
    report(outs)


if __name__ == "__main__":
    if _gallery.short_run():
        outs = {
            "star": run(resolution=16, fields=True),
            **{name: run(resolution=12, shape=shape) for name, shape in (("cross", CROSS), ("irregular", IRREGULAR))},
        }
        plot(outs)
        report(outs)
    else:
        main()
