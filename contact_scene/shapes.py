"""Face shapes of flat punches.

Every shape is a frozen dataclass that validates itself and knows its area, centroid,
bounding box, equivalent radius sqrt(A/pi), incircle (the largest inscribed circle,
used by the lower bound, theory Eqs. 18-19) and filling factor.  ``contains`` is the
closed set: points on the boundary are inside (to a relative tolerance of 1e-9 of the
shape's size), which makes the rasterisation rule of :mod:`contact_scene.raster`
well defined when a cell centre falls exactly on an edge.

Units are whatever the scene uses (SI recommended); nothing here assumes a scale.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import NamedTuple

import numpy as np
from scipy import ndimage, optimize

from .errors import SceneError, check_int, check_real

__all__ = [
    "Incircle", "Shape", "Circle", "Ellipse", "Polygon", "Rectangle", "Square", "Triangle",
    "RegularPolygon", "Star", "PowerLawStar", "Union", "Difference", "TwoCircles",
    "SquareWithFaults", "Brush", "ImageMask", "Transformed",
]

_REL_TOL = 1e-9


class Incircle(NamedTuple):
    radius: float
    center: tuple[float, float]


def _pair(field_name: str, value) -> tuple[float, float]:
    try:
        a, b = value
    except (TypeError, ValueError):
        raise SceneError(field_name, f"must be a pair of numbers (got {value!r})") from None
    return (check_real(field_name, a), check_real(field_name, b))


class Shape:
    """Base class: a closed, bounded planar region with positive area."""

    kind = "shape"
    #: whether ``area`` is exact (closed form) or a fine numerical quadrature
    area_is_exact = True

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
        return _REL_TOL * self.size

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
        return _fine_raster_centroid(self)

    def incircle(self) -> Incircle:
        """Largest inscribed circle; this default works on a fine raster (to 1e-3 of the size)."""
        return _raster_incircle(self)

    def ring_filling(self, radius: float, center=None, samples: int = 4096) -> float:
        """phi(r) of Eqs. 25-31: the fraction of the circle of the given radius that lies in the shape."""
        cx, cy = self.centroid if center is None else center
        t = (np.arange(samples) + 0.5) * (2 * math.pi / samples)
        return float(np.mean(self.contains(cx + radius * np.cos(t), cy + radius * np.sin(t))))

    # -- transformations -------------------------------------------------
    def rotated(self, angle_deg: float, about=None) -> "Shape":
        about = self.centroid if about is None else about
        return Transformed(self, rotation_deg=angle_deg, about=tuple(about))

    def mirrored(self, about=None) -> "Shape":
        """Reflection x -> -x about a vertical line through ``about`` (default: the centroid)."""
        about = self.centroid if about is None else about
        return Transformed(self, mirror=True, about=tuple(about))

    def scaled(self, factor: float) -> "Shape":
        return Transformed(self, scale=factor, about=(0.0, 0.0))

    def describe(self) -> str:
        return self.kind


# ---------------------------------------------------------------------------
# numerical fall-backs
# ---------------------------------------------------------------------------

def _fine_grid(shape: Shape, n: int):
    xmin, ymin, xmax, ymax = shape.bounds
    h = max(xmax - xmin, ymax - ymin) / n
    xs = np.arange(xmin - h, xmax + 1.5 * h, h)
    ys = np.arange(ymin - h, ymax + 1.5 * h, h)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    return X, Y, h


def _fine_raster_centroid(shape: Shape, n: int = 1024) -> tuple[float, float]:
    X, Y, _ = _fine_grid(shape, n)
    m = shape.contains(X, Y)
    return float(X[m].mean()), float(Y[m].mean())


def _raster_incircle(shape: Shape, n: int = 1024) -> Incircle:
    X, Y, h = _fine_grid(shape, n)
    m = shape.contains(X, Y)
    dist = ndimage.distance_transform_edt(m) * h
    i = np.unravel_index(np.argmax(dist), dist.shape)
    # the transform measures centre to the nearest outside centre; the boundary is half a cell nearer
    return Incircle(float(dist[i] - 0.5 * h), (float(X[i]), float(Y[i])))


def _raster_area(shape: Shape, n: int = 2048) -> float:
    X, Y, h = _fine_grid(shape, n)
    return float(np.count_nonzero(shape.contains(X, Y)) * h * h)


# ---------------------------------------------------------------------------
# circle and ellipse
# ---------------------------------------------------------------------------

@dataclass(frozen=True)
class Circle(Shape):
    radius: float
    center: tuple[float, float] = (0.0, 0.0)
    kind = "circle"

    def __post_init__(self):
        object.__setattr__(self, "radius", check_real("indenter.radius", self.radius, lo=0, lo_open=True))
        object.__setattr__(self, "center", _pair("indenter.center", self.center))

    def contains(self, x, y):
        x, y = np.asarray(x, float), np.asarray(y, float)
        return np.hypot(x - self.center[0], y - self.center[1]) <= self.radius * (1 + _REL_TOL)

    def signed_distance(self, x, y):
        return np.hypot(np.asarray(x) - self.center[0], np.asarray(y) - self.center[1]) - self.radius

    @property
    def area(self):
        return math.pi * self.radius**2

    @property
    def bounds(self):
        cx, cy = self.center
        r = self.radius
        return (cx - r, cy - r, cx + r, cy + r)

    @property
    def centroid(self):
        return self.center

    def incircle(self):
        return Incircle(self.radius, self.center)

    def describe(self):
        return f"circle r={self.radius:g}"


@dataclass(frozen=True)
class Ellipse(Shape):
    semi_major: float
    semi_minor: float
    rotation_deg: float = 0.0
    center: tuple[float, float] = (0.0, 0.0)
    kind = "ellipse"

    def __post_init__(self):
        a = check_real("indenter.semi_major", self.semi_major, lo=0, lo_open=True)
        b = check_real("indenter.semi_minor", self.semi_minor, lo=0, lo_open=True, hi=a)
        object.__setattr__(self, "semi_major", a)
        object.__setattr__(self, "semi_minor", b)
        object.__setattr__(self, "rotation_deg", check_real("indenter.rotation_deg", self.rotation_deg))
        object.__setattr__(self, "center", _pair("indenter.center", self.center))

    def contains(self, x, y):
        t = math.radians(self.rotation_deg)
        dx = np.asarray(x, float) - self.center[0]
        dy = np.asarray(y, float) - self.center[1]
        u = dx * math.cos(t) + dy * math.sin(t)
        v = -dx * math.sin(t) + dy * math.cos(t)
        return (u / self.semi_major) ** 2 + (v / self.semi_minor) ** 2 <= 1 + 2 * _REL_TOL

    @property
    def area(self):
        return math.pi * self.semi_major * self.semi_minor

    @property
    def eccentricity(self) -> float:
        return math.sqrt(1 - (self.semi_minor / self.semi_major) ** 2)

    @property
    def bounds(self):
        t = math.radians(self.rotation_deg)
        a, b = self.semi_major, self.semi_minor
        hx = math.hypot(a * math.cos(t), b * math.sin(t))
        hy = math.hypot(a * math.sin(t), b * math.cos(t))
        cx, cy = self.center
        return (cx - hx, cy - hy, cx + hx, cy + hy)

    @property
    def centroid(self):
        return self.center

    def incircle(self):
        # the curvature radius at the ends of the minor axis, a^2/b, is >= b: the circle of radius b fits
        return Incircle(self.semi_minor, self.center)


# ---------------------------------------------------------------------------
# polygons
# ---------------------------------------------------------------------------

def _segments_intersect(p, q, r, s) -> np.ndarray:
    """Proper or touching intersection of segments pq and rs (arrays of points, shape (..., 2))."""
    def orient(a, b, c):
        return (b[..., 0] - a[..., 0]) * (c[..., 1] - a[..., 1]) - (b[..., 1] - a[..., 1]) * (c[..., 0] - a[..., 0])
    d1, d2 = orient(r, s, p), orient(r, s, q)
    d3, d4 = orient(p, q, r), orient(p, q, s)
    return ((d1 * d2) < 0) & ((d3 * d4) < 0)


class PolygonalShape(Shape):
    """A simple polygon given by ``vertices`` (counter-clockwise after validation)."""

    @property
    def vertices(self) -> np.ndarray:  # pragma: no cover - abstract
        raise NotImplementedError

    @cached_property
    def _verts(self) -> np.ndarray:
        v = np.asarray(self.vertices, dtype=float)
        if v.ndim != 2 or v.shape[1] != 2 or len(v) < 3:
            raise SceneError("indenter.vertices", f"a polygon needs at least 3 (x, y) vertices (got {len(v)})")
        if not np.all(np.isfinite(v)):
            raise SceneError("indenter.vertices", "vertices must be finite numbers")
        self._check_simple(v)
        a = _shoelace(v)
        scale = np.ptp(v, axis=0).max()
        if abs(a) <= 1e-12 * scale**2 or scale == 0:
            raise SceneError("indenter.vertices", "the polygon is empty (zero area); give at least 3 non-collinear vertices")
        return v[::-1].copy() if a < 0 else v

    @staticmethod
    def _check_simple(v: np.ndarray) -> None:
        n = len(v)
        if n < 4:
            return
        p, q = v, np.roll(v, -1, axis=0)
        i, j = np.triu_indices(n, k=2)
        keep = ~((i == 0) & (j == n - 1))  # the first and last edge share a vertex
        i, j = i[keep], j[keep]
        for lo in range(0, len(i), 2_000_000):
            sl = slice(lo, lo + 2_000_000)
            hit = _segments_intersect(p[i[sl]], q[i[sl]], p[j[sl]], q[j[sl]])
            if hit.any():
                k = np.flatnonzero(hit)[0] + lo
                raise SceneError(
                    "indenter.vertices",
                    f"the polygon intersects itself (edges {i[k]} and {j[k]} cross); give a simple polygon",
                )

    @property
    def area(self):
        return float(_shoelace(self._verts))

    @property
    def bounds(self):
        v = self._verts
        return (float(v[:, 0].min()), float(v[:, 1].min()), float(v[:, 0].max()), float(v[:, 1].max()))

    @property
    def centroid(self):
        v = self._verts
        x, y = v[:, 0], v[:, 1]
        xn, yn = np.roll(x, -1), np.roll(y, -1)
        c = x * yn - xn * y
        a = c.sum() / 2
        return (float(((x + xn) * c).sum() / (6 * a)), float(((y + yn) * c).sum() / (6 * a)))

    @cached_property
    def is_convex(self) -> bool:
        v = self._verts
        e = np.roll(v, -1, axis=0) - v
        cross = e[:, 0] * np.roll(e[:, 1], -1) - e[:, 1] * np.roll(e[:, 0], -1)
        return bool(np.all(cross >= -1e-12 * self.size**2))

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
        for (x0, y0), (x1, y1) in zip(v, np.roll(v, -1, axis=0)):
            i0 = np.searchsorted(ys, min(y0, y1) - tol, "left")
            i1 = np.searchsorted(ys, max(y0, y1) + tol, "right")
            if i1 <= i0:
                continue
            X, Y = xs[i0:i1], ys[i0:i1]
            # even-odd crossing with the half-open rule; the boundary test below closes the set
            cross = (y0 > Y) != (y1 > Y)
            if cross.any():
                xi = x0 + (Y[cross] - y0) * (x1 - x0) / (y1 - y0)
                idx = np.flatnonzero(cross)[X[cross] < xi]
                inside[i0 + idx] ^= True
            # closed set: points within tol of the edge are inside
            ex, ey = x1 - x0, y1 - y0
            L2 = ex * ex + ey * ey
            t = np.clip(((X - x0) * ex + (Y - y0) * ey) / L2, 0, 1)
            on = np.hypot(X - (x0 + t * ex), Y - (y0 + t * ey)) <= tol
            inside[i0:i1] |= on
        out = np.empty(len(xs), bool)
        out[order] = inside
        return out.reshape(shape)

    def signed_distance(self, x, y):
        """Exact signed distance to the boundary (negative inside)."""
        x = np.asarray(x, float)
        y = np.asarray(y, float)
        v = self._verts
        d = np.full(np.broadcast(x, y).shape, np.inf)
        for (x0, y0), (x1, y1) in zip(v, np.roll(v, -1, axis=0)):
            ex, ey = x1 - x0, y1 - y0
            t = np.clip(((x - x0) * ex + (y - y0) * ey) / (ex * ex + ey * ey), 0, 1)
            d = np.minimum(d, np.hypot(x - (x0 + t * ex), y - (y0 + t * ey)))
        return np.where(self.contains(x, y), -d, d)

    def incircle(self):
        v = self._verts
        if self.is_convex:
            # Chebyshev centre: max r s.t. n_i . c + r <= n_i . v_i for every edge (an LP)
            e = np.roll(v, -1, axis=0) - v
            n = np.column_stack([e[:, 1], -e[:, 0]]) / np.hypot(e[:, 0], e[:, 1])[:, None]
            A = np.column_stack([n, np.ones(len(n))])
            b = np.einsum("ij,ij->i", n, v)
            res = optimize.linprog([0, 0, -1], A_ub=A, b_ub=b, bounds=[(None, None)] * 3, method="highs")
            cx, cy, r = res.x
            return Incircle(float(r), (float(cx), float(cy)))
        # non-convex: best point of a sampling grid, polished on the exact distance
        X, Y, _ = _fine_grid(self, 200)
        d = -self.signed_distance(X, Y)
        i = np.unravel_index(np.argmax(d), d.shape)
        res = optimize.minimize(
            lambda c: float(self.signed_distance(c[0], c[1])), [X[i], Y[i]],
            method="Nelder-Mead", options={"xatol": 1e-12 * self.size, "fatol": 1e-14 * self.size},
        )
        c = res.x if -res.fun >= d[i] else (X[i], Y[i])
        r = max(-res.fun, d[i])
        return Incircle(float(r), (float(c[0]), float(c[1])))

    def rotated(self, angle_deg, about=None):
        about = self.centroid if about is None else about
        t = math.radians(angle_deg)
        R = np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
        return Polygon(tuple(map(tuple, (self._verts - about) @ R.T + about)))

    def mirrored(self, about=None):
        about = self.centroid if about is None else about
        v = self._verts.copy()
        v[:, 0] = 2 * about[0] - v[:, 0]
        return Polygon(tuple(map(tuple, v[::-1])))

    def scaled(self, factor):
        check_real("scale", factor, lo=0, lo_open=True)
        return Polygon(tuple(map(tuple, self._verts * factor)))


def _shoelace(v: np.ndarray) -> float:
    x, y = v[:, 0], v[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def _rotate_points(pts: np.ndarray, angle_deg: float, center) -> np.ndarray:
    t = math.radians(angle_deg)
    R = np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
    return pts @ R.T + np.asarray(center, float)


@dataclass(frozen=True)
class Polygon(PolygonalShape):
    vertices: tuple = ()
    kind = "polygon"

    def __post_init__(self):
        try:
            verts = tuple((float(a), float(b)) for a, b in self.vertices)
        except (TypeError, ValueError):
            raise SceneError("indenter.vertices", "must be a list of [x, y] number pairs") from None
        object.__setattr__(self, "vertices", verts)
        self._verts  # validate now


@dataclass(frozen=True)
class Rectangle(PolygonalShape):
    width: float
    height: float
    rotation_deg: float = 0.0
    center: tuple[float, float] = (0.0, 0.0)
    kind = "rectangle"

    def __post_init__(self):
        object.__setattr__(self, "width", check_real("indenter.width", self.width, lo=0, lo_open=True))
        object.__setattr__(self, "height", check_real("indenter.height", self.height, lo=0, lo_open=True))
        object.__setattr__(self, "rotation_deg", check_real("indenter.rotation_deg", self.rotation_deg))
        object.__setattr__(self, "center", _pair("indenter.center", self.center))

    @property
    def vertices(self):
        w, h = self.width / 2, self.height / 2
        return _rotate_points(np.array([[-w, -h], [w, -h], [w, h], [-w, h]]), self.rotation_deg, self.center)

    @property
    def aspect_ratio(self) -> float:
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
    side: float
    rotation_deg: float = 0.0
    center: tuple[float, float] = (0.0, 0.0)
    kind = "square"

    def __post_init__(self):
        object.__setattr__(self, "side", check_real("indenter.side", self.side, lo=0, lo_open=True))
        object.__setattr__(self, "rotation_deg", check_real("indenter.rotation_deg", self.rotation_deg))
        object.__setattr__(self, "center", _pair("indenter.center", self.center))

    @property
    def vertices(self):
        s = self.side / 2
        return _rotate_points(np.array([[-s, -s], [s, -s], [s, s], [-s, s]]), self.rotation_deg, self.center)

    @property
    def centroid(self):
        return self.center

    def incircle(self):
        return Incircle(self.side / 2, self.center)

    def describe(self):
        return f"square side={self.side:g}"


@dataclass(frozen=True)
class Triangle(PolygonalShape):
    """A triangle from three vertices; ``Triangle.equilateral(side)`` for the paper's punch."""

    vertices: tuple = ()
    kind = "triangle"

    def __post_init__(self):
        if len(self.vertices) != 3:
            raise SceneError("indenter.vertices", f"a triangle needs exactly 3 vertices (got {len(self.vertices)})")
        object.__setattr__(self, "vertices", Polygon(self.vertices).vertices)
        self._verts

    @classmethod
    def equilateral(cls, side: float, rotation_deg: float = 0.0, center=(0.0, 0.0)) -> "Triangle":
        side = check_real("indenter.side", side, lo=0, lo_open=True)
        R = side / math.sqrt(3)
        t = np.radians(90 + np.array([0, 120, 240]))
        pts = np.column_stack([R * np.cos(t), R * np.sin(t)])
        return cls(tuple(map(tuple, _rotate_points(pts, rotation_deg, center))))


