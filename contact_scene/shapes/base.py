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


class Incircle(NamedTuple):
    radius: float
    center: tuple[float, float]


class Shape:
    """Base class: a closed, bounded planar region with positive area."""

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
        raise NotImplementedError

    @property
    def area(self) -> float:  # pragma: no cover - abstract
        raise NotImplementedError

    @property
    def bounds(self) -> tuple[float, float, float, float]:  # pragma: no cover - abstract
        raise NotImplementedError

    # -- derived ----------------------------------------------------------
    @property
    def size(self) -> float:
        xmin, ymin, xmax, ymax = self.bounds
        return max(xmax - xmin, ymax - ymin)

    @property
    def tolerance(self) -> float:
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
        return numerical.raster_centroid(self)

    def incircle(self) -> Incircle:
        """Largest inscribed circle; this default works on a fine raster (to 1e-3 of the size)."""
        return Incircle(*numerical.raster_incircle(self))

    def ring_filling(self, radius: float, center=None, samples: int = 4096) -> float:
        """phi(r) of Eqs. 25-31: the fraction of the circle of the given radius that lies in the shape."""
        cx, cy = self.centroid if center is None else center
        t = (np.arange(samples) + 0.5) * (2 * math.pi / samples)
        return float(np.mean(self.contains(cx + radius * np.cos(t), cy + radius * np.sin(t))))

    # -- transformations -------------------------------------------------
    # (Transformed is a Shape itself, so it is imported where it is used)
    def rotated(self, angle_deg: float, about=None) -> Shape:
        from .transformed import Transformed

        about = self.centroid if about is None else about
        return Transformed(self, rotation_deg=angle_deg, about=tuple(about))

    def mirrored(self, about=None) -> Shape:
        """Reflection x -> -x about a vertical line through ``about`` (default: the centroid)."""
        from .transformed import Transformed

        about = self.centroid if about is None else about
        return Transformed(self, mirror=True, about=tuple(about))

    def scaled(self, factor: float) -> Shape:
        from .transformed import Transformed

        return Transformed(self, scale=factor, about=(0.0, 0.0))

    def describe(self) -> str:
        return self.kind
