"""The closed forms of the formula sheet, checked through identities between them."""

import math

import numpy as np
import pytest
from scipy import integrate, optimize

from contact_scene import theory as T

E, W, A = 1.7, 0.3, 0.8


def test_element_constant_closed_form_and_two_square_integral():
    # Eq. 20: the constant equals J_0 / (2 pi); J_0 by brute-force 2-D quadrature, independently
    J0, _ = integrate.dblquad(lambda v, u: 4 * (1 - u) * (1 - v) / math.hypot(u, v), 0, 1, 0, 1, epsabs=1e-11)
    assert T.ELEMENT_ENERGY_CONSTANT == pytest.approx(J0 / (2 * math.pi), rel=1e-8)
    assert T.graded_two_square_integral(0.0) == pytest.approx(J0, rel=1e-9)
    assert round(T.ELEMENT_ENERGY_CONSTANT, 6) == 0.473201


@pytest.mark.parametrize("k", [-0.75, -0.3, 0.4])
def test_two_square_integral_brute_force(k):
    ref, _ = integrate.dblquad(
        lambda v, u: 4 * (1 - u) * (1 - v) * math.hypot(u, v) ** -(1 + k), 0, 1, 0, 1, epsabs=1e-10, epsrel=1e-10
    )
    assert T.graded_two_square_integral(k) == pytest.approx(ref, rel=1e-6)


def test_kendall_identities():
    K = T.kendall_stiffness(E_star=E, radius=A)
    dc = T.kendall_critical_approach(E_star=E, radius=A, work=W)
    FA = T.kendall_adhesion_force(E_star=E, radius=A, work=W)
    assert FA == pytest.approx(K * abs(dc), rel=1e-14)  # Eq. 6 = K |d_c|
    assert T.kendall_detachment_force(E_star=E, radius=A, work=W) == pytest.approx(K * dc, rel=1e-14)  # Eq. 5
    # Eq. 3 at d_c gives back a; Eq. 2 is stationary in a there
    assert T.critical_radius(E_star=E, approach=dc, work=W) == pytest.approx(A)
    h = 1e-6
    dU = (
        T.kendall_energy(E_star=E, radius=A + h, approach=dc, work=W)
        - T.kendall_energy(E_star=E, radius=A - h, approach=dc, work=W)
    ) / (2 * h)
    assert abs(dU) < 1e-8
    # Eqs. 7-8: the elastic energy is the work of the linear force F = K d up to d_c, and the
    # total energy of Eq. 2 at detachment is U_el - U_ad
    Uel, Uad = T.kendall_energies_at_detachment(radius=A, work=W)
    work_of_force, _ = integrate.quad(lambda d: K * d, 0.0, dc)
    assert Uel == pytest.approx(work_of_force, rel=1e-12)
    assert Uel - Uad == pytest.approx(T.kendall_energy(E_star=E, radius=A, approach=dc, work=W), rel=1e-12)
    # Griffith: G = w at the detachment force, and the sheet's compliance form G = (d^2/2) (dK/da) / (2 pi a)
    assert T.flat_circle_energy_release_rate(force=FA, E_star=E, radius=A) == pytest.approx(W)
    dK_da = (T.kendall_stiffness(E_star=E, radius=A + h) - T.kendall_stiffness(E_star=E, radius=A - h)) / (2 * h)
    assert dc**2 / 2 * dK_da / (2 * math.pi * A) == pytest.approx(W, rel=1e-8)


#: F_A / F_A,upper (Eq. 13) extrapolated to N -> infinity from the Griffith BEM at 64 and 128
#: elements per radius (docs/accuracy.md, zero-range section): square 0.877, triangle 0.809
CONVERGED_FRACTION_OF_UPPER = {"square": 0.877, "triangle": 0.809}


