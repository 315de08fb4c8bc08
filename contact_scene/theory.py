"""Closed-form theory of adhesive flat punches (the formula sheet, ``shared/theory.md``).

The functions take their physical arguments by keyword, in consistent units (the
parameter descriptions give SI units; any consistent set works).  Sign conventions follow
the sheet: an approach d < 0 means the punch is pulled; a force F < 0 is tensile;
"adhesion force" F_A is the magnitude of the largest tensile force.  ``E_star`` is
E / (1 - nu^2) of a homogeneous half-space; graded functions take E0, c0 and k.

Every equation number (Eq. N) is that of the formula sheet, which restates the equations of
the source paper (Popov, Pohrt & Li, Friction 5(3), 2017) and adds the ones derived for this
package; each function's References name the papers the closed form comes from.
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
    "UNIFORM_DISC_DISHING",
    "long_range_flat_circle_force",
]


# ---------------------------------------------------------------------------
# Section 1: circular flat punch on a homogeneous half-space (Kendall)
# ---------------------------------------------------------------------------


def kendall_stiffness(*, E_star: float, radius: float) -> float:
    """Normal stiffness of a circular flat punch, K = 2 E* a (Eq. 1).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    radius : float
        Punch radius a (m), > 0.

    Returns
    -------
    float
        K = dF/dd of the fully attached punch (N/m).

    References
    ----------
    - Kendall, K., "The adhesion and surface energy of elastic solids", J. Phys. D 4:1186-1195 (1971).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return 2.0 * E_star * radius


def kendall_energy(*, E_star: float, radius: float, approach: float, work: float) -> float:
    """Total energy of an attached circular flat punch, U = E* a d^2 - pi a^2 w (Eq. 2).

    Elastic energy at approach d minus the adhesion energy of the contact of radius a; its
    minimum over a at fixed d gives the critical radius (Eq. 3).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    radius : float
        Punch radius a (m), > 0.
    approach : float
        Approach d of the punch (m); d < 0 when it is pulled.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.

    Returns
    -------
    float
        U (J).

    References
    ----------
    - Kendall, K., "The adhesion and surface energy of elastic solids", J. Phys. D 4:1186-1195 (1971).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return E_star * radius * approach**2 - math.pi * radius**2 * work


def critical_radius(*, E_star: float, approach: float, work: float) -> float:
    """Critical radius at a given approach, a_c = E* d^2 / (2 pi w) (Eq. 3).

    The radius of the contact in equilibrium (dU/da = 0 in Eq. 2) at approach d.

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    approach : float
        Approach d of the punch (m); d < 0 when it is pulled.
    work : float
        Work of adhesion w per unit area (J/m^2), > 0.

    Returns
    -------
    float
        a_c (m).

    References
    ----------
    - Kendall, K., "The adhesion and surface energy of elastic solids", J. Phys. D 4:1186-1195 (1971).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return E_star * approach**2 / (2.0 * math.pi * work)


def kendall_critical_approach(*, E_star: float, radius: float, work: float) -> float:
    """Critical approach of a circular flat punch, d_c = -sqrt(2 pi a w / E*) (Eq. 4).

    The approach at which the punch of radius a detaches.

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    radius : float
        Punch radius a (m), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.

    Returns
    -------
    float
        d_c (m), <= 0: the punch is pulled.

    References
    ----------
    - Kendall, K., "The adhesion and surface energy of elastic solids", J. Phys. D 4:1186-1195 (1971).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return -math.sqrt(2.0 * math.pi * radius * work / E_star)


def kendall_detachment_force(*, E_star: float, radius: float, work: float) -> float:
    """Force at detachment of a circular flat punch, F_c = K d_c = -sqrt(8 pi E* w a^3) (Eq. 5).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    radius : float
        Punch radius a (m), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.

    Returns
    -------
    float
        F_c (N), <= 0: tensile.

    See Also
    --------
    kendall_adhesion_force : its magnitude (Eq. 6).

    References
    ----------
    - Kendall, K., "The adhesion and surface energy of elastic solids", J. Phys. D 4:1186-1195 (1971).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return -math.sqrt(8.0 * math.pi * E_star * work * radius**3)


