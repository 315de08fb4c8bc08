"""Declared fields (contact_scene.validation): every range of every scene part, shape and solver
setting is refused just outside and accepted just inside, by an error naming the field as the user
spells it and stating the range.

The walk over the declarations covers a new field automatically; the hand-written table of the key
physical ranges fails when a declaration is dropped or loosened (the walk alone would not notice)."""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import math
import pkgutil

import pytest
from hypothesis import given, settings, strategies as st

import bem_energy as be
import bem_griffith as bg
import contact_scene as cs
import crossval
import fem_reference as fr
from bem_energy.potentials import Potential
from bem_energy.settings import EnergySettings, ZeroRangeSettings
from bem_griffith.settings import GriffithSettings
from contact_scene.validation import check_fields, declared_fields, real
from fem_reference.solver import FemSettings

PACKAGES = ("contact_scene", "bem_griffith", "bem_energy", "fem_reference", "crossval", "halfspace")


def _validated_classes() -> set[type]:
    """Every dataclass in the packages that declares a checked field."""
    found = set()
    for name in PACKAGES:
        package = importlib.import_module(name)
        modules = [package] + [
            importlib.import_module(f"{name}.{m.name}")
            for m in pkgutil.walk_packages(package.__path__)
            if not m.name.endswith("__main__")
        ]
        for module in modules:
            for obj in vars(module).values():
                if inspect.isclass(obj) and dataclasses.is_dataclass(obj) and declared_fields(obj):
                    found.add(obj)
    return found


VALIDATED = sorted(_validated_classes(), key=lambda c: c.__name__)


def _image(tmp_path_factory) -> str:
    import matplotlib.image as mpimg
    import numpy as np

    path = tmp_path_factory.mktemp("validation") / "disc.png"
    yy, xx = np.mgrid[0:40, 0:40]
    mpimg.imsave(path, np.where((xx - 19.5) ** 2 + (yy - 19.5) ** 2 <= 15**2, 0.0, 1.0), cmap="gray", vmin=0, vmax=1)
    return str(path)


@pytest.fixture(scope="module")
def examples(tmp_path_factory):
    """class -> (the prefix its errors use, valid instances: together they switch on every
    conditional field)."""
    image = _image(tmp_path_factory)
    return {
        cs.Homogeneous: ("material", [cs.Homogeneous(1.0, 0.3)]),
        cs.PowerLawGraded: ("material", [cs.PowerLawGraded(1.0, 1.0, 0.25)]),
        cs.Paraboloid: ("indenter", [cs.Paraboloid(5.0)]),
        cs.Sphere: ("indenter", [cs.Sphere(5.0)]),
        cs.Cone: ("indenter", [cs.Cone(60.0)]),
        cs.Adhesion: ("adhesion", [cs.Adhesion(1.0, 0.1)]),
        cs.Loading: ("loading", [cs.Loading()]),
        cs.Outputs: ("outputs", [cs.Outputs()]),
        cs.Grid: ("grid", [cs.Grid(), cs.Grid(elements_per_radius=8, periodic=True, period=4.0)]),
        cs.Circle: ("indenter", [cs.Circle(1.0)]),
        cs.Ellipse: ("indenter", [cs.Ellipse(2.0, 1.0)]),
        cs.Square: ("indenter", [cs.Square(1.0)]),
        cs.Rectangle: ("indenter", [cs.Rectangle(1.0, 2.0)]),
        cs.RegularPolygon: ("indenter", [cs.RegularPolygon(6, 1.0)]),
        cs.Star: ("indenter", [cs.Star(5, 1.0, 0.5)]),
        cs.PowerLawStar: ("indenter", [cs.PowerLawStar(6, 0.5, 1.0)]),
        cs.TwoCircles: ("indenter", [cs.TwoCircles(1.0, 0.5, 2.0)]),
        cs.SquareWithFaults: ("indenter", [cs.SquareWithFaults(1.0, 0.2, 0.2, 2, 0.5, 0.05)]),
        cs.Brush: ("indenter", [cs.Brush(1.0, 0.05), cs.Brush(1.0, 0.05, layout="random", count=10, seed=3)]),
        cs.ImageMask: ("indenter", [cs.ImageMask(path=image, pixel_size=0.05)]),
        type(cs.Circle(1.0).scaled(2.0)): ("indenter", [cs.Circle(1.0).scaled(2.0)]),
        GriffithSettings: ("settings", [GriffithSettings(), GriffithSettings(driver="fixed_step", step=0.01)]),
        EnergySettings: ("settings", [EnergySettings()]),
        ZeroRangeSettings: ("settings", [ZeroRangeSettings()]),
        FemSettings: ("fem", [FemSettings()]),
        Potential: ("adhesion", [Potential(1.0, 0.1)]),
    }