def test_bounds_coincide_for_circle_and_bracket_the_converged_square_and_triangle():
    area = math.pi * A**2
    assert T.upper_bound_force(E_star=E, work=W, area=area) == pytest.approx(
        T.kendall_adhesion_force(E_star=E, radius=A, work=W)
    )
    assert T.upper_bound_approach(E_star=E, work=W, area=area) == pytest.approx(
        T.kendall_critical_approach(E_star=E, radius=A, work=W)
    )
    # square of side s: incircle s/2, equivalent radius s/sqrt(pi), so lower/upper = (pi/4)^(3/4) for the
    # force (F ~ a^(3/2)) and (pi/4)^(1/4) for the approach (d ~ a^(1/2)); equilateral triangle of side s:
    # incircle s/(2 sqrt 3), area sqrt(3) s^2/4
    side = 2.0
    faces = {"square": (side**2, side / 2), "triangle": (math.sqrt(3) / 4 * side**2, side / (2 * math.sqrt(3)))}
    for face, (face_area, incircle) in faces.items():
        radius_ratio = incircle / math.sqrt(face_area / math.pi)
        up = T.upper_bound_force(E_star=E, work=W, area=face_area)
        lo = T.lower_bound_force(E_star=E, work=W, incircle_radius=incircle)
        assert lo / up == pytest.approx(radius_ratio**1.5, rel=1e-13)
        d_up = T.upper_bound_approach(E_star=E, work=W, area=face_area)
        d_lo = T.lower_bound_approach(E_star=E, work=W, incircle_radius=incircle)
        assert d_lo / d_up == pytest.approx(radius_ratio**0.5, rel=1e-13)
        assert lo / up < CONVERGED_FRACTION_OF_UPPER[face] < 1.0
    assert (math.pi / 4) ** 0.75 == pytest.approx(
        T.lower_bound_force(E_star=E, work=W, incircle_radius=1.0) / T.upper_bound_force(E_star=E, work=W, area=4.0),
        rel=1e-13,
    )
    # filling factor (Eq. 24): F ~ sqrt(phi), and a constant phi in Eq. 28 gives the same force
    up = T.upper_bound_force(E_star=E, work=W, area=4.0)
    assert T.upper_bound_force(E_star=E, work=W, area=4, filling_factor=0.25) == pytest.approx(up / 2)
    a_eq = math.sqrt(4.0 / math.pi)
    assert T.upper_bound_force(E_star=E, work=W, area=4.0, filling_factor=0.3) == pytest.approx(
        T.filling_adhesion_force(E_star=E, work=W, radius=a_eq, filling_at_radius=0.3), rel=1e-13
    )


def test_critical_stress_releases_the_work_of_adhesion_of_one_element():
    """Eq. 22 from the half-space itself: unloading a uniform stress sigma on a square element of
    side Delta releases its elastic energy (1/2) int sigma u dA = sigma^2 Delta^3 J_0 / (2 pi E*),
    u from Boussinesq's 1/(pi E* r); J_0 by brute-force quadrature.  At sigma_c this equals
    w Delta^2, for every Delta (so sigma_c ~ Delta^-1/2)."""
    J0, _ = integrate.dblquad(lambda v, u: 4 * (1 - u) * (1 - v) / math.hypot(u, v), 0, 1, 0, 1, epsabs=1e-11)
    for spacing in (0.01, 0.37):
        sigma = T.critical_stress(E_star=E, work=W, spacing=spacing)
        released = sigma**2 * spacing**3 * J0 / (2 * math.pi * E)
        assert released == pytest.approx(W * spacing**2, rel=1e-8)
    # the paper's number (Eq. 22)
    assert T.critical_stress(E_star=E, work=W, spacing=0.01) == pytest.approx(
        math.sqrt(E * W / (0.473201 * 0.01)), rel=1e-6
    )


@pytest.mark.parametrize("k", [-0.5, 0.25, 0.7])
def test_graded_consistency(k):
    E0, c0 = 2.0, 0.7
    K = T.graded_stiffness(E0=E0, c0=c0, k=k, radius=A)
    dc = T.graded_critical_approach(E0=E0, c0=c0, k=k, radius=A, work=W)
    FA = T.graded_adhesion_force(E0=E0, c0=c0, k=k, radius=A, work=W)
    assert FA == pytest.approx(K * abs(dc), rel=1e-12)  # Eq. 39 = Eq. 34 x Eq. 38
    h = 1e-6  # Eqs. 36-37: dU/da = 0 at d_c
    dU = (
        T.graded_energy(E0=E0, c0=c0, k=k, radius=A + h, approach=dc, work=W)
        - T.graded_energy(E0=E0, c0=c0, k=k, radius=A - h, approach=dc, work=W)
    ) / (2 * h)
    assert abs(dU) < 1e-7


