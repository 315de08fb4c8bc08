"""Closed-form theory of adhesive flat punches (the formula sheet, ``shared/theory.md``).

All functions are keyword-only, in consistent units (SI recommended).  Sign conventions
follow the sheet: an approach d < 0 means the punch is pulled; a force F < 0 is tensile;
"adhesion force" F_A is the magnitude of the largest tensile force.  ``E_star`` is
E / (1 - nu^2) of a homogeneous half-space; graded functions take E0, c0 and k.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from scipy import integrate, optimize, special

__all__ = [
    "ELEMENT_ENERGY_CONSTANT",
    "SQUARE_BETA",
    "kendall_stiffness",
    "kendall_energy",
    "critical_radius",
    "kendall_critical_approach",
    "kendall_detachment_force",
    "kendall_adhesion_force",
    "kendall_energies_at_detachment",
    "flat_circle_energy_release_rate",
    "compact_shape_stiffness",
    "upper_bound_force",
    "upper_bound_approach",
    "holm_radius",
    "lower_bound_force",
    "lower_bound_approach",
    "element_energy_constant",
    "critical_stress",
    "filling_equilibrium_approach",
    "filling_adhesion_force",
    "filling_energy",
    "filling_is_stable",
    "filling_last_stable_radius",
    "constant_force_filling",
    "graded_green_coefficient",
    "graded_stiffness",
    "graded_energy",
    "graded_critical_approach",
    "graded_psi",
    "graded_adhesion_force",
    "force_at_nominal_area",
    "graded_two_square_integral",
    "graded_criterion_constant",
    "graded_critical_stress",
    "elliptical_punch_stiffness",
    "jkr_pulloff_force",
    "jkr_force",
    "jkr_approach",
]


# ---------------------------------------------------------------------------
# Section 1: circular flat punch on a homogeneous half-space (Kendall)
# ---------------------------------------------------------------------------


def kendall_stiffness(*, E_star: float, radius: float) -> float:
    """Eq. 1: K = 2 E* a."""
    return 2.0 * E_star * radius


def kendall_energy(*, E_star: float, radius: float, approach: float, work: float) -> float:
    """Eq. 2: U = E* a d^2 - pi a^2 w."""
    return E_star * radius * approach**2 - math.pi * radius**2 * work


def critical_radius(*, E_star: float, approach: float, work: float) -> float:
    """Eq. 3: a_c = E* d^2 / (2 pi w), the radius in equilibrium at approach d."""
    return E_star * approach**2 / (2.0 * math.pi * work)


def kendall_critical_approach(*, E_star: float, radius: float, work: float) -> float:
    """Eq. 4: d_c = -sqrt(2 pi a w / E*) (negative: pulled)."""
    return -math.sqrt(2.0 * math.pi * radius * work / E_star)


def kendall_detachment_force(*, E_star: float, radius: float, work: float) -> float:
    """Eq. 5: F_c = K d_c = -sqrt(8 pi E* w a^3) (negative: tensile)."""
    return -math.sqrt(8.0 * math.pi * E_star * work * radius**3)


def kendall_adhesion_force(*, E_star: float, radius: float, work: float) -> float:
    """Eq. 6: F_A = sqrt(8 pi E* w a^3)."""
    return math.sqrt(8.0 * math.pi * E_star * work * radius**3)


def kendall_energies_at_detachment(*, radius: float, work: float) -> tuple[float, float]:
    """Eqs. 7-8: (U_el, U_ad) = (2 pi a^2 w, pi a^2 w) at the moment of detachment."""
    return 2.0 * math.pi * radius**2 * work, math.pi * radius**2 * work


def flat_circle_energy_release_rate(*, force: float, E_star: float, radius: float) -> float:
    """G = F^2 / (8 pi E* a^3) at the edge of a flat circular contact carrying force F (Sect. 1)."""
    return force**2 / (8.0 * math.pi * E_star * radius**3)


# ---------------------------------------------------------------------------
# Section 2: arbitrary cross-sections
# ---------------------------------------------------------------------------

#: Eq. 9: stiffness factor of the square flat punch
SQUARE_BETA = 1.021


def compact_shape_stiffness(*, E_star: float, area: float, beta: float = 1.0) -> float:
    """Eq. 9: K ~ 2 E* beta sqrt(A/pi) (beta = 1.021 for a square, <= 1.021 for rounded shapes)."""
    return 2.0 * E_star * beta * math.sqrt(area / math.pi)


def upper_bound_force(*, E_star: float, work: float, area: float, filling_factor: float = 1.0) -> float:
    """Eq. 13 (and Eq. 24 with filling factor phi): sqrt(8 pi E* phi w (A/pi)^(3/2))."""
    return math.sqrt(8.0 * math.pi * E_star * filling_factor * work * (area / math.pi) ** 1.5)


def upper_bound_approach(*, E_star: float, work: float, area: float, filling_factor: float = 1.0) -> float:
    """Eq. 14: d_c,upper = -sqrt(2 pi phi w sqrt(A/pi) / E*)."""
    return -math.sqrt(2.0 * math.pi * filling_factor * work * math.sqrt(area / math.pi) / E_star)


def holm_radius(*, stiffness: float, E_star: float) -> float:
    """Eqs. 15-17: radius of the circle with the same stiffness, a_H = K / (2 E*)."""
    return stiffness / (2.0 * E_star)


def lower_bound_force(*, E_star: float, work: float, incircle_radius: float) -> float:
    """Eq. 18: F_A,lower = sqrt(8 pi E* w a_in^3)."""
    return kendall_adhesion_force(E_star=E_star, radius=incircle_radius, work=work)


def lower_bound_approach(*, E_star: float, work: float, incircle_radius: float) -> float:
    """Eq. 19: d_c,lower = -sqrt(2 pi a_in w / E*)."""
    return kendall_critical_approach(E_star=E_star, radius=incircle_radius, work=work)


# ---------------------------------------------------------------------------
# Section 3: the local detachment criterion of the BEM
# ---------------------------------------------------------------------------


def element_energy_constant() -> float:
    """Eq. 20: (2/pi) [ln(1 + sqrt 2) - (sqrt 2 - 1)/3] = 0.4732010044..., the energy released
    (in units of sigma^2 Delta^3 / E*) when a uniformly loaded square element is unloaded."""
    return (2.0 / math.pi) * (math.log(1.0 + math.sqrt(2.0)) - (math.sqrt(2.0) - 1.0) / 3.0)


ELEMENT_ENERGY_CONSTANT = element_energy_constant()


def critical_stress(*, E_star: float, work: float, spacing: float) -> float:
    """Eq. 22: sigma_c = sqrt(E* w / (0.473201 Delta))."""
    return math.sqrt(E_star * work / (ELEMENT_ENERGY_CONSTANT * spacing))


# ---------------------------------------------------------------------------
# Section 4: filling factor phi(r)
# ---------------------------------------------------------------------------


def filling_energy(*, E_star: float, work: float, radius: float, approach: float, filling) -> float:
    """Eq. 25: U = E* a d^2 - 2 pi w int_0^a phi(r) r dr (``filling`` is the callable phi)."""
    adhering_moment, _ = integrate.quad(lambda r: filling(r) * r, 0.0, radius, limit=200)
    return E_star * radius * approach**2 - 2.0 * math.pi * work * adhering_moment


def filling_equilibrium_approach(*, E_star: float, work: float, radius: float, filling_at_radius: float) -> float:
    """Eq. 27: d = -sqrt(2 pi phi(a) a w / E*)."""
    return -math.sqrt(2.0 * math.pi * filling_at_radius * radius * work / E_star)


def filling_adhesion_force(*, E_star: float, work: float, radius: float, filling_at_radius: float) -> float:
    """Eq. 28: F = sqrt(8 pi E* a^3 phi(a) w)."""
    return math.sqrt(8.0 * math.pi * E_star * radius**3 * filling_at_radius * work)


def constant_force_filling(*, core_radius: float):
    """Eq. 29: phi(a) = (a0/a)^3 (for a >= a0) makes Eq. 28 independent of a."""
    return lambda a: np.minimum(1.0, (core_radius / np.asarray(a, float)) ** 3)


def filling_is_stable(*, radius: float, filling, step: float | None = None) -> bool:
    """Eq. 30: shrinking is stable while d(a phi(a))/da > 0 (central difference)."""
    h = step if step is not None else 1e-6 * radius
    return (radius + h) * filling(radius + h) - (radius - h) * filling(radius - h) > 0


def filling_last_stable_radius(*, filling, radius_min: float, radius_max: float) -> float:
    """Eq. 31: the radius where d(a phi(a))/da = 0, bracketed in [radius_min, radius_max]."""

    def stability_slope(a):
        h = 1e-7 * a
        return ((a + h) * filling(a + h) - (a - h) * filling(a - h)) / (2 * h)

    return optimize.brentq(stability_slope, radius_min, radius_max, xtol=1e-14 * radius_max)


# ---------------------------------------------------------------------------
# Section 5: power-law graded half-space
# ---------------------------------------------------------------------------


def graded_green_coefficient(*, E0: float, c0: float, k: float) -> float:
    """Surface Green's function w(r) = A_k P / r^(1+k): A_k = (3+k) c0^k / (2 pi (1+k)(2+k) E0)."""
    return (3.0 + k) * c0**k / (2.0 * math.pi * (1.0 + k) * (2.0 + k) * E0)


