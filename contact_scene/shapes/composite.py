"""Faces built from other faces: unions, faces with cuts, and the paper's two circles (Fig. 15).

Area and centroid are exact when the pieces do not overlap (judged by their bounding boxes),
otherwise a quadrature on a fine raster; ``area_is_exact`` says which.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from scipy import ndimage

from ..errors import SceneError
from ..validation import real
from . import numerical
from .base import Incircle, Shape, ldexp_saturating
from .conics import Circle, Ellipse
from .polygons import PolygonalShape

__all__ = ["Union", "Difference", "TwoCircles"]

#: cells across the larger side of the auxiliary raster on which a difference finds its separate
#: parts: at least the first (the incircle raster's, 1e-3 of the size), more where a piece is
#: narrow, at most the second (the area raster's cost)
_PARTS_CELLS_ACROSS = (1024, 2048)
#: auxiliary cells wanted across the narrowest estimated width of a base or cut piece
_PARTS_CELLS_PER_WIDTH = 4


def _pairwise_disjoint(shapes) -> bool:
    """Whether no two of the shapes' bounding boxes meet: of every pair, one lies strictly left
    of, right of, below or above the other (touching boxes meet).  Sorted by their left edges, a
    box can only meet those that start before its right edge ends: each box is compared with those
    alone, not with all (a brush has up to 1e5 pillars)."""
    if len(shapes) < 2:
        return True
    boxes = np.array([shape.bounds for shape in shapes], float)
    boxes = boxes[np.argsort(boxes[:, 0], kind="stable")]
    x0, y0, x1, y1 = boxes.T
    # the boxes after i in that order whose left edge is at or before i's right edge meet it in x
    last = np.searchsorted(x0, x1, side="right")
    for i in range(len(boxes)):
        j = slice(i + 1, last[i])
        if np.any((y0[j] <= y1[i]) & (y0[i] <= y1[j])):
            return False
    return True


def _weighted_centroid(areas, centroids) -> tuple[float, float]:
    areas = np.asarray(areas, float)
    centroids = np.asarray(centroids, float)
    # weights of order one: an area times a coordinate is a length cubed, which overflows for
    # faces of 1e103 and more while their areas and coordinates do not
    weights = areas / np.max(np.abs(areas))
    cx, cy = (weights[:, None] * centroids).sum(0) / weights.sum()
    return float(cx), float(cy)


@dataclass(frozen=True)
class Union(Shape):
    """The union of shapes.

    The area is exact when the parts' bounding boxes are disjoint, otherwise a quadrature on a
    2048-cell raster (``area_is_exact`` says which).

    Parameters
    ----------
    parts : tuple of Shape
        The shapes joined, at least one.

    Raises
    ------
    contact_scene.SceneError
        Naming ``indenter.parts``, for no parts or a part that is not a shape.
    """

    parts: tuple = ()
    kind = "union"

    def _complete(self):
        parts = tuple(self.parts) if isinstance(self.parts, (tuple, list)) else ()
        if not parts or not all(isinstance(p, Shape) for p in parts):
            raise SceneError("indenter.parts", "a union needs a tuple of at least one shape")
        object.__setattr__(self, "parts", parts)

    def contains(self, x, y):
        out = self.parts[0].contains(x, y)
        for p in self.parts[1:]:
            out = out | p.contains(x, y)
        return out

    @cached_property
    def _disjoint(self) -> bool:
        return _pairwise_disjoint(self.parts)

    @property
    def area_is_exact(self):
        return self._disjoint

    def incircle(self):
        if self._disjoint:  # separate parts: the largest part's incircle, exactly
            return max((p.incircle() for p in self.parts), key=lambda c: c.radius)
        return Incircle(*numerical.raster_incircle(self))

    def smallest_part_incircle(self):
        if self._disjoint:
            return min((p.smallest_part_incircle() for p in self.parts), key=lambda c: c.radius)
        # bounding boxes that meet do not make the parts meet (a disc in a ring's hole): the
        # islands of an auxiliary raster, as a difference finds them
        return self._smallest_part

    @cached_property
    def _smallest_part(self) -> Incircle:
        return _smallest_island_incircle(self, _pieces(self), [])

    @cached_property
    def area(self):
        if self._disjoint:
            return float(sum(p.area for p in self.parts))
        return numerical.raster_area(self)

    @property
    def bounds(self):
        b = np.array([p.bounds for p in self.parts])
        return (float(b[:, 0].min()), float(b[:, 1].min()), float(b[:, 2].max()), float(b[:, 3].max()))

    @cached_property
    def centroid(self):
        if self._disjoint:
            return _weighted_centroid([p.area for p in self.parts], [p.centroid for p in self.parts])
        return numerical.raster_centroid(self)


def _pieces(shape: Shape) -> list[Shape]:
    """The pieces whose union is the shape: a union's parts (recursively), else the shape itself."""
    if isinstance(shape, Union):
        return [piece for part in shape.parts for piece in _pieces(part)]
    return [shape]


