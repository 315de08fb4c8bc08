"""Indenter profiles: the height h(x, y) >= 0 of the rigid face above its lowest point.

The gap under a punch at approach d is g = u - (d - h): a flat face has h = 0.  The apex
sits at ``apex`` (default: the face's origin).  The paper validates its BEM on the flat
cylinder (Kendall), the paraboloid (JKR) and the cone.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .validation import check_fields, point, real

__all__ = ["Profile", "Flat", "Paraboloid", "Sphere", "Cone"]


class Profile:
    kind = "profile"
    is_flat = False

    def height(self, x, y) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError


@dataclass(frozen=True)
class Flat(Profile):
    kind = "flat"
    is_flat = True

    def height(self, x, y):
        return np.zeros(np.broadcast(np.asarray(x), np.asarray(y)).shape)


@dataclass(frozen=True)
class Paraboloid(Profile):
    """h = r^2 / (2 R): the JKR sphere in the small-slope limit."""

    radius: float = real(gt=0, name="indenter.profile_radius")
    apex: tuple[float, float] = point(name="indenter.profile_apex")
    kind = "paraboloid"

    def __post_init__(self):
        check_fields(self, "indenter")

    def height(self, x, y):
        r2 = (np.asarray(x) - self.apex[0]) ** 2 + (np.asarray(y) - self.apex[1]) ** 2
        return r2 / (2 * self.radius)


@dataclass(frozen=True)
class Sphere(Profile):
    """h = R - sqrt(R^2 - r^2); the face must lie within r < R."""

    radius: float = real(gt=0, name="indenter.profile_radius")
    apex: tuple[float, float] = point(name="indenter.profile_apex")
    kind = "sphere"

    def __post_init__(self):
        check_fields(self, "indenter")

    def height(self, x, y):
        r2 = (np.asarray(x) - self.apex[0]) ** 2 + (np.asarray(y) - self.apex[1]) ** 2
        R = self.radius
        return R - np.sqrt(np.maximum(R * R - r2, 0.0))


@dataclass(frozen=True)
class Cone(Profile):
    """h = r / tan(alpha), alpha the half-angle at the tip (90 deg would be flat)."""

    half_angle_deg: float = real(gt=0, lt=90)
    apex: tuple[float, float] = point(name="indenter.profile_apex")
    kind = "cone"

    def __post_init__(self):
        check_fields(self, "indenter")

    def height(self, x, y):
        r = np.hypot(np.asarray(x) - self.apex[0], np.asarray(y) - self.apex[1])
        return r / math.tan(math.radians(self.half_angle_deg))
