"""What every face shape is and knows: the ``Shape`` base class and the ``Incircle`` it reports.

A shape is a closed, bounded planar region with positive area.  Subclasses provide
``contains``, ``area`` and ``bounds``; the rest (centroid, incircle, filling factor, ring
filling) has a numerical default here that a subclass replaces by its closed form where one
exists.  ``contains`` is the closed set: points on the boundary are inside, to a relative
tolerance of ``BOUNDARY_REL_TOL`` of the shape's size, which makes the rasterisation rule of
:mod:`contact_scene.raster` well defined when a cell centre falls exactly on an edge.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ..validation import check_fields
from . import numerical

__all__ = ["Incircle", "Shape", "BOUNDARY_REL_TOL"]

#: points this close to the boundary (relative to the shape's size) belong to the closed shape
BOUNDARY_REL_TOL = 1e-9


def ldexp_saturating(x: float, e: int) -> float:
    """x 2^e, exact where representable; +-inf past the largest float (math.ldexp raises there) and
    zero below the smallest, which the grid then refuses by name (a face's size that leaves
    floating point)."""
    try:
        return math.ldexp(x, e)
    except OverflowError:
        return math.copysign(math.inf, x)


class Incircle(NamedTuple):
    """The largest circle inscribed in a face (the lower bound's circle, Eqs. 18-19).

    Parameters
    ----------
    radius : float
        Radius a_in of the circle, > 0.
    center : tuple of float
        (x, y) of its centre.
    """

    radius: float
    center: tuple[float, float]


class Shape:
    """Base class of the face shapes: a closed, bounded planar region with positive area.

    Subclasses are frozen dataclasses whose parameters are checked on construction (a
    :class:`~contact_scene.SceneError` names the parameter and its range); see the module for
    what each provides and what has a numerical default.
    """

    kind = "shape"

    @property
    def area_is_exact(self) -> bool:
        """Whether ``area`` is exact (closed form) or a fine numerical quadrature."""
        return True

    def __post_init__(self):
        check_fields(self, "indenter")
        self._complete()

    def _complete(self) -> None:
        """Called once the declared parameters are checked: builds what they imply (parts,
        cuts) and checks conditions that span several of them."""

    # -- to be provided -------------------------------------------------
    def contains(self, x, y) -> np.ndarray:  # pragma: no cover - abstract
        """Whether points lie in the closed shape.

        Points on the boundary, to a relative tolerance of ``BOUNDARY_REL_TOL`` of the shape's size
        (:attr:`tolerance`), are inside: this fixes the rasterisation rule when a cell centre falls
        exactly on an edge.

        Parameters
        ----------
        x, y : float or array_like
            Coordinates of the points (broadcast together).

        Returns
        -------
        numpy.ndarray
            Boolean array of the broadcast shape of x and y.
        """
        raise NotImplementedError

    @property
    def area(self) -> float:  # pragma: no cover - abstract
        """Area A of the face: the part that adheres (see :attr:`nominal_area`)."""
        raise NotImplementedError

    @property
    def bounds(self) -> tuple[float, float, float, float]:  # pragma: no cover - abstract
        """(xmin, ymin, xmax, ymax), an axis-aligned box that contains the face."""
        raise NotImplementedError

    # -- derived ----------------------------------------------------------
    @property
    def size(self) -> float:
        """The larger side of the bounding box: the length scale of the shape's tolerances."""
        xmin, ymin, xmax, ymax = self.bounds
        return max(xmax - xmin, ymax - ymin)

    @property
    def tolerance(self) -> float:
        """``BOUNDARY_REL_TOL * size``: points this close to the boundary belong to the shape."""
        return BOUNDARY_REL_TOL * self.size

    @property
    def equivalent_radius(self) -> float:
        """sqrt(A/pi), the radius of the circle of the same (nominal) area (Eqs. 13-14)."""
        return math.sqrt(self.nominal_area / math.pi)

    @property
    def nominal_area(self) -> float:
        """The area of the face as a whole; differs from ``area`` for brushes and faults."""
        return self.area

    @property
    def filling_factor(self) -> float:
        """Fraction of the nominal area that adheres (phi of Eq. 24)."""
        return self.area / self.nominal_area

    @property
    def centroid(self) -> tuple[float, float]:
        """(x, y) of the face's centroid; the default is a quadrature on a fine raster."""
        return numerical.raster_centroid(self)

    def incircle(self) -> Incircle:
        """The largest inscribed circle (used by the lower bound, Eqs. 18-19).

        This default works on a fine raster (to 1e-3 of the size); shapes with a closed form
        replace it.

        Returns
        -------
        Incircle
            Radius and centre.
        """
        return Incircle(*numerical.raster_incircle(self))

    def smallest_part_incircle(self) -> Incircle:
        """The incircle of the face's narrowest separate part, which a grid must resolve.

        A grid too coarse for it would lose that part from the raster.  The incircle itself for
        a connected face; composite faces of separate parts replace it.

        Returns
        -------
        Incircle
            Radius and centre.
        """
        return self.incircle()

    def ring_filling(self, radius: float, center=None, samples: int = 4096) -> float:
        """phi(r) of Eqs. 25-31: the fraction of a circle that lies in the shape.

        Parameters
        ----------
        radius : float
            Radius r of the circle, > 0.
        center : tuple of float, optional
            (x, y) of the circle's centre; the shape's centroid by default.
        samples : int, optional
            Points sampled evenly along the circle, >= 1.

        Returns
        -------
        float
            The fraction of the samples inside the shape, in [0, 1].
        """
        cx, cy = self.centroid if center is None else center
        t = (np.arange(samples) + 0.5) * (2 * math.pi / samples)
        return float(np.mean(self.contains(cx + radius * np.cos(t), cy + radius * np.sin(t))))

    # -- transformations -------------------------------------------------
    # (Transformed is a Shape itself, so it is imported where it is used)
    def rotated(self, angle_deg: float, about=None) -> Shape:
        """The shape rotated counter-clockwise by ``angle_deg`` about a point.

        Parameters
        ----------
        angle_deg : float
            Rotation angle in degrees.
        about : tuple of float, optional
            (x, y) of the centre of rotation; the shape's centroid by default.

        Returns
        -------
        Shape
            The rotated shape (a polygon for polygonal shapes, else a :class:`Transformed`).
        """
        from .transformed import Transformed

        about = self.centroid if about is None else about
        return Transformed(self, rotation_deg=angle_deg, about=tuple(about))

    def mirrored(self, about=None) -> Shape:
        """Reflection x -> -x about a vertical line through ``about``.

        Parameters
        ----------
        about : tuple of float, optional
            A point on the mirror line; the shape's centroid by default.

        Returns
        -------
        Shape
            The mirrored shape (a polygon for polygonal shapes, else a :class:`Transformed`).
        """
        from .transformed import Transformed

        about = self.centroid if about is None else about
        return Transformed(self, mirror=True, about=tuple(about))

    def scaled(self, factor: float) -> Shape:
        """The shape scaled by ``factor`` about the origin.

        Parameters
        ----------
        factor : float
            Scale factor, > 0.

        Returns
        -------
        Shape
            The scaled shape (a polygon for polygonal shapes, else a :class:`Transformed`).

        Raises
        ------
        contact_scene.SceneError
            Naming ``scale``, for a factor that is not > 0.
        """
        from .transformed import Transformed

        return Transformed(self, scale=factor, about=(0.0, 0.0))

    def describe(self) -> str:
        """A short description for reports and logs.

        Returns
        -------
        str
            The shape's kind, with its size where the shape gives one (e.g. ``"circle r=1"``).
        """
        return self.kind