def _width_estimate(piece: Shape) -> float:
    """area / (sqrt(2) size): at most the narrowest width w of a convex piece.

    For a convex set of diameter D, w D / 2 <= area <= w D, and D / sqrt(2) <= size <= D, so
    w / 2 <= area / size <= sqrt(2) w.  A piece with a narrow arm (a star, a ring) can be
    narrower than this says.
    """
    return piece.area / (math.sqrt(2) * piece.size)


#: cells across the raster that measures a difference's area (``numerical.raster_area``)
AREA_RASTER_CELLS = 2048
#: a difference with less than this fraction of its base's area is checked for emptiness
#: against its closed cuts (an area made of the cuts' outlines only)
SMALL_AREA = 0.01


def _closure(shape: Shape, x, y):
    """Closed set, with the boundary band that :func:`_interior` leaves to the face."""
    if hasattr(shape, "signed_distance"):
        return shape.signed_distance(x, y) <= shape.tolerance
    return shape.contains(x, y)


def _interior(shape: Shape, x, y):
    """Open interior: a cut removes its interior, so the cut's boundary stays part of the face."""
    if hasattr(shape, "signed_distance"):
        return shape.signed_distance(x, y) < -shape.tolerance
    return shape.contains(x, y)


@dataclass(frozen=True)
class Difference(Shape):
    """A face with cuts: ``base`` with the interiors of ``cuts`` removed.

    The area is exact when every cut is a convex polygon or circle inside a convex base and the
    cuts' bounding boxes are disjoint.  The cuts remove their interiors only, so their
    boundaries stay part of the face.

    Parameters
    ----------
    base : Shape
        The uncut face; its area is the nominal area (phi of Eq. 24 = area / nominal area).
    cuts : tuple of Shape, optional
        The shapes cut out.

    Raises
    ------
    contact_scene.SceneError
        Naming ``indenter.base`` (no base shape) or ``indenter.cuts`` (cuts that remove the
        whole face).
    """

    # None only as the marker of a missing base, which _complete turns into a SceneError naming the field
    base: Shape = None  # type: ignore[assignment]
    cuts: tuple = ()
    kind = "difference"

    def _complete(self):
        if not isinstance(self.base, Shape):
            raise SceneError("indenter.base", "a difference needs a base shape")
        cuts = self.cuts if isinstance(self.cuts, (tuple, list)) else None
        if cuts is None or not all(isinstance(c, Shape) for c in cuts):
            raise SceneError("indenter.cuts", "must be a tuple of shapes")
        object.__setattr__(self, "cuts", tuple(cuts))
        if self.area <= 0:
            if not self.base.area > 0:  # an area that underflowed, not one the cuts took away
                raise SceneError(
                    "indenter.base", f"the base's area underflows (size {self.base.size:g}): rescale lengths"
                )
            raise SceneError("indenter.cuts", "the cuts remove the whole face; the shape is empty")
        # the cuts keep their boundaries, so cuts that cover the base (one equal to it, or two
        # meeting along a line) leave their outlines, which the area's raster counts: a small
        # area is checked against the closed cuts, and a face they cover entirely is empty
        if not self._exact and self.area < SMALL_AREA * self.base.area and not self._beyond_closed_cuts():
            raise SceneError(
                "indenter.cuts",
                f"the cuts cover the whole face but for their own outlines (area {self.area:.3g} on the raster "
                "that measures it): the shape is empty",
            )

    def _beyond_closed_cuts(self) -> bool:
        """Whether any cell of the area's raster lies in the base outside every closed cut."""
        X, Y, _ = numerical.fine_grid(self, AREA_RASTER_CELLS)
        out = self.base.contains(X, Y)
        for c in self.cuts:
            out &= ~_closure(c, X, Y)
        return bool(out.any())

    def contains(self, x, y):
        out = self.base.contains(x, y)
        for c in self.cuts:
            out = out & ~_interior(c, x, y)
        return out

    @cached_property
    def _exact(self) -> bool:
        base = self.base
        if not (isinstance(base, (Circle, Ellipse)) or (isinstance(base, PolygonalShape) and base.is_convex)):
            return False
        for c in self.cuts:
            if not isinstance(c, PolygonalShape) or not np.all(base.contains(c._verts[:, 0], c._verts[:, 1])):
                return False
        return _pairwise_disjoint(self.cuts)

    @property
    def area_is_exact(self):
        return self._exact

    @cached_property
    def area(self):
        if self._exact:
            return float(self.base.area - sum(c.area for c in self.cuts))
        return numerical.raster_area(self, AREA_RASTER_CELLS)

    @property
    def nominal_area(self):
        return self.base.area

    @property
    def bounds(self):
        return self.base.bounds

    @cached_property
    def centroid(self):
        if self._exact:
            return _weighted_centroid(
                [self.base.area] + [-c.area for c in self.cuts], [self.base.centroid] + [c.centroid for c in self.cuts]
            )
        return numerical.raster_centroid(self)

    def smallest_part_incircle(self):
        """The incircle of the face's narrowest separate part, which a grid must resolve: an estimate.

        Cuts can split the base into separate parts (a bar across a disc).  They are found on an
        auxiliary raster as its 4-connected islands (cells touching only at a corner are apart),
        each measured by the distance transform of its cells.  The raster has 1024 cells across
        the face's larger side, or more, up to 2048, so that 4 cells span the narrowest piece of
        the base or of a cut (a union's parts count one by one).  A piece's width is estimated as
        area / (sqrt(2) size), at most the width of a convex piece: a convex cut is then wider
        than a cell, which neighbouring cells cannot step across, so the islands it separates
        stay apart.  Each piece is evaluated on the cells of its bounding box only, so a union
        of many parts costs in proportion to their number.

        With one island the face's :meth:`incircle` is returned, as for any connected face.  With
        several, the narrowest island's radius is its deepest cell's distance to the nearest cell
        outside minus one cell, h: the raster's error goes to the side that refuses a grid, so the
        estimate is below the true radius (to order h^2 / radius) by less than 2 h, and h is 1e-3
        of the face's size or less.  An island of a cell or two is at the raster's limit and is
        given h / 2; a part narrower than a cell can be missed, as can a cut where it is narrower
        than a cell (a piece narrower than 4 cells at the 2048 limit, or a non-convex one with
        narrow arms).

        Returns
        -------
        Incircle
            Radius and centre.
        """
        return self._smallest_part

    @cached_property
    def _smallest_part(self) -> Incircle:
        base_pieces = _pieces(self.base)
        # a cut's interior is removed (its boundary stays face); a union cut's parts are closed,
        # as the union's own contains is
        cut_pieces = [(piece, True) for cut in self.cuts if isinstance(cut, Union) for piece in _pieces(cut)]
        cut_pieces += [(cut, False) for cut in self.cuts if not isinstance(cut, Union)]
        return _smallest_island_incircle(self, base_pieces, cut_pieces)


