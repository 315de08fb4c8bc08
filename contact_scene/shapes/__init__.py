"""Face shapes of flat punches, one family per module.

Every shape is a frozen dataclass that validates its declared parameters (:mod:`.fields`)
and knows its area, centroid, bounding box, equivalent radius sqrt(A/pi), incircle (the
largest inscribed circle, used by the lower bound, theory Eqs. 18-19) and filling factor
(:mod:`.base`).  The families:

- :mod:`.conics`: Circle, Ellipse
- :mod:`.polygons`: Polygon, Rectangle, Square, Triangle, RegularPolygon
- :mod:`.stars`: Star, PowerLawStar
- :mod:`.composite`: Union, Difference, TwoCircles
- :mod:`.faults`: SquareWithFaults;  :mod:`.brush`: Brush
- :mod:`.image`: ImageMask;  :mod:`.transformed`: Transformed (rotated, mirrored, scaled)

:mod:`.numerical` holds the fine-raster geometry used where no closed form exists.
Units are whatever the scene uses (SI recommended); nothing here assumes a scale.
"""

from .base import BOUNDARY_REL_TOL, Incircle, Shape
from .brush import Brush
from .composite import Difference, TwoCircles, Union
from .conics import Circle, Ellipse
from .faults import SquareWithFaults
from .image import ImageMask
from .polygons import Polygon, PolygonalShape, Rectangle, RegularPolygon, Square, Triangle
from .stars import PowerLawStar, Star
from .transformed import Transformed

__all__ = [
    "Incircle",
    "Shape",
    "Circle",
    "Ellipse",
    "Polygon",
    "Rectangle",
    "Square",
    "Triangle",
    "RegularPolygon",
    "Star",
    "PowerLawStar",
    "Union",
    "Difference",
    "TwoCircles",
    "SquareWithFaults",
    "Brush",
    "ImageMask",
    "Transformed",
    "PolygonalShape",
    "BOUNDARY_REL_TOL",
]