@dataclass(frozen=True)
class RegularPolygon(PolygonalShape):
    n_sides: int
    circumradius: float
    rotation_deg: float = 0.0
    center: tuple[float, float] = (0.0, 0.0)
    kind = "regular_polygon"

    def __post_init__(self):
        object.__setattr__(self, "n_sides", check_int("indenter.n_sides", self.n_sides, lo=3, hi=100_000))
        object.__setattr__(self, "circumradius", check_real("indenter.circumradius", self.circumradius, lo=0, lo_open=True))
        object.__setattr__(self, "rotation_deg", check_real("indenter.rotation_deg", self.rotation_deg))
        object.__setattr__(self, "center", _pair("indenter.center", self.center))

    @property
    def vertices(self):
        t = 2 * np.pi * np.arange(self.n_sides) / self.n_sides
        pts = self.circumradius * np.column_stack([np.cos(t), np.sin(t)])
        return _rotate_points(pts, self.rotation_deg, self.center)

    @property
    def centroid(self):
        return self.center

    def incircle(self):
        return Incircle(self.circumradius * math.cos(math.pi / self.n_sides), self.center)


@dataclass(frozen=True)
class Star(PolygonalShape):
    """n rays: vertices alternate between the outer radius (tips) and the inner radius."""

    n_rays: int
    outer_radius: float
    inner_radius: float
    rotation_deg: float = 0.0
    center: tuple[float, float] = (0.0, 0.0)
    kind = "star"

    def __post_init__(self):
        object.__setattr__(self, "n_rays", check_int("indenter.n_rays", self.n_rays, lo=2, hi=10_000))
        R = check_real("indenter.outer_radius", self.outer_radius, lo=0, lo_open=True)
        object.__setattr__(self, "outer_radius", R)
        object.__setattr__(self, "inner_radius", check_real("indenter.inner_radius", self.inner_radius, lo=0, lo_open=True, hi=R))
        object.__setattr__(self, "rotation_deg", check_real("indenter.rotation_deg", self.rotation_deg))
        object.__setattr__(self, "center", _pair("indenter.center", self.center))

    @property
    def vertices(self):
        n = self.n_rays
        t = np.pi / 2 + np.pi * np.arange(2 * n) / n
        r = np.where(np.arange(2 * n) % 2 == 0, self.outer_radius, self.inner_radius)
        return _rotate_points(np.column_stack([r * np.cos(t), r * np.sin(t)]), self.rotation_deg, self.center)

    @property
    def centroid(self):
        return self.center


