"""
Fig. 3: the JKR sphere and grid orientation
===========================================

(a) The sphere pulled from a Hertzian press: its force against the contact radius
a = sqrt(A/pi) approaches the JKR curve F(a) = 4 E* a^3 / (3 R) - sqrt(8 pi w E* a^3) at first
order as the grid is refined, and the contact stays round on the square grid.  Only the
states after the contact receded from the pressed (pinned) one are compared: those are the
ones JKR describes.

(b) A square punch rotated against the grid gives the same force-approach curve up to the
staircase of its boundary: F_A / A^(3/4) (A the rasterised area, Eq. 13's scaling) agrees
within the 0.5/N envelope (0.65 % against 0.5/N = 2.1 % at 24 per radius).  The raw forces
differ more (up to 4.7 % at 24 per radius), mostly because the rotated squares' rasters have
different areas; so the panel draws each curve scaled from its own raster's area to the
nominal one (F by (A_nom / A)^(3/4), d by (A_nom / A)^(1/4): the same face scaled in size),
and its legend gives each raster's area and both forces.

The short version runs the sphere at 16, 24, 32 elements per face radius and the squares at
24 per radius; the full version at 24, 48, 96 and 64::

    python examples/fig03_jkr_and_orientation.py        # full version, writes fig03_jkr_and_orientation.png
    from examples.fig03_jkr_and_orientation import run  # short version (used by the tests)
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

SPHERE = cs.Scene(
    cs.Indenter(cs.Circle(0.42), cs.Paraboloid(1.0)),
    cs.Homogeneous(0.75, 0.5),
    cs.Adhesion(0.01),
    cs.Loading(press_approach=0.15),
)


def jkr(resolutions=(16, 24, 32)) -> dict:
    import bem_griffith as bg

    out = {}
    for N in resolutions:
        r = bg.solve(SPHERE, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)))
        c = r.curve
        i = int(np.argmax(-c.force))
        sel = _receding(c)
        a = np.sqrt(c.contact_area[sel] / np.pi)
        F_jkr = T.jkr_force(E_star=1.0, work=0.01, sphere_radius=1.0, contact_radius=a)
        scale = T.jkr_pulloff_force(work=0.01, sphere_radius=1.0)
        dev = np.abs(c.force[sel] - F_jkr) / scale
        # roundness of the contact half-way to pull-off: radius of the outermost contact cell in
        # eight sectors, max over min
        d_mid = 0.5 * (c.approach[0] + c.approach[i])
        r2 = bg.solve(
            dataclasses.replace(SPHERE, outputs=cs.Outputs(snapshots=(d_mid,))),
            bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)),
        )
        out[N] = {
            "result": r,
            "max_deviation": float(dev.max()),
            "mean_deviation": float(dev.mean()),
            "roundness": _roundness(r2.snapshots[0]),
            "spacing": r.grid_spacing,
        }
    return out


def _receding(c):
    """JKR describes a receding contact edge (G = w there): the points after the contact first
    shrank below the pressed (Hertz, pinned) area, up to the force maximum."""
    i = int(np.argmax(-c.force))
    return (np.arange(len(c)) <= i) & (c.contact_area < c.contact_area[0]) & (c.contact_area > 0)


def _roundness(snap) -> float:
    X, Y = snap.centres()
    x, y = X[snap.contact], Y[snap.contact]
    rad, ang = np.hypot(x, y), np.arctan2(y, x)
    sector = ((ang + np.pi) / (2 * np.pi / 8)).astype(int) % 8
    rmax = np.array([rad[sector == s].max() for s in range(8)])
    return float(rmax.max() / rmax.min())


#: the rotated squares' side
SIDE = 2.0


def orientations(angles=(0.0, 15.0, 30.0, 45.0), N: float = 24) -> dict:
    import bem_griffith as bg

    out = {}
    for ang in angles:
        sq = cs.Square(SIDE).rotated(ang)
        sc = cs.Scene(cs.Indenter(sq), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
        out[ang] = bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=N)))
    return out


def area_normalised_spread(squares: dict) -> float:
    """Largest relative difference of F_A / A^(3/4) (A the rasterised area; Eq. 13 scales
    so) between the orientations and the axis-aligned square."""
    ref = squares[0.0]
    base = ref.pulloff_force / ref.curve.contact_area[0] ** 0.75
    return max(abs(r.pulloff_force / r.curve.contact_area[0] ** 0.75 / base - 1) for r in squares.values())


def run(resolutions=(16, 24, 32), N_square: float = 24) -> dict:
    return {"jkr": jkr(resolutions), "square": orientations(N=N_square)}


def plot(out: dict, path=None):
    """(a) the receding sphere contact against the JKR curve, (b) the rotated squares' curves."""
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(1, 2, figsize=(12, 5.4), layout="constrained")
    a = np.linspace(1e-3, 0.42, 200)
    axs[0].plot(
        a,
        T.jkr_force(E_star=1.0, work=0.01, sphere_radius=1.0, contact_radius=a),
        "k-",
        lw=0.8,
        label="JKR: F = 4 E* a^3 / (3R) - sqrt(8 pi w E* a^3)",
    )
    for N, o in out["jkr"].items():
        c = o["result"].curve
        # every state whose contact has receded from the pressed (pinned) one; the deviation is
        # measured up to the force maximum, past it (fixed grips) the contact keeps following JKR
        sel = (c.contact_area < c.contact_area[0]) & (c.contact_area > 0)
        axs[0].plot(
            np.sqrt(c.contact_area[sel] / np.pi),
            c.force[sel],
            ".",
            ms=3,
            label=f"BEM, {N:g} per face radius: max deviation {o['max_deviation']:.1%} of F_pull-off",
        )
    axs[0].set_xlabel("contact radius a = sqrt(A / pi)")
    axs[0].set_ylabel("force F")
    axs[0].set_title(
        "(a) sphere (R = 1, E* = 1, w = 0.01) pulled from a Hertz press:\n"
        "the receding contact (face radius 0.42); deviations up to the force maximum",
        fontsize=9,
    )
    axs[0].legend(fontsize=7, loc="upper right")
    _plot_orientations(axs[1], out["square"])
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def _plot_orientations(ax, squares: dict) -> None:
    """The rotated squares' curves, each scaled to the nominal area A_nom = 4 from its own
    rasterised area A (F by (A_nom / A)^(3/4), d by (A_nom / A)^(1/4): a face scaled in size),
    which is what the claim of panel (b) is about."""
    A_nom = SIDE**2
    ref = squares[0.0]
    N = (A_nom / np.pi) ** 0.5 / ref.grid_spacing
    F0 = ref.pulloff_force
    base = _scaled(ref, A_nom)[0]
    inset = ax.inset_axes((0.12, 0.56, 0.4, 0.36))
    for ang, r in squares.items():
        A = r.curve.contact_area[0]  # the whole rasterised face is in contact at the start
        s = (A_nom / A) ** 0.25
        ax.plot(
            r.curve.approach * s,
            r.curve.force * s**3,
            label=f"{ang:g} deg: raster area {A / A_nom - 1:+.2%}; F_A raw {r.pulloff_force / F0 - 1:+.2%},"
            f" scaled {_scaled(r, A_nom)[0] / base - 1:+.2%}",
        )
        inset.plot(r.curve.approach * s, r.curve.force * s**3, lw=1)
    d_c = _scaled(ref, A_nom)[1]
    inset.set_xlim(1.06 * d_c, 0.9 * d_c)
    inset.set_ylim(-1.03 * base, -0.93 * base)
    inset.set_title("near pull-off", fontsize=7)
    inset.tick_params(labelsize=6)
    ax.indicate_inset_zoom(inset, edgecolor="0.5")
    spread = area_normalised_spread(squares)
    raw = max(abs(r.pulloff_force / F0 - 1) for r in squares.values())
    ax.set_xlabel("approach d (A_nom / A)^(1/4)")
    ax.set_ylabel("force F (A_nom / A)^(3/4)")
    ax.set_title(
        "(b) square (side 2, E* = w = 1) rotated against the grid,\n"
        f"N = {N:.0f} per radius; curves scaled from each raster's area A to A_nom = 4:\n"
        f"F_A / A^(3/4) within {spread:.2%} (the 0.5/N envelope: {0.5 / N:.1%});\n"
        f"raw F_A within {raw:.2%}, mostly the rasters' different areas",
        fontsize=9,
    )
    ax.legend(
        fontsize=7, loc="lower right", title="square at: raster area A / A_nom - 1; F_A against 0 deg", title_fontsize=7
    )