def test_every_validated_class_has_an_example(examples):
    """A new class with declared fields must be added to ``examples`` to be walked."""
    assert set(examples) == set(VALIDATED)


# -- the walk over every declaration -------------------------------------------------------------


def _range_phrase(lower, lower_open, upper, upper_open) -> str:
    """How a message states the allowed values ("in (-1, 0.5]", "> 0", "<= 4")."""
    if lower is not None and upper is not None:
        return f"in {'(' if lower_open else '['}{lower:g}, {upper:g}{')' if upper_open else ']'}"
    if lower is not None:
        return f"{'>' if lower_open else '>='} {lower:g}"
    if upper is not None:
        return f"{'<' if upper_open else '<='} {upper:g}"
    return ""


def _inside_and_outside(kind, lower, lower_open, upper, upper_open):
    """Values just inside the range (at a closed bound, a hair inside an open one) and just outside."""
    inside, outside = [], []
    if kind == "whole":
        if lower is not None:
            inside.append(int(lower))
            outside.append(int(lower) - 1)
        if upper is not None:
            inside.append(int(upper))
            outside.append(int(upper) + 1)
        return inside, outside
    for bound, is_open, direction in ((lower, lower_open, 1.0), (upper, upper_open, -1.0)):
        if bound is None:
            continue
        beyond = math.nextafter(bound, -direction * math.inf)
        if is_open:
            inside.append(bound + direction * 1e-9 * max(abs(bound), 1.0))
            outside += [bound, beyond]
        else:
            inside.append(float(bound))
            outside.append(beyond)
    return inside, outside


def _construct(obj, attribute, value):
    return dataclasses.replace(obj, **{attribute: value})


def _refused(obj, attribute, value, name) -> cs.SceneError:
    with pytest.raises(cs.SceneError) as exc:
        _construct(obj, attribute, value)
    assert exc.value.field == name, (attribute, value, str(exc.value))
    return exc.value


#: inside values whose construction is too slow for a unit test: their acceptance is checked
#: on the declared check alone
_TOO_COSTLY = {("Brush", "count")}  # 100000 random pillars take minutes to place


def _accepted(obj, attribute, check, value, name):
    """The declared check accepts ``value``; the object then constructs, or is refused by a rule
    that is not this field's range (another field's, e.g. a star's outer radius shrunk below its
    inner one, or a rule joining fields: a periodic grid needs its period)."""
    check.check(obj, name, value)
    if (type(obj).__name__, attribute) in _TOO_COSTLY:
        return None
    try:
        return _construct(obj, attribute, value)
    except cs.SceneError as exc:
        assert exc.field != name or not str(exc).startswith(f"{name}: must be"), (attribute, value, str(exc))
        return None


CASES = [(cls, attribute) for cls in VALIDATED for attribute, _ in declared_fields(cls)]


