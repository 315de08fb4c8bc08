"""Faces bounded by straight edges: any simple polygon, and the regular ones the paper uses
(square, rectangle, equilateral triangle, regular n-gon) with their closed-form incircles."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy import optimize

from ..errors import SceneError, check_real
from ..validation import point, real, whole
from . import numerical
from .base import Incircle, Shape, ldexp_saturating

__all__ = [
    "PolygonalShape",
    "Polygon",
    "Rectangle",
    "Square",
    "Triangle",
    "RegularPolygon",
    "shoelace_area",
    "rotate_points",
]

#: edge pairs tested for crossings per vectorised batch (bounds the memory of the test)
_EDGE_PAIRS_PER_BATCH = 2_000_000


def shoelace_area(vertices: np.ndarray) -> float:
    """Signed area of the polygon (positive when the vertices run counter-clockwise)."""
    x, y = vertices[:, 0], vertices[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _unit_frame(vertices: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """The vertices in a frame of unit size: (unit, origin, e) with vertices = origin + 2^e unit.

    The origin is the centre of the bounding box and 2^e the power of two at or above its larger
    side, so the unit coordinates lie within [-1/2, 1/2] and scaling back by 2^e is exact.  The
    polygon's products (areas, first moments, the incircle's linear programme, the crossing
    tests) are formed there: in the given units they under- or overflow long before the
    coordinates do (a first moment is a length cubed), and the incircle's solver, whose
    tolerances are absolute, gave a face of nanometres a radius 4 per cent too large and one of
    1e-30 a radius of zero."""
    low, high = vertices.min(axis=0), vertices.max(axis=0)
    origin = low + 0.5 * (high - low)
    extent = float(np.max(high - low))
    e = math.frexp(extent)[1] if extent > 0 and math.isfinite(extent) else 0
    return np.ldexp(vertices - origin, -e), origin, e


def rotate_points(points: np.ndarray, angle_deg: float, center) -> np.ndarray:
    """Points given about the origin, rotated counter-clockwise and moved to ``center``."""
    t = math.radians(angle_deg)
    rotation = np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
    return points @ rotation.T + np.asarray(center, float)


def _segments_cross(p, q, r, s) -> np.ndarray:
    """Whether segments pq and rs cross properly (arrays of points, shape (..., 2))."""

    def orientation(a, b, c):
        return (b[..., 0] - a[..., 0]) * (c[..., 1] - a[..., 1]) - (b[..., 1] - a[..., 1]) * (c[..., 0] - a[..., 0])

    side_p, side_q = orientation(r, s, p), orientation(r, s, q)
    side_r, side_s = orientation(p, q, r), orientation(p, q, s)
    return ((side_p * side_q) < 0) & ((side_r * side_s) < 0)


class PolygonalShape(Shape):
    """A simple polygon given by ``vertices`` (counter-clockwise after validation)."""

    #: corners computed at strictly increasing angles around a centre: the polygon is simple
    #: without the check of every pair of edges (quadratic: 5e9 pairs for 100000 sides)
    simple_by_construction = False

    @property
    def vertices(self) -> tuple | np.ndarray:  # pragma: no cover - abstract
        """The corners as given (a field of Polygon and Triangle) or as computed from the parameters."""
        raise NotImplementedError

    @cached_property
    def _verts(self) -> np.ndarray:
        v = np.asarray(self.vertices, dtype=float)
        if v.ndim != 2 or v.shape[1] != 2 or len(v) < 3:
            raise SceneError("indenter.vertices", f"a polygon needs at least 3 (x, y) vertices (got {len(v)})")
        if not np.all(np.isfinite(v)):
            raise SceneError("indenter.vertices", "vertices must be finite numbers")
        repeated = np.flatnonzero(np.all(v == np.roll(v, -1, axis=0), axis=1))
        if repeated.size:
            # a zero-length edge has no normal: the incircle's linear programme and the
            # rasteriser's edge tests would fail on it deep inside
            i = int(repeated[0])
            raise SceneError(
                "indenter.vertices",
                f"vertices {i} and {(i + 1) % len(v)} coincide; give each corner once (a closed ring's "
                "last vertex repeats its first: leave it out)",
            )
        with np.errstate(over="ignore"):  # an extent past the largest float: refused just below
            extent_finite = np.isfinite(np.ptp(v, axis=0)).all()
        if not extent_finite:
            raise SceneError("indenter.vertices", "the polygon's extent overflows floating point: rescale lengths")
        unit, _, _ = _unit_frame(v)
        if not self.simple_by_construction:
            self._check_simple(unit)
        signed_area = shoelace_area(unit)
        extent = np.ptp(unit, axis=0).max()
        if not abs(signed_area) > 1e-12 * extent**2 or extent == 0:
            raise SceneError(
                "indenter.vertices", "the polygon is empty (zero area); give at least 3 non-collinear vertices"
            )
        return v[::-1].copy() if signed_area < 0 else v

    @cached_property
    def _unit(self) -> tuple[np.ndarray, np.ndarray, int]:
        """:func:`_unit_frame` of the validated (counter-clockwise) vertices."""
        return _unit_frame(self._verts)

    @staticmethod
    def _check_simple(v: np.ndarray) -> None:
        n = len(v)
        if n < 4:
            return
        starts, ends = v, np.roll(v, -1, axis=0)
        i, j = np.triu_indices(n, k=2)
        keep = ~((i == 0) & (j == n - 1))  # the first and last edge share a vertex
        i, j = i[keep], j[keep]
        for batch_start in range(0, len(i), _EDGE_PAIRS_PER_BATCH):
            batch = slice(batch_start, batch_start + _EDGE_PAIRS_PER_BATCH)
            crossing = _segments_cross(starts[i[batch]], ends[i[batch]], starts[j[batch]], ends[j[batch]])
            if crossing.any():
                k = np.flatnonzero(crossing)[0] + batch_start
                raise SceneError(
                    "indenter.vertices",
                    f"the polygon intersects itself (edges {i[k]} and {j[k]} cross); give a simple polygon",
                )

    @property
    def area(self):
        unit, _, e = self._unit
        return ldexp_saturating(shoelace_area(unit), 2 * e)

    @property
    def bounds(self):
        v = self._verts
        return (float(v[:, 0].min()), float(v[:, 1].min()), float(v[:, 0].max()), float(v[:, 1].max()))

    @property
    def centroid(self):
        unit, origin, e = self._unit
        x, y = unit[:, 0], unit[:, 1]
        x_next, y_next = np.roll(x, -1), np.roll(y, -1)
        cross = x * y_next - x_next * y
        twice_area = cross.sum()
        return (
            float(origin[0] + ldexp_saturating(float(((x + x_next) * cross).sum() / (3 * twice_area)), e)),
            float(origin[1] + ldexp_saturating(float(((y + y_next) * cross).sum() / (3 * twice_area)), e)),
        )

    @cached_property
    def is_convex(self) -> bool:
        """Whether the polygon is convex (no inward turn at any corner, to round-off)."""
        unit, _, _ = self._unit
        edges = np.roll(unit, -1, axis=0) - unit
        turn = edges[:, 0] * np.roll(edges[:, 1], -1) - edges[:, 1] * np.roll(edges[:, 0], -1)
        return bool(np.all(turn >= -1e-12 * np.ptp(unit, axis=0).max() ** 2))

    def contains(self, x, y):
        x = np.asarray(x, float)
        y = np.asarray(y, float)
        shape = np.broadcast(x, y).shape
        px = np.broadcast_to(x, shape).ravel()
        py = np.broadcast_to(y, shape).ravel()
        order = np.argsort(py, kind="stable")
        xs, ys = px[order], py[order]
        inside = np.zeros(len(xs), bool)
        tol = self.tolerance
        v = self._verts
        for (x0, y0), (x1, y1) in zip(v, np.roll(v, -1, axis=0), strict=True):
            i0 = np.searchsorted(ys, min(y0, y1) - tol, "left")
            i1 = np.searchsorted(ys, max(y0, y1) + tol, "right")
            if i1 <= i0:
                continue
            X, Y = xs[i0:i1], ys[i0:i1]
            # even-odd crossing with the half-open rule; the boundary test below closes the set
            cross = (y0 > Y) != (y1 > Y)
            if cross.any():
                x_cross = x0 + (Y[cross] - y0) * (x1 - x0) / (y1 - y0)
                idx = np.flatnonzero(cross)[X[cross] < x_cross]
                inside[i0 + idx] ^= True
            # closed set: points within tol of the edge are inside
            ex, ey = x1 - x0, y1 - y0
            t = np.clip(((X - x0) * ex + (Y - y0) * ey) / (ex * ex + ey * ey), 0, 1)
            on_edge = np.hypot(X - (x0 + t * ex), Y - (y0 + t * ey)) <= tol
            inside[i0:i1] |= on_edge
        out = np.empty(len(xs), bool)
        out[order] = inside
        return out.reshape(shape)

    def signed_distance(self, x, y):
        """Exact signed distance to the boundary (negative inside).

        Parameters
        ----------
        x, y : float or array_like
            Coordinates of the points (broadcast together).

        Returns
        -------
        numpy.ndarray
            The distance to the nearest edge, negative for points inside, of the broadcast shape.
        """
        x = np.asarray(x, float)
        y = np.asarray(y, float)
        v = self._verts
        d = np.full(np.broadcast(x, y).shape, np.inf)
        for (x0, y0), (x1, y1) in zip(v, np.roll(v, -1, axis=0), strict=True):
            ex, ey = x1 - x0, y1 - y0
            t = np.clip(((x - x0) * ex + (y - y0) * ey) / (ex * ex + ey * ey), 0, 1)
            d = np.minimum(d, np.hypot(x - (x0 + t * ex), y - (y0 + t * ey)))
        return np.where(self.contains(x, y), -d, d)

    def incircle(self):
        if self.is_convex:
            # Chebyshev centre: max r s.t. n_i . c + r <= n_i . v_i for every edge (an LP), in
            # the unit frame: HiGHS's tolerances are absolute
            unit, origin, e = self._unit
            edges = np.roll(unit, -1, axis=0) - unit
            normals = np.column_stack([edges[:, 1], -edges[:, 0]]) / np.hypot(edges[:, 0], edges[:, 1])[:, None]
            A = np.column_stack([normals, np.ones(len(normals))])
            b = np.einsum("ij,ij->i", normals, unit)
            res = optimize.linprog([0, 0, -1], A_ub=A, b_ub=b, bounds=[(None, None)] * 3, method="highs")
            if res.x is not None:  # the LP of a convex polygon is feasible; else the search below
                cx, cy, r = res.x
                centre = (origin[0] + ldexp_saturating(float(cx), e), origin[1] + ldexp_saturating(float(cy), e))
                return Incircle(ldexp_saturating(float(r), e), (float(centre[0]), float(centre[1])))
        # non-convex: best point of a sampling grid, polished on the exact distance
        X, Y, _ = numerical.fine_grid(self, 200)
        depth = -self.signed_distance(X, Y)
        i = np.unravel_index(np.argmax(depth), depth.shape)
        res = optimize.minimize(  # type: ignore[call-overload]  # scipy-stubs' options TypedDict lacks fatol
            lambda c: float(self.signed_distance(c[0], c[1])),
            [X[i], Y[i]],
            method="Nelder-Mead",
            options={"xatol": 1e-12 * self.size, "fatol": 1e-14 * self.size},
        )
        c = res.x if -res.fun >= depth[i] else (X[i], Y[i])
        r = max(-res.fun, depth[i])
        return Incircle(float(r), (float(c[0]), float(c[1])))

    def rotated(self, angle_deg, about=None):
        about = self.centroid if about is None else about
        t = math.radians(angle_deg)
        rotation = np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
        return Polygon(tuple(map(tuple, (self._verts - about) @ rotation.T + about)))

    def mirrored(self, about=None):
        about = self.centroid if about is None else about
        v = self._verts.copy()
        v[:, 0] = 2 * about[0] - v[:, 0]
        return Polygon(tuple(map(tuple, v[::-1])))

    def scaled(self, factor):
        check_real("scale", factor, lo=0, lo_open=True)
        return Polygon(tuple(map(tuple, self._verts * factor)))


@dataclass(frozen=True)
class Polygon(PolygonalShape):
    """A simple polygon: any face bounded by straight edges.

    Parameters
    ----------
    vertices : sequence of (float, float)
        At least 3 (x, y) corners in order, either orientation (stored counter-clockwise); the
        edges must not cross and the area must not be zero.

    Raises
    ------
    contact_scene.SceneError
        Naming ``indenter.vertices``: fewer than 3 vertices, non-numbers, a self-intersecting
        or empty polygon.
    """

    vertices: tuple = ()
    kind = "polygon"

    def _complete(self):
        try:
            verts = tuple((float(a), float(b)) for a, b in self.vertices)
        except (TypeError, ValueError):
            raise SceneError("indenter.vertices", "must be a list of [x, y] number pairs") from None
        object.__setattr__(self, "vertices", verts)
        self._verts  # noqa: B018  (the property validates the vertices now, at construction)


@dataclass(frozen=True)
class Rectangle(PolygonalShape):
    """A rectangular face.

    Parameters
    ----------
    width : float
        Side along x before rotation, > 0.
    height : float
        Side along y before rotation, > 0.
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

    width: float = real(gt=0)
    height: float = real(gt=0)
    rotation_deg: float = real(0.0)
    center: tuple[float, float] = point()
    simple_by_construction = True
    kind = "rectangle"

    @property
    def vertices(self):
        w, h = self.width / 2, self.height / 2
        return rotate_points(np.array([[-w, -h], [w, -h], [w, h], [-w, h]]), self.rotation_deg, self.center)

    @property
    def aspect_ratio(self) -> float:
        """The longer side over the shorter, >= 1."""
        return max(self.width, self.height) / min(self.width, self.height)

    @property
    def centroid(self):
        return self.center

    def incircle(self):
        return Incircle(min(self.width, self.height) / 2, self.center)

    def describe(self):
        return f"rectangle {self.width:g} x {self.height:g}"