def graded_stiffness(*, E0: float, c0: float, k: float, radius: float) -> float:
    """Eq. 34: K(a) = 4 (2+k) cos(k pi/2) / (3+k) * E0 a^(1+k) / c0^k."""
    return 4.0 * (2.0 + k) * math.cos(k * math.pi / 2) / (3.0 + k) * E0 * radius ** (1.0 + k) / c0**k


def graded_energy(*, E0: float, c0: float, k: float, radius: float, approach: float, work: float) -> float:
    """Eq. 35: U = 2 (2+k) cos(k pi/2)/(3+k) * E0 a^(1+k) d^2 / c0^k - pi a^2 w."""
    return (
        2.0 * (2.0 + k) * math.cos(k * math.pi / 2) / (3.0 + k) * E0 * radius ** (1.0 + k) * approach**2 / c0**k
        - math.pi * radius**2 * work
    )


def graded_critical_approach(*, E0: float, c0: float, k: float, radius: float, work: float) -> float:
    """Eq. 38 (from Eqs. 36-37): d_c = -[pi w (3+k) c0^k a^(1-k) / ((2+k)(1+k) cos(k pi/2) E0)]^(1/2)."""
    return -math.sqrt(
        math.pi
        * work
        * (3.0 + k)
        * c0**k
        * radius ** (1.0 - k)
        / ((2.0 + k) * (1.0 + k) * math.cos(k * math.pi / 2) * E0)
    )