@dataclass(frozen=True)
class PowerLawStar(PolygonalShape):
    """A star whose rays are cut so that the ring filling factor is phi(r) = (r0/r)^3 for
    r0 <= r <= R (Eq. 29 of the sheet: constant adhesion force over that range).

    For r < r0 the face is the full disc of radius ``core_radius``.  The curved ray flanks
    are polygons with ``samples`` vertices each; area and phi are those of the polygon.
    """

    n_rays: int
    core_radius: float
    outer_radius: float
    samples: int = 64
    rotation_deg: float = 0.0
    center: tuple[float, float] = (0.0, 0.0)
    kind = "power_law_star"

    def __post_init__(self):
        object.__setattr__(self, "n_rays", check_int("indenter.n_rays", self.n_rays, lo=2, hi=1000))
        r0 = check_real("indenter.core_radius", self.core_radius, lo=0, lo_open=True)
        object.__setattr__(self, "core_radius", r0)
        object.__setattr__(self, "outer_radius", check_real("indenter.outer_radius", self.outer_radius, lo=r0, lo_open=True))
        object.__setattr__(self, "samples", check_int("indenter.samples", self.samples, lo=4, hi=10_000))
        object.__setattr__(self, "rotation_deg", check_real("indenter.rotation_deg", self.rotation_deg))
        object.__setattr__(self, "center", _pair("indenter.center", self.center))

    def design_filling(self, r):
        """The phi(r) the rays are designed for."""
        r = np.asarray(r, float)
        return np.where(r <= self.core_radius, 1.0, (self.core_radius / np.maximum(r, 1e-300)) ** 3)

    @property
    def vertices(self):
        n, r0, R = self.n_rays, self.core_radius, self.outer_radius
        r = np.geomspace(r0, R, self.samples)
        half = np.pi / n * (r0 / r) ** 3
        pts = []
        for k in range(n):
            c = np.pi / 2 + 2 * np.pi * k / n
            left = c - half  # ascending along the right-hand flank, then back down the left
            right = c + half
            pts.append(np.column_stack([r * np.cos(left), r * np.sin(left)]))
            pts.append(np.column_stack([r[::-1] * np.cos(right[::-1]), r[::-1] * np.sin(right[::-1])]))
        v = np.vstack(pts)
        # consecutive rays meet at r0: drop the duplicated junction vertices
        keep = np.ones(len(v), bool)
        d = np.hypot(*(v - np.roll(v, 1, axis=0)).T)
        keep[d < 1e-12 * R] = False
        return _rotate_points(v[keep], self.rotation_deg, self.center)

    @property
    def centroid(self):
        return self.center