#: cells across an island's width (twice its radius) on the raster that measures again an island
#: the first raster found, and the most cells across its box
_ISLAND_REFINE_CELLS, _ISLAND_REFINE_MAX_CELLS = 128, 4096


def _raster_inside(xs, ys, h, base_pieces, cut_pieces, keep=None):
    """Which of the cell centres ``xs`` x ``ys`` lie in the face, each piece evaluated on its own
    box's cells only; also each base piece's (cells, mask) where ``keep`` asks for them."""

    def block(piece):
        # the cells of the piece's bounding box, padded by a cell for its boundary tolerance
        x0, y0, x1, y1 = piece.bounds
        i = slice(np.searchsorted(xs, x0 - h, "left"), np.searchsorted(xs, x1 + h, "right"))
        j = slice(np.searchsorted(ys, y0 - h, "left"), np.searchsorted(ys, y1 + h, "right"))
        X, Y = np.meshgrid(xs[i], ys[j], indexing="ij")
        return (i, j), X, Y

    inside = np.zeros((len(xs), len(ys)), bool)
    masks = []
    for piece in base_pieces:
        where, X, Y = block(piece)
        mask = np.asarray(piece.contains(X, Y), bool)
        inside[where] |= mask
        if keep:
            masks.append((where, mask))
    for piece, closed in cut_pieces:
        where, X, Y = block(piece)
        inside[where] &= ~np.asarray(piece.contains(X, Y) if closed else _interior(piece, X, Y), bool)
    return inside, masks


