"""The built-in default suite: scenes every method is checked on (and the pytest plugin's
reference scenes).  Dimensionless unless the paper gives units (E* = 1, w = 1, unit size)."""
from __future__ import annotations

import contact_scene as cs

__all__ = ["SUITE", "scene"]

_INC = cs.Homogeneous(0.75, 0.5)          # E* = 1, nu = 1/2


def _flat(name, shape, material=_INC, work=1.0):
    return cs.Scene(cs.Indenter(shape), material, cs.Adhesion(work), name=name)


SUITE: dict[str, cs.Scene] = {
    "kendall_circle": _flat("kendall_circle", cs.Circle(1.0), cs.Homogeneous(1.0, 0.3)),
    "incompressible_circle": _flat("incompressible_circle", cs.Circle(1.0)),
    "graded_circle_k0.25": _flat("graded_circle_k0.25", cs.Circle(1.0), cs.PowerLawGraded(1.0, 1.0, 0.25)),
    "graded_circle_k0.5": _flat("graded_circle_k0.5", cs.Circle(1.0), cs.PowerLawGraded(1.0, 1.0, 0.5)),
    "square": _flat("square", cs.Square(2.0)),
    "triangle": _flat("triangle", cs.Triangle.equilateral(2.0)),
    "star": _flat("star", cs.Star(5, 1.0, 0.45)),
    "rectangle": _flat("rectangle", cs.Rectangle(4.0, 1.0)),
    "two_circles": _flat("two_circles", cs.TwoCircles(radius1=1.0, radius2=0.6, distance=1.3)),
    "jkr_sphere": cs.Scene(cs.Indenter(cs.Circle(0.42), cs.Paraboloid(1.0)), _INC, cs.Adhesion(0.01),
                           cs.Loading(press_approach=0.15), name="jkr_sphere"),
}


def scene(name: str) -> cs.Scene:
    if name not in SUITE:
        raise cs.SceneError("scene", f"unknown built-in scene {name!r}; one of: {', '.join(SUITE)}")
    return SUITE[name]