# ---------------------------------------------------------------------------
# composite shapes
# ---------------------------------------------------------------------------

def _bbox_disjoint(a: Shape, b: Shape) -> bool:
    ax0, ay0, ax1, ay1 = a.bounds
    bx0, by0, bx1, by1 = b.bounds
    return ax1 < bx0 or bx1 < ax0 or ay1 < by0 or by1 < ay0


def _pairwise_disjoint(shapes) -> bool:
    return all(_bbox_disjoint(shapes[i], shapes[j]) for i in range(len(shapes)) for j in range(i + 1, len(shapes)))


@dataclass(frozen=True)
class Union(Shape):
    """Union of shapes.  The area is exact when the parts' bounding boxes are disjoint,
    otherwise a quadrature on a 2048-cell raster (``area_is_exact`` says which)."""

    parts: tuple = ()
    kind = "union"

    def __post_init__(self):
        parts = tuple(self.parts)
        if not parts or not all(isinstance(p, Shape) for p in parts):
            raise SceneError("indenter.parts", "a union needs at least one shape")
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
        return _raster_incircle(self)

    @cached_property
    def area(self):
        if self._disjoint:
            return float(sum(p.area for p in self.parts))
        return _raster_area(self)

    @property
    def bounds(self):
        b = np.array([p.bounds for p in self.parts])
        return (float(b[:, 0].min()), float(b[:, 1].min()), float(b[:, 2].max()), float(b[:, 3].max()))

    @cached_property
    def centroid(self):
        if self._disjoint:
            a = np.array([p.area for p in self.parts])
            c = np.array([p.centroid for p in self.parts])
            return tuple(map(float, (a[:, None] * c).sum(0) / a.sum()))
        return _fine_raster_centroid(self)


