"""Numerical geometry on a fine raster, for shapes without a closed form (unions of
overlapping parts, cut faces, images): area, centroid and incircle, each accurate to about
1e-3 of the shape's size or better, and the separate parts (islands) of a raster."""

from __future__ import annotations

import numpy as np
from scipy import ndimage

__all__ = ["fine_grid", "raster_area", "raster_centroid", "raster_incircle", "smallest_island"]


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


def smallest_island(inside: np.ndarray) -> tuple[int, float, tuple[int, ...]]:
    """The separate parts of a raster and the narrowest of them.

    Islands are the 4-connected components of ``inside``: cells touching only at a corner, which
    meet in a point, are apart (the more islands, the narrower the narrowest).  An island's depth
    is the largest distance, in cells, from one of its cell centres to the nearest centre outside
    the face (``scipy.ndimage.distance_transform_edt``); the narrowest island is the one of least
    depth.  ``inside`` must have an empty border, or the array's edge does not count as outside.

    Returns (number of islands, depth of the narrowest, its deepest cell's index); with fewer
    than two islands, (number, 0.0, ()): the face's incircle is then its narrowest part's.
    """
    labels, n = ndimage.label(inside)
    if n < 2:
        return n, 0.0, ()
    depth = ndimage.distance_transform_edt(inside)
    index = np.arange(1, n + 1)
    peaks = np.asarray(ndimage.maximum(depth, labels, index), float)
    k = int(np.argmin(peaks))
    where = np.asarray(ndimage.maximum_position(depth, labels, k + 1), np.int64).ravel()
    return n, float(peaks[k]), tuple(int(i) for i in where)