@dataclass(frozen=True)
class Square(PolygonalShape):
    """A square face (the paper's square punch; stiffness factor beta = 1.021, Eq. 9).

    Parameters
    ----------
    side : float
        Side length, > 0.
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

    side: float = real(gt=0)
    rotation_deg: float = real(0.0)
    center: tuple[float, float] = point()
    simple_by_construction = True
    kind = "square"

    @property
    def vertices(self):
        s = self.side / 2
        return rotate_points(np.array([[-s, -s], [s, -s], [s, s], [-s, s]]), self.rotation_deg, self.center)

    @property
    def centroid(self):
        return self.center

    def incircle(self):
        return Incircle(self.side / 2, self.center)

    def describe(self):
        return f"square side={self.side:g}"


@dataclass(frozen=True)
class Triangle(PolygonalShape):
    """A triangle from three vertices; ``Triangle.equilateral(side)`` for the paper's punch.

    Parameters
    ----------
    vertices : sequence of (float, float)
        Exactly 3 (x, y) corners, not collinear.

    Raises
    ------
    contact_scene.SceneError
        Naming ``indenter.vertices``: not 3 vertices, non-numbers or a degenerate triangle.
    """

    vertices: tuple = ()
    kind = "triangle"

    def _complete(self):
        if not hasattr(self.vertices, "__len__") or isinstance(self.vertices, str):
            raise SceneError(
                "indenter.vertices", "must be a list of 3 [x, y] number pairs (Triangle.equilateral(side) for a side)"
            )
        if len(self.vertices) != 3:
            raise SceneError("indenter.vertices", f"a triangle needs exactly 3 vertices (got {len(self.vertices)})")
        object.__setattr__(self, "vertices", Polygon(self.vertices).vertices)
        self._verts  # noqa: B018  (the property validates the vertices now, at construction)

    @classmethod
    def equilateral(cls, side: float, rotation_deg: float = 0.0, center=(0.0, 0.0)) -> Triangle:
        """The equilateral triangle of side ``side``, one corner pointing up (before rotation).

        Parameters
        ----------
        side : float
            Side length, > 0.
        rotation_deg : float, optional
            Counter-clockwise rotation about the centre, in degrees; 0 by default.
        center : tuple of float, optional
            (x, y) of the centroid; the origin by default.

        Returns
        -------
        Triangle
            The triangle.

        Raises
        ------
        contact_scene.SceneError
            Naming ``indenter.side``, for a side that is not > 0.
        """
        side = check_real("indenter.side", side, lo=0, lo_open=True)
        circumradius = side / math.sqrt(3)
        t = np.radians(90 + np.array([0, 120, 240]))
        corners = np.column_stack([circumradius * np.cos(t), circumradius * np.sin(t)])
        return cls(tuple(map(tuple, rotate_points(corners, rotation_deg, center))))


@dataclass(frozen=True)
class RegularPolygon(PolygonalShape):
    """A regular polygon with ``n_sides`` corners on a circle.

    Parameters
    ----------
    n_sides : int
        Number of corners, 3 <= n <= 100000.
    circumradius : float
        Radius of the circle through the corners, > 0.
    rotation_deg : float, optional
        Counter-clockwise rotation about the centre, in degrees (0: a corner on the +x axis).
    center : tuple of float, optional
        (x, y) of the centre; the origin by default.

    Raises
    ------
    contact_scene.SceneError
        Naming the parameter as a scene file spells it (``indenter.<name>``) and its allowed
        range, for a value out of that range.
    """

    n_sides: int = whole(ge=3, le=100_000)
    circumradius: float = real(gt=0)
    rotation_deg: float = real(0.0)
    center: tuple[float, float] = point()
    simple_by_construction = True
    kind = "regular_polygon"

    @property
    def vertices(self):
        t = 2 * np.pi * np.arange(self.n_sides) / self.n_sides
        corners = self.circumradius * np.column_stack([np.cos(t), np.sin(t)])
        return rotate_points(corners, self.rotation_deg, self.center)

    @property
    def centroid(self):
        return self.center

    def incircle(self):
        return Incircle(self.circumradius * math.cos(math.pi / self.n_sides), self.center)