@dataclass(frozen=True)
class Difference(Shape):
    """``base`` with ``cuts`` removed.  The area is exact when every cut is a convex polygon or
    circle inside a convex base and the cuts' bounding boxes are disjoint."""

    base: Shape = None
    cuts: tuple = ()
    kind = "difference"

    def __post_init__(self):
        if not isinstance(self.base, Shape):
            raise SceneError("indenter.base", "a difference needs a base shape")
        object.__setattr__(self, "cuts", tuple(self.cuts))
        if self.area <= 0:
            raise SceneError("indenter.cuts", "the cuts remove the whole face; the shape is empty")

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
        return _raster_area(self)

    @property
    def nominal_area(self):
        return self.base.area

    @property
    def bounds(self):
        return self.base.bounds

    @cached_property
    def centroid(self):
        if self._exact:
            a = np.array([self.base.area] + [-c.area for c in self.cuts])
            c = np.array([self.base.centroid] + [c.centroid for c in self.cuts])
            return tuple(map(float, (a[:, None] * c).sum(0) / a.sum()))
        return _fine_raster_centroid(self)


def _interior(shape: Shape, x, y):
    """Open interior: a cut removes its interior, so the cut's boundary stays part of the face."""
    if hasattr(shape, "signed_distance"):
        return shape.signed_distance(x, y) < -shape.tolerance
    return shape.contains(x, y)