def _boxes_meet(a, b) -> bool:
    return not (a[2] < b[0] or b[2] < a[0] or a[3] < b[1] or b[3] < a[1])


def _smallest_island_incircle(face: Shape, base_pieces: list, cut_pieces: list) -> Incircle:
    """The incircle of the narrowest island of ``face`` on an auxiliary raster (see
    :meth:`Difference.smallest_part_incircle`); ``face.incircle()`` when it has one island.

    ``base_pieces`` are joined, then each (piece, closed) of ``cut_pieces`` removed: the closed
    piece where ``closed``, else its open interior.  An island that is one base piece, met by no
    other piece and no cut, takes that piece's own (exact) smallest-part incircle; the others that
    may be the narrowest are measured again on a raster of their own box, 128 cells across their
    width, so that the estimate's shortfall (under two of its cells) is a small part of the
    island, not of the face (at 4 cells per piece width over the whole face, a disc of radius 0.01 in a ring of
    radius 1 came out 22 % small, and a grid that resolves it was refused)."""
    narrowest = min(_width_estimate(piece) for piece in base_pieces + [piece for piece, _ in cut_pieces])
    xmin, ymin, xmax, ymax = face.bounds
    size = face.size
    fewest, most = _PARTS_CELLS_ACROSS
    cells = fewest
    if narrowest > 0 and math.isfinite(narrowest):
        cells = min(max(fewest, math.ceil(_PARTS_CELLS_PER_WIDTH * size / narrowest)), most)
    h = size / cells
    # the cell centres of numerical.fine_grid: the box plus one empty cell each side
    xs = np.arange(xmin - h, xmax + 1.5 * h, h)
    ys = np.arange(ymin - h, ymax + 1.5 * h, h)
    inside, masks = _raster_inside(xs, ys, h, base_pieces, cut_pieces, keep=True)
    labels, n, peaks, where_peak = numerical.islands(inside)
    if n < 2:
        return face.incircle()
    # which base pieces cover which islands: an island that is one piece alone, reached by no cut,
    # is that piece, whose own incircle is exact
    cut_boxes = [piece.bounds for piece, _ in cut_pieces]
    covering: dict[int, list[int]] = {}
    exact: dict[int, Incircle] = {}
    piece_labels = []
    for k, (where, mask) in enumerate(masks):
        under = {int(v) for v in np.unique(labels[where][mask])} - {0}
        piece_labels.append(under)
        for lab in under:
            covering.setdefault(lab, []).append(k)
    for lab, pieces in covering.items():
        if len(pieces) == 1 and piece_labels[pieces[0]] == {lab}:
            piece = base_pieces[pieces[0]]
            if not any(_boxes_meet(piece.bounds, box) for box in cut_boxes):
                exact[lab] = piece.smallest_part_incircle()
    # the raster's estimates: below the true radius by less than 2 h, above it by at most h
    low = np.maximum(peaks - 1.0, 0.5) * h
    high = (peaks + 1.0) * h
    best = min(
        [c.radius for c in exact.values()] + [float(high[lab - 1]) for lab in range(1, n + 1) if lab not in exact]
    )
    candidates: list[Incircle] = list(exact.values())
    boxes = ndimage.find_objects(labels)
    for lab in range(1, n + 1):
        if lab in exact or low[lab - 1] > best:
            continue
        peak = where_peak[lab - 1]
        candidates.append(
            _refined_island(boxes[lab - 1], peak, float(peaks[lab - 1]), xs, ys, h, base_pieces, cut_pieces)
            or Incircle(float(low[lab - 1]), (float(xs[peak[0]]), float(ys[peak[1]])))
        )
    return min(candidates, key=lambda c: c.radius)


