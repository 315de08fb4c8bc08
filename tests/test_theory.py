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
    ref, _ = integrate.dblquad(lambda v, u: 4 * (1 - u) * (1 - v) * math.hypot(u, v) ** -(1 + k), 0, 1, 0, 1,
                               epsabs=1e-10, epsrel=1e-10)
    assert T.graded_two_square_integral(k) == pytest.approx(ref, rel=1e-6)


def test_kendall_identities():
    K = T.kendall_stiffness(E_star=E, radius=A)
    dc = T.kendall_critical_approach(E_star=E, radius=A, work=W)
    FA = T.kendall_adhesion_force(E_star=E, radius=A, work=W)
    assert FA == pytest.approx(K * abs(dc), rel=1e-14)                     # Eq. 6 = K |d_c|
    assert T.kendall_detachment_force(E_star=E, radius=A, work=W) == pytest.approx(-FA)
    # Eq. 3 at d_c gives back a; Eq. 2 is stationary in a there
    assert T.critical_radius(E_star=E, approach=dc, work=W) == pytest.approx(A)
    h = 1e-6
    dU = (T.kendall_energy(E_star=E, radius=A + h, approach=dc, work=W)
          - T.kendall_energy(E_star=E, radius=A - h, approach=dc, work=W)) / (2 * h)
    assert abs(dU) < 1e-8
    Uel, Uad = T.kendall_energies_at_detachment(radius=A, work=W)
    assert Uel == pytest.approx(0.5 * K * dc**2) and Uad == pytest.approx(Uel / 2)
    # Griffith: G = w at the detachment force
    assert T.flat_circle_energy_release_rate(force=FA, E_star=E, radius=A) == pytest.approx(W)


def test_bounds_coincide_for_circle_and_order_for_square():
    area = math.pi * A**2
    assert T.upper_bound_force(E_star=E, work=W, area=area) == pytest.approx(T.kendall_adhesion_force(E_star=E, radius=A, work=W))
    assert T.lower_bound_force(E_star=E, work=W, incircle_radius=A) == pytest.approx(T.upper_bound_force(E_star=E, work=W, area=area))
    side = 2.0
    up = T.upper_bound_force(E_star=E, work=W, area=side**2)
    lo = T.lower_bound_force(E_star=E, work=W, incircle_radius=side / 2)
    assert up > lo
    assert T.upper_bound_approach(E_star=E, work=W, area=side**2) < T.lower_bound_approach(E_star=E, work=W, incircle_radius=1.0) < 0
    # filling factor: F ~ sqrt(phi) (Eq. 24)
    assert T.upper_bound_force(E_star=E, work=W, area=4, filling_factor=0.25) == pytest.approx(up / 2)


def test_critical_stress_balances_element_energy():
    dx = 0.01
    s = T.critical_stress(E_star=E, work=W, spacing=dx)
    assert T.ELEMENT_ENERGY_CONSTANT * s**2 * dx**3 / E == pytest.approx(W * dx**2)


@pytest.mark.parametrize("k", [-0.5, 0.25, 0.7])
def test_graded_consistency(k):
    E0, c0 = 2.0, 0.7
    K = T.graded_stiffness(E0=E0, c0=c0, k=k, radius=A)
    dc = T.graded_critical_approach(E0=E0, c0=c0, k=k, radius=A, work=W)
    FA = T.graded_adhesion_force(E0=E0, c0=c0, k=k, radius=A, work=W)
    assert FA == pytest.approx(K * abs(dc), rel=1e-12)                     # Eq. 39 = Eq. 34 x Eq. 38
    h = 1e-6                                                               # Eqs. 36-37: dU/da = 0 at d_c
    dU = (T.graded_energy(E0=E0, c0=c0, k=k, radius=A + h, approach=dc, work=W)
          - T.graded_energy(E0=E0, c0=c0, k=k, radius=A - h, approach=dc, work=W)) / (2 * h)
    assert abs(dU) < 1e-7