@dataclass(frozen=True)
class TwoCircles(Union):
    """Two circles of radii r1, r2 whose centres are ``distance`` apart (Fig. 15); exact lens area."""

    # built from the radii, not passed: TwoCircles(r1, r2, distance) must not bind r1 to ``parts``
    parts: tuple = field(default=(), init=False, repr=False)
    radius1: float = 1.0
    radius2: float = 1.0
    distance: float = 2.0
    kind = "two_circles"

    def __post_init__(self):
        r1 = check_real("indenter.radius1", self.radius1, lo=0, lo_open=True)
        r2 = check_real("indenter.radius2", self.radius2, lo=0, lo_open=True)
        d = check_real("indenter.distance", self.distance, lo=0)
        object.__setattr__(self, "parts", (Circle(r1, (-d / 2, 0.0)), Circle(r2, (d / 2, 0.0))))

    @cached_property
    def area(self):
        r1, r2, d = self.radius1, self.radius2, self.distance
        if d >= r1 + r2:
            return math.pi * (r1**2 + r2**2)
        if d <= abs(r1 - r2):
            return math.pi * max(r1, r2) ** 2
        a1 = r1**2 * math.acos((d**2 + r1**2 - r2**2) / (2 * d * r1))
        a2 = r2**2 * math.acos((d**2 + r2**2 - r1**2) / (2 * d * r2))
        a3 = 0.5 * math.sqrt((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2))
        return math.pi * (r1**2 + r2**2) - (a1 + a2 - a3)

    @property
    def area_is_exact(self):
        return True

    def incircle(self):
        # a disc wider than the larger circle would have to fit in the union's waist, which is narrower
        big = self.parts[0] if self.radius1 >= self.radius2 else self.parts[1]
        return Incircle(big.radius, big.center)