def graded_psi(k: float) -> float:
    """Eq. 40: psi(k) = 2 (2+k) cos(k pi/2) / ((3+k)(1+k))."""
    return 2.0 * (2.0 + k) * math.cos(k * math.pi / 2) / ((3.0 + k) * (1.0 + k))


def graded_adhesion_force(
    *, E0: float, c0: float, k: float, radius: float, work: float, filling_factor: float = 1.0
) -> float:
    """Eq. 39 (Eq. 41 with filling factor): F_A = sqrt(8 pi psi(k) E0 phi w a^(3+k) / c0^k)."""
    return math.sqrt(8.0 * math.pi * graded_psi(k) * E0 * filling_factor * work * radius ** (3.0 + k) / c0**k)


def force_at_nominal_area(force, *, area, nominal_area, k: float = 0.0):
    """A pull-off force scaled from a face of ``area`` (e.g. its rasterised staircase) to the
    same shape at ``nominal_area``: F ~ a^((3+k)/2) ~ A^((3+k)/4) (Eqs. 6 and 39).  Takes
    arrays."""
    return force * (nominal_area / area) ** ((3.0 + k) / 4.0)


@lru_cache(maxsize=256)
def graded_two_square_integral(k: float) -> float:
    """J_k = integral over two unit squares of |x - x'|^-(1+k)  (sheet, section 5).

    Reduced exactly to the difference vector (u, v) in [0, 1]^2 with weight (1-u)(1-v), then
    to polar coordinates over the triangle 0 <= v <= u <= 1, where the radial integral is
    closed-form; one smooth integral over the angle remains.  J_0 = 2.973210...
    """
    if not -1.0 < k < 1.0:
        raise ValueError(f"k must be in (-1, 1) (got {k})")

    def radial(t):
        c, s = math.cos(t), math.sin(t)
        R = 1.0 / c
        return R ** (1 - k) / (1 - k) - (c + s) * R ** (2 - k) / (2 - k) + c * s * R ** (3 - k) / (3 - k)

    val, _ = integrate.quad(radial, 0.0, math.pi / 4, epsabs=0, epsrel=1e-13, limit=200)
    return 8.0 * val


def graded_criterion_constant(k: float) -> float:
    """kappa(k) of Eq. 42: 1/sqrt(C_k), C_k = (3+k) J_k / (4 pi (1+k)(2+k))."""
    C = (3.0 + k) * graded_two_square_integral(k) / (4.0 * math.pi * (1.0 + k) * (2.0 + k))
    return 1.0 / math.sqrt(C)


def graded_critical_stress(*, E0: float, c0: float, k: float, work: float, spacing: float) -> float:
    """Eq. 42: sigma_c = kappa(k) sqrt(E0 w / (c0^k Delta^(1-k)))."""
    return graded_criterion_constant(k) * math.sqrt(E0 * work / (c0**k * spacing ** (1.0 - k)))


# ---------------------------------------------------------------------------
# ellipse and sphere
# ---------------------------------------------------------------------------


def elliptical_punch_stiffness(*, E_star: float, semi_major: float, semi_minor: float) -> float:
    """Galin: F = pi E* a d / K(e), e^2 = 1 - b^2/a^2, K the complete elliptic integral of
    the first kind (scipy's ellipk takes the parameter m = e^2).  e = 0 gives Eq. 1."""
    m = 1.0 - (semi_minor / semi_major) ** 2
    return math.pi * E_star * semi_major / special.ellipk(m)


def jkr_pulloff_force(*, work: float, sphere_radius: float) -> float:
    """JKR: magnitude of the largest tensile force on a sphere, 1.5 pi w R."""
    return 1.5 * math.pi * work * sphere_radius


def jkr_force(*, E_star: float, work: float, sphere_radius: float, contact_radius):
    """JKR force at contact radius a: F = 4 E* a^3 / (3 R) - sqrt(8 pi w E* a^3)."""
    a = np.asarray(contact_radius, float)
    return 4.0 * E_star * a**3 / (3.0 * sphere_radius) - np.sqrt(8.0 * math.pi * work * E_star * a**3)


def jkr_approach(*, E_star: float, work: float, sphere_radius: float, contact_radius):
    """JKR approach at contact radius a: d = a^2 / R - sqrt(2 pi w a / E*)."""
    a = np.asarray(contact_radius, float)
    return a**2 / sphere_radius - np.sqrt(2.0 * math.pi * work * a / E_star)
