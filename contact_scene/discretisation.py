"""Discretisation settings, kept apart from the physics of a scene."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from .errors import SceneError
from .shapes import Shape
from .validation import check_fields, flag, real

__all__ = ["Grid", "finest_elements_per_radius"]


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

    Parameters
    ----------
    elements_per_radius : float or None, optional
        N, elements per equivalent radius sqrt(A/pi), in (0, 1e5]; 32 by default.  None when
        ``spacing`` is given.
    spacing : float or None, optional
        The element side Delta (a length), > 0; None (the default) to derive it from
        ``elements_per_radius``.
    periodic : bool, optional
        Repeat the face's square cell over the plane; False by default.
    period : float or None, optional
        Side of the periodic cell (a length), > 0; required when ``periodic``, and only then.

    Raises
    ------
    contact_scene.SceneError
        Naming ``grid.<field>`` and its allowed range for a value out of that range;
        ``grid.period`` for a periodic grid without a period or a period without
        ``periodic = True``; ``grid.elements_per_radius`` when neither it nor ``spacing`` is
        given.
    """

    elements_per_radius: float | None = real(32.0, gt=0, le=1e5, optional=True)
    spacing: float | None = real(None, gt=0, optional=True)
    periodic: bool = flag(False)
    period: float | None = real(None, gt=0, optional=True, when=lambda grid: grid.periodic)

    def __post_init__(self):
        check_fields(self, "grid")
        # which fields must be given depends on the others: not a range of any one of them
        if self.periodic and self.period is None:
            raise SceneError("grid.period", "a periodic grid needs the period (side of the square cell, > 0)")
        if not self.periodic and self.period is not None:
            raise SceneError("grid.period", "a period is meaningful only with periodic = true")
        if self.spacing is None and self.elements_per_radius is None:
            raise SceneError("grid.elements_per_radius", "give elements_per_radius or spacing")

    def spacing_for(self, shape: Shape) -> float:
        """The element side Delta this grid gives a face.

        Parameters
        ----------
        shape : contact_scene.Shape
            The face; its equivalent radius sqrt(A/pi) (nominal area A) sets Delta when the
            grid gives ``elements_per_radius``.

        Returns
        -------
        float
            ``spacing`` if given, else sqrt(A/pi) / ``elements_per_radius``; on a periodic grid
            reduced to period / n, n the smallest whole number with period / n <= that value.
        """
        if self.spacing is not None:
            h = self.spacing
        else:
            assert self.elements_per_radius is not None  # __post_init__ requires one of the two
            h = shape.equivalent_radius / self.elements_per_radius
            if not 0 < h < math.inf:
                # the face's area under- or overflowed (a radius of 1e-200 or 1e200): the grid the user
                # asked for is fine, the face's size is not
                raise SceneError(
                    "indenter",
                    f"the face's size leaves floating point (equivalent radius {shape.equivalent_radius!r}): "
                    "rescale lengths, e.g. to the face's radius",
                )
        if self.periodic:
            assert self.period is not None  # __post_init__ requires it when periodic
            h = self.period / math.ceil(self.period / h * (1 - 1e-12))
        return h


def finest_elements_per_radius(shape: Shape, memory_gb: Callable[[int, int], float], limit_gb: float) -> int:
    """The finest grid, in elements per equivalent radius, whose memory fits in ``limit_gb``.

    Each solver has its own memory model; the grid is the face's bounding box plus a ring of
    cells, as the rasteriser lays it.

    Parameters
    ----------
    shape : contact_scene.Shape
        The face.
    memory_gb : callable
        ``memory_gb(nx, ny)``: the solver's estimate, in GB, for an nx x ny raster.
    limit_gb : float
        The memory limit in GB.

    Returns
    -------
    int
        The largest whole number of elements per radius that fits, at least 1.
    """
    xmin, ymin, xmax, ymax = shape.bounds

    def need(n: float) -> float:
        h = shape.equivalent_radius / n
        return memory_gb(math.ceil((xmax - xmin) / h) + 2, math.ceil((ymax - ymin) / h) + 2)

    fits, too_fine = 1.0, 2.0
    while need(too_fine) <= limit_gb:
        fits, too_fine = too_fine, 2 * too_fine
    for _ in range(40):  # need(n) grows like n^2: bisect to a whole number
        middle = 0.5 * (fits + too_fine)
        fits, too_fine = (middle, too_fine) if need(middle) <= limit_gb else (fits, middle)
    return math.floor(fits)