@dataclass(frozen=True)
class SquareWithFaults(Difference):
    """A square face with the faults of Fig. 7: an optional V-shaped notch cut into the middle
    of the top edge, and ``line_cuts`` straight cuts of width ``cut_width`` running from the
    left edge inward by ``line_cut_length`` at evenly spaced heights."""

    base: Shape = field(default=None, init=False, repr=False)
    cuts: tuple = field(default=(), init=False, repr=False)
    side: float = 1.0
    v_cut_depth: float = 0.0
    v_cut_width: float = 0.0
    line_cuts: int = 0
    line_cut_length: float = 0.0
    cut_width: float = 0.0
    kind = "square_with_faults"

    def __post_init__(self):
        L = check_real("indenter.side", self.side, lo=0, lo_open=True)
        dv = check_real("indenter.v_cut_depth", self.v_cut_depth, lo=0, hi=L, hi_open=True)
        wv = check_real("indenter.v_cut_width", self.v_cut_width, lo=0, hi=L)
        n = check_int("indenter.line_cuts", self.line_cuts, lo=0, hi=1000)
        ll = check_real("indenter.line_cut_length", self.line_cut_length, lo=0, hi=L, hi_open=True)
        w = check_real("indenter.cut_width", self.cut_width, lo=0, hi=L / max(2 * n + 1, 1))
        if (dv > 0) != (wv > 0):
            raise SceneError("indenter.v_cut_width", "a V cut needs both v_cut_depth > 0 and v_cut_width > 0")
        if n and (ll <= 0 or w <= 0):
            raise SceneError("indenter.cut_width", "line cuts need line_cut_length > 0 and cut_width > 0")
        cuts = []
        h = L / 2
        if dv > 0:
            cuts.append(Polygon(((-wv / 2, h), (0.0, h - dv), (wv / 2, h))))
        for i in range(n):
            yc = -h + L * (i + 1) / (n + 1)
            cuts.append(Polygon(((-h, yc - w / 2), (-h + ll, yc - w / 2), (-h + ll, yc + w / 2), (-h, yc + w / 2))))
        object.__setattr__(self, "base", Square(L))
        object.__setattr__(self, "cuts", tuple(cuts))


@dataclass(frozen=True)
class Brush(Union):
    """Circular pillars of radius ``pillar_radius`` inside a square of side ``side`` (Fig. 8).

    ``layout = "regular"`` puts them on a square lattice of pitch ``pitch``; ``"random"``
    places ``count`` non-overlapping pillars uniformly at random (reproducible by ``seed``);
    ``"mixed"`` places ``count`` columns at random too, alternately circular and square, each
    sized uniformly between half and all of ``pillar_radius`` (a square column of "radius" r
    has side r sqrt(pi), the area of the disc), as in the paper's mixed brushes (Fig. 8a).
    The nominal area is the square's, so area / nominal_area is the phi of Eq. 24.
    """

    parts: tuple = field(default=(), init=False, repr=False)
    side: float = 1.0
    pillar_radius: float = 0.05
    layout: str = "regular"
    pitch: float = 0.2
    count: int = 0
    seed: int = 0
    kind = "brush"

    def __post_init__(self):
        L = check_real("indenter.side", self.side, lo=0, lo_open=True)
        rp = check_real("indenter.pillar_radius", self.pillar_radius, lo=0, lo_open=True, hi=L / 2)
        if self.layout == "regular":
            p = check_real("indenter.pitch", self.pitch, lo=2 * rp, lo_open=True)
            m = int(math.floor((L - 2 * rp) / p + 1e-9)) + 1
            off = -(m - 1) * p / 2
            centres = [(off + i * p, off + j * p) for i in range(m) for j in range(m)]
            parts = tuple(Circle(rp, c) for c in centres)
        elif self.layout in ("random", "mixed"):
            cnt = check_int("indenter.count", self.count, lo=1, hi=100_000)
            rng = np.random.default_rng(check_int("indenter.seed", self.seed, lo=0))
            mixed = self.layout == "mixed"
            placed = []                                     # (x, y, half-width of the bounding box)
            for _ in range(200 * cnt):
                if len(placed) == cnt:
                    break
                r = rng.uniform(0.5 * rp, rp) if mixed else rp
                c = rng.uniform(-L / 2 + rp, L / 2 - rp, 2)
                # a small gap keeps the pillars' bounding boxes apart, so the area stays exact
                if all(max(abs(c[0] - q[0]), abs(c[1] - q[1])) > (r + q[2]) * 1.000001 for q in placed):
                    placed.append((float(c[0]), float(c[1]), r))
            if len(placed) < cnt:
                raise SceneError("indenter.count", f"could place only {len(placed)} of {cnt} non-overlapping pillars; lower count or pillar_radius")
            parts = tuple(Square(r * math.sqrt(math.pi), center=(x, y)) if mixed and i % 2 else Circle(r, (x, y))
                          for i, (x, y, r) in enumerate(placed))
        else:
            raise SceneError("indenter.layout", f"must be 'regular', 'random' or 'mixed' (got {self.layout!r})")
        object.__setattr__(self, "parts", parts)

    @property
    def nominal_area(self):
        return self.side**2

    @property
    def bounds(self):
        h = self.side / 2
        return (-h, -h, h, h)



