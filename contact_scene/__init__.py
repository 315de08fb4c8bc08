"""The shared language of the package: scenes, face shapes, rasters, results and theory."""

from . import theory
from .discretisation import Grid
from .errors import SceneError
from .io import load_scene, scene_from_dict, shape_from_dict, summarise
from .materials import Homogeneous, Material, PowerLawGraded
from .profiles import Cone, Flat, Paraboloid, Profile, Sphere
from .raster import Raster, rasterise, rasterise_periodic
from .result import QUANTITIES, Curve, ErrorBar, Result, Snapshot, SolverStats
from .scene import Adhesion, Indenter, Loading, Outputs, Scene
from .shapes import (
    Brush,
    Circle,
    Difference,
    Ellipse,
    ImageMask,
    Incircle,
    Polygon,
    PowerLawStar,
    Rectangle,
    RegularPolygon,
    Shape,
    Square,
    SquareWithFaults,
    Star,
    Transformed,
    Triangle,
    TwoCircles,
    Union,
)

__all__ = [
    "theory",
    "Grid",
    "SceneError",
    "load_scene",
    "scene_from_dict",
    "shape_from_dict",
    "summarise",
    "Homogeneous",
    "Material",
    "PowerLawGraded",
    "Cone",
    "Flat",
    "Paraboloid",
    "Profile",
    "Sphere",
    "Raster",
    "rasterise",
    "rasterise_periodic",
    "Curve",
    "Result",
    "Snapshot",
    "SolverStats",
    "ErrorBar",
    "QUANTITIES",
    "Adhesion",
    "Indenter",
    "Loading",
    "Outputs",
    "Scene",
    "Brush",
    "Circle",
    "Difference",
    "Ellipse",
    "ImageMask",
    "Incircle",
    "Polygon",
    "PowerLawStar",
    "Rectangle",
    "RegularPolygon",
    "Shape",
    "Square",
    "SquareWithFaults",
    "Star",
    "Transformed",
    "Triangle",
    "TwoCircles",
    "Union",
]
