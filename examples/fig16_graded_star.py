"""Fig. 16: a star punch on power-law graded half-spaces, E(z) = E0 (z/c0)^k.

For k > 0 detachment runs from the tips inward and the force passes its maximum well before
the end; for k < 0 the punch detaches more brittlely: the last stable contact is larger and
its force is close to the maximum.  (The forces use the calibrated graded criterion,
``bem_griffith.criterion``, which puts the circle on Eq. 39 at every k; the ratios compared
here, within one k, do not depend on that calibration.)

    python examples/fig16_graded_star.py        # full version, writes fig16_graded_star.png
    from examples.fig16_graded_star import run  # short version (used by the tests)
"""
from __future__ import annotations

import numpy as np

import contact_scene as cs

STAR = cs.Star(5, 1.0, 0.45)


def run(resolution: float = 16, exponents=(0.5, -0.5)) -> dict:
    import bem_griffith as bg

    out = {}
    for k in exponents:
        sc = cs.Scene(cs.Indenter(STAR), cs.PowerLawGraded(1.0, 1.0, k), cs.Adhesion(1.0))
        r = bg.solve(sc, bg.Settings(grid=cs.Grid(elements_per_radius=resolution)))
        c = r.curve
        i = int(np.argmax(-c.force))
        A0 = c.contact_area[0]
        out[k] = {"result": r,
                  "area_at_max": c.contact_area[i] / A0,
                  "last_stable_area": r.last_stable.contact_area / A0,
                  "last_force_over_max": r.last_stable.force / c.force[i],
                  "incircle_area": np.pi * STAR.incircle().radius ** 2 / A0}
    return out


def main(path: str = "fig16_graded_star.png") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from crossval.plotting import plot_contact, plot_curve

    ks = (0.75, 0.5, 0.25, 0.0, -0.25, -0.5)
    out = run(resolution=48, exponents=ks)
    fig, axs = plt.subplots(1, 3, figsize=(12, 3.8))
    for k, o in out.items():
        r = o["result"]
        plot_curve(r, axs[0], normalise=(abs(r.pulloff_approach), r.pulloff_force), label=f"k = {k:g}")
    axs[0].legend(fontsize=7)
    axs[0].set_title("(a) force / its maximum")
    plot_contact(out[0.5]["result"].last_stable, axs[1])
    axs[1].set_title("(b) last stable contact, k = 0.5", fontsize=9)
    plot_contact(out[-0.5]["result"].last_stable, axs[2])
    axs[2].set_title("last stable contact, k = -0.5", fontsize=9)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    for k, o in out.items():
        print(f"k = {k:+.2f}: area at F_max {o['area_at_max']:.3f}, last stable area {o['last_stable_area']:.3f} "
              f"(incircle {o['incircle_area']:.3f}), F_last / F_max {o['last_force_over_max']:.3f}")


if __name__ == "__main__":
    main()