@dataclass(frozen=True)
class ImageMask(Shape):
    """A face read from an image: pixels darker than ``threshold`` (0..1) belong to the face
    (``invert`` flips that).  Pixel (row 0, col 0) is the top-left corner; the image is
    centred on the origin, x to the right, y up."""

    path: str = ""
    pixel_size: float = 1.0
    threshold: float = 0.5
    invert: bool = False
    kind = "image"

    def __post_init__(self):
        object.__setattr__(self, "pixel_size", check_real("indenter.pixel_size", self.pixel_size, lo=0, lo_open=True))
        object.__setattr__(self, "threshold", check_real("indenter.threshold", self.threshold, lo=0, hi=1))
        if not np.any(self._mask):
            raise SceneError("indenter.path", f"the image {self.path!r} has no face pixels (none darker than threshold={self.threshold:g})")

    @cached_property
    def _mask(self) -> np.ndarray:
        import matplotlib.image as mpimg

        try:
            img = np.asarray(mpimg.imread(self.path), float)
        except (OSError, ValueError, SyntaxError) as exc:
            raise SceneError("indenter.path", f"cannot read image {self.path!r}: {exc}") from None
        if img.ndim == 3:
            rgb = img[..., :3]
            if img.dtype.kind in "ui" or rgb.max() > 1:
                rgb = rgb / 255.0
            img = rgb @ np.array([0.299, 0.587, 0.114])
        elif img.max() > 1:
            img = img / 255.0
        m = img < self.threshold
        if self.invert:
            m = ~m
        # rows run down the image; store as [ix, iy] with y up
        return np.ascontiguousarray(m[::-1, :].T)

    def contains(self, x, y):
        m = self._mask
        nx, ny = m.shape
        h = self.pixel_size
        ix = np.floor(np.asarray(x, float) / h + nx / 2).astype(np.int64)
        iy = np.floor(np.asarray(y, float) / h + ny / 2).astype(np.int64)
        ok = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
        out = np.zeros(np.broadcast(ix, iy).shape, bool)
        out[ok] = m[ix[ok], iy[ok]]
        return out

    @property
    def area(self):
        return float(np.count_nonzero(self._mask)) * self.pixel_size**2

    @property
    def bounds(self):
        nx, ny = self._mask.shape
        h = self.pixel_size
        return (-nx * h / 2, -ny * h / 2, nx * h / 2, ny * h / 2)

    @property
    def centroid(self):
        ix, iy = np.nonzero(self._mask)
        nx, ny = self._mask.shape
        h = self.pixel_size
        return (float((ix.mean() + 0.5 - nx / 2) * h), float((iy.mean() + 0.5 - ny / 2) * h))

    def incircle(self):
        m = np.pad(self._mask, 1)
        d = ndimage.distance_transform_edt(m)
        i = np.unravel_index(np.argmax(d), d.shape)
        nx, ny = self._mask.shape
        h = self.pixel_size
        c = ((i[0] - 1 + 0.5 - nx / 2) * h, (i[1] - 1 + 0.5 - ny / 2) * h)
        return Incircle(float((d[i] - 0.5) * h), (float(c[0]), float(c[1])))


@dataclass(frozen=True)
class Transformed(Shape):
    """A shape rotated (counter-clockwise, degrees), mirrored (x -> -x, before rotating) and
    scaled about the point ``about``."""

    shape: Shape = None
    rotation_deg: float = 0.0
    mirror: bool = False
    scale: float = 1.0
    about: tuple[float, float] = (0.0, 0.0)
    kind = "transformed"

    def __post_init__(self):
        object.__setattr__(self, "scale", check_real("scale", self.scale, lo=0, lo_open=True))

    @cached_property
    def _matrix(self) -> np.ndarray:
        t = math.radians(self.rotation_deg)
        M = self.scale * np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
        if self.mirror:
            M = M @ np.diag([-1.0, 1.0])
        return M

    def _forward(self, x, y):
        M = self._matrix
        ax, ay = self.about
        return ax + M[0, 0] * (x - ax) + M[0, 1] * (y - ay), ay + M[1, 0] * (x - ax) + M[1, 1] * (y - ay)

    def contains(self, x, y):
        Mi = np.linalg.inv(self._matrix)
        ax, ay = self.about
        dx, dy = np.asarray(x, float) - ax, np.asarray(y, float) - ay
        return self.shape.contains(ax + Mi[0, 0] * dx + Mi[0, 1] * dy, ay + Mi[1, 0] * dx + Mi[1, 1] * dy)

    @property
    def area(self):
        return self.shape.area * self.scale**2

    @property
    def nominal_area(self):
        return self.shape.nominal_area * self.scale**2

    @property
    def area_is_exact(self):
        return self.shape.area_is_exact

    @property
    def bounds(self):
        # the transformed bounding box of the original: conservative, which is all rasterising needs
        x0, y0, x1, y1 = self.shape.bounds
        X, Y = self._forward(np.array([x0, x1, x1, x0]), np.array([y0, y0, y1, y1]))
        return (float(X.min()), float(Y.min()), float(X.max()), float(Y.max()))

    @property
    def centroid(self):
        cx, cy = self._forward(*self.shape.centroid)
        return (float(cx), float(cy))

    def incircle(self):
        r, c = self.shape.incircle()
        cx, cy = self._forward(*c)
        return Incircle(r * self.scale, (float(cx), float(cy)))
