"""Scene files (TOML) and the scene summary.

Schema (every key is checked; unknown keys are errors)::

    name = "Kendall circle"            # optional
    [indenter]
    shape = "circle"                   # see SHAPE_KEYS for every shape and its keys
    radius = 1.0
    rotation_deg = 0.0                 # any shape: rotate about its centroid
    mirror = false                     # any shape: reflect x -> -x about its centroid
    profile = "flat"                   # flat | paraboloid | sphere (profile_radius) | cone (half_angle_deg)
    [material]
    model = "homogeneous"              # youngs_modulus, poisson_ratio
    # model = "power_law_graded"       # surface_modulus, reference_depth, exponent
    [adhesion]
    work_of_adhesion = 1.0             # range, potential (only with range): energy method only
    [loading]                          # optional: press_approach | press_force, turning_points, pull_limit
    [outputs]                          # optional: curve, snapshots, fields

Composite shapes nest tables: ``shape = "union"`` with ``parts = [{shape = "circle", ...}]``;
``shape = "difference"`` with ``base = {...}`` and ``cuts = [{...}]``.  An image face gives
``path`` relative to the scene file.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Set as AbstractSet
from pathlib import Path

from . import shapes, theory
from .errors import SceneError, check_real
from .materials import Homogeneous, PowerLawGraded
from .profiles import Cone, Flat, Paraboloid, Sphere
from .scene import Adhesion, Indenter, Loading, Outputs, Scene
from .shapes.brush import LAYOUT_PARAMETERS, LAYOUTS as BRUSH_LAYOUTS, unused_by_layout

__all__ = ["load_scene", "scene_from_dict", "shape_from_dict", "summarise", "SHAPE_KEYS"]

#: shape name -> (required keys, optional keys)
SHAPE_KEYS: dict[str, tuple[set, set]] = {
    "circle": ({"radius"}, {"center"}),
    "ellipse": ({"semi_major", "semi_minor"}, {"center"}),
    "square": ({"side"}, {"center"}),
    "rectangle": ({"width", "height"}, {"center"}),
    "triangle": (set(), {"side", "vertices"}),
    "regular_polygon": ({"n_sides", "circumradius"}, {"center"}),
    "star": ({"n_rays", "outer_radius", "inner_radius"}, {"center"}),
    "polygon": ({"vertices"}, set()),
    "power_law_star": ({"n_rays", "core_radius", "outer_radius"}, {"samples", "center"}),
    "two_circles": ({"radius1", "radius2", "distance"}, set()),
    "square_with_faults": ({"side"}, {"v_cut_depth", "v_cut_width", "line_cuts", "line_cut_length", "cut_width"}),
    "brush": ({"side", "pillar_radius"}, {"layout", "pitch", "count", "seed"}),
    "image": ({"path", "pixel_size"}, {"threshold", "invert"}),
    "union": ({"parts"}, set()),
    "difference": ({"base", "cuts"}, set()),
}
_COMMON = {"shape", "rotation_deg", "mirror"}
_PROFILE_KEYS = {"profile", "profile_radius", "half_angle_deg"}
_NATIVE_ROTATION = {"ellipse", "square", "rectangle", "regular_polygon", "star", "power_law_star"}


#: why ``adhesion.potential`` is refused without ``adhesion.range``
POTENTIAL_NEEDS_RANGE = (
    "names the form of a finite-range interaction and needs adhesion.range; without a range the "
    "scene is the zero-range limit, which has no potential (the energy BEM's zero-range sequence "
    "takes its potential from ZeroRangeSettings.potential)"
)


def _check_keys(section: str, d: dict, allowed: AbstractSet[str], required: AbstractSet[str] = frozenset()):
    if not isinstance(d, dict):
        raise SceneError(section, f"must be a table (got {type(d).__name__})")
    for k in d:
        if k not in allowed:
            raise SceneError(f"{section}.{k}", f"unknown key; allowed keys: {', '.join(sorted(allowed))}")
    missing = sorted(k for k in required if k not in d)
    if missing:
        also = f" (also missing: {', '.join(missing[1:])})" if len(missing) > 1 else ""
        raise SceneError(f"{section}.{missing[0]}", f"is required{also}")


def shape_from_dict(d: dict, *, base_dir: Path | None = None, section: str = "indenter") -> shapes.Shape:
    """Build a face shape from its table of a scene file (the module's schema).

    Parameters
    ----------
    d : dict
        The shape's table: ``shape`` (a key of :data:`SHAPE_KEYS`), that shape's required and
        optional keys, and optionally ``rotation_deg`` (degrees, about the centroid) and
        ``mirror`` (bool, x -> -x about the centroid).  The indenter's table may also hold the
        profile's keys, which are read elsewhere.
    base_dir : pathlib.Path or None, optional
        Directory a relative image ``path`` is taken from (the scene file's); the current
        directory when None.
    section : str, optional
        Dotted name of the table in the scene file, used in error messages
        (``"indenter"``; nested parts get ``"indenter.parts[0]"`` etc.).

    Returns
    -------
    contact_scene.Shape
        The shape, rotated and mirrored as asked (shapes with a rotation parameter of their own
        take ``rotation_deg`` directly and keep their closed forms).

    Raises
    ------
    contact_scene.SceneError
        Naming the offending key (e.g. ``indenter.radius``): a missing or unknown shape, a
        missing required key, an unknown key, or a value out of the shape's allowed range.
    """
    if not isinstance(d, dict) or "shape" not in d:
        raise SceneError(f"{section}.shape", f"is required; one of: {', '.join(sorted(SHAPE_KEYS))}")
    kind = d["shape"]
    if not isinstance(kind, str) or kind not in SHAPE_KEYS:
        raise SceneError(f"{section}.shape", f"unknown shape {kind!r}; one of: {', '.join(sorted(SHAPE_KEYS))}")
    required, optional = SHAPE_KEYS[kind]
    _check_keys(
        section, d, required | optional | _COMMON | (_PROFILE_KEYS if section == "indenter" else set()), required
    )
    params = {k: d[k] for k in required | optional if k in d}
    if "center" in params:
        params["center"] = tuple(params["center"]) if isinstance(params["center"], list) else params["center"]
    # checked whenever given: a falsy value ("", false, []) is as wrong as any other non-number
    rotation = check_real(f"{section}.rotation_deg", d["rotation_deg"]) if "rotation_deg" in d else 0.0
    # shapes with a rotation parameter of their own take it and keep their closed forms; others are wrapped
    if kind in _NATIVE_ROTATION and "rotation_deg" in d:
        params["rotation_deg"] = rotation
        rotation = 0.0
    try:
        shape = _build(kind, params, base_dir, section)
    except TypeError as exc:  # a wrongly typed nested value
        raise SceneError(section, f"invalid parameters for shape {kind!r}: {exc}") from None
    mirror = d.get("mirror", False)
    if not isinstance(mirror, bool):
        raise SceneError(f"{section}.mirror", f"must be true or false (got {mirror!r})")
    if mirror:
        shape = shape.mirrored()
    if rotation:
        shape = shape.rotated(rotation)
    return shape


def _build(kind, params, base_dir, section):
    if kind == "circle":
        return shapes.Circle(**params)
    if kind == "ellipse":
        return shapes.Ellipse(**params)
    if kind == "square":
        return shapes.Square(**params)
    if kind == "rectangle":
        return shapes.Rectangle(**params)
    if kind == "triangle":
        if ("side" in params) == ("vertices" in params):
            raise SceneError(f"{section}.side", "give either side (equilateral) or vertices")
        if "side" in params:
            return shapes.Triangle.equilateral(params["side"])
        return shapes.Triangle(_vertices(params["vertices"], section))
    if kind == "regular_polygon":
        return shapes.RegularPolygon(**params)
    if kind == "star":
        return shapes.Star(**params)
    if kind == "polygon":
        return shapes.Polygon(_vertices(params["vertices"], section))
    if kind == "power_law_star":
        return shapes.PowerLawStar(**params)
    if kind == "two_circles":
        return shapes.TwoCircles(**params)
    if kind == "square_with_faults":
        return shapes.SquareWithFaults(**params)
    if kind == "brush":
        # a key the layout does not use is refused even at its default value: the file gave it,
        # so its author expects it to act (the class alone cannot tell a default from a given one)
        layout = params.get("layout", "regular")
        if layout in BRUSH_LAYOUTS:  # (another layout is refused by the class, naming the layout)
            for key in sorted(LAYOUT_PARAMETERS):
                if key in params and layout not in LAYOUT_PARAMETERS[key]:
                    message = unused_by_layout(key, layout, layout_given="layout" in params)
                    raise SceneError(f"{section}.{key}", f"{message}; leave it out")
        return shapes.Brush(**params)
    if kind == "image":
        p = params.pop("path")
        if not isinstance(p, str):
            raise SceneError(f"{section}.path", "must be a file name")
        path = Path(p) if base_dir is None or Path(p).is_absolute() else base_dir / p
        return shapes.ImageMask(path=str(path), **params)
    if kind == "union":
        parts = params["parts"]
        if not isinstance(parts, list) or not parts:
            raise SceneError(f"{section}.parts", "must be a non-empty list of shape tables")
        return shapes.Union(
            tuple(shape_from_dict(p, base_dir=base_dir, section=f"{section}.parts[{i}]") for i, p in enumerate(parts))
        )
    if kind == "difference":
        cuts = params["cuts"]
        if not isinstance(cuts, list):
            raise SceneError(f"{section}.cuts", "must be a list of shape tables")
        return shapes.Difference(
            shape_from_dict(params["base"], base_dir=base_dir, section=f"{section}.base"),
            tuple(shape_from_dict(c, base_dir=base_dir, section=f"{section}.cuts[{i}]") for i, c in enumerate(cuts)),
        )
    raise AssertionError(kind)  # pragma: no cover


def _vertices(v, section):
    if not isinstance(v, list) or not all(isinstance(p, list) and len(p) == 2 for p in v):
        raise SceneError(f"{section}.vertices", "must be a list of [x, y] pairs")
    for p in v:
        for c in p:
            if isinstance(c, bool) or not isinstance(c, (int, float)):
                raise SceneError(f"{section}.vertices", f"coordinates must be numbers (got {c!r})")
    return tuple(tuple(p) for p in v)


def _profile_from_dict(d: dict):
    kind = d.get("profile", "flat")
    if not isinstance(kind, str):
        raise SceneError("indenter.profile", f"must be one of: cone, flat, paraboloid, sphere (got {kind!r})")
    if kind == "flat":
        for k in ("profile_radius", "half_angle_deg"):
            if k in d:
                raise SceneError(f"indenter.{k}", "only applies to a curved profile")
        return Flat()
    if kind in ("sphere", "paraboloid"):
        if "profile_radius" not in d:
            raise SceneError("indenter.profile_radius", f"is required for profile {kind!r}")
        if "half_angle_deg" in d:
            raise SceneError("indenter.half_angle_deg", f"only applies to a cone, not to profile {kind!r}")
        return (Sphere if kind == "sphere" else Paraboloid)(d["profile_radius"])
    if kind == "cone":
        if "half_angle_deg" not in d:
            raise SceneError("indenter.half_angle_deg", "is required for profile 'cone'")
        if "profile_radius" in d:
            raise SceneError("indenter.profile_radius", "only applies to a sphere or paraboloid, not to a cone")
        return Cone(d["half_angle_deg"])
    raise SceneError("indenter.profile", f"unknown profile {kind!r}; one of: cone, flat, paraboloid, sphere")


def _material_from_dict(d: dict):
    if not isinstance(d, dict):
        raise SceneError(
            "material",
            f"must be a table, [material] with model = 'homogeneous' or 'power_law_graded' and its moduli (got {d!r})",
        )
    model = d.get("model")
    if not isinstance(model, str):
        model = repr(model)
    if model == "homogeneous":
        _check_keys("material", d, {"model", "youngs_modulus", "poisson_ratio"}, {"youngs_modulus", "poisson_ratio"})
        return Homogeneous(d["youngs_modulus"], d["poisson_ratio"])
    if model == "power_law_graded":
        _check_keys(
            "material",
            d,
            {"model", "surface_modulus", "reference_depth", "exponent"},
            {"surface_modulus", "reference_depth", "exponent"},
        )
        return PowerLawGraded(d["surface_modulus"], d["reference_depth"], d["exponent"])
    raise SceneError("material.model", f"must be 'homogeneous' or 'power_law_graded' (got {model!r})")


def scene_from_dict(d: dict, *, base_dir: Path | None = None) -> Scene:
    """Build a scene from the parsed tables of a scene file.

    Parameters
    ----------
    d : dict
        The whole file as a dict (the module's schema): ``indenter``, ``material`` and
        ``adhesion`` required; ``name``, ``description``, ``loading`` and ``outputs`` optional.
    base_dir : pathlib.Path or None, optional
        Directory relative paths in the file (image faces) are taken from.

    Returns
    -------
    contact_scene.Scene
        The validated scene.

    Raises
    ------
    contact_scene.SceneError
        Naming the field (``adhesion.work_of_adhesion``, ``loading.turning_points``, ...) of a
        missing, unknown, wrongly typed or out-of-range entry.
    """
    _check_keys(
        "scene",
        d,
        {"name", "description", "indenter", "material", "adhesion", "loading", "outputs"},
        {"indenter", "material", "adhesion"},
    )
    name = d.get("name", "")
    if not isinstance(name, str):
        raise SceneError("name", "must be a string")
    if not isinstance(d.get("description", ""), str):
        raise SceneError("description", "must be a string")
    indenter_table = d["indenter"]
    shape = shape_from_dict(indenter_table, base_dir=base_dir)
    indenter = Indenter(shape, _profile_from_dict(indenter_table))
    material = _material_from_dict(d["material"])
    adhesion_table = d["adhesion"]
    _check_keys("adhesion", adhesion_table, {"work_of_adhesion", "range", "potential"}, {"work_of_adhesion"})
    if "potential" in adhesion_table and "range" not in adhesion_table:
        # refused even when it names the default: the file gave it, and it would have no effect
        raise SceneError("adhesion.potential", f"{POTENTIAL_NEEDS_RANGE}; give range too, or leave potential out")
    adhesion = Adhesion(
        adhesion_table["work_of_adhesion"], adhesion_table.get("range"), adhesion_table.get("potential", "exponential")
    )
    loading_table = d.get("loading", {})
    _check_keys("loading", loading_table, {"press_approach", "press_force", "turning_points", "pull_limit"})
    turning_points = loading_table.get("turning_points", [])
    if not isinstance(turning_points, list):
        raise SceneError("loading.turning_points", "must be a list of approaches")
    loading = Loading(
        loading_table.get("press_approach"),
        loading_table.get("press_force"),
        tuple(turning_points),
        loading_table.get("pull_limit"),
    )
    outputs_table = d.get("outputs", {})
    _check_keys("outputs", outputs_table, {"curve", "snapshots", "fields"})
    for k in ("curve", "fields"):
        if k in outputs_table and not isinstance(outputs_table[k], bool):
            raise SceneError(f"outputs.{k}", f"must be true or false (got {outputs_table[k]!r})")
    snapshots = outputs_table.get("snapshots", [])
    if not isinstance(snapshots, list):
        raise SceneError("outputs.snapshots", "must be a list of approaches")
    outputs = Outputs(outputs_table.get("curve", True), tuple(snapshots), outputs_table.get("fields", False))
    return Scene(indenter, material, adhesion, loading, outputs, name)


def load_scene(path) -> Scene:
    """Read a scene file (TOML, the module's schema).

    Parameters
    ----------
    path : str or os.PathLike
        The scene file (UTF-8, with or without a byte-order mark); an image face's relative
        ``path`` is taken from its directory.

    Returns
    -------
    contact_scene.Scene
        The validated scene; a file without ``name`` gets the file's stem as its name.

    Raises
    ------
    contact_scene.SceneError
        With field ``file`` when the file cannot be read, is not UTF-8 or not valid TOML;
        otherwise naming the offending field, as :func:`scene_from_dict`.
    """
    path = Path(path)
    try:
        # "utf-8-sig" drops one leading byte-order mark and is UTF-8 otherwise.  A BOM is accepted
        # rather than refused: it is an encoding signature, not part of the text (a TOML file is
        # UTF-8 by definition, so it tells nothing), and some editors (older Windows Notepad)
        # write one by default; refusing it would only make the user re-save an otherwise valid
        # file.  (tomllib itself reports it as "Invalid statement (at line 1, column 1)".)
        text = path.read_bytes().decode("utf-8-sig")
    except OSError as exc:
        raise SceneError("file", f"cannot read {str(path)!r}: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise SceneError("file", f"{str(path)!r} is not UTF-8 text") from None
    try:
        d = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError("file", f"{str(path)!r} is not valid TOML: {exc}") from None
    scene = scene_from_dict(d, base_dir=path.parent)
    if not scene.name:
        import dataclasses

        scene = dataclasses.replace(scene, name=path.stem)
    return scene


def summarise(scene: Scene) -> dict:
    """Geometry and closed-form bounds of a scene (``crossval scene check``).

    Parameters
    ----------
    scene : contact_scene.Scene
        The scene to describe.

    Returns
    -------
    dict
        Name, shape, profile and material kinds; the face's area, nominal area, filling factor,
        equivalent radius and incircle; the work of adhesion.  For a flat punch, the
        closed-form estimates of :mod:`contact_scene.theory`: ``stiffness_estimate`` (Eq. 9 or
        34), ``upper_bound_force``/``upper_bound_approach`` (Eqs. 13-14, 24; Eqs. 38, 39, 41 for a
        graded half-space, on the circle of equal area), ``lower_bound_force``/
        ``lower_bound_approach`` (Eqs. 18-19 on the incircle) and, for a circle, Kendall's or
        the graded punch's force, approach and stiffness; for a curved homogeneous profile,
        ``jkr_force``.

    Raises
    ------
    contact_scene.SceneError
        Naming the entry of the summary that evaluates to a non-finite number.
    """
    shape = scene.indenter.shape
    inc = shape.incircle()
    w = scene.adhesion.work_of_adhesion
    out = {
        "name": scene.name,
        "shape": shape.kind,
        "profile": scene.indenter.profile.kind,
        "material": scene.material.kind,
        "area": shape.area,
        "area_is_exact": bool(shape.area_is_exact),
        "nominal_area": shape.nominal_area,
        "filling_factor": shape.filling_factor,
        "equivalent_radius": shape.equivalent_radius,
        "incircle_radius": inc.radius,
        "incircle_center": list(inc.center),
        "work_of_adhesion": w,
    }
    material = scene.material
    phi = shape.filling_factor
    flat = scene.indenter.profile.is_flat
    if isinstance(material, Homogeneous):
        E = material.effective_modulus
        out["effective_modulus"] = E
        if flat:
            out["stiffness_estimate"] = theory.compact_shape_stiffness(E_star=E, area=shape.nominal_area)
            out["upper_bound_force"] = theory.upper_bound_force(
                E_star=E, work=w, area=shape.nominal_area, filling_factor=phi
            )
            out["upper_bound_approach"] = theory.upper_bound_approach(
                E_star=E, work=w, area=shape.nominal_area, filling_factor=phi
            )
            out["lower_bound_force"] = theory.lower_bound_force(E_star=E, work=w, incircle_radius=inc.radius)
            out["lower_bound_approach"] = theory.lower_bound_approach(E_star=E, work=w, incircle_radius=inc.radius)
            if isinstance(shape, shapes.Circle):
                out["kendall_force"] = theory.kendall_adhesion_force(E_star=E, radius=shape.radius, work=w)
                out["kendall_approach"] = theory.kendall_critical_approach(E_star=E, radius=shape.radius, work=w)
                out["kendall_stiffness"] = theory.kendall_stiffness(E_star=E, radius=shape.radius)
        elif isinstance(scene.indenter.profile, (Sphere, Paraboloid)):
            out["jkr_force"] = theory.jkr_pulloff_force(work=w, sphere_radius=scene.indenter.profile.radius)
    elif isinstance(material, PowerLawGraded):
        E0, c0, k = material.surface_modulus, material.reference_depth, material.exponent
        out["exponent"] = k
        out["poisson_ratio"] = material.poisson_ratio
        if flat:
            a_eq = shape.equivalent_radius
            out["stiffness_estimate"] = theory.graded_stiffness(E0=E0, c0=c0, k=k, radius=a_eq)
            out["upper_bound_force"] = theory.graded_adhesion_force(
                E0=E0, c0=c0, k=k, radius=a_eq, work=w, filling_factor=phi
            )
            out["upper_bound_approach"] = theory.graded_critical_approach(E0=E0, c0=c0, k=k, radius=a_eq, work=phi * w)
            out["lower_bound_force"] = theory.graded_adhesion_force(E0=E0, c0=c0, k=k, radius=inc.radius, work=w)
            out["lower_bound_approach"] = theory.graded_critical_approach(E0=E0, c0=c0, k=k, radius=inc.radius, work=w)
            if isinstance(shape, shapes.Circle):
                out["graded_force"] = theory.graded_adhesion_force(E0=E0, c0=c0, k=k, radius=shape.radius, work=w)
                out["graded_approach"] = theory.graded_critical_approach(E0=E0, c0=c0, k=k, radius=shape.radius, work=w)
                out["graded_stiffness"] = theory.graded_stiffness(E0=E0, c0=c0, k=k, radius=shape.radius)
    for key, val in out.items():
        if isinstance(val, float) and not math.isfinite(val):  # pragma: no cover - guarded by validation
            raise SceneError(key, "evaluates to a non-finite number")
    return out