@pytest.mark.parametrize("cls,attribute", CASES, ids=[f"{c.__name__}.{a}" for c, a in CASES])
def test_each_declared_field_refuses_just_outside_and_accepts_just_inside(examples, cls, attribute):
    prefix, instances = examples[cls]
    check = dict(declared_fields(cls))[attribute]
    name = check.name or f"{prefix}.{attribute}"  # as a scene file or the settings class spells it
    applies = [obj for obj in instances if check.when is None or check.when(obj)]
    assert applies, f"no example switches on {cls.__name__}.{attribute}"
    for obj in applies:
        if check.optional:
            built = _accepted(obj, attribute, check, None, name)
            assert built is None or getattr(built, attribute) is None
        else:
            _refused(obj, attribute, None, name)
        if check.kind in ("real", "whole", "reals"):
            lower, lower_open, upper, upper_open = check.bounds(obj)
            phrase = _range_phrase(lower, lower_open, upper, upper_open)
            inside, outside = _inside_and_outside(check.kind, lower, lower_open, upper, upper_open)
            others = tuple(getattr(obj, attribute)) if check.kind == "reals" else None

            def pack(v, others=others):
                """A value of the field: a tuple of reals gets ``v`` ahead of the example's own."""
                return v if others is None else (v, *others)

            for v in outside + [math.nan, math.inf, -math.inf, "1", True]:
                message = str(_refused(obj, attribute, pack(v), name))
                assert phrase in message, (v, message, phrase)
            if check.kind == "whole":
                _refused(obj, attribute, 2.5, name)
            if not inside:  # unbounded: any finite number
                inside = [0.0, -3.0, 7.5]
            stored_type = int if check.kind == "whole" else float
            for v in inside:
                # a float field given an int stores a float: 1 and 1.0 make one repr, one cache key
                given_as = [v, int(v)] if check.kind != "whole" and float(v).is_integer() else [v]
                for g in given_as:
                    built = _accepted(obj, attribute, check, pack(g), name)
                    if built is None:
                        continue
                    stored = getattr(built, attribute)
                    if check.kind == "reals":  # (stored sorted, for the ratios of a sequence)
                        stored = next(x for x in stored if x == v)
                    assert stored == v and type(stored) is stored_type
            if check.kind == "reals":
                for v in ("0.1", 0.5):  # a string, a lone number: not a list of numbers
                    assert "list of numbers" in str(_refused(obj, attribute, v, name))
        elif check.kind == "choice":
            message = str(_refused(obj, attribute, "no-such-option", name))
            assert all(repr(c) in message for c in check.choices)
            for c in check.choices:
                _accepted(obj, attribute, check, c, name)
        elif check.kind == "flag":
            for v in (0, 1, "yes"):
                assert "true or false" in str(_refused(obj, attribute, v, name))
            for v in (True, False):
                _accepted(obj, attribute, check, v, name)
        elif check.kind == "point":
            for v in ((0.0,), (0.0, math.nan), (math.inf, 0.0), "ab", 3.0):
                _refused(obj, attribute, v, name)
            built = _accepted(obj, attribute, check, (1, -2), name)
            assert built is None or getattr(built, attribute) == (1.0, -2.0)
        else:  # pragma: no cover - a new kind must be added to this walk
            raise AssertionError(f"unknown kind {check.kind!r}")


UNUSED_CASES = [
    (cls, attribute) for cls, attribute in CASES if dict(declared_fields(cls))[attribute].unused is not None
]


@pytest.mark.parametrize("cls,attribute", UNUSED_CASES, ids=[f"{c.__name__}.{a}" for c, a in UNUSED_CASES])
def test_a_field_not_used_here_is_refused_unless_it_keeps_its_default(examples, cls, attribute):
    """A declared field that does not apply (its ``when`` is false) and says so (``unused``) is
    refused by name when given another value than its default, the value it would ignore (a
    regular brush given count = -3, a random one given pitch = -7); the default still builds."""
    prefix, instances = examples[cls]
    check = dict(declared_fields(cls))[attribute]
    name = check.name or f"{prefix}.{attribute}"
    default = next(f.default for f in dataclasses.fields(cls) if f.name == attribute)
    idle = [obj for obj in instances if not check.when(obj)]
    assert idle, f"no example switches off {cls.__name__}.{attribute}"
    for obj in idle:
        assert getattr(_construct(obj, attribute, default), attribute) == default
        others = [default + 1, -3, "x", math.nan] + ([False] if isinstance(default, int) else [])
        for value in others:
            message = str(_refused(obj, attribute, value, name))
            assert "only applies to" in message, message


def test_a_brush_names_the_layouts_that_use_a_parameter():
    with pytest.raises(cs.SceneError, match=r"indenter.count: only applies to layouts 'random' and 'mixed'"):
        cs.Brush(1.0, 0.05, layout="regular", count=-3, seed=-1)
    with pytest.raises(cs.SceneError, match=r"indenter.pitch: only applies to layout 'regular', not to layout 'mixed'"):
        cs.Brush(1.0, 0.05, layout="mixed", count=5, pitch=-7)
    with pytest.raises(cs.SceneError, match=r"indenter.seed: only applies to layouts"):
        cs.Brush(1.0, 0.05, seed=3)
    # each layout's own parameters, the others at their defaults
    assert len(cs.Brush(1.0, 0.05, pitch=0.3, count=0, seed=0).parts) == 16  # 4 x 4 at pitch 0.3
    assert len(cs.Brush(1.0, 0.05, layout="random", count=4, seed=2, pitch=0.2).parts) == 4