def kendall_adhesion_force(*, E_star: float, radius: float, work: float) -> float:
    """Adhesion force of a circular flat punch, F_A = sqrt(8 pi E* w a^3) (Eq. 6).

    Kendall's pull-off force: the magnitude of the largest tensile force.

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    radius : float
        Punch radius a (m), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.

    Returns
    -------
    float
        F_A (N), >= 0.

    References
    ----------
    - Kendall, K., "The adhesion and surface energy of elastic solids", J. Phys. D 4:1186-1195 (1971).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return math.sqrt(8.0 * math.pi * E_star * work * radius**3)


def kendall_energies_at_detachment(*, radius: float, work: float) -> tuple[float, float]:
    """Elastic and adhesion energies at detachment, (2 pi a^2 w, pi a^2 w) (Eqs. 7-8).

    Parameters
    ----------
    radius : float
        Punch radius a (m), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.

    Returns
    -------
    U_el : float
        Elastic energy 2 pi a^2 w at the moment of detachment (J).
    U_ad : float
        Adhesion energy pi a^2 w of the contact (J).

    References
    ----------
    - Kendall, K., "The adhesion and surface energy of elastic solids", J. Phys. D 4:1186-1195 (1971).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return 2.0 * math.pi * radius**2 * work, math.pi * radius**2 * work


def flat_circle_energy_release_rate(*, force: float, E_star: float, radius: float) -> float:
    """Energy release rate at the edge of a flat circular contact, G = F^2 / (8 pi E* a^3).

    Equivalently K_I = F / (2 a sqrt(pi a)) and G = K_I^2 / (2 E*) (formula sheet, section 1);
    setting G = w gives Kendall's detachment force (Eq. 5).

    Parameters
    ----------
    force : float
        Normal force F carried by the contact (N); the sign does not matter.
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    radius : float
        Punch radius a (m), > 0.

    Returns
    -------
    float
        G (J/m^2), >= 0.

    References
    ----------
    - Kendall, K., "The adhesion and surface energy of elastic solids", J. Phys. D 4:1186-1195 (1971).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return force**2 / (8.0 * math.pi * E_star * radius**3)


# ---------------------------------------------------------------------------
# Section 2: arbitrary cross-sections
# ---------------------------------------------------------------------------

#: Eq. 9: stiffness factor of the square flat punch
SQUARE_BETA = 1.021


def compact_shape_stiffness(*, E_star: float, area: float, beta: float = 1.0) -> float:
    """Stiffness of a compact flat punch of any face shape, K ~ 2 E* beta sqrt(A/pi) (Eq. 9).

    An approximation: the circle of the same area with a shape factor beta (1.021 for the
    square, :data:`SQUARE_BETA`; at most 1.021 for rounded shapes).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    area : float
        Face area A (m^2), > 0.
    beta : float, optional
        Shape factor beta, > 0; 1 (the circle) by default.

    Returns
    -------
    float
        K (N/m).

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return 2.0 * E_star * beta * math.sqrt(area / math.pi)


def upper_bound_force(*, E_star: float, work: float, area: float, filling_factor: float = 1.0) -> float:
    """Upper bound of the adhesion force of a face, sqrt(8 pi E* phi w (A/pi)^(3/2)) (Eqs. 13, 24).

    Kendall's force (Eq. 6) for the circle of the same area; with a filling factor phi the
    work of adhesion becomes phi w (Eq. 24), so the bound goes like sqrt(phi).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    area : float
        Face area A (m^2), > 0.
    filling_factor : float, optional
        Fraction phi of the nominal area that adheres, 0 < phi <= 1 (Eq. 24); 1 by default.

    Returns
    -------
    float
        F_A,upper (N), >= 0.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return math.sqrt(8.0 * math.pi * E_star * filling_factor * work * (area / math.pi) ** 1.5)


def upper_bound_approach(*, E_star: float, work: float, area: float, filling_factor: float = 1.0) -> float:
    """Approach at the upper bound, d_c,upper = -sqrt(2 pi phi w sqrt(A/pi) / E*) (Eq. 14).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    area : float
        Face area A (m^2), > 0.
    filling_factor : float, optional
        Fraction phi of the nominal area that adheres, 0 < phi <= 1 (Eq. 24); 1 by default.

    Returns
    -------
    float
        d_c,upper (m), <= 0.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return -math.sqrt(2.0 * math.pi * filling_factor * work * math.sqrt(area / math.pi) / E_star)


