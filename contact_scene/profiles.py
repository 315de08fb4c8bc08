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
    """Base class of the indenter profiles: the height h(x, y) >= 0 of the face above its lowest point.

    ``kind`` names the profile as a scene file does (``profile`` in ``[indenter]``);
    ``is_flat`` is True for the flat face alone: it touches with its whole face at d = 0, so it
    needs no press, which a curved profile does (see :class:`~contact_scene.Scene`).
    """

    kind = "profile"
    is_flat = False

    def height(self, x, y) -> np.ndarray:  # pragma: no cover - abstract
        """The height h of the face above its lowest point.

        Parameters
        ----------
        x, y : float or array_like
            Coordinates in the plane of the face (broadcast together).

        Returns
        -------
        numpy.ndarray
            h >= 0 at each point, of the broadcast shape of x and y.
        """
        raise NotImplementedError


@dataclass(frozen=True)
class Flat(Profile):
    """A flat face, h = 0: the punch of Kendall's solution (Eqs. 1-8)."""

    kind = "flat"
    is_flat = True

    def height(self, x, y):
        return np.zeros(np.broadcast(np.asarray(x), np.asarray(y)).shape)


@dataclass(frozen=True)
class Paraboloid(Profile):
    """h = r^2 / (2 R): the JKR sphere in the small-slope limit.

    Parameters
    ----------
    radius : float
        R, the radius of curvature at the apex (a length), > 0.
    apex : tuple of float, optional
        (x, y) of the apex, r being measured from it; the face's origin by default.

    Raises
    ------
    contact_scene.SceneError
        Naming ``indenter.profile_radius`` or ``indenter.profile_apex`` and the allowed range,
        for a value out of that range.
    """

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
    """h = R - sqrt(R^2 - r^2); the face must lie within r < R.

    That the face fits under the sphere is checked by :class:`~contact_scene.Indenter`, which
    knows the face.

    Parameters
    ----------
    radius : float
        R, the sphere's radius (a length), > 0.
    apex : tuple of float, optional
        (x, y) of the apex, r being measured from it; the face's origin by default.

    Raises
    ------
    contact_scene.SceneError
        Naming ``indenter.profile_radius`` or ``indenter.profile_apex`` and the allowed range,
        for a value out of that range.
    """

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
    """h = r / tan(alpha), alpha the half-angle at the tip (90 deg would be flat).

    Parameters
    ----------
    half_angle_deg : float
        alpha, in degrees, in (0, 90).
    apex : tuple of float, optional
        (x, y) of the tip, r being measured from it; the face's origin by default.

    Raises
    ------
    contact_scene.SceneError
        Naming ``indenter.half_angle_deg`` or ``indenter.profile_apex`` and the allowed range,
        for a value out of that range.
    """

    half_angle_deg: float = real(gt=0, lt=90)
    apex: tuple[float, float] = point(name="indenter.profile_apex")
    kind = "cone"

    def __post_init__(self):
        check_fields(self, "indenter")

    def height(self, x, y):
        r = np.hypot(np.asarray(x) - self.apex[0], np.asarray(y) - self.apex[1])
        return r / math.tan(math.radians(self.half_angle_deg))