def test_unused_needs_when():
    with pytest.raises(TypeError, match="give when too"):
        real(1.0, unused="only applies elsewhere")


# -- the key physical ranges, written out ------------------------------------------------------

_EPS = 1e-12

#: (what, build from one value, the field the error names, refused values, accepted values);
#: the ranges of the theory sheet and the methods' domains, which no declaration may lose
KEY_RANGES = [
    ("E > 0", lambda v: cs.Homogeneous(v, 0.3), "material.youngs_modulus", [0.0, -1.0], [_EPS, 1e9]),
    (
        "-1 < nu <= 1/2",
        lambda v: cs.Homogeneous(1.0, v),
        "material.poisson_ratio",
        [-1.0, 0.5 + _EPS],
        [0.5, -1 + _EPS],
    ),
    ("E0 > 0", lambda v: cs.PowerLawGraded(v, 1.0, 0.0), "material.surface_modulus", [0.0], [_EPS]),
    ("c0 > 0", lambda v: cs.PowerLawGraded(1.0, v, 0.0), "material.reference_depth", [0.0], [_EPS]),
    (
        "-1 < k < 1 (Eq. 32)",
        lambda v: cs.PowerLawGraded(1.0, 1.0, v),
        "material.exponent",
        [-1.0, 1.0],
        [-1 + _EPS, 1 - _EPS],
    ),  # fmt: skip
    ("w >= 0", lambda v: cs.Adhesion(v), "adhesion.work_of_adhesion", [-_EPS], [0.0, 1.0]),
    ("range > 0", lambda v: cs.Adhesion(1.0, v), "adhesion.range", [0.0], [_EPS]),
    ("press force >= 0", lambda v: cs.Loading(press_force=v), "loading.press_force", [-_EPS], [0.0]),
    ("pull limit < 0", lambda v: cs.Loading(pull_limit=v), "loading.pull_limit", [0.0], [-_EPS]),
    ("profile radius > 0", lambda v: cs.Paraboloid(v), "indenter.profile_radius", [0.0], [_EPS]),
    ("0 < cone half-angle < 90", lambda v: cs.Cone(v), "indenter.half_angle_deg", [0.0, 90.0], [_EPS, 90 - 1e-9]),
    ("radius > 0", lambda v: cs.Circle(v), "indenter.radius", [0.0], [_EPS]),
    ("semi-minor <= semi-major", lambda v: cs.Ellipse(1.0, v), "indenter.semi_minor", [0.0, 1 + 1e-9], [1.0]),
    ("inner radius <= outer", lambda v: cs.Star(5, 1.0, v), "indenter.inner_radius", [0.0, 1 + 1e-9], [1.0]),
    ("pitch > 2 pillar radius", lambda v: cs.Brush(1.0, 0.1, pitch=v), "indenter.pitch", [0.2], [0.2 + 1e-9]),
    ("element spacing > 0", lambda v: cs.Grid(spacing=v), "grid.spacing", [0.0], [_EPS]),
    ("elements per radius > 0", lambda v: cs.Grid(elements_per_radius=v), "grid.elements_per_radius", [0.0], [_EPS]),
    (
        "0 < l_c / a <= 1",
        lambda v: ZeroRangeSettings(ratios=(0.5, 0.25, v)),
        "settings.ratios",
        [0.0, 1 + 1e-9],
        [1.0, _EPS],
    ),  # fmt: skip
    (
        "consecutive l_c / a apart by >= 1.5",
        lambda v: ZeroRangeSettings(ratios=(0.3, 0.3 / v), rate=0.5),
        "settings.ratios",
        [1.5 * (1 - 1e-9), 1.0 + 1e-9],
        [1.5, 2.0, 0.3 / 0.2],  # the last is 1.4999999999999998: a step of 1.5 written as 0.3, 0.2
    ),  # fmt: skip
    (
        "flat press approach >= 0",
        lambda v: cs.Scene(
            cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0), cs.Loading(press_approach=v)
        ),
        "loading.press_approach",
        [-_EPS, -1.0],
        [0.0, _EPS],
    ),  # fmt: skip
    ("Taylor-Hood degree 2..4", lambda v: FemSettings(order=v), "fem.order", [1, 5], [2, 4]),
    ("CG tolerance in (0, 1e-2]", lambda v: GriffithSettings(rtol=v), "settings.rtol", [0.0, 0.011], [1e-2, 1e-16]),
]