def holm_radius(*, stiffness: float, E_star: float) -> float:
    """Holm radius a_H = K / (2 E*), the radius of the circle with the same stiffness (Eqs. 15-17).

    Parameters
    ----------
    stiffness : float
        Stiffness K of the face (N/m), > 0.
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.

    Returns
    -------
    float
        a_H (m).

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return stiffness / (2.0 * E_star)


def lower_bound_force(*, E_star: float, work: float, incircle_radius: float) -> float:
    """Lower bound of the adhesion force of a face, F_A,lower = sqrt(8 pi E* w a_in^3) (Eq. 18).

    Kendall's force (Eq. 6) of the largest inscribed circle.

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    incircle_radius : float
        Radius a_in of the largest circle inscribed in the face (m), > 0.

    Returns
    -------
    float
        F_A,lower (N), >= 0.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return kendall_adhesion_force(E_star=E_star, radius=incircle_radius, work=work)


def lower_bound_approach(*, E_star: float, work: float, incircle_radius: float) -> float:
    """Approach at the lower bound, d_c,lower = -sqrt(2 pi a_in w / E*) (Eq. 19).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    incircle_radius : float
        Radius a_in of the largest circle inscribed in the face (m), > 0.

    Returns
    -------
    float
        d_c,lower (m), <= 0.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return kendall_critical_approach(E_star=E_star, radius=incircle_radius, work=work)


# ---------------------------------------------------------------------------
# Section 3: the local detachment criterion of the BEM
# ---------------------------------------------------------------------------


def element_energy_constant() -> float:
    """Energy constant of one square element, (2/pi) [ln(1 + sqrt 2) - (sqrt 2 - 1)/3] (Eq. 20).

    The energy released when the uniform stress sigma on one square element of side Delta
    drops to zero is this constant times sigma^2 Delta^3 / E*.  It equals J_0 / (2 pi), with
    J_0 the integral of 1/abs(x - x') over two unit squares (:func:`graded_two_square_integral`).

    Returns
    -------
    float
        0.4732010044..., dimensionless.

    References
    ----------
    - Pohrt, R., Popov, V.L., "Adhesive contact simulation of elastic solids using local mesh-dependent
      detachment criterion in boundary elements method", Facta Universitatis, Mech. Eng. 13(1):3-10 (2015).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return (2.0 / math.pi) * (math.log(1.0 + math.sqrt(2.0)) - (math.sqrt(2.0) - 1.0) / 3.0)


ELEMENT_ENERGY_CONSTANT = element_energy_constant()


def critical_stress(*, E_star: float, work: float, spacing: float) -> float:
    """Critical tensile stress of the local detachment criterion, sqrt(E* w / (0.473201 Delta)) (Eq. 22).

    An element detaches when its tensile stress exceeds sigma_c: the energy it releases
    (Eq. 20) then exceeds the adhesion energy w Delta^2 of its area.

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    spacing : float
        Element side Delta of the boundary-element grid (m), > 0.

    Returns
    -------
    float
        sigma_c (Pa), >= 0.

    References
    ----------
    - Pohrt, R., Popov, V.L., "Adhesive contact simulation of elastic solids using local mesh-dependent
      detachment criterion in boundary elements method", Facta Universitatis, Mech. Eng. 13(1):3-10 (2015).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return math.sqrt(E_star * work / (ELEMENT_ENERGY_CONSTANT * spacing))


# ---------------------------------------------------------------------------
# Section 4: filling factor phi(r)
# ---------------------------------------------------------------------------


def filling_energy(*, E_star: float, work: float, radius: float, approach: float, filling) -> float:
    """Total energy with a radial filling factor, U = E* a d^2 - 2 pi w int_0^a phi(r) r dr (Eq. 25).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    radius : float
        Punch radius a (m), > 0.
    approach : float
        Approach d of the punch (m); d < 0 when it is pulled.
    filling : callable
        phi(r), the fraction of the circle of radius r that adheres (0 <= phi <= 1); called with
        a float.

    Returns
    -------
    float
        U (J); the integral by adaptive quadrature.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    adhering_moment, _ = integrate.quad(lambda r: filling(r) * r, 0.0, radius, limit=200)
    return E_star * radius * approach**2 - 2.0 * math.pi * work * adhering_moment


def filling_equilibrium_approach(*, E_star: float, work: float, radius: float, filling_at_radius: float) -> float:
    """Equilibrium approach with a filling factor, d = -sqrt(2 pi phi(a) a w / E*) (Eq. 27).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    radius : float
        Punch radius a (m), > 0.
    filling_at_radius : float
        phi(a), the filling factor at the contact's edge, 0 <= phi <= 1.

    Returns
    -------
    float
        d (m), <= 0.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return -math.sqrt(2.0 * math.pi * filling_at_radius * radius * work / E_star)


def filling_adhesion_force(*, E_star: float, work: float, radius: float, filling_at_radius: float) -> float:
    """Force in equilibrium with a filling factor, F = sqrt(8 pi E* a^3 phi(a) w) (Eq. 28).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    radius : float
        Punch radius a (m), > 0.
    filling_at_radius : float
        phi(a), the filling factor at the contact's edge, 0 <= phi <= 1.

    Returns
    -------
    float
        The magnitude of the tensile force F (N), >= 0.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return math.sqrt(8.0 * math.pi * E_star * radius**3 * filling_at_radius * work)


def constant_force_filling(*, core_radius: float):
    """Filling factor phi(a) = min(1, (a0/a)^3) for which the force of Eq. 28 is constant (Eq. 29).

    Parameters
    ----------
    core_radius : float
        Radius a0 of the fully filled core (m), > 0.

    Returns
    -------
    callable
        phi(a), taking a float or an array of radii and returning the same shape.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return lambda a: np.minimum(1.0, (core_radius / np.asarray(a, float)) ** 3)


def filling_is_stable(*, radius: float, filling, step: float | None = None) -> bool:
    """Whether the shrinking contact is stable at radius a: d(a phi(a))/da > 0 (Eq. 30).

    The derivative by a central difference.

    Parameters
    ----------
    radius : float
        Punch radius a (m), > 0.
    filling : callable
        phi(r), the fraction of the circle of radius r that adheres (0 <= phi <= 1); called with
        a float.
    step : float or None, optional
        Step h of the central difference (m), > 0 and < radius; 1e-6 radius by default.

    Returns
    -------
    bool
        True while shrinking is stable.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    h = step if step is not None else 1e-6 * radius
    return (radius + h) * filling(radius + h) - (radius - h) * filling(radius - h) > 0


def filling_last_stable_radius(*, filling, radius_min: float, radius_max: float) -> float:
    """Radius of the last stable state, where d(a phi(a))/da = 0 (Eq. 31).

    The root of the derivative (central differences) by Brent's method.

    Parameters
    ----------
    filling : callable
        phi(r), the fraction of the circle of radius r that adheres (0 <= phi <= 1); called with
        a float.
    radius_min : float
        Lower end of the bracket (m), > 0.
    radius_max : float
        Upper end of the bracket (m), > radius_min; the derivative must change sign between the two.

    Returns
    -------
    float
        The radius (m), to 1e-14 radius_max.

    Raises
    ------
    ValueError
        When the derivative has the same sign at both ends of the bracket.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """

    def stability_slope(a):
        h = 1e-7 * a
        return ((a + h) * filling(a + h) - (a - h) * filling(a - h)) / (2 * h)

    return optimize.brentq(stability_slope, radius_min, radius_max, xtol=1e-14 * radius_max)


# ---------------------------------------------------------------------------
# Section 5: power-law graded half-space
# ---------------------------------------------------------------------------


def graded_green_coefficient(*, E0: float, c0: float, k: float) -> float:
    """Coefficient A_k of the graded half-space's surface Green's function w(r) = A_k P / r^(1+k).

    A_k = (3+k) c0^k / (2 pi (1+k)(2+k) E0), for E(z) = E0 (z/c0)^k (Eq. 32) and Poisson ratio
    nu = 1/(2+k) (Eq. 33); k = 0 gives 1/(pi E*) with E* = 4 E0 / 3 (formula sheet, section 5).

    Parameters
    ----------
    E0 : float
        Modulus of the graded half-space at the reference depth, E(c0) = E0 (Pa), > 0.
    c0 : float
        Reference depth c0 of E(z) = E0 (z/c0)^k (m), > 0.
    k : float
        Exponent of the power-law grading, -1 < k < 1 (k = 0 is homogeneous, with E* = 4 E0 / 3).

    Returns
    -------
    float
        A_k (m^(2+k)/N: w in m for P in N and r in m).

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return (3.0 + k) * c0**k / (2.0 * math.pi * (1.0 + k) * (2.0 + k) * E0)


def graded_stiffness(*, E0: float, c0: float, k: float, radius: float) -> float:
    """Stiffness of a circular flat punch on a graded half-space (Eq. 34).

    K(a) = 4 (2+k) cos(k pi/2) / (3+k) * E0 a^(1+k) / c0^k; k = 0 gives Eq. 1.

    Parameters
    ----------
    E0 : float
        Modulus of the graded half-space at the reference depth, E(c0) = E0 (Pa), > 0.
    c0 : float
        Reference depth c0 of E(z) = E0 (z/c0)^k (m), > 0.
    k : float
        Exponent of the power-law grading, -1 < k < 1 (k = 0 is homogeneous, with E* = 4 E0 / 3).
    radius : float
        Punch radius a (m), > 0.

    Returns
    -------
    float
        K (N/m).

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return 4.0 * (2.0 + k) * math.cos(k * math.pi / 2) / (3.0 + k) * E0 * radius ** (1.0 + k) / c0**k


def graded_energy(*, E0: float, c0: float, k: float, radius: float, approach: float, work: float) -> float:
    """Total energy of a circular flat punch on a graded half-space (Eq. 35).

    U = 2 (2+k) cos(k pi/2)/(3+k) * E0 a^(1+k) d^2 / c0^k - pi a^2 w.

    Parameters
    ----------
    E0 : float
        Modulus of the graded half-space at the reference depth, E(c0) = E0 (Pa), > 0.
    c0 : float
        Reference depth c0 of E(z) = E0 (z/c0)^k (m), > 0.
    k : float
        Exponent of the power-law grading, -1 < k < 1 (k = 0 is homogeneous, with E* = 4 E0 / 3).
    radius : float
        Punch radius a (m), > 0.
    approach : float
        Approach d of the punch (m); d < 0 when it is pulled.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.

    Returns
    -------
    float
        U (J).

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return (
        2.0 * (2.0 + k) * math.cos(k * math.pi / 2) / (3.0 + k) * E0 * radius ** (1.0 + k) * approach**2 / c0**k
        - math.pi * radius**2 * work
    )


def graded_critical_approach(*, E0: float, c0: float, k: float, radius: float, work: float) -> float:
    """Critical approach of a circular flat punch on a graded half-space (Eq. 38).

    d_c = -[pi w (3+k) c0^k a^(1-k) / ((2+k)(1+k) cos(k pi/2) E0)]^(1/2), from the critical state
    of Eqs. 36-37.

    Parameters
    ----------
    E0 : float
        Modulus of the graded half-space at the reference depth, E(c0) = E0 (Pa), > 0.
    c0 : float
        Reference depth c0 of E(z) = E0 (z/c0)^k (m), > 0.
    k : float
        Exponent of the power-law grading, -1 < k < 1 (k = 0 is homogeneous, with E* = 4 E0 / 3).
    radius : float
        Punch radius a (m), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.

    Returns
    -------
    float
        d_c (m), <= 0.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return -math.sqrt(
        math.pi
        * work
        * (3.0 + k)
        * c0**k
        * radius ** (1.0 - k)
        / ((2.0 + k) * (1.0 + k) * math.cos(k * math.pi / 2) * E0)
    )


def graded_psi(k: float) -> float:
    """Factor psi(k) = 2 (2+k) cos(k pi/2) / ((3+k)(1+k)) of the graded adhesion force (Eq. 40).

    Parameters
    ----------
    k : float
        Exponent of the power-law grading, -1 < k < 1 (k = 0 is homogeneous, with E* = 4 E0 / 3).

    Returns
    -------
    float
        psi(k), dimensionless; psi(0) = 4/3.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return 2.0 * (2.0 + k) * math.cos(k * math.pi / 2) / ((3.0 + k) * (1.0 + k))


def graded_adhesion_force(
    *, E0: float, c0: float, k: float, radius: float, work: float, filling_factor: float = 1.0
) -> float:
    """Adhesion force of a circular flat punch on a graded half-space (Eqs. 39, 41).

    F_A = sqrt(8 pi psi(k) E0 phi w a^(3+k) / c0^k), with psi of Eq. 40; a filling factor phi
    replaces w by phi w (Eq. 41).

    Parameters
    ----------
    E0 : float
        Modulus of the graded half-space at the reference depth, E(c0) = E0 (Pa), > 0.
    c0 : float
        Reference depth c0 of E(z) = E0 (z/c0)^k (m), > 0.
    k : float
        Exponent of the power-law grading, -1 < k < 1 (k = 0 is homogeneous, with E* = 4 E0 / 3).
    radius : float
        Punch radius a (m), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    filling_factor : float, optional
        Fraction phi of the nominal area that adheres, 0 < phi <= 1 (Eq. 24); 1 by default.

    Returns
    -------
    float
        F_A (N), >= 0.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return math.sqrt(8.0 * math.pi * graded_psi(k) * E0 * filling_factor * work * radius ** (3.0 + k) / c0**k)


def force_at_nominal_area(force, *, area, nominal_area, k: float = 0.0):
    """Pull-off force scaled from one face area to the same shape at another, F ~ A^((3+k)/4).

    For a face of ``area`` (e.g. its rasterised staircase) scaled to ``nominal_area``:
    F ~ a^((3+k)/2) (Eqs. 6 and 39), and a ~ sqrt(A).

    Parameters
    ----------
    force : float or array_like
        Pull-off force F at ``area`` (N).
    area : float or array_like
        Area of the face the force belongs to (m^2), > 0.
    nominal_area : float or array_like
        Area to scale to (m^2), > 0.
    k : float, optional
        Exponent of the grading, -1 < k < 1; 0 (homogeneous) by default.

    Returns
    -------
    float or numpy.ndarray
        The force at ``nominal_area``, broadcast over the arguments.

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return force * (nominal_area / area) ** ((3.0 + k) / 4.0)


@lru_cache(maxsize=256)
def graded_two_square_integral(k: float) -> float:
    """J_k, the integral over two unit squares of abs(x - x')^-(1+k) (formula sheet, section 5).

    Reduced exactly to the difference vector (u, v) in [0, 1]^2 with weight (1-u)(1-v), then
    to polar coordinates over the triangle 0 <= v <= u <= 1, where the radial integral is
    closed-form; one smooth integral over the angle remains.  J_0 = 2.973210...

    Parameters
    ----------
    k : float
        Exponent of the power-law grading, -1 < k < 1 (k = 0 is homogeneous, with E* = 4 E0 / 3).

    Returns
    -------
    float
        J_k, dimensionless, to a relative 1e-13.

    Raises
    ------
    ValueError
        If k is outside (-1, 1).

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
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
    """kappa(k) = 1/sqrt(C_k) of the graded detachment criterion (Eq. 42).

    C_k = (3+k) J_k / (4 pi (1+k)(2+k)), from the isolated-element energy argument of Eq. 20;
    k = 0 reproduces Eq. 22.  An estimate: the paper calibrates its kappa numerically.

    Parameters
    ----------
    k : float
        Exponent of the power-law grading, -1 < k < 1 (k = 0 is homogeneous, with E* = 4 E0 / 3).

    Returns
    -------
    float
        kappa(k), dimensionless.

    Raises
    ------
    ValueError
        If k is outside (-1, 1).

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    C = (3.0 + k) * graded_two_square_integral(k) / (4.0 * math.pi * (1.0 + k) * (2.0 + k))
    return 1.0 / math.sqrt(C)


def graded_critical_stress(*, E0: float, c0: float, k: float, work: float, spacing: float) -> float:
    """Critical tensile stress on a graded half-space, kappa(k) sqrt(E0 w / (c0^k Delta^(1-k))) (Eq. 42).

    Parameters
    ----------
    E0 : float
        Modulus of the graded half-space at the reference depth, E(c0) = E0 (Pa), > 0.
    c0 : float
        Reference depth c0 of E(z) = E0 (z/c0)^k (m), > 0.
    k : float
        Exponent of the power-law grading, -1 < k < 1 (k = 0 is homogeneous, with E* = 4 E0 / 3).
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    spacing : float
        Element side Delta of the boundary-element grid (m), > 0.

    Returns
    -------
    float
        sigma_c (Pa), >= 0.

    Raises
    ------
    ValueError
        If k is outside (-1, 1).

    References
    ----------
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return graded_criterion_constant(k) * math.sqrt(E0 * work / (c0**k * spacing ** (1.0 - k)))


# ---------------------------------------------------------------------------
# ellipse and sphere
# ---------------------------------------------------------------------------


def elliptical_punch_stiffness(*, E_star: float, semi_major: float, semi_minor: float) -> float:
    """Stiffness of an elliptical flat punch, K = pi E* a / K(e) (Galin).

    F = pi E* a d / K(e) with e^2 = 1 - b^2/a^2 and K the complete elliptic integral of the
    first kind (scipy's ellipk takes the parameter m = e^2).  e = 0 gives Eq. 1.

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    semi_major : float
        Semi-major axis a (m), > 0.
    semi_minor : float
        Semi-minor axis b (m), 0 < b <= a.

    Returns
    -------
    float
        K (N/m).

    References
    ----------
    - Galin, L.A., "Contact Problems in the Theory of Elasticity" (1953; English translation 1961).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    m = 1.0 - (semi_minor / semi_major) ** 2
    return math.pi * E_star * semi_major / special.ellipk(m)


def jkr_pulloff_force(*, work: float, sphere_radius: float) -> float:
    """JKR pull-off force of a sphere, 1.5 pi w R: the magnitude of the largest tensile force.

    Under force control; a check of the boundary-element method named by the paper.

    Parameters
    ----------
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    sphere_radius : float
        Radius R of the sphere (m), > 0.

    Returns
    -------
    float
        1.5 pi w R (N), >= 0.

    References
    ----------
    - Johnson, K.L., Kendall, K., Roberts, A.D., "Surface energy and the contact of elastic solids",
      Proc. R. Soc. Lond. A 324:301-313 (1971).
    - Popov, V.L., Pohrt, R., Li, Q., "Strength of adhesive contacts: influence of contact geometry and
      material gradients", Friction 5(3):308-325 (2017).
    """
    return 1.5 * math.pi * work * sphere_radius


def jkr_force(*, E_star: float, work: float, sphere_radius: float, contact_radius):
    """JKR force at contact radius a, F = 4 E* a^3 / (3 R) - sqrt(8 pi w E* a^3).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    sphere_radius : float
        Radius R of the sphere (m), > 0.
    contact_radius : float or array_like
        Contact radius a (m), >= 0.

    Returns
    -------
    float or numpy.ndarray
        F (N), of the shape of ``contact_radius``; negative is tensile.

    References
    ----------
    - Johnson, K.L., Kendall, K., Roberts, A.D., "Surface energy and the contact of elastic solids",
      Proc. R. Soc. Lond. A 324:301-313 (1971).
    """
    a = np.asarray(contact_radius, float)
    return 4.0 * E_star * a**3 / (3.0 * sphere_radius) - np.sqrt(8.0 * math.pi * work * E_star * a**3)


def jkr_approach(*, E_star: float, work: float, sphere_radius: float, contact_radius):
    """JKR approach at contact radius a, d = a^2 / R - sqrt(2 pi w a / E*).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), >= 0.
    sphere_radius : float
        Radius R of the sphere (m), > 0.
    contact_radius : float or array_like
        Contact radius a (m), >= 0.

    Returns
    -------
    float or numpy.ndarray
        d (m), of the shape of ``contact_radius``.

    References
    ----------
    - Johnson, K.L., Kendall, K., Roberts, A.D., "Surface energy and the contact of elastic solids",
      Proc. R. Soc. Lond. A 324:301-313 (1971).
    """
    a = np.asarray(contact_radius, float)
    return a**2 / sphere_radius - np.sqrt(2.0 * math.pi * work * a / E_star)


# ---------------------------------------------------------------------------
# finite range: the long-range (stiff) limit of a flat circle
# ---------------------------------------------------------------------------

#: (u(0) - mean u) / (sigma a / E*) for a uniform pressure sigma on a circle of radius a:
#: u(0) = 2 sigma a / E*, its mean over the circle 16 sigma a / (3 pi E*)
UNIFORM_DISC_DISHING = 2.0 - 16.0 / (3.0 * math.pi)


def long_range_flat_circle_force(*, E_star: float, radius: float, work: float, range: float, potential: str) -> float:
    """Pull-off force of a flat circle whose process zone l_c is long: pi a^2 sigma0 (1 - c a / l_c).

    With a finite-range potential (peak stress sigma0 = w / rho, l_c = E* rho^2 / w), to first
    order in eps = sigma0 a / (E* rho) = a / l_c; derived for this package (not in the source
    paper).  When l_c >> a the adhesive traction deforms the body by about sigma0 a / E*, far
    less than the range, so the traction is nearly its peak sigma0 everywhere on the face and
    the tension is largest where the gaps are smallest: when the surface last touches the
    punch.  To first order the surface then takes the displacement of a uniform pressure sigma0
    on the circle, largest at the centre (2 sigma0 a / E*), which is where it touches, and the
    gaps are g(r) = u(0) - u(r).  Exponential potential, traction sigma0 exp(-g / rho) ~
    sigma0 (1 - g / rho): F_A = pi a^2 sigma0 (1 - (u(0) - mean u) / rho), so
    c = 2 - 16 / (3 pi) (:data:`UNIFORM_DISC_DISHING`); the next order, of eps^2, is not
    derived (nor the maximum's shift slightly into contact, where the central bulge pressed
    against the punch gains adhesion linearly and costs a Hertz-like reaction, an eps^3
    effect).  An asymptotic result for eps << 1.
    Maugis-Dugdale, traction sigma0 while g < rho: every gap is below the range at the last
    touch while u(0) - u(a) = (2 - 4/pi) sigma0 a / E* < rho, i.e. eps < 1 / (2 - 4/pi), and
    then F_A = pi a^2 sigma0 exactly (c = 0).

    Parameters
    ----------
    E_star : float
        Effective modulus E* = E / (1 - nu^2) of the homogeneous half-space (Pa), > 0.
    radius : float
        Punch radius a (m), > 0.
    work : float
        Work of adhesion w per unit area (J/m^2), > 0.
    range : float
        Range rho of the potential (m), > 0.
    potential : str
        ``"exponential"`` or ``"maugis_dugdale"`` (:class:`bem_energy.Potential`).

    Returns
    -------
    float
        F_A (N), > 0.

    Raises
    ------
    ValueError
        For an unknown potential, a Maugis-Dugdale process zone too short for the exact result
        (eps >= 1 / (2 - 4/pi)), or an exponential one so short that the first-order force is
        not positive (eps >= 1 / c; the expansion is for eps << 1).
    """
    sigma0 = work / range
    eps = sigma0 * radius / (E_star * range)
    area = math.pi * radius**2
    if potential == "exponential":
        if UNIFORM_DISC_DISHING * eps >= 1.0:
            raise ValueError(f"eps = a / l_c = {eps:g} is not below 1 / c: the first order is no force there")
        return area * sigma0 * (1.0 - UNIFORM_DISC_DISHING * eps)
    if potential == "maugis_dugdale":
        if eps * (2.0 - 4.0 / math.pi) >= 1.0:
            raise ValueError(f"eps = a / l_c = {eps:g} is not below 1 / (2 - 4/pi): the edge gap reaches the range")
        return area * sigma0
    raise ValueError(f"potential: must be 'exponential' or 'maugis_dugdale' (got {potential!r})")
