"""Discretisation settings, kept apart from the physics of a scene."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import SceneError, check_real
from .shapes import Shape

__all__ = ["Grid"]


@dataclass(frozen=True)
class Grid:
    """A square boundary-element grid.

    ``elements_per_radius`` N sets the spacing Delta = sqrt(A/pi) / N (A the nominal face
    area); ``spacing`` sets Delta directly and wins when both are given.

    ``periodic = True`` puts the face in a square cell of side ``period`` repeated over the
    plane (an array of punches, e.g. one column of a brush), instead of alone on an infinite
    half-space.  The spacing is then reduced to period / n, n the smallest whole number of
    cells with period / n <= Delta, so the cell is a whole number of elements.  Approaches
    are measured from the mean plane of the surface (the zero Fourier mode carries no
    displacement): a net load per cell would move a periodic half-space infinitely far.
    Implemented by the Griffith BEM for homogeneous bodies; other methods refuse it.
    """

    elements_per_radius: float | None = 32.0
    spacing: float | None = None
    periodic: bool = False
    period: float | None = None

    def __post_init__(self):
        if not isinstance(self.periodic, bool):
            raise SceneError("grid.periodic", f"must be true or false (got {self.periodic!r})")
        if self.periodic:
            if self.period is None:
                raise SceneError("grid.period", "a periodic grid needs the period (side of the square cell, > 0)")
            object.__setattr__(self, "period", check_real("grid.period", self.period, lo=0, lo_open=True))
        elif self.period is not None:
            raise SceneError("grid.period", "a period is meaningful only with periodic = true")
        if self.spacing is not None:
            object.__setattr__(self, "spacing", check_real("grid.spacing", self.spacing, lo=0, lo_open=True))
        elif self.elements_per_radius is None:
            raise SceneError("grid.elements_per_radius", "give elements_per_radius or spacing")
        if self.elements_per_radius is not None:
            object.__setattr__(
                self,
                "elements_per_radius",
                check_real("grid.elements_per_radius", self.elements_per_radius, lo=0, lo_open=True, hi=1e5),
            )

    def spacing_for(self, shape: Shape) -> float:
        if self.spacing is not None:
            h = self.spacing
        else:
            assert self.elements_per_radius is not None  # __post_init__ requires one of the two
            h = shape.equivalent_radius / self.elements_per_radius
        if self.periodic:
            assert self.period is not None  # __post_init__ requires it when periodic
            h = self.period / math.ceil(self.period / h * (1 - 1e-12))
        return h
