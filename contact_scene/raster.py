"""Rasterising a face onto a square grid.

Rule: the grid's nodes (cell corners) lie at ``anchor + (i, j) * spacing``, with the anchor at
the shape's centroid; a cell belongs to the face when its centre lies in the closed shape.
Because centroid and cell centres move with the shape, rotating (or mirroring) a shape and the
grid together gives exactly the same cells; rotating only the shape gives the same face up to
the staircase of the boundary.  The mask is indexed ``mask[ix, iy]`` with x along axis 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import SceneError
from .shapes import Shape

__all__ = [
    "Raster",
    "rasterise",
    "rasterise_periodic",
    "MIN_INCIRCLE_CELLS",
    "FACE_SIZE_RANGE",
    "MAX_REACH_OVER_SIZE",
    "check_face_size",
]

#: a face is refused when fewer than this many cells span its incircle's diameter
MIN_INCIRCLE_CELLS = 4


@dataclass(frozen=True, eq=False)
class Raster:
    """A face on a square grid: the cells whose centres lie in the shape.

    Built by :func:`rasterise` and :func:`rasterise_periodic` (the module's rule fixes which
    cells belong to the face); the solvers discretise the half-space on its cells.

    Parameters
    ----------
    mask : numpy.ndarray
        Boolean (nx, ny) array, True on the cells of the face, indexed ``mask[ix, iy]`` with x
        along axis 0.
    spacing : float
        Side of the square cells, > 0 (the scene's length unit).
    origin : tuple of float
        (x, y) of the centre of cell (0, 0).
    """

    mask: np.ndarray  # bool, [ix, iy]
    spacing: float
    origin: tuple[float, float]  # centre of cell (0, 0)

    @property
    def shape(self) -> tuple[int, int]:
        """(nx, ny), the number of cells along x and y."""
        return self.mask.shape

    @property
    def cell_area(self) -> float:
        """Area of one cell, spacing^2."""
        return self.spacing**2

    @property
    def area(self) -> float:
        """Area of the face on the grid: the number of its cells times spacing^2.

        It differs from the shape's area by the staircase of the boundary.
        """
        return float(np.count_nonzero(self.mask)) * self.spacing**2

    def centres(self) -> tuple[np.ndarray, np.ndarray]:
        """Coordinates of the cell centres.

        Returns
        -------
        x, y : numpy.ndarray
            Two (nx, ny) arrays (``indexing="ij"``): the centre of cell (ix, iy) is
            ``(x[ix, iy], y[ix, iy])``.
        """
        nx, ny = self.mask.shape
        x = self.origin[0] + self.spacing * np.arange(nx)
        y = self.origin[1] + self.spacing * np.arange(ny)
        return np.meshgrid(x, y, indexing="ij")


#: the range of a face's size (the larger side of its bounding box) the geometry is computed in:
#: areas, and the squared edge lengths of the inside tests, stay normal floating-point numbers
FACE_SIZE_RANGE = (1e-150, 1e150)

#: how far from the origin, in multiples of its size, a face may lie: 2^40, where its coordinates'
#: rounding (2^-52 of them) is 2^-12 of its size.  Measured: the rasters of a circle, a square and
#: a star at spacing size/50 are those at the origin up to offsets of 1e12 sizes, not at 1e14
MAX_REACH_OVER_SIZE = 2.0**40


def check_face_size(shape: Shape) -> None:
    """Refuse a face whose size lies outside :data:`FACE_SIZE_RANGE`, or that lies farther from the
    origin than :data:`MAX_REACH_OVER_SIZE` times its size.

    Beyond either the rasteriser's inside tests would return a wrong face without a word: the
    squares of its lengths under- or overflow, or the rounding of its coordinates reaches the
    boundary tolerance.

    Parameters
    ----------
    shape : contact_scene.Shape
        The face.

    Raises
    ------
    contact_scene.SceneError
        Naming ``indenter``, with the size and the range.
    """
    size = shape.size
    lo, hi = FACE_SIZE_RANGE
    if not lo <= size <= hi:
        raise SceneError(
            "indenter",
            f"the face's size ({size:g}, the larger side of its bounding box) must lie in [{lo:g}, {hi:g}], "
            "where its area is a floating-point number: rescale lengths, e.g. to the face's radius",
        )
    reach = max(abs(b) for b in shape.bounds)
    if reach > MAX_REACH_OVER_SIZE * size:
        raise SceneError(
            "indenter",
            f"the face lies {reach / size:.3g} of its sizes from the origin (at most {MAX_REACH_OVER_SIZE:.3g}): "
            "the rounding of its coordinates reaches its boundary tolerance; move it to the origin",
        )


def rasterise(
    shape: Shape, spacing: float, *, min_incircle_cells: float = MIN_INCIRCLE_CELLS, field: str = "grid.spacing"
) -> Raster:
    """Cells of side ``spacing`` whose centres lie in ``shape`` (the module's rule).

    The grid is anchored at the shape's centroid, so a shape rotated together with its grid gives
    the same cells; the raster is cropped to the face plus one empty ring of cells.

    Parameters
    ----------
    shape : contact_scene.Shape
        The face to rasterise.
    spacing : float
        Side of the cells, a finite number > 0 (the scene's length unit).
    min_incircle_cells : float, optional
        Fewest cells allowed across the diameter of the face's incircle (:data:`MIN_INCIRCLE_CELLS`
        by default): a coarser grid cannot represent the face.
    field : str, optional
        The name a :class:`~contact_scene.SceneError` gives the spacing (the scene field it came
        from), ``"grid.spacing"`` by default.

    Returns
    -------
    Raster
        The face's cells, with ``origin`` at the centre of cell (0, 0).

    Raises
    ------
    contact_scene.SceneError
        Naming ``indenter`` for a face whose size lies outside :data:`FACE_SIZE_RANGE`; naming
        ``field``: a spacing that is not a finite number > 0, one with fewer than
        ``min_incircle_cells`` cells across the incircle of the face's smallest separate part
        (``Shape.smallest_part_incircle``; the message gives the largest spacing allowed), a
        raster of more than 2^31 cells, or one in which no cell centre lies in the face.
    """
    if not (isinstance(spacing, (int, float)) and math.isfinite(spacing) and spacing > 0):
        raise SceneError(field, f"must be a finite number > 0 (got {spacing!r})")
    check_face_size(shape)
    # every separate part of the face, not only the largest, must be resolved, or a small one is
    # lost from the raster without a word
    r_in = shape.smallest_part_incircle().radius
    if 2 * r_in < min_incircle_cells * spacing:
        which = "its incircle" if r_in == shape.incircle().radius else "the incircle of its smallest separate part"
        raise SceneError(
            field,
            f"too coarse for the face: {2 * r_in / spacing:.3g} cells across {which} "
            f"(diameter {2 * r_in:g}); need >= {min_incircle_cells:g}, "
            f"i.e. spacing <= {2 * r_in / min_incircle_cells:g}",
        )
    cx, cy = shape.centroid
    xmin, ymin, xmax, ymax = shape.bounds
    i0 = math.floor((xmin - cx) / spacing) - 1
    i1 = math.ceil((xmax - cx) / spacing) + 1
    j0 = math.floor((ymin - cy) / spacing) - 1
    j1 = math.ceil((ymax - cy) / spacing) + 1
    nx, ny = i1 - i0, j1 - j0
    if nx * ny > 2**31:
        raise SceneError(field, f"a {nx} x {ny} raster is too large; choose a coarser spacing")
    x = cx + (i0 + 0.5 + np.arange(nx)) * spacing
    y = cy + (j0 + 0.5 + np.arange(ny)) * spacing
    X, Y = np.meshgrid(x, y, indexing="ij")
    mask = np.asarray(shape.contains(X, Y), bool)
    if not mask.any():
        raise SceneError(field, "no cell centre falls inside the face; refine the grid")
    # crop to the cells in use (one empty ring kept for clarity of plots)
    ix = np.flatnonzero(mask.any(axis=1))
    iy = np.flatnonzero(mask.any(axis=0))
    sx = slice(max(ix[0] - 1, 0), min(ix[-1] + 2, nx))
    sy = slice(max(iy[0] - 1, 0), min(iy[-1] + 2, ny))
    return Raster(np.ascontiguousarray(mask[sx, sy]), float(spacing), (float(x[sx.start]), float(y[sy.start])))


def rasterise_periodic(
    shape: Shape, spacing: float, period: float, *, min_incircle_cells: float = MIN_INCIRCLE_CELLS
) -> Raster:
    """The face in one cell of a periodic array: a (period / spacing)^2 grid.

    The grid is centred on the face's centroid and gives the same cells (same anchor rule) as
    :func:`rasterise`; the boundary-element methods repeat it with period ``period`` in x and y.

    Parameters
    ----------
    shape : contact_scene.Shape
        The face in one periodic cell.
    spacing : float
        Side of the cells, a finite number > 0.
    period : float
        Side of the periodic cell, a whole number of ``spacing`` (see
        :meth:`contact_scene.Grid.spacing_for`), large enough for the face to fit with one empty
        cell between it and its copies.
    min_incircle_cells : float, optional
        Fewest cells allowed across the diameter of the face's incircle, as for :func:`rasterise`.

    Returns
    -------
    Raster
        An (n, n) raster, n = period / spacing, with the face in the middle.

    Raises
    ------
    contact_scene.SceneError
        Naming ``grid.period``: a period that is not a whole number of elements, or too small for
        the face and its gap of one element; naming ``grid.spacing``: as :func:`rasterise`.
    """
    n = round(period / spacing)
    if n < 1 or abs(n * spacing - period) > 1e-9 * period:
        raise SceneError("grid.period", f"the period {period:g} is not a whole number of elements of side {spacing:g}")
    inner = rasterise(shape, spacing, min_incircle_cells=min_incircle_cells)
    cx, cy = shape.centroid
    # cell (i, j) of the periodic grid has its centre at centroid + (i - n // 2 + 1/2) * spacing
    i0 = -(n // 2)
    ox = round((inner.origin[0] - cx) / spacing - 0.5) - i0
    oy = round((inner.origin[1] - cy) / spacing - 0.5) - i0
    mx, my = inner.shape
    # the raster keeps one empty ring; the face itself must leave a gap to its copies
    ix = np.flatnonzero(inner.mask.any(axis=1))
    iy = np.flatnonzero(inner.mask.any(axis=0))
    if ox + ix[0] < 1 or ox + ix[-1] > n - 2 or oy + iy[0] < 1 or oy + iy[-1] > n - 2:
        xmin, ymin, xmax, ymax = shape.bounds
        raise SceneError(
            "grid.period",
            f"the face ({xmax - xmin:g} x {ymax - ymin:g}) does not fit in the periodic "
            f"cell of side {period:g} with a gap of one element to its copies; enlarge the period",
        )
    mask = np.zeros((n, n), bool)
    sx = slice(max(ox, 0), min(ox + mx, n))
    sy = slice(max(oy, 0), min(oy + my, n))
    mask[sx, sy] = inner.mask[sx.start - ox : sx.stop - ox, sy.start - oy : sy.stop - oy]
    origin = (cx + (i0 + 0.5) * spacing, cy + (i0 + 0.5) * spacing)
    return Raster(mask, float(spacing), origin)
