"""Figs. 5-6: a star punch detaches from the tips inward and ends close to its incircle.

Normalised by the incircle's Kendall force and approach (the lower bound, Eqs. 18-19), the
last stable state lies near (1, 1).  The full version also draws the contact sequence like
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


def run(resolution: float = 16, *, fields: bool = False) -> dict:
    import bem_griffith as bg

    scene = cs.Scene(cs.Indenter(STAR), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
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
    nx, ny = s_first.contact.shape
    X, Y = np.meshgrid(s_first.origin[0] + s_first.spacing * np.arange(nx),
                       s_first.origin[1] + s_first.spacing * np.arange(ny), indexing="ij")
    lost = _face_mask(r2) & ~s_first.contact
    r_lost = np.hypot(X[lost], Y[lost])
    inc = STAR.incircle().radius
    F_lo = T.lower_bound_force(E_star=1.0, work=1.0, incircle_radius=inc)
    d_lo = T.lower_bound_approach(E_star=1.0, work=1.0, incircle_radius=inc)
    ls = r.last_stable
    return {"result": r, "snapshots": r2.snapshots, "first_lost_radius": float(r_lost.min()) if r_lost.size else np.nan,
            "tip_radius": STAR.outer_radius,
            "last_stable_normalised": (ls.approach / d_lo, ls.force / -F_lo),
            "last_area_over_incircle": ls.contact_area / (np.pi * inc**2), "mid": snaps[d_mid]}


def _face_mask(result):
    from contact_scene import rasterise

    return rasterise(STAR, result.grid_spacing).mask


def main(path: str = "fig05_star.png") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from crossval.plotting import plot_contact, plot_surface

    out = run(resolution=48, fields=True)
    face = _face_mask(out["result"])
    fig = plt.figure(figsize=(14, 3.6))
    for i, s in enumerate([*out["snapshots"], out["result"].last_stable]):
        plot_contact(s, fig.add_subplot(1, 4, i + 1), face=face)
    plot_surface(out["mid"], fig.add_subplot(1, 4, 4, projection="3d"), stride=2)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    d, F = out["last_stable_normalised"]
    print(f"first cells lost at r >= {out['first_lost_radius']:.3f} (tips at {out['tip_radius']:.3f}); "
          f"last stable state at d/d_lower = {d:.3f}, F/F_lower = {F:.3f}, "
          f"area / incircle area = {out['last_area_over_incircle']:.3f}")


if __name__ == "__main__":
    main()
