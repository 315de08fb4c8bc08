"""Discretisation settings, kept apart from the physics of a scene."""
from __future__ import annotations

from dataclasses import dataclass

from .errors import SceneError, check_real
from .shapes import Shape

__all__ = ["Grid"]


@dataclass(frozen=True)
class Grid:
    """A square boundary-element grid.

    ``elements_per_radius`` N sets the spacing Delta = sqrt(A/pi) / N (A the nominal face
    area); ``spacing`` sets Delta directly and wins when both are given.  ``periodic`` asks for
    a half-space periodic over the grid instead of infinite: no solver implements it yet, and
    each refuses it with a SceneError rather than ignoring it.
    """

    elements_per_radius: float | None = 32.0
    spacing: float | None = None
    periodic: bool = False

    def __post_init__(self):
        if self.spacing is not None:
            object.__setattr__(self, "spacing", check_real("grid.spacing", self.spacing, lo=0, lo_open=True))
        elif self.elements_per_radius is None:
            raise SceneError("grid.elements_per_radius", "give elements_per_radius or spacing")
        if self.elements_per_radius is not None:
            object.__setattr__(self, "elements_per_radius",
                               check_real("grid.elements_per_radius", self.elements_per_radius, lo=0, lo_open=True, hi=1e5))

    def spacing_for(self, shape: Shape) -> float:
        if self.spacing is not None:
            return self.spacing
        return shape.equivalent_radius / self.elements_per_radius
