"""The press before the pull: without adhesion (as in the Griffith solver), to the scene's
approach or force, and the initial stiffness of that contact."""

from __future__ import annotations

import numpy as np
from scipy import optimize

from contact_scene import Scene, SceneError

from .equilibria import Equilibria
from .minimisers import Minimum

__all__ = ["press", "initial_stiffness"]


def press(eq: Equilibria, scene: Scene, approach_scale: float) -> tuple[float, Minimum]:
    """(approach d0, equilibrium) at the end of the press: the scene's press approach (0 by
    default), or the approach whose non-adhesive force is the scene's press force, found by
    bracketing outward in steps of ``approach_scale`` and Brent's method."""
    prob = eq.prob
    loading = scene.loading
    U = np.zeros(prob.padded)
    if loading.press_force is not None and loading.press_force > 0:
        target = loading.press_force
        state = {"U": U}

        def excess(d):
            m = eq.minimum(state["U"], d, False)
            state["U"] = m.U
            return eq.force(m) - target

        first_touch = float(prob.height.min())
        lower_d, upper_d = first_touch, first_touch + max(approach_scale, prob.spacing)
        while excess(upper_d) < 0:
            lower_d, upper_d = upper_d, first_touch + 2 * (upper_d - first_touch)
        try:
            d0 = optimize.brentq(excess, lower_d, upper_d, xtol=1e-10 * (upper_d - first_touch), rtol=1e-12)
        except ValueError:
            # no sign change: a target below what the minimiser resolves at the first touch (its
            # force there is round-off), and that touch is the press
            if lower_d != first_touch or excess(lower_d) < 0:
                raise
            d0 = lower_d
        return d0, eq.minimum(state["U"], d0, False)
    d0 = loading.press_approach if loading.press_approach is not None else 0.0
    if prob.height.size and d0 <= prob.height.min() and not scene.indenter.profile.is_flat:
        raise SceneError("loading.press_approach", f"approach {d0:g} brings no element of the face into contact")
    return d0, eq.minimum(U, d0, False)


def initial_stiffness(eq: Equilibria, scene: Scene, d0: float, m0: Minimum, approach_scale: float) -> float:
    """Initial slope of the non-adhesive force: exact for a flat face in full contact; a
    one-sided difference over 1e-3 of the press depth for a curved one."""
    prob = eq.prob
    if scene.indenter.profile.is_flat:
        dd = max(approach_scale, prob.spacing)
        m1 = eq.minimum(m0.U + dd * prob.face, d0 + dd, False)
        return (eq.force(m1) - eq.force(m0)) / dd
    dd = 1e-3 * max(d0 - float(prob.height.min()), prob.spacing)
    m1 = eq.minimum(m0.U, d0 + dd, False)
    return (eq.force(m1) - eq.force(m0)) / dd
