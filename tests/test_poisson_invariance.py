"""A rigid punch on a homogeneous half-space feels the material only through E* = E / (1 - nu^2)
(Eqs. 1-8: the surface Green's function is 1 / (pi E* r)).  At equal E*, whatever Poisson's
ratio, both BEMs must therefore return the same numbers, up to round-off.  E* = 1 is exact in
floating point for every nu below (E = fl(1 - nu^2), then E / fl(1 - nu^2) = 1), so any
difference comes from a solver that reads E or nu instead of E*; the mutant test shows the
check catches one that uses E.
"""

import bem_energy as be
import bem_griffith as bg
import contact_scene as cs

NUS = (-0.5, 0.0, 0.3, 0.5)
# a small triangle (no symmetry the grid could hide a bug behind) on a coarse grid
FACE = cs.Triangle.equilateral(1.0)


def _scenes(work, range_=None):
    out = []
    for nu in NUS:
        mat = cs.Homogeneous(1.0 - nu**2, nu)
        out.append(cs.Scene(cs.Indenter(FACE), mat, cs.Adhesion(work, range_)))
    return out


def _griffith(sc):
    return bg.solve(sc, bg.GriffithSettings(grid=cs.Grid(elements_per_radius=8)))


def _energy(sc):
    return be.solve(sc, be.EnergySettings(grid=cs.Grid(elements_per_radius=8), minimiser="pk"))


def _spread(results):
    """Largest relative spread of pull-off force, pull-off approach and stiffness over the list."""
    worst = 0.0
    for name in ("pulloff_force", "pulloff_approach", "stiffness"):
        vals = [getattr(r, name) for r in results]
        ref = max(abs(v) for v in vals)
        worst = max(worst, (max(vals) - min(vals)) / ref)
    return worst


def _runs():
    g = [_griffith(sc) for sc in _scenes(1.0)]
    e = [_energy(sc) for sc in _scenes(0.02, 0.06)]  # finite range: l_c = E* rho^2 / w = 0.18
    return g, e


def test_both_bems_depend_on_nu_only_through_the_effective_modulus():
    assert all(sc.material.effective_modulus == 1.0 for sc in _scenes(1.0))
    g, e = _runs()
    assert all(r.converged for r in g + e)
    assert g[0].pulloff_force > 0 and e[0].pulloff_force > 0
    assert _spread(g) <= 1e-12
    assert _spread(e) <= 1e-12


def test_the_check_catches_a_solver_that_uses_youngs_modulus(monkeypatch):
    # mutant: every solver reads E where it should read E*; the results then scale with
    # 1 - nu^2 (0.75 ... 1 here) and the spread is far above round-off
    monkeypatch.setattr(cs.Homogeneous, "effective_modulus", property(lambda self: self.youngs_modulus))
    g, e = _runs()
    assert _spread(g) > 0.1
    assert _spread(e) > 0.1