def test_graded_reduces_to_homogeneous_incompressible_at_k0():
    E0, c0 = 3.0, 5.0
    Es = 4 * E0 / 3
    assert T.graded_stiffness(E0=E0, c0=c0, k=0.0, radius=A) == pytest.approx(T.kendall_stiffness(E_star=Es, radius=A))
    assert T.graded_adhesion_force(E0=E0, c0=c0, k=0.0, radius=A, work=W) == pytest.approx(
        T.kendall_adhesion_force(E_star=Es, radius=A, work=W)
    )
    assert T.graded_critical_approach(E0=E0, c0=c0, k=0.0, radius=A, work=W) == pytest.approx(
        T.kendall_critical_approach(E_star=Es, radius=A, work=W)
    )
    assert T.graded_critical_stress(E0=E0, c0=c0, k=0.0, work=W, spacing=0.01) == pytest.approx(
        T.critical_stress(E_star=Es, work=W, spacing=0.01)
    )
    assert T.graded_green_coefficient(E0=E0, c0=c0, k=0.0) == pytest.approx(1 / (math.pi * Es))


def _disk_potential(x, k):
    """int over the unit disk of (1-|y|^2)^((k-1)/2) |x-y|^-(1+k) dy, in polar coordinates about x,
    with both algebraic end singularities handled by quad's 'alg' weight."""

    def inner(t):
        e = np.array([math.cos(t), math.sin(t)])
        b = float(x @ e)
        c = float(x @ x) - 1.0
        rmax = -b + math.sqrt(b * b - c)
        rneg = -b - math.sqrt(b * b - c)
        val, _ = integrate.quad(
            lambda r: (r - rneg) ** ((k - 1) / 2), 0, rmax, weight="alg", wvar=(-k, (k - 1) / 2), epsabs=1e-12
        )
        return val

    v, _ = integrate.quad(inner, 0, 2 * math.pi, epsabs=1e-11, limit=200)
    return v


@pytest.mark.parametrize("k", [-0.4, 0.0, 0.5])
def test_graded_stiffness_from_green_function(k):
    # the sheet's identity: the potential is pi^2 / cos(pi k/2) everywhere in the disk ...
    for x in (np.array([0.0, 0.0]), np.array([0.3, 0.5])):
        assert _disk_potential(x, k) == pytest.approx(math.pi**2 / math.cos(math.pi * k / 2), rel=1e-7)
    # ... so the pressure (1-r^2)^((k-1)/2) gives a uniform displacement: K = F / d reproduces Eq. 34
    Ak = T.graded_green_coefficient(E0=1.0, c0=1.0, k=k)
    F = 2 * math.pi / (k + 1)
    d = Ak * math.pi**2 / math.cos(math.pi * k / 2)
    assert F / d == pytest.approx(T.graded_stiffness(E0=1.0, c0=1.0, k=k, radius=1.0), rel=1e-12)


def test_kappa_matches_table_within_its_digits():
    table = {
        -0.9: 0.7785,
        -0.75: 1.1867,
        -0.5: 1.5425,
        -0.25: 1.6859,
        0: 1.6786,
        0.25: 1.5449,
        0.5: 1.2928,
        0.75: 0.9061,
        0.9: 0.5604,
    }
    for k, v in table.items():
        assert T.graded_criterion_constant(k) == pytest.approx(v, abs=6e-5)


def test_ellipse_reduces_to_circle_and_lies_between_inscribed_and_equal_area():
    assert T.elliptical_punch_stiffness(E_star=E, semi_major=A, semi_minor=A) == pytest.approx(
        T.kendall_stiffness(E_star=E, radius=A)
    )
    K = T.elliptical_punch_stiffness(E_star=E, semi_major=2.0, semi_minor=1.0)
    assert T.kendall_stiffness(E_star=E, radius=1.0) < K
    assert K < T.kendall_stiffness(E_star=E, radius=2.0)


@pytest.mark.parametrize("aspect", [0.95, 0.9])
def test_nearly_circular_ellipse_is_stiffer_than_its_equal_area_circle_by_m2_over_64(aspect):
    """Galin's K = pi E* a / K(m), m = e^2, against the circle of the same area (radius sqrt(ab)):
    with K(m) = pi/2 (1 + m/4 + 9 m^2/64 + 25 m^3/256 + ...) and sqrt(a/b) = (1 - m)^(-1/4)
    = 1 + m/4 + 5 m^2/32 + 15 m^3/128 + ..., the ratio is 1 + m^2/64 + m^3/64 + O(m^4)."""
    a, b = 1.3, 1.3 * aspect
    m = 1 - aspect**2
    ratio = T.elliptical_punch_stiffness(E_star=E, semi_major=a, semi_minor=b) / T.kendall_stiffness(
        E_star=E, radius=math.sqrt(a * b)
    )
    assert ratio - 1 == pytest.approx(m**2 / 64 + m**3 / 64, rel=2 * m**2)


