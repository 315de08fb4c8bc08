"""Numerical geometry on a fine raster, for shapes without a closed form (unions of
overlapping parts, cut faces, images): area, centroid and incircle, each accurate to about
1e-3 of the shape's size or better, and the separate parts (islands) of a raster."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from scipy import ndimage

__all__ = ["fine_grid", "raster_area", "raster_centroid", "raster_incircle", "islands", "Islands", "smallest_island"]


def fine_grid(shape, cells_across: int):
    """Cell centres covering the shape's bounding box (plus one cell each side) with
    ``cells_across`` cells over its larger side; returns (X, Y, cell side)."""
    xmin, ymin, xmax, ymax = shape.bounds
    h = max(xmax - xmin, ymax - ymin) / cells_across
    xs = np.arange(xmin - h, xmax + 1.5 * h, h)
    ys = np.arange(ymin - h, ymax + 1.5 * h, h)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    return X, Y, h


def raster_centroid(shape, cells_across: int = 1024) -> tuple[float, float]:
    X, Y, _ = fine_grid(shape, cells_across)
    inside = shape.contains(X, Y)
    return float(X[inside].mean()), float(Y[inside].mean())


def raster_incircle(shape, cells_across: int = 1024) -> tuple[float, tuple[float, float]]:
    """(radius, centre) of the largest inscribed circle found on the raster."""
    X, Y, h = fine_grid(shape, cells_across)
    inside = shape.contains(X, Y)
    dist = ndimage.distance_transform_edt(inside) * h
    i = np.unravel_index(np.argmax(dist), dist.shape)
    # the transform measures centre to the nearest outside centre; the boundary is half a cell nearer
    return float(dist[i] - 0.5 * h), (float(X[i]), float(Y[i]))


def raster_area(shape, cells_across: int = 2048) -> float:
    X, Y, h = fine_grid(shape, cells_across)
    return float(np.count_nonzero(shape.contains(X, Y)) * h * h)


class Islands(NamedTuple):
    """The separate parts of a raster (:func:`islands`)."""

    #: each cell's island, 1 ... number (0 outside)
    labels: np.ndarray
    #: the number of islands
    number: int
    #: each island's depth, in cells (island k at index k - 1)
    depths: np.ndarray
    #: each island's deepest cell, (i, j)
    deepest: list[tuple[int, int]]


def islands(inside: np.ndarray) -> Islands:
    """The separate parts of a raster, each with its depth and its deepest cell.

    Islands are the 4-connected components of ``inside``: cells touching only at a corner, which
    meet in a point, are apart (the more islands, the narrower the narrowest).  An island's depth
    is the largest distance, in cells, from one of its cell centres to the nearest centre outside
    the face (``scipy.ndimage.distance_transform_edt``).  ``inside`` must have an empty border,
    or the array's edge does not count as outside.  Depths and deepest cells are computed only
    for two or more islands (a face of one part has its incircle).

    Parameters
    ----------
    inside : numpy.ndarray
        The raster, boolean.

    Returns
    -------
    Islands
        Labels, number, depths and deepest cells (the last two empty for fewer than two islands).
    """
    labels, n = ndimage.label(inside)
    if n < 2:
        return Islands(labels, n, np.zeros(0), [])
    depth = ndimage.distance_transform_edt(inside)
    index = np.arange(1, n + 1)
    depths = np.asarray(ndimage.maximum(depth, labels, index), float)
    deepest = [(int(w[0]), int(w[1])) for w in ndimage.maximum_position(depth, labels, index)]
    return Islands(labels, n, depths, deepest)


def smallest_island(inside: np.ndarray) -> tuple[int, float, tuple[int, ...]]:
    """The separate parts of a raster and the narrowest of them (:func:`islands`), the island of
    least depth.

    Returns (number of islands, depth of the narrowest, its deepest cell's index); with fewer
    than two islands, (number, 0.0, ()): the face's incircle is then its narrowest part's.
    """
    found = islands(inside)
    if found.number < 2:
        return found.number, 0.0, ()
    k = int(np.argmin(found.depths))
    return found.number, float(found.depths[k]), found.deepest[k]
