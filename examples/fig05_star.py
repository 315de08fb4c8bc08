"""Figs. 5-6: a star punch detaches from the tips inward and ends close to its incircle.

Normalised by the incircle's Kendall force and approach (the lower bound, Eqs. 18-19), the
star's last stable state lies near (1, 1).  Fig. 6's "complicated shapes" (here a cross and
an irregular concave polygon) also lose their first cells at convex corners and end at an
approach near the incircle's, but keep more than the incircle: a cross's arms behave like
short strips (Figs. 10-11), so its last stable force is 2.2-2.5 times the lower bound.  The full version also draws the contact sequence like
the paper (face grey, remaining contact black) and a 3-D view of the surface half-way through
the detachment.

    python examples/fig05_star.py        # full version, writes fig05_star.png
    from examples.fig05_star import run  # short version (used by the tests)
"""
from __future__ import annotations

import dataclasses

import numpy as np

import contact_scene as cs
from contact_scene import theory as T

STAR = cs.Star(5, 1.0, 0.45)
#: Fig. 6's "complicated shapes": a cross and an irregular concave polygon
CROSS = cs.Polygon(((-0.3, -1.0), (0.3, -1.0), (0.3, -0.3), (1.0, -0.3), (1.0, 0.3), (0.3, 0.3), (0.3, 1.0),
                    (-0.3, 1.0), (-0.3, 0.3), (-1.0, 0.3), (-1.0, -0.3), (-0.3, -0.3)))
IRREGULAR = cs.Polygon(((-1.0, -0.6), (0.2, -0.9), (0.5, -0.3), (1.1, -0.5), (0.9, 0.4), (0.3, 0.5), (0.1, 1.0),
                        (-0.6, 0.7), (-0.4, 0.1)))


def run(resolution: float = 16, *, fields: bool = False, shape=STAR) -> dict:
    """Pull ``shape`` off; where the first cells were lost, and the last stable state
    normalised by the incircle's Kendall force and approach (Eqs. 18-19)."""
    import bem_griffith as bg

    scene = cs.Scene(cs.Indenter(shape), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    st = bg.Settings(grid=cs.Grid(elements_per_radius=resolution))
    r = bg.solve(scene, st)
    c = r.curve
    A0 = c.contact_area[0]
    first = int(np.argmax(c.contact_area < A0))            # the first recorded loss of contact
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
    return {"result": r, "snapshots": r2.snapshots, "first_lost_radius": float(r_lost.min()) if r_lost.size else np.nan,
            "tip_radius": float(np.hypot(v[:, 0] - cx, v[:, 1] - cy).max()),
            "first_lost_to_corner": float(to_corner.max() / r.grid_spacing) if r_lost.size else np.nan,
            "last_stable_normalised": (ls.approach / d_lo, ls.force / -F_lo),
            "last_area_over_incircle": ls.contact_area / (np.pi * inc**2), "mid": snaps[d_mid]}


def _face_mask(result, shape=STAR):
    from contact_scene import rasterise

    return rasterise(shape, result.grid_spacing).mask


def main(path: str = "fig05_star.png") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from crossval.plotting import plot_contact, plot_surface

    out = run(resolution=48, fields=True)
    others = {name: run(resolution=48, shape=shape) for name, shape in (("cross", CROSS), ("irregular", IRREGULAR))}
    face = _face_mask(out["result"])
    fig = plt.figure(figsize=(14, 7.2))
    for i, s in enumerate([*out["snapshots"], out["result"].last_stable]):
        plot_contact(s, fig.add_subplot(2, 4, i + 1), face=face)
    plot_surface(out["mid"], fig.add_subplot(2, 4, 4, projection="3d"), stride=2)
    col = 5
    for (name, o), shape in zip(others.items(), (CROSS, IRREGULAR)):
        f = _face_mask(o["result"], shape)
        plot_contact(o["snapshots"][0], fig.add_subplot(2, 4, col), face=f)
        plot_contact(o["result"].last_stable, fig.add_subplot(2, 4, col + 1), face=f)
        col += 2
    fig.savefig(path, dpi=120, bbox_inches="tight")
    for name, o in {"star": out, **others}.items():
        d, F = o["last_stable_normalised"]
        print(f"{name}: first cells lost at r >= {o['first_lost_radius']:.3f} (farthest vertex at {o['tip_radius']:.3f}), "
              f"within {o['first_lost_to_corner']:.2f} cells of a convex corner; last stable state at "
              f"d/d_lower = {d:.3f}, F/F_lower = {F:.3f}, area / incircle area = {o['last_area_over_incircle']:.3f}")


if __name__ == "__main__":
    main()