def test_jkr_pulloff_is_force_minimum():
    R = 2.0
    res = optimize.minimize_scalar(
        lambda a: T.jkr_force(E_star=E, work=W, sphere_radius=R, contact_radius=a),
        bounds=(1e-6, 5),
        method="bounded",
        options={"xatol": 1e-12},
    )
    assert -res.fun == pytest.approx(T.jkr_pulloff_force(work=W, sphere_radius=R), rel=1e-8)


def test_filling_factor_relations():
    a0 = 0.5
    phi = T.constant_force_filling(core_radius=a0)
    forces = [
        T.filling_adhesion_force(E_star=E, work=W, radius=a, filling_at_radius=float(phi(a))) for a in (0.6, 0.8, 1.2)
    ]
    assert np.ptp(forces) < 1e-12 * forces[0]  # Eq. 29
    assert forces[0] == pytest.approx(T.kendall_adhesion_force(E_star=E, radius=a0, work=W))
    b = 0.7

    def smooth(a):
        return 1.0 / (1.0 + (a / b) ** 2)

    assert T.filling_last_stable_radius(filling=smooth, radius_min=0.1, radius_max=2.0) == pytest.approx(
        b, rel=1e-7
    )  # Eq. 31
    assert T.filling_is_stable(radius=0.5, filling=smooth) and not T.filling_is_stable(radius=1.0, filling=smooth)
    # Eq. 27 is the stationary point of Eq. 25 in a
    a = 0.9
    d = T.filling_equilibrium_approach(E_star=E, work=W, radius=a, filling_at_radius=smooth(a))
    h = 1e-5
    dU = (
        T.filling_energy(E_star=E, work=W, radius=a + h, approach=d, filling=smooth)
        - T.filling_energy(E_star=E, work=W, radius=a - h, approach=d, filling=smooth)
    ) / (2 * h)
    assert abs(dU) < 1e-7


@pytest.mark.parametrize("k", [-0.5, 0.0, 0.5])
def test_force_at_nominal_area_follows_eq39_under_a_change_of_size(k):
    F = lambda a: T.graded_adhesion_force(E0=1.3, c0=0.7, k=k, radius=a, work=0.4)  # noqa: E731
    a, b = 1.0, 1.07
    assert T.force_at_nominal_area(F(a), area=math.pi * a**2, nominal_area=math.pi * b**2, k=k) == pytest.approx(
        F(b), rel=1e-13
    )


def test_long_range_flat_circle_force_scales_with_the_units_and_refuses_outside_its_range():
    """Lengths times L and stresses times S: w scales as S L, rho as L, F_A as S L^2 (eps is
    unchanged).  The exponential potential's first-order force falls below the peak-stress one
    by c eps; Maugis-Dugdale's is that exactly, up to the edge gap reaching the range."""
    args = dict(E_star=1.3, radius=0.7, work=0.4, range=2.0)
    for potential in ("exponential", "maugis_dugdale"):
        F = T.long_range_flat_circle_force(**args, potential=potential)
        for L, S in ((1e-6, 1e9), (1e3, 1e-2)):
            scaled = dict(E_star=1.3 * S, radius=0.7 * L, work=0.4 * S * L, range=2.0 * L)
            assert T.long_range_flat_circle_force(**scaled, potential=potential) == pytest.approx(F * S * L**2)
    peak = math.pi * 0.7**2 * 0.4 / 2.0
    eps = 0.4 * 0.7 / (1.3 * 2.0**2)
    assert T.long_range_flat_circle_force(**args, potential="maugis_dugdale") == pytest.approx(peak)
    assert T.long_range_flat_circle_force(**args, potential="exponential") == pytest.approx(
        peak * (1 - (2 - 16 / (3 * math.pi)) * eps)
    )
    short = dict(args, range=0.2)  # eps = 5.4: past either potential's range of validity
    for potential in ("exponential", "maugis_dugdale"):
        with pytest.raises(ValueError, match="eps"):
            T.long_range_flat_circle_force(**short, potential=potential)
    with pytest.raises(ValueError, match="potential"):
        T.long_range_flat_circle_force(**args, potential="lennard_jones")