def test_graded_reduces_to_homogeneous_incompressible_at_k0():
    E0, c0 = 3.0, 5.0
    Es = 4 * E0 / 3
    assert T.graded_stiffness(E0=E0, c0=c0, k=0.0, radius=A) == pytest.approx(T.kendall_stiffness(E_star=Es, radius=A))
    assert T.graded_adhesion_force(E0=E0, c0=c0, k=0.0, radius=A, work=W) == pytest.approx(T.kendall_adhesion_force(E_star=Es, radius=A, work=W))
    assert T.graded_critical_approach(E0=E0, c0=c0, k=0.0, radius=A, work=W) == pytest.approx(T.kendall_critical_approach(E_star=Es, radius=A, work=W))
    assert T.graded_critical_stress(E0=E0, c0=c0, k=0.0, work=W, spacing=0.01) == pytest.approx(T.critical_stress(E_star=Es, work=W, spacing=0.01))
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
        val, _ = integrate.quad(lambda r: (r - rneg) ** ((k - 1) / 2), 0, rmax, weight="alg",
                                wvar=(-k, (k - 1) / 2), epsabs=1e-12)
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
    table = {-0.9: 0.7785, -0.75: 1.1867, -0.5: 1.5425, -0.25: 1.6859, 0: 1.6786, 0.25: 1.5449,
             0.5: 1.2928, 0.75: 0.9061, 0.9: 0.5604}
    for k, v in table.items():
        assert T.graded_criterion_constant(k) == pytest.approx(v, abs=6e-5)


def test_ellipse_reduces_to_circle_and_lies_between_inscribed_and_equal_area():
    assert T.elliptical_punch_stiffness(E_star=E, semi_major=A, semi_minor=A) == pytest.approx(T.kendall_stiffness(E_star=E, radius=A))
    K = T.elliptical_punch_stiffness(E_star=E, semi_major=2.0, semi_minor=1.0)
    assert T.kendall_stiffness(E_star=E, radius=1.0) < K
    assert K < T.kendall_stiffness(E_star=E, radius=2.0)


def test_jkr_pulloff_is_force_minimum():
    R = 2.0
    res = optimize.minimize_scalar(lambda a: T.jkr_force(E_star=E, work=W, sphere_radius=R, contact_radius=a),
                                   bounds=(1e-6, 5), method="bounded", options={"xatol": 1e-12})
    assert -res.fun == pytest.approx(T.jkr_pulloff_force(work=W, sphere_radius=R), rel=1e-8)


def test_filling_factor_relations():
    a0 = 0.5
    phi = T.constant_force_filling(core_radius=a0)
    forces = [T.filling_adhesion_force(E_star=E, work=W, radius=a, filling_at_radius=float(phi(a))) for a in (0.6, 0.8, 1.2)]
    assert np.ptp(forces) < 1e-12 * forces[0]                              # Eq. 29
    assert forces[0] == pytest.approx(T.kendall_adhesion_force(E_star=E, radius=a0, work=W))
    b = 0.7
    smooth = lambda a: 1.0 / (1.0 + (a / b) ** 2)
    assert T.filling_last_stable_radius(filling=smooth, radius_min=0.1, radius_max=2.0) == pytest.approx(b, rel=1e-7)  # Eq. 31
    assert T.filling_is_stable(radius=0.5, filling=smooth) and not T.filling_is_stable(radius=1.0, filling=smooth)
    # Eq. 27 is the stationary point of Eq. 25 in a
    a = 0.9
    d = T.filling_equilibrium_approach(E_star=E, work=W, radius=a, filling_at_radius=smooth(a))
    h = 1e-5
    dU = (T.filling_energy(E_star=E, work=W, radius=a + h, approach=d, filling=smooth)
          - T.filling_energy(E_star=E, work=W, radius=a - h, approach=d, filling=smooth)) / (2 * h)
    assert abs(dU) < 1e-7


@pytest.mark.parametrize("k", [-0.5, 0.0, 0.5])
def test_force_at_nominal_area_follows_eq39_under_a_change_of_size(k):
    F = lambda a: T.graded_adhesion_force(E0=1.3, c0=0.7, k=k, radius=a, work=0.4)  # noqa: E731
    a, b = 1.0, 1.07
    assert T.force_at_nominal_area(F(a), area=math.pi * a**2, nominal_area=math.pi * b**2, k=k) == pytest.approx(F(b), rel=1e-13)
