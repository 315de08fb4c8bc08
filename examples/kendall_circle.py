"""
Kendall's flat punch, three ways
================================

Kendall's flat circular punch (radius 1, E* = w = 1) by the closed form (Eqs. 1-6), the
Griffith BEM and the FEM reference.  Both computed curves lie on Kendall's in units of his
pull-off force and approach; the BEM's pull-off force zig-zags with the staircase of the
rasterised circle inside its envelope 0.5 Delta/a, the FEM's error is below 1e-4.

The BEM runs at 64 elements per radius; the full version refines the FEM's mesh (grading 1
instead of 2), the tests run the BEM at 16 per radius::

    python examples/kendall_circle.py            # full version, writes kendall_circle.png
    from examples.kendall_circle import run      # short version (used by the tests)
"""

from __future__ import annotations

import contact_scene as cs
from contact_scene import theory as T

try:  # imported as examples.<name> (tests) or run as a script
    from examples import _gallery
except ImportError:
    import _gallery


def run(resolution: float = 16, fem_grading: float = 2.0) -> dict:
    import bem_griffith as bg
    import fem_reference as fr

    scene = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    bem = bg.solve(scene, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=resolution)))
    fem = fr.solve(scene, fr.FemSettings(grading=fem_grading))
    E = scene.material.effective_modulus
    return {
        "kendall": T.kendall_adhesion_force(E_star=E, radius=1.0, work=1.0),
        "kendall_approach": T.kendall_critical_approach(E_star=E, radius=1.0, work=1.0),
        "bem": bem,
        "fem": fem,
        "fem_grading": fem_grading,
    }


def plot(out: dict, path=None):
    """Both computed curves against Kendall's, normalised by his pull-off force and approach."""
    import matplotlib.pyplot as plt
    from matplotlib.ticker import MultipleLocator

    dK, FK = abs(out["kendall_approach"]), out["kendall"]
    fig, ax = plt.subplots(figsize=(7, 5), layout="constrained")
    ax.plot(
        [0.0, -1.0, -1.0],
        [0.0, -1.0, 0.0],
        color="grey",
        lw=4,
        alpha=0.4,
        label="Kendall: F = 2 E* a d up to d_c (Eqs. 1, 4-6)",
    )
    N = 1.0 / out["bem"].grid_spacing  # the circle's radius is 1
    labels = {
        "bem": f"Griffith BEM, {N:.0f} elements per radius",
        "fem": "FEM reference" + (f", mesh grading {out['fem_grading']:g}" if "fem_grading" in out else ""),
    }
    for key, style in (("bem", "-"), ("fem", "--")):
        label = labels[key]
        r = out[key]
        ax.plot(
            r.curve.approach / dK,
            r.curve.force / FK,
            style,
            label=f"{label}: F_A / F_Kendall - 1 = {r.pulloff_force / FK - 1:+.1e}",
        )
    # the methods differ by under a per cent: a close-up of the pull-off corner
    ins = ax.inset_axes([0.56, 0.08, 0.4, 0.4])
    for line in ax.get_lines():
        ins.plot(
            *line.get_data(),
            ls=line.get_linestyle(),
            lw=line.get_linewidth(),
            color=line.get_color(),
            alpha=line.get_alpha(),
        )
    ins.set_xlim(-1.015, -0.985)
    ins.set_ylim(-1.01, -0.97)
    ins.tick_params(labelsize=7)
    ins.xaxis.set_major_locator(MultipleLocator(0.01))
    ins.set_title("close-up at pull-off", fontsize=8)
    ax.indicate_inset_zoom(ins, edgecolor="0.5")
    ax.set_xlabel("approach d / |d_c|  (Eq. 4)")
    ax.set_ylabel("force F / F_A,Kendall  (Eq. 6)")
    ax.set_title("Kendall's circular flat punch (radius 1, E* = w = 1)", fontsize=10)
    ax.legend(fontsize=8, loc="upper center")
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def report(out: dict) -> None:
    for name in ("bem", "fem"):
        r = out[name]
        print(f"{name}: F_A / F_Kendall - 1 = {r.pulloff_force / out['kendall'] - 1:+.2e}")


def main(path=None) -> None:
    import matplotlib

    matplotlib.use("Agg")
    out = run(resolution=64, fem_grading=1.0)
    plot(out, path or _gallery.picture_path("kendall_circle"))
    report(out)


if __name__ == "__main__":
    if _gallery.short_run():
        out = run(resolution=64, fem_grading=2.0)
        plot(out)
        report(out)
    else:
        main()
