"""Fig. 7: a square punch with faults (a V notch, straight line cuts) detaches almost like
the plain square, with a force scaled by the square root of the filling factor (Eq. 24).

The filling factor phi is the face area over the nominal (uncut) square.  Eq. 24 replaces w
by phi w in the upper bound, so F_max / F_max(plain square) should be close to sqrt(phi).

    python examples/fig07_faults.py        # full version, writes fig07_faults.png
    from examples.fig07_faults import run  # short version (used by the tests)
"""
from __future__ import annotations

import contact_scene as cs
from contact_scene import theory as T

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
    E = cs.Homogeneous(0.75, 0.5)       # E* = 1
    for name, kw in FAULTS.items():
        shape = cs.SquareWithFaults(side=1.0, **kw)
        sc = cs.Scene(cs.Indenter(shape), E, cs.Adhesion(1.0))
        r = bg.solve(sc, bg.Settings(grid=cs.Grid(spacing=1.0 / cells_per_side)))
        phi = shape.area / shape.nominal_area
        up = T.upper_bound_force(E_star=1.0, work=1.0, area=shape.nominal_area, filling_factor=phi)
        out[name] = {"result": r, "phi": phi, "F": r.pulloff_force, "F_over_upper": r.pulloff_force / up}
    plain = out["plain"]["F"]
    for o in out.values():
        o["F_over_plain"] = o["F"] / plain
        o["sqrt_phi"] = o["phi"] ** 0.5
    return out


def main(path: str = "fig07_faults.png") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from crossval.plotting import plot_contact, plot_curve

    out = run(cells_per_side=96)
    fig, axs = plt.subplots(1, len(out) + 1, figsize=(3.2 * (len(out) + 1), 3.2))
    for ax, (name, o) in zip(axs[1:], out.items()):
        plot_contact(o["result"].last_stable, ax)
        ax.set_title(f"{name}\nphi = {o['phi']:.3f}", fontsize=8)
    for name, o in out.items():
        plot_curve(o["result"], axs[0], label=name)
    axs[0].legend(fontsize=6)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    for name, o in out.items():
        print(f"{name:>16}: phi = {o['phi']:.4f}  F/F_plain = {o['F_over_plain']:.4f}  sqrt(phi) = {o['sqrt_phi']:.4f}"
              f"  ratio = {o['F_over_plain'] / o['sqrt_phi']:.4f}  F/F_upper(phi) = {o['F_over_upper']:.4f}")


if __name__ == "__main__":
    main()