def _refined_island(box, peak, depth_cells, xs, ys, h, base_pieces, cut_pieces) -> Incircle | None:
    """The island of the first raster in ``box`` (slices), its deepest cell at ``peak``, measured
    on a raster of its own box (padded by two of the first raster's cells),
    with :data:`_ISLAND_REFINE_CELLS` cells across its width (``depth_cells``: its depth on the
    first raster); None where the finer raster does not find it there."""
    x0, x1 = xs[box[0].start] - 2 * h, xs[box[0].stop - 1] + 2 * h
    y0, y1 = ys[box[1].start] - 2 * h, ys[box[1].stop - 1] + 2 * h
    # cells of a size set by the island's own width (its radius on the first raster, at most
    # depth + 1 cells), not by its box, which a long thin island makes wide
    width = 2 * (depth_cells + 1.0) * h
    hf = max(min(h, width / _ISLAND_REFINE_CELLS), max(x1 - x0, y1 - y0) / _ISLAND_REFINE_MAX_CELLS)
    fx = np.arange(x0, x1 + 0.5 * hf, hf)
    fy = np.arange(y0, y1 + 0.5 * hf, hf)
    region = (x0 - hf, y0 - hf, x1 + hf, y1 + hf)
    near_base = [p for p in base_pieces if _boxes_meet(p.bounds, region)]
    near_cuts = [(p, c) for p, c in cut_pieces if _boxes_meet(p.bounds, region)]
    inside, _ = _raster_inside(fx, fy, hf, near_base, near_cuts)
    # the box's border belongs to the first raster's outside cells or to other islands: cut it so
    # that the distance transform sees the box's edge as outside
    inside[0, :] = inside[-1, :] = inside[:, 0] = inside[:, -1] = False
    fine_labels, _ = ndimage.label(inside)
    i = int(np.clip(np.searchsorted(fx, xs[peak[0]]), 0, len(fx) - 1))
    j = int(np.clip(np.searchsorted(fy, ys[peak[1]]), 0, len(fy) - 1))
    own = fine_labels[i, j]
    if own == 0:
        return None
    depth = ndimage.distance_transform_edt(fine_labels == own)
    at = np.unravel_index(int(np.argmax(depth)), depth.shape)
    return Incircle(float(max(depth[at] - 1.0, 0.5) * hf), (float(fx[at[0]]), float(fy[at[1]])))


@dataclass(frozen=True)
class TwoCircles(Union):
    """Two circles whose centres are ``distance`` apart (Fig. 15), with the exact lens area.

    The centres lie on the x axis at -distance/2 and +distance/2; the circles may overlap.

    Parameters
    ----------
    radius1 : float, optional
        Radius of the left circle, > 0; 1 by default.
    radius2 : float, optional
        Radius of the right circle, > 0; 1 by default.
    distance : float, optional
        Distance between the centres, >= 0; 2 by default.

    Raises
    ------
    contact_scene.SceneError
        Naming the parameter (``indenter.radius1`` etc.) and its allowed range.
    """

    # built from the radii, not passed: TwoCircles(r1, r2, distance) must not bind r1 to ``parts``
    parts: tuple = field(default=(), init=False, repr=False)
    radius1: float = real(1.0, gt=0)
    radius2: float = real(1.0, gt=0)
    distance: float = real(2.0, ge=0)
    kind = "two_circles"

    def _complete(self):
        half = self.distance / 2
        object.__setattr__(self, "parts", (Circle(self.radius1, (-half, 0.0)), Circle(self.radius2, (half, 0.0))))

    @cached_property
    def area(self):
        # in units of the larger radius (a power of two, so scaling back is exact): the kite's
        # product of four lengths under- or overflows for radii beyond 1e+-77, the whole face's
        # area only beyond 1e+-154
        e = math.frexp(max(self.radius1, self.radius2))[1]
        r1, r2, d = (ldexp_saturating(x, -e) for x in (self.radius1, self.radius2, self.distance))
        if d >= r1 + r2:
            unit = math.pi * (r1**2 + r2**2)
        elif d <= abs(r1 - r2):
            unit = math.pi * max(r1, r2) ** 2
        else:
            # the lens both discs cover: two circular segments
            segment1 = r1**2 * math.acos((d**2 + r1**2 - r2**2) / (2 * d * r1))
            segment2 = r2**2 * math.acos((d**2 + r2**2 - r1**2) / (2 * d * r2))
            kite = 0.5 * math.sqrt((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2))
            unit = math.pi * (r1**2 + r2**2) - (segment1 + segment2 - kite)
        return ldexp_saturating(unit, 2 * e)

    @property
    def area_is_exact(self):
        return True

    def incircle(self):
        # a disc wider than the larger circle would have to fit in the union's waist, which is narrower
        big = self.parts[0] if self.radius1 >= self.radius2 else self.parts[1]
        return Incircle(big.radius, big.center)

    def smallest_part_incircle(self):
        if self.distance < self.radius1 + self.radius2:
            return self.incircle()  # one connected face
        small = self.parts[1] if self.radius1 >= self.radius2 else self.parts[0]
        return Incircle(small.radius, small.center)
