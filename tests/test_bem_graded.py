"""Power-law graded half-spaces in the Griffith BEM (theory sheet section 5)."""

import numpy as np
import pytest

import bem_griffith as bg
import contact_scene as cs
from bem_griffith.kernel import graded_square_integral, love_square_integral
from contact_scene import theory as T
from square_quadrature import square_integral_reference


@pytest.mark.parametrize("k", [-0.9, -0.5, 0.25, 0.75, 0.95])
@pytest.mark.parametrize("x,y", [(0.0, 0.0), (0.3, 0.1), (1.7, 0.4), (3.0, -2.0)])
def test_graded_element_integral_matches_quadrature(k, x, y):
    assert graded_square_integral(x, y, 0.5, k) == pytest.approx(square_integral_reference(x, y, k), rel=1e-7)


def test_k0_is_love():
    X, Y = np.meshgrid(np.linspace(-3, 3, 13), np.linspace(-2, 2, 9))
    assert np.allclose(graded_square_integral(X, Y, 0.5, 0.0), love_square_integral(X, Y, 0.5), rtol=1e-12)


def test_k0_equals_homogeneous_incompressible():
    E0 = 1.2
    g = cs.Scene(cs.Indenter(cs.Triangle.equilateral(2.0)), cs.PowerLawGraded(E0, 3.0, 0.0), cs.Adhesion(0.7))
    h = cs.Scene(cs.Indenter(cs.Triangle.equilateral(2.0)), cs.Homogeneous(E0, 0.5), cs.Adhesion(0.7))
    st = bg.Settings(grid=cs.Grid(elements_per_radius=16), stop_when_certainly_detached=False)
    a, b = bg.solve(g, st), bg.solve(h, st)
    assert a.pulloff_force == pytest.approx(b.pulloff_force, rel=1e-9)
    assert a.pulloff_approach == pytest.approx(b.pulloff_approach, rel=1e-9)
    assert a.stiffness == pytest.approx(b.stiffness, rel=1e-10)


@pytest.mark.parametrize("k", [-0.75, -0.5, -0.25, 0.25, 0.5, 0.75])
def test_graded_circle_stiffness_matches_eq34(k):
    # Eq. 34; the staircase and the uniform-pressure elements give a first-order error
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.PowerLawGraded(1.0, 1.0, k), cs.Adhesion(1.0))
    errs = []
    for N in (16, 32):
        r = bg.press(sc, bg.Settings(grid=cs.Grid(elements_per_radius=N)))
        errs.append(abs(r.stiffness / T.graded_stiffness(E0=1.0, c0=1.0, k=k, radius=1.0) - 1))
    assert errs[1] < 0.1 / 32 * 1.5 and errs[0] < 0.1 / 16 * 1.5
