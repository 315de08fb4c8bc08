"""
The energy BEM's zero-range limit
=================================

The energy-minimisation BEM approaching Kendall as the adhesive range shrinks.

Each finite range rho (process zone l_c = E* rho^2 / w) gives a pull-off force below
Kendall's.  Over coarse ranges (l_c / a = 0.32 ... 0.08) the circle's shortfall goes like
sqrt(l_c / a), which the short version uses (``rate=0.5``); below that the local rate rises
(0.55-0.65 at 0.04 ... 0.01), so the full version runs the default: ranges down to
l_c = 0.01 a with the rate fitted, the procedure that also serves faces with corners::

    python examples/energy_zero_range.py        # full version, writes energy_zero_range.png
    from examples.energy_zero_range import run  # short version (used by the tests)
"""

from __future__ import annotations

import contact_scene as cs
from contact_scene import theory as T


def run(ratios=(0.32, 0.16, 0.08), minimum_elements_per_radius: float = 16, rate: float | None = 0.5) -> dict:
    import bem_energy as be

    scene = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.0), cs.Adhesion(0.02))
    res = be.solve(
        scene, be.ZeroRangeSettings(ratios=ratios, minimum_elements_per_radius=minimum_elements_per_radius, rate=rate)
    )
    FK = T.kendall_adhesion_force(E_star=1.0, radius=1.0, work=0.02)
    zr = res.info["zero_range"]
    return {
        "result": res,
        "kendall": FK,
        "ratios": zr["process_zone_ratios"],
        "forces": [f / FK for f in zr["pulloff_forces"]],
        "extrapolated": res.pulloff_force / FK,
    }


def main(path: str = "energy_zero_range.png") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    out = run(ratios=(0.08, 0.04, 0.02, 0.01), minimum_elements_per_radius=24, rate=None)
    p = out["result"].info["zero_range"]["fitted_rate"]
    s = np.asarray(out["ratios"]) ** p
    fig, ax = plt.subplots()
    ax.plot(s, out["forces"], "o", label="finite range (2 elements per l_c)")
    ax.plot([0.0], [out["extrapolated"]], "s", label="extrapolated")
    ax.plot([0.0, s.max()], [out["extrapolated"], out["forces"][0]], ":", color="grey")
    ax.axhline(1.0, color="k", lw=0.6, label="Kendall")
    ax.set_xlabel(f"(l_c / a)^{p:.2f} (fitted rate)")
    ax.set_ylabel("F_A / F_Kendall")
    ax.legend()
    fig.savefig(path, dpi=120)
    print(
        f"extrapolated F_A / F_Kendall - 1 = {out['extrapolated'] - 1:+.3%} "
        f"(estimate {out['result'].accuracy_estimate:.2%})"
    )


if __name__ == "__main__":
    try:  # run as a script, or by the documentation's gallery
        from examples import _gallery
    except ImportError:
        import _gallery

    if _gallery.short_run():  # the tests' sequence, l_c / a = 0.32, 0.16, 0.08 at rate 1/2
        import matplotlib.pyplot as plt
        import numpy as np

        out = run()
        p = out["result"].info["zero_range"]["rate"]
        s = np.asarray(out["ratios"]) ** p
        fig, ax = plt.subplots()
        ax.plot(s, out["forces"], "o", label="finite range (the tests' coarse grids)")
        ax.plot([0.0], [out["extrapolated"]], "s", label="extrapolated")
        ax.plot([0.0, s.max()], [out["extrapolated"], out["forces"][0]], ":", color="grey")
        ax.axhline(1.0, color="k", lw=0.6, label="Kendall")
        ax.set_ylim(top=1.02)
        ax.set_xlabel(f"(l_c / a)^{p:.2f} (rate fixed)")
        ax.set_ylabel("F_A / F_Kendall")
        ax.set_title("zero-range limit of the energy BEM, circle", fontsize=10)
        ax.legend()
        print(
            f"extrapolated F_A / F_Kendall - 1 = {out['extrapolated'] - 1:+.3%} "
            f"(estimate {out['result'].accuracy_estimate:.2%})"
        )
    else:
        main(str(_gallery.picture_path("energy_zero_range")))
