"""The graded detachment criterion: Eq. 42's constant and its calibration on the flat circle.

Eq. 42 sets sigma_c = kappa(k) sqrt(E0 w / (c0^k Delta^(1-k))) with kappa from the energy
released by one isolated element (theory sheet, section 5).  On the flat circle this does not
reproduce Eq. 39 for k != 0: its pull-off tends to r(k) times what the same grid gives at
k = 0 (where Eq. 22 meets Kendall), r from 0.26 at k = -0.95 through 1 to 1.07 at k = 0.5
(``python benchmarks/study_griffith_graded.py``).  The element energy argument leaves out the
edge singularity, whose exponent (k - 1)/2 changes with k.

A flat punch pulled from touching is linear in the approach between events, with thresholds
proportional to sigma_c: scaling sigma_c scales every force and approach of a solve and
leaves the sequence of contact sets unchanged.  So one factor per k decides the absolute
level, and the ratios between faces do not depend on it.  ``"calibrated"`` divides sigma_c by
r(k) (table below): the graded circle then behaves as the homogeneous one does on the same
grid, up to r's own first-order approach rho / r = 1 + (c / r) / N (``CIRCLE_FIRST_ORDER``)
and its uncertainty; other faces inherit the factor, as every face does at k = 0.
``"eq42"`` keeps the sheet's constant.  Pull-offs compared with Eq. 39 on the circle under
``"calibrated"`` are therefore residuals of this calibration, not independent checks.

Interpolation between the measured exponents: kappa(k) of Eq. 42 vanishes like sqrt(1 + k)
as k -> -1 (C_k carries 1 / (1 + k), the two-square integral J_k tends to 1), while the
constant the circle needs, kappa / r, stays finite (about 2.2 at k = -0.95).  So r itself
has a square-root end, which a polynomial interpolant of r misses (a monotone cubic in r
predicts k = -0.9 from the other entries 4.2 % low); s(k) = r / sqrt(1 + k) is smooth
over the whole range, 1.15 at k = -0.95 to 0.73 at k = 0.95, and is what is interpolated
(monotone cubic; each entry predicted from the others, across gaps twice the table's, within
0.12 %).  Between the entries the interpolated r is checked by fresh solves at k = +-0.925
(``tests/test_bem_graded.py``), where s's square root matters most.

Why a ratio to k = 0: F_A / F_A(Eq. 39) itself drifts down by about 0.5-0.9 % per doubling of the
resolution between 64 and 181 per radius for -0.95 <= k <= 0.75, k = 0 included (the most
stressed staircase cells set the first detachments, and finer grids sample more of them); the
ratio on the same grid moves by 0.1-1.6 % over 32-181 per radius and fits c/N to 0.2 %.  At
k = 0.9 and 0.95 the pressure is nearly uniform (edge exponent (k - 1)/2 = -0.05, -0.025)
and the graded circle's own F_A / F_A(Eq. 39) stays within 0.1 % from 45 to 181 per radius,
so the ratio there carries the homogeneous circle's staircase jitter (+-0.2 %): the c/N fit
leaves residuals of 0.24 % and 0.27 %, which u contains.  Off the sweep (40 and 56 per
radius) the ratio stays within u of the fit at all four |k| >= 0.9 (tested at 40 and 56 for
k = -0.9, 0.9, 0.95, at 56 only for k = -0.95, where 40 sits 0.6 % above the fit).
"""

from __future__ import annotations

import math

import numpy as np

from contact_scene import SceneError

__all__ = ["CIRCLE_FIRST_ORDER", "CIRCLE_RATIO", "CRITERIA", "calibration", "interpolate", "stress_factor"]

CRITERIA = ("calibrated", "eq42")

#: k -> (r, u): the flat circle's pull-off under Eq. 42's kappa relative to Eq. 39, divided
#: by the same ratio at k = 0 on the same grid, extrapolated to Delta -> 0 by a c/N fit over
#: 32-181 elements per radius (forces scaled to the nominal area), and its uncertainty: the
#: larger of the change to a c/sqrt(N) fit and the largest residual
#: (``python benchmarks/study_griffith_graded.py``).  k = 0 is Eq. 22, validated on Kendall's
#: circle: r = 1 there by definition.
CIRCLE_RATIO: dict[float, tuple[float, float]] = {
    -0.95: (0.25726, 0.0022),
    -0.9: (0.36255, 0.0029),
    -0.75: (0.56572, 0.0035),
    -0.5: (0.77591, 0.0027),
    -0.25: (0.91205, 0.0012),
    0.0: (1.0, 0.0),
    0.25: (1.05020, 0.0016),
    0.5: (1.06684, 0.0032),
    0.75: (1.05033, 0.0036),
    0.9: (1.02468, 0.0037),
    0.95: (1.01312, 0.0034),
}

#: k -> c / r of the same fits, for the exponents beyond |k| = 0.75 (within them |c| / r <= 0.44):
#: on an N-per-radius grid the calibrated circle's F_A / F_A(Eq. 39) relative to the
#: homogeneous circle's F_A / F_Kendall (both scaled to the nominal area) is 1 + (c / r) / N,
#: within u / r.
CIRCLE_FIRST_ORDER: dict[float, float] = {
    -0.95: +0.597,
    -0.9: +0.558,
    0.9: -0.208,
    0.95: -0.180,
}


def _table() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The stored exponents k, ratios r and uncertainties u, in increasing k."""
    exponents = np.array(sorted(CIRCLE_RATIO))
    ratios = np.array([CIRCLE_RATIO[x][0] for x in exponents])
    uncertainties = np.array([CIRCLE_RATIO[x][1] for x in exponents])
    return exponents, ratios, uncertainties


def interpolate(exponents, ratios, uncertainties, k: float) -> tuple[float, float]:
    """(r, u) at k from measured r(k) and u(k): s = r / sqrt(1 + k) and the relative
    uncertainty u / r are interpolated (monotone cubic), since r has a square-root end at
    k = -1 (module doc)."""
    from scipy.interpolate import PchipInterpolator

    exponents, ratios, uncertainties = (np.asarray(a, float) for a in (exponents, ratios, uncertainties))
    square_root_end = np.sqrt(1.0 + exponents)
    smooth_ratio = float(PchipInterpolator(exponents, ratios / square_root_end)(k))
    relative_uncertainty = float(PchipInterpolator(exponents, uncertainties / ratios)(k))
    ratio = smooth_ratio * math.sqrt(1.0 + k)
    return ratio, relative_uncertainty * ratio


def calibration(k: float) -> tuple[float, float]:
    """(r, u) at exponent k, interpolated between the measured exponents; outside them a
    SceneError naming the setting and the covered range."""
    exponents, ratios, uncertainties = _table()
    if not exponents[0] <= k <= exponents[-1]:
        raise SceneError(
            "settings.graded_criterion",
            f"the calibrated criterion covers {exponents[0]:g} <= k <= {exponents[-1]:g} (got material.exponent "
            f"k = {k!r}); use graded_criterion = 'eq42' (uncalibrated, any -1 < k < 1) there",
        )
    return interpolate(exponents, ratios, uncertainties, k)


def stress_factor(k: float, criterion: str) -> float:
    """The factor on Eq. 42's sigma_c (``criterion`` as validated by ``GriffithSettings``)."""
    return 1.0 / calibration(k)[0] if criterion == "calibrated" and k != 0 else 1.0