def _scaled(r, A_nom: float) -> tuple[float, float]:
    """Pull-off force and approach of ``r`` scaled from its rasterised area to ``A_nom``."""
    s = (A_nom / r.curve.contact_area[0]) ** 0.25
    return r.pulloff_force * s**3, r.pulloff_approach * s


def report(out: dict) -> None:
    for N, o in out["jkr"].items():
        print(
            f"JKR {N}: max |F - F_JKR(a)| / F_pulloff = {o['max_deviation']:.3f}, mean {o['mean_deviation']:.3f}, "
            f"roundness {o['roundness']:.3f}"
        )
    F0 = out["square"][0.0].pulloff_force
    for ang, r in out["square"].items():
        print(f"square at {ang:g} deg: F_A / F_A(0 deg) - 1 = {r.pulloff_force / F0 - 1:+.4f}")
    print(f"largest spread of F_A / A^(3/4) over the orientations: {area_normalised_spread(out['square']):.4f}")


def main(path=None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    out = run(resolutions=(24, 48, 96), N_square=64)
    plot(out, path or _gallery.picture_path("fig03_jkr_and_orientation"))
    report(out)


if __name__ == "__main__":
    if _gallery.short_run():
        out = run(resolutions=(16, 24, 32), N_square=24)
        plot(out)
        report(out)
    else:
        main()
