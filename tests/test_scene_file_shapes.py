"""Every shape a scene file can name builds the shape its table describes, with its keys
mapped to the constructor's; and each kind of malformed shape or profile table is refused,
naming the key."""

from __future__ import annotations

import pytest

import contact_scene as cs
from contact_scene import shapes
from contact_scene.io import SHAPE_KEYS, scene_from_dict, shape_from_dict

CASES = {
    "circle": ({"radius": 1.5, "center": [0.5, -0.25]}, shapes.Circle(1.5, center=(0.5, -0.25))),
    "ellipse": ({"semi_major": 2.0, "semi_minor": 0.5, "rotation_deg": 20.0}, shapes.Ellipse(2.0, 0.5, 20.0)),
    "square": ({"side": 2.0}, shapes.Square(2.0)),
    "rectangle": ({"width": 4.0, "height": 1.0, "rotation_deg": 10.0}, shapes.Rectangle(4.0, 1.0, 10.0)),
    "triangle": ({"vertices": [[0, 0], [2, 0], [0.5, 1.5]]}, shapes.Triangle(((0, 0), (2, 0), (0.5, 1.5)))),
    "regular_polygon": ({"n_sides": 6, "circumradius": 1.0}, shapes.RegularPolygon(6, 1.0)),
    "star": ({"n_rays": 5, "outer_radius": 1.0, "inner_radius": 0.45}, shapes.Star(5, 1.0, 0.45)),
    "polygon": ({"vertices": [[0, 0], [2, 0], [2, 1], [0, 2]]}, shapes.Polygon(((0, 0), (2, 0), (2, 1), (0, 2)))),
    "power_law_star": (
        {"n_rays": 4, "core_radius": 0.3, "outer_radius": 1.0, "samples": 32},
        shapes.PowerLawStar(4, 0.3, 1.0, samples=32),
    ),
    "two_circles": ({"radius1": 1.0, "radius2": 0.6, "distance": 1.3}, shapes.TwoCircles(1.0, 0.6, 1.3)),
    "square_with_faults": (
        {"side": 2.0, "v_cut_depth": 0.3, "v_cut_width": 0.2},
        shapes.SquareWithFaults(2.0, v_cut_depth=0.3, v_cut_width=0.2),
    ),
    "brush": ({"side": 2.0, "pillar_radius": 0.1, "pitch": 0.5}, shapes.Brush(2.0, 0.1, pitch=0.5)),
    "union": (
        {"parts": [{"shape": "circle", "radius": 1.0}, {"shape": "square", "side": 1.0, "center": [1.0, 0.0]}]},
        shapes.Union((shapes.Circle(1.0), shapes.Square(1.0, center=(1.0, 0.0)))),
    ),
    "difference": (
        {"base": {"shape": "square", "side": 2.0}, "cuts": [{"shape": "circle", "radius": 0.3}]},
        shapes.Difference(shapes.Square(2.0), (shapes.Circle(0.3),)),
    ),
}


def test_the_cases_cover_every_shape_but_the_image():
    assert set(CASES) == set(SHAPE_KEYS) - {"image"}


@pytest.mark.parametrize("kind", sorted(CASES))
def test_a_shape_table_builds_its_shape(kind):
    table, shape = CASES[kind]
    assert shape_from_dict({"shape": kind, **table}) == shape


def test_rotation_and_mirror():
    # a shape without its own rotation parameter is wrapped; one with it keeps its closed form
    two = {"shape": "two_circles", "radius1": 1.0, "radius2": 0.6, "distance": 1.3}
    assert shape_from_dict({**two, "rotation_deg": 30.0}) == shapes.TwoCircles(1.0, 0.6, 1.3).rotated(30.0)
    assert shape_from_dict({**two, "mirror": True}) == shapes.TwoCircles(1.0, 0.6, 1.3).mirrored()
    star = {"shape": "star", "n_rays": 5, "outer_radius": 1.0, "inner_radius": 0.45}
    assert shape_from_dict({**star, "rotation_deg": 30.0}) == shapes.Star(5, 1.0, 0.45, rotation_deg=30.0)


@pytest.mark.parametrize("value", ["", False, [], True, "30", [30.0], float("nan")])
@pytest.mark.parametrize(
    "table",
    [
        {"shape": "circle", "radius": 1.0},  # wrapped in a rotation
        {"shape": "triangle", "side": 1.0},  # wrapped in a rotation
        {"shape": "square", "side": 1.0},  # takes rotation_deg itself
    ],
    ids=lambda t: t["shape"],
)
def test_a_rotation_that_is_not_a_number_is_refused_even_when_falsy(table, value):
    # "", false and [] used to pass as "no rotation" on a wrapped shape
    with pytest.raises(cs.SceneError, match="must be a") as caught:
        shape_from_dict({**table, "rotation_deg": value})
    assert caught.value.field == "indenter.rotation_deg"


def test_a_zero_rotation_is_no_rotation():
    assert shape_from_dict({"shape": "triangle", "side": 1.0, "rotation_deg": 0}) == shapes.Triangle.equilateral(1.0)
    assert shape_from_dict({"shape": "square", "side": 1.0, "rotation_deg": 0}) == shapes.Square(1.0)


