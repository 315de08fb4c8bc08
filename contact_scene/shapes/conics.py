"""Faces bounded by one conic: the circle (Kendall's punch) and the ellipse (Galin's)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..validation import point, real
from .base import BOUNDARY_REL_TOL, Incircle, Shape

__all__ = ["Circle", "Ellipse"]


@dataclass(frozen=True)
class Circle(Shape):
    """A circular face: Kendall's flat punch.

    Parameters
    ----------
    radius : float
        Radius a, > 0.
    center : tuple of float, optional
        (x, y) of the centre; the origin by default.

    Raises
    ------
    contact_scene.SceneError
        Naming the parameter as a scene file spells it (``indenter.<name>``) and its allowed
        range, for a value out of that range.
    """

    radius: float = real(gt=0)
    center: tuple[float, float] = point()
    kind = "circle"

    def contains(self, x, y):
        x, y = np.asarray(x, float), np.asarray(y, float)
        return np.hypot(x - self.center[0], y - self.center[1]) <= self.radius * (1 + BOUNDARY_REL_TOL)

    def signed_distance(self, x, y):
        """Signed distance to the circle (negative inside).

        Parameters
        ----------
        x, y : float or array_like
            Coordinates of the points (broadcast together).

        Returns
        -------
        numpy.ndarray
            abs(r - centre) - radius at each point.
        """
        return np.hypot(np.asarray(x) - self.center[0], np.asarray(y) - self.center[1]) - self.radius

    @property
    def area(self):
        try:
            return math.pi * self.radius**2
        except OverflowError:  # a radius past 1e154: inf, which the grid then refuses by name
            return math.inf

    @property
    def bounds(self):
        cx, cy = self.center
        r = self.radius
        return (cx - r, cy - r, cx + r, cy + r)

    @property
    def centroid(self):
        return self.center

    def incircle(self):
        return Incircle(self.radius, self.center)

    def describe(self):
        return f"circle r={self.radius:g}"


@dataclass(frozen=True)
class Ellipse(Shape):
    """An elliptical face (Galin's punch, :func:`contact_scene.theory.elliptical_punch_stiffness`).

    Parameters
    ----------
    semi_major : float
        Semi-major axis a, > 0.
    semi_minor : float
        Semi-minor axis b, 0 < b <= a.
    rotation_deg : float, optional
        Counter-clockwise angle of the major axis from the x axis, in degrees; 0 by default.
    center : tuple of float, optional
        (x, y) of the centre; the origin by default.

    Raises
    ------
    contact_scene.SceneError
        Naming the parameter as a scene file spells it (``indenter.<name>``) and its allowed
        range, for a value out of that range.
    """

    semi_major: float = real(gt=0)
    semi_minor: float = real(gt=0, le=lambda ellipse: ellipse.semi_major)
    rotation_deg: float = real(0.0)
    center: tuple[float, float] = point()
    kind = "ellipse"

    def contains(self, x, y):
        t = math.radians(self.rotation_deg)
        dx = np.asarray(x, float) - self.center[0]
        dy = np.asarray(y, float) - self.center[1]
        along_major = dx * math.cos(t) + dy * math.sin(t)
        along_minor = -dx * math.sin(t) + dy * math.cos(t)
        return (along_major / self.semi_major) ** 2 + (along_minor / self.semi_minor) ** 2 <= 1 + 2 * BOUNDARY_REL_TOL

    @property
    def area(self):
        return math.pi * self.semi_major * self.semi_minor

    @property
    def eccentricity(self) -> float:
        """e = sqrt(1 - b^2/a^2)."""
        return math.sqrt(1 - (self.semi_minor / self.semi_major) ** 2)

    @property
    def bounds(self):
        t = math.radians(self.rotation_deg)
        a, b = self.semi_major, self.semi_minor
        half_width = math.hypot(a * math.cos(t), b * math.sin(t))
        half_height = math.hypot(a * math.sin(t), b * math.cos(t))
        cx, cy = self.center
        return (cx - half_width, cy - half_height, cx + half_width, cy + half_height)

    @property
    def centroid(self):
        return self.center

    def incircle(self):
        # the curvature radius at the ends of the minor axis, a^2/b, is >= b: the circle of radius b fits
        return Incircle(self.semi_minor, self.center)
