"""The graded detachment criterion: Eq. 42's constant and its calibration on the flat circle.

Eq. 42 sets sigma_c = kappa(k) sqrt(E0 w / (c0^k Delta^(1-k))) with kappa from the energy
released by one isolated element (theory sheet, section 5).  On the flat circle this does not
reproduce Eq. 39 for k != 0: its pull-off tends to r(k) times what the same grid gives at
k = 0 (where Eq. 22 meets Kendall), r from 0.57 at k = -0.75 through 1 to 1.07 at k = 0.5
(``python benchmarks/study_griffith_graded.py``).  The element energy argument leaves out the
edge singularity, whose exponent (k - 1)/2 changes with k.

A flat punch pulled from touching is linear in the approach between events, with thresholds
proportional to sigma_c: scaling sigma_c scales every force and approach of a solve and
leaves the sequence of contact sets unchanged.  So one factor per k decides the absolute
level, and the ratios between faces do not depend on it.  ``"calibrated"`` divides sigma_c by
r(k) (table below, interpolated monotonically in k): the graded circle then behaves as the
homogeneous one does on the same grid, up to r's own first-order approach (|c| / r <= 0.44 / N
in the sweep) and its uncertainty; other faces inherit the factor, as every face does at
k = 0.  ``"eq42"`` keeps the sheet's constant.

Why a ratio to k = 0: F_A / F_A(Eq. 39) itself drifts down by about 0.5 % per doubling of the
resolution between 64 and 181 per radius at every k, k = 0 included (the most stressed
staircase cells set the first detachments, and finer grids sample more of them); the ratio
on the same grid moves by 0.1-0.6 % over 32-181 per radius and fits c/N to 0.2 %.
"""
from __future__ import annotations

import numpy as np

from contact_scene import SceneError

__all__ = ["CIRCLE_RATIO", "CRITERIA", "calibration", "stress_factor"]

CRITERIA = ("calibrated", "eq42")

#: k -> (r, u): the flat circle's pull-off under Eq. 42's kappa relative to Eq. 39, divided
#: by the same ratio at k = 0 on the same grid, extrapolated to Delta -> 0 by a c/N fit over
#: 32-181 elements per radius (forces scaled to the nominal area), and its uncertainty: the
#: larger of the change to a c/sqrt(N) fit and the largest residual
#: (``python benchmarks/study_griffith_graded.py``, run 2026-11-22).  k = 0 is Eq. 22,
#: validated on Kendall's circle: r = 1 there by definition.
CIRCLE_RATIO: dict[float, tuple[float, float]] = {
    -0.75: (0.56572, 0.0035),
    -0.5: (0.77591, 0.0027),
    -0.25: (0.91205, 0.0012),
    0.0: (1.0, 0.0),
    0.25: (1.05020, 0.0016),
    0.5: (1.06684, 0.0032),
    0.75: (1.05033, 0.0036),
}


def calibration(k: float) -> tuple[float, float]:
    """(r, u) at exponent k, interpolated monotonically between the measured exponents."""
    from scipy.interpolate import PchipInterpolator

    ks = np.array(sorted(CIRCLE_RATIO))
    if not ks[0] <= k <= ks[-1]:
        raise SceneError("settings.graded_criterion",
                         f"the calibrated criterion covers {ks[0]:g} <= k <= {ks[-1]:g} (got k = {k:g}); "
                         "use graded_criterion = 'eq42' (uncalibrated) there")
    r = PchipInterpolator(ks, [CIRCLE_RATIO[x][0] for x in ks])(k)
    u = PchipInterpolator(ks, [CIRCLE_RATIO[x][1] for x in ks])(k)
    return float(r), float(u)


def stress_factor(k: float, criterion: str) -> float:
    """The factor on Eq. 42's sigma_c (``criterion`` as validated by ``Settings``)."""
    return 1.0 / calibration(k)[0] if criterion == "calibrated" and k != 0 else 1.0
