"""Kendall's flat circular punch, three ways: closed form, Griffith BEM and FEM reference.

    python examples/kendall_circle.py            # full version, writes kendall_circle.png
    from examples.kendall_circle import run      # short version (used by the tests)
"""
from __future__ import annotations

import contact_scene as cs
from contact_scene import theory as T


def run(resolution: float = 16, fem_grading: float = 2.0) -> dict:
    import bem_griffith as bg
    import fem_reference as fr

    scene = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    bem = bg.solve(scene, bg.Settings(grid=cs.Grid(elements_per_radius=resolution)))
    fem = fr.solve(scene, fr.FemSettings(grading=fem_grading))
    E = scene.material.effective_modulus
    return {
        "kendall": T.kendall_adhesion_force(E_star=E, radius=1.0, work=1.0),
        "kendall_approach": T.kendall_critical_approach(E_star=E, radius=1.0, work=1.0),
        "bem": bem,
        "fem": fem,
    }


def main(path: str = "kendall_circle.png") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from crossval.plotting import plot_curve

    out = run(resolution=64, fem_grading=1.0)
    fig, ax = plt.subplots()
    plot_curve(out["bem"], ax, normalise=(out["kendall_approach"], out["kendall"]), label="Griffith BEM, 64/radius")
    plot_curve(out["fem"], ax, normalise=(out["kendall_approach"], out["kendall"]), label="FEM reference", ls="--")
    ax.axhline(-1.0, color="grey", lw=0.5)
    ax.legend()
    fig.savefig(path, dpi=120)
    for name in ("bem", "fem"):
        r = out[name]
        print(f"{name}: F_A / F_Kendall - 1 = {r.pulloff_force / out['kendall'] - 1:+.2e}")


if __name__ == "__main__":
    main()