def _check_key_range(build, name, refused, accepted):
    for v in refused:
        with pytest.raises(cs.SceneError) as exc:
            build(v)
        assert exc.value.field == name, str(exc.value)
    for v in accepted:
        build(v)


@pytest.mark.parametrize("what,build,name,refused,accepted", KEY_RANGES, ids=[k[0] for k in KEY_RANGES])
def test_key_physical_ranges(what, build, name, refused, accepted):
    _check_key_range(build, name, refused, accepted)


def test_a_dropped_bound_is_caught_by_the_key_ranges():
    """The mutant: the graded exponent without its upper bound (k = 1 would pass, where the
    Green's function of Eq. 32 no longer exists)."""

    @dataclasses.dataclass(frozen=True)
    class LooseGraded:
        surface_modulus: float = real(gt=0)
        reference_depth: float = real(gt=0)
        exponent: float = real(gt=-1)

        def __post_init__(self):
            check_fields(self, "material")

    _, _, name, refused, accepted = next(k for k in KEY_RANGES if k[0].startswith("-1 < k < 1"))
    with pytest.raises(pytest.fail.Exception):
        _check_key_range(lambda v: LooseGraded(1.0, 1.0, v), name, refused, accepted)


# -- random values against the declared range ---------------------------------------------------

#: fields with fixed numeric bounds on classes whose construction does no work (shapes build their
#: parts, which at an extreme size is no test of the range)
_NUMERIC = [
    (obj, attribute, check)
    for obj in (
        cs.Homogeneous(1.0, 0.3),
        cs.PowerLawGraded(1.0, 1.0, 0.25),
        cs.Paraboloid(5.0),
        cs.Cone(60.0),
        cs.Adhesion(1.0, 0.1),
        cs.Loading(),
        cs.Grid(),
        GriffithSettings(),
        EnergySettings(),
        ZeroRangeSettings(),
        FemSettings(),
        Potential(1.0, 0.1),
    )
    for attribute, check in declared_fields(obj)
    if check.kind == "real"
    and check.when is None
    and not any(callable(b) for b in (check.gt, check.ge, check.lt, check.le))
]
_PREFIX = {
    cs.Homogeneous: "material",
    cs.PowerLawGraded: "material",
    cs.Paraboloid: "indenter",
    cs.Cone: "indenter",
    cs.Adhesion: "adhesion",
    cs.Loading: "loading",
    cs.Grid: "grid",
    GriffithSettings: "settings",
    EnergySettings: "settings",
    ZeroRangeSettings: "settings",
    FemSettings: "fem",
    Potential: "adhesion",
}


@settings(max_examples=300, deadline=None)
@given(case=st.sampled_from(_NUMERIC), data=st.data())
def test_a_random_value_is_refused_by_name_exactly_when_outside_its_range(case, data):
    obj, attribute, check = case
    lower, lower_open, upper, upper_open = check.bounds(obj)
    near = [b for b in (lower, upper) if b is not None]
    value = data.draw(
        st.one_of(
            st.floats(allow_nan=True, allow_infinity=True),
            st.sampled_from(near + [math.nextafter(b, s * math.inf) for b in near for s in (-1, 1)] or [0.0]),
        )
    )
    inside = (
        math.isfinite(value)
        and (lower is None or (value > lower if lower_open else value >= lower))
        and (upper is None or (value < upper if upper_open else value <= upper))
    )
    name = check.name or f"{_PREFIX[type(obj)]}.{attribute}"
    try:
        built = dataclasses.replace(obj, **{attribute: value})
    except cs.SceneError as exc:
        assert exc.field != name or not inside, str(exc)
    else:
        assert inside and getattr(built, attribute) == value


_KENDALL = cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(0.75, 0.5), cs.Adhesion(1.0))


