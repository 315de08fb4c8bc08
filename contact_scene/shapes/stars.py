"""Star-shaped faces: the paper's n-ray star (Fig. 14) and the star whose rays are cut to a
prescribed ring filling factor (Eq. 29)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..validation import point, real, whole
from .polygons import PolygonalShape, rotate_points

__all__ = ["Star", "PowerLawStar"]


@dataclass(frozen=True)
class Star(PolygonalShape):
    """An n-ray star (the paper's star punch, Fig. 14).

    The vertices alternate between the outer radius (the tips) and the inner radius; a tip
    points along +y before rotation.

    Parameters
    ----------
    n_rays : int
        Number of rays, 2 <= n <= 10000.
    outer_radius : float
        Radius of the tips, > 0.
    inner_radius : float
        Radius of the notches between the rays, 0 < r <= outer_radius.
    rotation_deg : float, optional
        Counter-clockwise rotation about the centre, in degrees; 0 by default.
    center : tuple of float, optional
        (x, y) of the centre; the origin by default.

    Raises
    ------
    contact_scene.SceneError
        Naming the parameter as a scene file spells it (``indenter.<name>``) and its allowed
        range, for a value out of that range.
    """

    n_rays: int = whole(ge=2, le=10_000)
    outer_radius: float = real(gt=0)
    inner_radius: float = real(gt=0, le=lambda star: star.outer_radius)
    rotation_deg: float = real(0.0)
    center: tuple[float, float] = point()
    simple_by_construction = True
    kind = "star"

    @property
    def vertices(self):
        n = self.n_rays
        t = np.pi / 2 + np.pi * np.arange(2 * n) / n
        r = np.where(np.arange(2 * n) % 2 == 0, self.outer_radius, self.inner_radius)
        return rotate_points(np.column_stack([r * np.cos(t), r * np.sin(t)]), self.rotation_deg, self.center)

    @property
    def centroid(self):
        return self.center


@dataclass(frozen=True)
class PowerLawStar(PolygonalShape):
    """A star whose rays are cut to the ring filling factor phi(r) = (r0/r)^3 (Eq. 29).

    For r0 <= r <= R the filling factor makes the adhesion force of Eq. 28 independent of the
    radius.  For r < r0 the face is the full disc of radius ``core_radius``.  The curved ray
    flanks are polygons with ``samples`` vertices each; area and phi are those of the polygon.

    Parameters
    ----------
    n_rays : int
        Number of rays, 2 <= n <= 1000.
    core_radius : float
        r0, the radius of the full core, > 0.
    outer_radius : float
        R, the radius of the ray tips, > core_radius.
    samples : int, optional
        Vertices per ray flank, 4 <= samples <= 10000; 64 by default.
    rotation_deg : float, optional
        Counter-clockwise rotation about the centre, in degrees; 0 by default.
    center : tuple of float, optional
        (x, y) of the centre; the origin by default.

    Raises
    ------
    contact_scene.SceneError
        Naming the parameter as a scene file spells it (``indenter.<name>``) and its allowed
        range, for a value out of that range.
    """

    n_rays: int = whole(ge=2, le=1000)
    core_radius: float = real(gt=0)
    outer_radius: float = real(gt=lambda star: star.core_radius)
    samples: int = whole(64, ge=4, le=10_000)
    rotation_deg: float = real(0.0)
    center: tuple[float, float] = point()
    kind = "power_law_star"

    def design_filling(self, r):
        """The filling factor phi(r) the rays are designed for: 1 in the core, (r0/r)^3 outside.

        Parameters
        ----------
        r : float or array_like
            Radii, >= 0.

        Returns
        -------
        numpy.ndarray
            phi at each radius, in (0, 1].
        """
        r = np.asarray(r, float)
        return np.where(r <= self.core_radius, 1.0, (self.core_radius / np.maximum(r, 1e-300)) ** 3)

    @property
    def vertices(self):
        n, r0, R = self.n_rays, self.core_radius, self.outer_radius
        r = np.geomspace(r0, R, self.samples)
        half_width = np.pi / n * (r0 / r) ** 3  # half the angle a ray covers at radius r
        flanks = []
        for k in range(n):
            axis = np.pi / 2 + 2 * np.pi * k / n
            right = axis - half_width  # ascending along the right-hand flank, then back down the left
            left = axis + half_width
            flanks.append(np.column_stack([r * np.cos(right), r * np.sin(right)]))
            flanks.append(np.column_stack([r[::-1] * np.cos(left[::-1]), r[::-1] * np.sin(left[::-1])]))
        v = np.vstack(flanks)
        # consecutive rays meet at r0: drop the duplicated junction vertices
        keep = np.ones(len(v), bool)
        step = np.hypot(*(v - np.roll(v, 1, axis=0)).T)
        keep[step < 1e-12 * R] = False
        return rotate_points(v[keep], self.rotation_deg, self.center)

    @property
    def centroid(self):
        return self.center
