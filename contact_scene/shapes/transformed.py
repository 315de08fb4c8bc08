"""Any face rotated, mirrored or scaled, without rebuilding it."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..errors import SceneError
from ..validation import flag, point, real
from .base import Incircle, Shape

__all__ = ["Transformed"]


@dataclass(frozen=True)
class Transformed(Shape):
    """A shape rotated, mirrored and scaled about a point, without rebuilding it.

    The point x maps to about + s R(theta) M (x - about), with M the mirror x -> -x (when
    ``mirror``), R the counter-clockwise rotation and s the scale.

    Parameters
    ----------
    shape : Shape
        The original shape.
    rotation_deg : float, optional
        Counter-clockwise rotation in degrees; 0 by default.
    mirror : bool, optional
        Reflect x -> -x (before rotating).
    scale : float, optional
        Scale factor, > 0; 1 by default.
    about : tuple of float, optional
        (x, y) of the fixed point; the origin by default.

    Raises
    ------
    contact_scene.SceneError
        Naming ``scale``, for a scale that is not > 0; ``indenter.shape`` for a ``shape`` that
        is not a Shape.
    """

    shape: Shape
    rotation_deg: float = real(0.0, name="rotation_deg")
    mirror: bool = flag(False, name="mirror")
    scale: float = real(1.0, gt=0, name="scale")
    about: tuple[float, float] = point((0.0, 0.0), name="about")
    kind = "transformed"

    def _complete(self):
        if not isinstance(self.shape, Shape):
            raise SceneError("indenter.shape", f"must be a Shape (got {type(self.shape).__name__})")

    @cached_property
    def _matrix(self) -> np.ndarray:
        t = math.radians(self.rotation_deg)
        M = self.scale * np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
        if self.mirror:
            M = M @ np.diag([-1.0, 1.0])
        return M

    def _forward(self, x, y):
        M = self._matrix
        ax, ay = self.about
        return ax + M[0, 0] * (x - ax) + M[0, 1] * (y - ay), ay + M[1, 0] * (x - ax) + M[1, 1] * (y - ay)

    def contains(self, x, y):
        inverse = np.linalg.inv(self._matrix)
        ax, ay = self.about
        dx, dy = np.asarray(x, float) - ax, np.asarray(y, float) - ay
        return self.shape.contains(
            ax + inverse[0, 0] * dx + inverse[0, 1] * dy, ay + inverse[1, 0] * dx + inverse[1, 1] * dy
        )

    @property
    def area(self):
        return self.shape.area * self.scale**2

    @property
    def nominal_area(self):
        return self.shape.nominal_area * self.scale**2

    @property
    def area_is_exact(self):
        return self.shape.area_is_exact

    @property
    def bounds(self):
        # the transformed bounding box of the original: conservative, which is all rasterising needs
        x0, y0, x1, y1 = self.shape.bounds
        X, Y = self._forward(np.array([x0, x1, x1, x0]), np.array([y0, y0, y1, y1]))
        return (float(X.min()), float(Y.min()), float(X.max()), float(Y.max()))

    @property
    def centroid(self):
        cx, cy = self._forward(*self.shape.centroid)
        return (float(cx), float(cy))

    def incircle(self):
        r, c = self.shape.incircle()
        cx, cy = self._forward(*c)
        return Incircle(r * self.scale, (float(cx), float(cy)))

    def smallest_part_incircle(self):
        r, c = self.shape.smallest_part_incircle()
        cx, cy = self._forward(*c)
        return Incircle(r * self.scale, (float(cx), float(cy)))