_BRUSH = {"shape": "brush", "side": 1.0, "pillar_radius": 0.05}


@pytest.mark.parametrize(
    "table, field, users",
    [
        ({"layout": "regular", "count": -3, "seed": -1}, "indenter.count", "layouts 'random' and 'mixed'"),
        ({"layout": "regular", "seed": 0}, "indenter.seed", "layouts 'random' and 'mixed'"),  # even the default
        ({"count": 10}, "indenter.count", "layouts 'random' and 'mixed'"),  # regular by default
        ({"layout": "random", "count": 5, "pitch": -7}, "indenter.pitch", "layout 'regular'"),
        ({"layout": "mixed", "count": 5, "pitch": 0.2}, "indenter.pitch", "layout 'regular'"),  # even the default
    ],
)
def test_a_brush_key_its_layout_does_not_use_is_refused(table, field, users):
    with pytest.raises(cs.SceneError, match=f"only applies to {users}") as caught:
        shape_from_dict({**_BRUSH, **table})
    assert caught.value.field == field


def test_each_brush_layout_takes_its_own_keys():
    regular = shape_from_dict({**_BRUSH, "layout": "regular", "pitch": 0.3})
    assert regular == shapes.Brush(1.0, 0.05, pitch=0.3)
    for layout in ("random", "mixed"):
        brush = shape_from_dict({**_BRUSH, "layout": layout, "count": 6, "seed": 2})
        assert brush == shapes.Brush(1.0, 0.05, layout=layout, count=6, seed=2) and len(brush.parts) == 6


@pytest.mark.parametrize(
    "table, field",
    [
        ({"side": 2.0}, None),  # the triangle's equilateral form is accepted
        ({}, "indenter.side"),
        ({"side": 2.0, "vertices": [[0, 0], [1, 0], [0, 1]]}, "indenter.side"),
        ({"vertices": [[0, 0], [1, 0]]}, "indenter.vertices"),
        ({"vertices": [[0, 0], [1, 0, 2], [0, 1]]}, "indenter.vertices"),
        ({"vertices": [[0, 0], [1, "a"], [0, 1]]}, "indenter.vertices"),
        ({"vertices": [[0, 0], [1, True], [0, 1]]}, "indenter.vertices"),
    ],
)
def test_a_triangle_takes_side_or_vertices(table, field):
    if field is None:
        assert shape_from_dict({"shape": "triangle", **table}) == shapes.Triangle.equilateral(2.0)
        return
    with pytest.raises(cs.SceneError) as caught:
        shape_from_dict({"shape": "triangle", **table})
    assert caught.value.field == field


@pytest.mark.parametrize(
    "table, field",
    [
        ({"shape": "union", "parts": []}, "indenter.parts"),
        ({"shape": "union", "parts": {"shape": "circle"}}, "indenter.parts"),
        ({"shape": "difference", "base": {"shape": "square", "side": 1.0}, "cuts": {}}, "indenter.cuts"),
        ({"shape": "circle", "radius": 1.0, "mirror": "yes"}, "indenter.mirror"),
        ({"shape": "image", "path": 3, "pixel_size": 0.1}, "indenter.path"),
        ({"shape": "hexagon", "side": 1.0}, "indenter.shape"),
        ({"radius": 1.0}, "indenter.shape"),
    ],
)
def test_a_malformed_shape_table_is_refused_by_key(table, field):
    with pytest.raises(cs.SceneError) as caught:
        shape_from_dict(table)
    assert caught.value.field == field


BASE = {
    "material": {"model": "homogeneous", "youngs_modulus": 1.0, "poisson_ratio": 0.3},
    "adhesion": {"work_of_adhesion": 1.0},
    "loading": {"press_approach": 0.1},
}


@pytest.mark.parametrize(
    "profile, field",
    [
        ({"profile": "flat", "profile_radius": 2.0}, "indenter.profile_radius"),
        ({"profile": "flat", "half_angle_deg": 80.0}, "indenter.half_angle_deg"),
        ({"profile": "sphere"}, "indenter.profile_radius"),
        ({"profile": "paraboloid"}, "indenter.profile_radius"),
        ({"profile": "cone"}, "indenter.half_angle_deg"),
        ({"profile": "pyramid"}, "indenter.profile"),
        ({"profile": 3}, "indenter.profile"),
    ],
)
def test_a_malformed_profile_is_refused_by_key(profile, field):
    d = {**BASE, "indenter": {"shape": "circle", "radius": 1.0, **profile}}
    with pytest.raises(cs.SceneError) as caught:
        scene_from_dict(d)
    assert caught.value.field == field


def test_each_profile_builds():
    for profile, expected in (
        ({"profile": "sphere", "profile_radius": 5.0}, cs.Sphere(5.0)),
        ({"profile": "paraboloid", "profile_radius": 5.0}, cs.Paraboloid(5.0)),
        ({"profile": "cone", "half_angle_deg": 80.0}, cs.Cone(80.0)),
    ):
        sc = scene_from_dict({**BASE, "indenter": {"shape": "circle", "radius": 1.0, **profile}})
        assert sc.indenter.profile == expected
