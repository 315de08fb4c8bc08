"""Long studies, outside CI: ``pytest -m slow``."""
from pathlib import Path

import pytest

import bem_griffith as bg
import contact_scene as cs
from contact_scene import theory as T

pytestmark = pytest.mark.slow


def test_kendall_envelope_up_to_128():
    sc = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))
    FK = T.kendall_adhesion_force(E_star=1.0, radius=1.0, work=1.0)
    for N in (80, 96, 112, 128):
        r = bg.solve(sc, bg.Settings(grid=cs.Grid(elements_per_radius=N)))
        assert abs(r.pulloff_force / FK - 1) <= 0.5 / N


def test_jkr_first_order_at_finer_grids():
    sc = cs.load_scene(Path(__file__).parents[1] / "scenes" / "jkr_sphere.toml")
    FJ = T.jkr_pulloff_force(work=0.01, sphere_radius=1.0)
    for N in (40, 48):
        err = bg.solve(sc, bg.Settings(grid=cs.Grid(elements_per_radius=N))).pulloff_force / FJ - 1
        assert 0 < err <= 2.5 / N      # first order from above, ~1.9/N in the sweep