@pytest.mark.parametrize(
    "build, name",
    [
        (lambda: cs.Indenter("circle"), "indenter.shape"),
        (lambda: cs.Indenter(cs.Circle(1.0), "flat"), "indenter.profile"),
        # the face's corner at r = sqrt(2) lies outside a sphere of radius 1.4
        (lambda: cs.Indenter(cs.Square(2.0), cs.Sphere(1.4)), "indenter.profile_radius"),
        (lambda: cs.Loading(press_approach=0.1, press_force=1.0), "loading.press_force"),
        (lambda: cs.Scene(cs.Circle(1.0), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0)), "indenter"),
        (lambda: cs.Scene(cs.Indenter(cs.Circle(1.0)), 1.0, cs.Adhesion(1.0)), "material"),
        (lambda: cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.3), 1.0), "adhesion"),
        (lambda: cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0), None), "loading"),
        (
            lambda: cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0), cs.Outputs()),
            "loading",
        ),
        (
            lambda: cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0), outputs=None),
            "outputs",
        ),
        (lambda: cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0), name=5), "name"),
        # a flat face touches at d = 0: a negative press leaves it hanging above the surface
        (
            lambda: cs.Scene(
                cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0), cs.Loading(press_approach=-0.1)
            ),
            "loading.press_approach",
        ),
        # a curved profile pressed to no force touches at one point only
        (
            lambda: cs.Scene(
                cs.Indenter(cs.Circle(1.0), cs.Paraboloid(2.0)),
                cs.Homogeneous(1.0, 0.3),
                cs.Adhesion(1.0),
                cs.Loading(press_force=0.0),
            ),
            "loading.press_force",
        ),
        # a closed ring repeats its first vertex: a zero-length edge
        (lambda: cs.Polygon(((0, 0), (1, 0), (0, 1), (0, 0))), "indenter.vertices"),
        (lambda: cs.Polygon(((0, 0), (1, 0), (1, 0), (0, 1))), "indenter.vertices"),
        # a transformed or composite face of something that is not a shape, a triangle of a number
        (lambda: cs.Transformed("circle"), "indenter.shape"),
        (lambda: cs.Triangle(5), "indenter.vertices"),
        (lambda: cs.Union(cs.Circle(1.0)), "indenter.parts"),
        (lambda: cs.Difference(cs.Circle(1.0), cs.Circle(0.5)), "indenter.cuts"),
        (lambda: cs.Difference(cs.Circle(1.0), (5,)), "indenter.cuts"),
        # a cut equal to the base: its outline stays (the cuts remove interiors only), a few
        # cells of the area's raster, and the face was taken for a tiny one
        (lambda: cs.Difference(cs.Circle(1.0), (cs.Circle(1.0),)), "indenter.cuts"),
        # more random pillars than the square's area holds: refused before 20000 * 50 draws
        (lambda: cs.Brush(1.0, 0.05, layout="random", count=20_000, seed=0), "indenter.count"),
        # a solver handed another solver's settings, or not a scene
        (lambda: bg.solve(_KENDALL, EnergySettings()), "settings"),
        (lambda: bg.press(_KENDALL, FemSettings()), "settings"),
        (lambda: bg.solve("circle"), "scene"),
        (lambda: be.solve(_KENDALL, GriffithSettings()), "settings"),
        (lambda: fr.solve(_KENDALL, GriffithSettings()), "settings"),
        # the harness asked for a method it does not have, or for a string of letters
        (lambda: crossval.compare(_KENDALL, methods=["nope"]), "methods"),
        (lambda: crossval.compare(_KENDALL, methods="bem_griffith"), "methods"),
        (lambda: crossval.compare(_KENDALL, methods=5), "methods"),
        (lambda: crossval.compare(_KENDALL, methods={"bem_griffith"}), "methods"),
        (lambda: crossval.reference(5), "scene"),
        # a resolution the table's or the FEM's reference does not read is still refused, not ignored
        (lambda: crossval.reference("square", resolution=-5), "resolution"),
        (lambda: crossval.reference("kendall_circle", resolution="abc"), "resolution"),
        # the pull ends at its limit: a turning point beyond it is never reached
        (lambda: cs.Loading(turning_points=(-0.5, 0.2, -3.0), pull_limit=-1.0), "loading.turning_points"),
        # a turning point that does not reverse the direction, or a first one above the press
        (lambda: cs.Loading(turning_points=(-1.0, -2.0)), "loading.turning_points"),
        (lambda: cs.Loading(turning_points=(-1.0, 0.5, 0.7)), "loading.turning_points"),
        (
            lambda: cs.Scene(
                cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0), cs.Adhesion(1.0), cs.Loading(turning_points=(1.0,))
            ),
            "loading.turning_points",
        ),
        # turning points are an ordered list, not the keys of a mapping
        (lambda: cs.Loading(turning_points={-1.0: 2}), "loading.turning_points"),
        (lambda: cs.Outputs(snapshots={-0.5}), "outputs.snapshots"),
        # a scene's own scales outside what double precision carries through the solvers: each
        # value at fault by name (a subnormal modulus would reach the FEM, which calls a
        # non-finite result a solver bug), a combination as the material
        (
            lambda: cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1e-320, 0.3), cs.Adhesion(1.0)),
            "material.youngs_modulus",
        ),
        # E* = E / (1 - nu^2) overflows: the material alone is within its declared range
        (
            lambda: cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.7e308, 0.5), cs.Adhesion(1.0)),
            "material.youngs_modulus",
        ),
        (
            lambda: cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.PowerLawGraded(1e120, 1.0, 0.5), cs.Adhesion(1.0)),
            "material.surface_modulus",
        ),
        (lambda: cs.Scene(cs.Indenter(cs.Circle(1e-120)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0)), "indenter"),
        (
            lambda: cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1e-120)),
            "adhesion.work_of_adhesion",
        ),
        (lambda: cs.Scene(cs.Indenter(cs.Circle(1e-60)), cs.Homogeneous(1e-60, 0.3), cs.Adhesion(1.0)), "material"),
        # units the scene takes whose ratio leaves the solvers' precision (the inverse symbol
        # underflowed: ZeroDivisionError; overflowed in single precision: a warning and no convergence)
        (
            lambda: bg.solve(
                cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1e50, 0.3), cs.Adhesion(1.0)),
                GriffithSettings(grid=cs.Grid(elements_per_radius=8)),
            ),
            "material",
        ),
        (
            lambda: bg.solve(
                cs.Scene(cs.Indenter(cs.Circle(1e45)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0)),
                GriffithSettings(grid=cs.Grid(elements_per_radius=8)),
            ),
            "material",
        ),
        (
            lambda: be.solve(
                cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1e-50, 0.3), cs.Adhesion(1.0, 0.05)),
                EnergySettings(grid=cs.Grid(elements_per_radius=8)),
            ),
            "material",
        ),
        # the zero-range sequence's ranges (~ sqrt(l_c w / E*)) below single precision: the
        # displacements underflowed and the minimiser made no progress (still running after 100 s)
        (
            lambda: be.solve(cs.Scene(cs.Indenter(cs.Circle(1.0)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1e-90))),
            "material",
        ),
        # a face whose area under- or overflows: the grid by elements per radius named it grid.spacing
        (
            lambda: bg.solve(
                cs.Scene(cs.Indenter(cs.Circle(1e-200)), cs.Homogeneous(1.0, 0.3), cs.Adhesion(1.0)),
                GriffithSettings(grid=cs.Grid(elements_per_radius=8)),
            ),
            "indenter",
        ),
        (lambda: cs.Grid(elements_per_radius=8).spacing_for(cs.Circle(1e200)), "indenter"),
        # a range whose square leaves floating point (the potential's curvature is w / rho^2)
        (lambda: cs.Adhesion(1.0, 1e-300), "adhesion.range"),
        # a potential shapes a finite-range interaction: without a range it would be ignored
        (lambda: cs.Adhesion(1.0, None, "maugis_dugdale"), "adhesion.potential"),
        (lambda: cs.Adhesion(1.0, 1e300), "adhesion.range"),
        # two process zones too close for the last step to say anything
        (lambda: ZeroRangeSettings(ratios=(0.32, 0.3199999), rate=0.5), "settings.ratios"),
        (lambda: ZeroRangeSettings(ratios=(0.08, 0.06, 0.03)), "settings.ratios"),
        (
            lambda: (
                cs.Scene(
                    cs.Indenter(cs.Circle(1.0)), cs.PowerLawGraded(1.0, 1.0, 0.5), cs.Adhesion(1.0)
                ).effective_modulus
            ),
            "material",
        ),
    ],
)
def test_a_scene_of_the_wrong_parts_is_refused_by_name(build, name):
    with pytest.raises(cs.SceneError) as caught:
        build()
    assert caught.value.field == name


def test_a_sphere_just_wider_than_the_face_is_accepted():
    cs.Indenter(cs.Square(2.0), cs.Sphere(math.sqrt(2.0) * (1 + 1e-9)))
    # a circle is measured on itself, not on its bounding box (which reaches sqrt(2) r), so a
    # sphere just wider than the disc is accepted
    cs.Indenter(cs.Circle(1.0), cs.Sphere(1.0 * (1 + 1e-9)))
    with pytest.raises(cs.SceneError, match="the face reaches r = 1.1 from the apex"):
        cs.Indenter(cs.Circle(1.0, (0.1, 0.0)), cs.Sphere(1.05))
