"""Face shapes: exact geometry, rasterisation rule, invariances."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import contact_scene as cs
from contact_scene.shapes.numerical import raster_area, raster_incircle

SHAPES = {
    "circle": cs.Circle(1.0),
    "ellipse": cs.Ellipse(2.0, 1.0, rotation_deg=20),
    "square": cs.Square(2.0),
    "rectangle": cs.Rectangle(3.0, 1.0, rotation_deg=30),
    "triangle": cs.Triangle.equilateral(1.0),
    "hexagon": cs.RegularPolygon(6, 1.0),
    "star": cs.Star(5, 1.0, 0.45),
    "two_circles": cs.TwoCircles(radius1=1.0, radius2=0.7, distance=1.5),
    "faults": cs.SquareWithFaults(
        side=1.0, v_cut_depth=0.3, v_cut_width=0.2, line_cuts=2, line_cut_length=0.4, cut_width=0.02
    ),
    "brush": cs.Brush(side=1.0, pillar_radius=0.06, pitch=0.2),
}


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_raster_area_error_is_bounded_by_the_staircase(name):
    # each cell the boundary crosses can be wrong by at most h^2, and there are ~ sqrt(2) P / h of
    # them: |A_raster - A| <= sqrt(2) P h.  P is measured on the finest raster (boundary cells x h).
    from scipy import ndimage

    s = SHAPES[name]
    fine = cs.rasterise(s, s.equivalent_radius / 256, min_incircle_cells=1)
    P = np.count_nonzero(fine.mask & ~ndimage.binary_erosion(fine.mask)) * fine.spacing
    errs = []
    for n in (16, 32, 64, 128):
        h = s.equivalent_radius / n
        err = abs(cs.rasterise(s, h, min_incircle_cells=1).area - s.area)
        assert err <= math.sqrt(2) * P * h
        errs.append(err / s.area)
    assert errs[-1] < 0.02


def test_analytic_areas_and_incircles():
    assert SHAPES["triangle"].area == pytest.approx(math.sqrt(3) / 4)
    assert SHAPES["triangle"].incircle().radius == pytest.approx(1 / (2 * math.sqrt(3)))
    assert SHAPES["hexagon"].area == pytest.approx(3 * math.sqrt(3) / 2)
    # star: n rays of two triangles (centre, tip, inner vertex)
    n, R, r = 5, 1.0, 0.45
    assert SHAPES["star"].area == pytest.approx(n * R * r * math.sin(math.pi / n))
    f = SHAPES["faults"]
    assert f.area_is_exact and f.area == pytest.approx(1.0 - 0.5 * 0.2 * 0.3 - 2 * 0.4 * 0.02)
    tc = SHAPES["two_circles"]  # lens area against a fine raster
    assert cs.Union(tc.parts).area == pytest.approx(tc.area, rel=2e-3)


@pytest.mark.parametrize("name", ["square", "rectangle", "hexagon"])
def test_closed_form_incircles_match_the_polygon_linear_programme(name):
    """The regular polygons' closed-form incircles against the general polygon's Chebyshev
    centre (a linear programme over the edges), on the same vertices."""
    s = SHAPES[name]
    r, c = s.incircle()
    r_lp, c_lp = cs.Polygon(tuple(map(tuple, s.vertices))).incircle()
    assert r == pytest.approx(r_lp, rel=1e-9)
    if name != "rectangle":  # a rectangle's incircle slides along its length
        assert c == pytest.approx(c_lp, abs=1e-9 * s.size)


def test_regular_brush_counts_its_pillars_and_its_filling_factor():
    """side 1, pitch 0.2, radius 0.06: the centres -0.4 ... 0.4 fit 5 x 5 pillars (a sixth
    column would need 5 x 0.2 + 2 x 0.06 = 1.12 > 1), centred on the square, so phi = 25 pi 0.06^2
    (Eq. 24)."""
    b = SHAPES["brush"]
    assert len(b.parts) == 25
    assert b.filling_factor == pytest.approx(25 * math.pi * 0.06**2, rel=1e-12)
    xs = sorted({p.center[0] for p in b.parts})
    assert xs == pytest.approx([-0.4, -0.2, 0.0, 0.2, 0.4], abs=1e-12)


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_incircle_is_inscribed_and_maximal(name):
    s = SHAPES[name]
    r, c = s.incircle()
    t = np.linspace(0, 2 * np.pi, 721)
    for rho in (0.999 * r, 0.5 * r):
        assert s.contains(c[0] + rho * np.cos(t), c[1] + rho * np.sin(t)).all()
    # independent check on a fine raster (accurate to about 1e-3 of the size)
    ref_radius, _ = raster_incircle(s, 1024)
    assert r == pytest.approx(ref_radius, abs=2e-3 * s.size)


def test_closed_set_includes_boundary():
    sq = cs.Square(2.0)
    assert sq.contains(1.0, 0.3) and sq.contains(1.0, 1.0) and not sq.contains(1.0 + 1e-6, 0.0)
    assert cs.Circle(1.0).contains(1.0, 0.0)


@pytest.mark.parametrize("name", ["square", "triangle", "star", "faults", "rectangle"])
def test_raster_rotation_by_90_and_mirror_are_exact(name):
    # nodes are anchored at the centroid, so the grid maps onto itself: the cells must too
    s = SHAPES[name]
    h = s.equivalent_radius / 20
    m = cs.rasterise(s, h).mask
    m90 = cs.rasterise(s.rotated(90), h).mask
    mm = cs.rasterise(s.mirrored(), h).mask
    assert np.array_equal(m90, np.rot90(m)) or np.array_equal(m90, np.rot90(m, -1))
    assert np.array_equal(mm, m[::-1, :])


@pytest.mark.parametrize("angle", [7.0, 33.0, 45.0])
def test_rotation_preserves_geometry(angle):
    s = SHAPES["star"]
    rs = s.rotated(angle)
    assert rs.area == pytest.approx(s.area)
    assert rs.incircle().radius == pytest.approx(s.incircle().radius, rel=1e-6)
    # within the staircase of docs/methods.md, sqrt(2) P h, with the star's perimeter P from its
    # ten edges (measured: a few cells, h^2 each)
    P = float(np.linalg.norm(np.roll(s.vertices, -1, axis=0) - s.vertices, axis=1).sum())
    h = s.equivalent_radius / 64
    a0, a1 = cs.rasterise(s, h).area, cs.rasterise(rs, h).area
    assert abs(a1 - a0) <= math.sqrt(2) * P * h


def test_bad_polygons_are_refused():
    with pytest.raises(cs.SceneError, match="intersects itself"):
        cs.Polygon(((0, 0), (1, 1), (1, 0), (0, 1)))
    with pytest.raises(cs.SceneError, match="empty"):
        cs.Polygon(((0, 0), (1, 1), (2, 2)))
    with pytest.raises(cs.SceneError, match="at least 3"):
        cs.Polygon(((0, 0), (1, 1)))


def test_too_coarse_grid_is_refused():
    with pytest.raises(cs.SceneError, match="too coarse"):
        cs.rasterise(cs.Circle(1.0), 0.6)
    cs.rasterise(cs.Circle(1.0), 0.5)


@pytest.mark.parametrize(
    "face",
    [
        cs.TwoCircles(1.0, 0.05, 5.0),
        cs.Union((cs.Circle(1.0), cs.Circle(0.05, (5.0, 0.0)))),
        cs.Transformed(cs.TwoCircles(1.0, 0.05, 5.0), scale=2.0, rotation_deg=30.0),
    ],
    ids=["two_circles", "union", "transformed"],
)
def test_a_grid_must_resolve_every_separate_part_of_the_face(face):
    # the large part's incircle allows spacing 0.5 (four cells across); the small part, 0.1 across
    # (0.2 scaled), would be lost from such a raster without a word
    scale = 2.0 if isinstance(face, cs.Transformed) else 1.0
    small = 0.05 * scale
    assert face.smallest_part_incircle().radius == pytest.approx(small)
    assert face.incircle().radius == pytest.approx(scale)
    with pytest.raises(cs.SceneError, match="smallest separate part"):
        cs.rasterise(face, 0.5 * scale)
    raster = cs.rasterise(face, 2 * small / 4)
    assert raster.mask.sum() * raster.spacing**2 == pytest.approx(face.area, rel=0.05)
    # overlapping circles are one face: its incircle, the larger circle's, is what must be resolved
    joined = cs.TwoCircles(1.0, 0.05, 1.0)
    assert joined.smallest_part_incircle() == joined.incircle()


def _segment_area(radius, height):
    """Area of the circular segment of ``height`` cut from a disc of ``radius`` by a chord."""
    d = radius - height
    return radius**2 * math.acos(d / radius) - d * math.sqrt(radius**2 - d**2)


#: faces that cuts split into a large part and a circular segment of height H, whose incircle
#: (radius H/2, tangent to the chord and the arc) is the narrowest part's
CUT_INTO_ISLANDS = {
    # a disc minus a bar 0.5 <= y <= 0.6: a segment of height 1.5 and a cap of height 0.4
    "disc_minus_bar": (cs.Difference(cs.Circle(1.0), (cs.Rectangle(3.0, 0.1, center=(0.0, 0.55)),)), 0.4),
    # an annulus 0.5 <= r <= 1 minus a bar 0.8 <= x <= 0.85: a C and a segment of height 0.15
    "annulus_minus_bar": (
        cs.Difference(cs.Circle(1.0), (cs.Circle(0.5), cs.Rectangle(0.05, 3.0, center=(0.825, 0.0)))),
        0.15,
    ),
}


@pytest.mark.parametrize("name", sorted(CUT_INTO_ISLANDS))
def test_a_grid_must_resolve_every_island_of_a_cut_face(name):
    """The large part's incircle allows a grid that keeps two or three cells of the segment (or
    merges it into the large part): the segment's own incircle, H/2, decides."""
    from scipy import ndimage

    face, height = CUT_INTO_ISLANDS[name]
    true_radius = height / 2
    h = face.size / 1024  # the auxiliary raster's cell: its pieces are wide, so its fewest cells
    r, (cx, cy) = face.smallest_part_incircle()
    # an estimate below the true radius, by less than two auxiliary cells
    assert true_radius - 2 * h <= r <= true_radius
    assert math.hypot(cx, cy) > 1 - height  # in the segment
    assert face.incircle().radius > 1.5 * true_radius  # the large part's
    # a grid coarser than the segment's true incircle allows is refused ...
    with pytest.raises(cs.SceneError, match="smallest separate part"):
        cs.rasterise(face, 2 * true_radius / 4 * 1.001)
    # ... and one inside the estimate's error accepted, with the segment an island of its own
    raster = cs.rasterise(face, 2 * (true_radius - 2 * h) / 4)
    labels, islands = ndimage.label(raster.mask)
    assert islands == 2
    sizes = np.bincount(labels.ravel())[1:] * raster.spacing**2
    assert sizes.min() == pytest.approx(_segment_area(1.0, height), rel=0.2)


def test_a_grid_must_resolve_a_part_whose_bounding_box_meets_another():
    """A disc of radius 0.1 in the hole of a ring 0.6 ... 1: the boxes meet, the parts do not.  The
    union's incircle is the ring's (0.2), which allowed a grid of two cells across the disc."""
    ring = cs.Difference(cs.Circle(1.0), (cs.Circle(0.6),))
    h = 2.0 / 1024  # the auxiliary raster's coarsest cell
    for r in (0.1, 0.01):
        face = cs.Union((ring, cs.Circle(r, (0.0123, 0.0071))))
        # an island that is one part, met by nothing else, is that part: its incircle is exact
        # (the raster's estimate alone was 22 % small at r = 0.01, and refused a grid that resolves it)
        assert face.smallest_part_incircle() == cs.Circle(r, (0.0123, 0.0071)).incircle()
        assert face.incircle().radius == pytest.approx(0.2, abs=2 * h)
        with pytest.raises(cs.SceneError, match="smallest separate part"):
            cs.rasterise(face, 2 * r / 4 * 1.001)
        cs.rasterise(face, 2 * r / 4 * 0.999)
    # a union whose overlapping parts make one piece keeps its incircle
    joined = cs.Union((cs.Circle(1.0), cs.Circle(0.5, (1.2, 0.0))))
    assert joined.smallest_part_incircle() == joined.incircle()


def test_a_thin_ring_is_a_face_and_cuts_that_cover_the_base_leave_none():
    """A cut keeps its outline, so the base minus itself, or a square minus two rectangles
    meeting along its midline, leaves cells of outline on the area's raster (taken for faces of
    area 4e-6 and 8e-3); the closed cuts cover them, and the shape is empty.  A ring 1e-3 wide
    (about 6600 cells of that raster) lies outside its closed cut and is a face."""
    with pytest.raises(cs.SceneError, match="the shape is empty"):
        cs.Difference(cs.Circle(1.0), (cs.Circle(1.0),))
    halves = (cs.Rectangle(1.0, 2.0, center=(-0.5, 0.0)), cs.Rectangle(1.0, 2.0, center=(0.5, 0.0)))
    with pytest.raises(cs.SceneError, match="the shape is empty"):
        cs.Difference(cs.Square(2.0), halves)
    ring = cs.Difference(cs.Circle(1.0), (cs.Circle(0.999),))
    h = 2.0 / 2048
    assert ring.area > 1000 * h * h
    # one half cut away leaves the other half
    assert cs.Difference(cs.Square(2.0), halves[:1]).area == pytest.approx(2.0, rel=0.01)


def test_a_brush_with_more_pillars_than_its_square_holds_is_refused_at_once():
    """20000 pillars of radius 0.05 need bounding boxes of 200 times the unit square: refused
    by the area bound, not after 50 draws per pillar."""
    with pytest.raises(cs.SceneError, match="exceed the square's area") as caught:
        cs.Brush(1.0, 0.05, layout="random", count=20_000, seed=0)
    assert caught.value.field == "indenter.count"


def test_cut_faces_in_one_piece_keep_their_incircle():
    """A connected difference (and one of islands inside a union or transformed) answers as before."""
    holed = cs.Difference(cs.Square(2.0), (cs.Circle(0.3),))
    for face in (SHAPES["faults"], holed):
        assert face.smallest_part_incircle() == face.incircle()
    face, height = CUT_INTO_ISLANDS["disc_minus_bar"]
    assert cs.Transformed(face, scale=2.0).smallest_part_incircle().radius == pytest.approx(
        2 * face.smallest_part_incircle().radius
    )
    far = cs.Union((face, cs.Circle(1.0, (5.0, 0.0))))
    assert far.smallest_part_incircle() == face.smallest_part_incircle()


def _image_of(tmp_path, pixels, name="face.png"):
    import matplotlib.image as mpimg

    p = tmp_path / name
    mpimg.imsave(p, np.where(pixels, 0.0, 1.0), cmap="gray", vmin=0, vmax=1)
    return str(p)


def test_a_grid_must_resolve_every_island_of_an_image(tmp_path):
    """A disc of radius 40 pixels and a 5 x 5 pixel island: the island's incircle, 2.5 pixels (the
    distance transform's answer for a square island is exact), decides the grid."""
    n, pixel = 200, 0.01
    yy, xx = np.mgrid[0:n, 0:n]
    pixels = (xx + 0.5 - 80) ** 2 + (yy + 0.5 - 100) ** 2 <= 40**2
    pixels[98:103, 160:165] = True  # rows 98..102 (the middle row is 100), columns 160..164
    s = cs.ImageMask(path=_image_of(tmp_path, pixels), pixel_size=pixel)
    r, (cx, cy) = s.smallest_part_incircle()
    assert r == pytest.approx(2.5 * pixel)
    assert (cx, cy) == pytest.approx((62.5 * pixel, -0.5 * pixel))  # the island's middle pixel
    assert s.incircle().radius > 35 * pixel  # the disc's
    with pytest.raises(cs.SceneError, match="smallest separate part"):
        cs.rasterise(s, 2 * r / 4 * 1.001)
    raster = cs.rasterise(s, 2 * r / 4 * 0.999)
    x, _ = raster.centres()
    assert raster.mask[x > 0.55].sum() * raster.spacing**2 == pytest.approx(25 * pixel**2, rel=0.2)
    # one island (pixels touching at a corner only are two): the image's incircle, as before
    one = cs.ImageMask(path=_image_of(tmp_path, pixels[:, :150], "one.png"), pixel_size=pixel)
    assert one.smallest_part_incircle() == one.incircle()
    corner = np.zeros((20, 20), bool)
    corner[5:10, 5:10] = corner[10:13, 10:13] = True
    two = cs.ImageMask(path=_image_of(tmp_path, corner, "corner.png"), pixel_size=pixel)
    assert two.smallest_part_incircle().radius == pytest.approx(1.5 * pixel)


def test_power_law_star_ring_filling_follows_design():
    s = cs.PowerLawStar(8, 0.3, 1.0, samples=128)
    for r in (0.4, 0.6, 0.9):
        assert s.ring_filling(r, samples=200_000) == pytest.approx(float(s.design_filling(r)), rel=2e-3)
    assert s.ring_filling(0.2) == 1.0


def test_image_mask(tmp_path):
    import matplotlib.image as mpimg

    n = 200
    yy, xx = np.mgrid[0:n, 0:n]
    disc = (xx + 0.5 - n / 2) ** 2 + (yy + 0.5 - n / 2) ** 2 <= 60**2
    img = np.where(disc, 0.0, 1.0)
    p = tmp_path / "face.png"
    mpimg.imsave(p, img, cmap="gray", vmin=0, vmax=1)
    s = cs.ImageMask(path=str(p), pixel_size=0.01)
    assert s.area == pytest.approx(math.pi * 0.6**2, rel=0.01)
    assert s.incircle().radius == pytest.approx(0.6, abs=0.015)
    with pytest.raises(cs.SceneError, match="cannot read"):
        cs.ImageMask(path=str(tmp_path / "missing.png"), pixel_size=0.01)
    for bad in (5, None, ""):
        with pytest.raises(cs.SceneError) as caught:
            cs.ImageMask(path=bad, pixel_size=0.01)
        assert caught.value.field == "indenter.path"


def test_image_mask_threshold_one_keeps_pure_white_out_of_the_face(tmp_path):
    # in colour, pure white's luma is 0.299 + 0.587 + 0.114, 0.9999999999999999 in floating point:
    # with threshold 1 the white background must not become face
    import matplotlib.image as mpimg

    img = np.ones((40, 40, 3))
    img[10:30, 15:25] = 0.5
    p = tmp_path / "grey.png"
    mpimg.imsave(p, img)
    s = cs.ImageMask(path=str(p), pixel_size=0.1, threshold=1.0)
    assert s.area == pytest.approx(20 * 10 * 0.01)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(-1, 1), st.floats(-1, 1)), min_size=3, max_size=12))
def test_convex_polygon_incircle_bound(points):
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = ConvexHull(np.array(points))
    except (QhullError, ValueError):
        return
    v = np.array(points)[hull.vertices]
    if hull.volume < 1e-3:
        return
    p = cs.Polygon(tuple(map(tuple, v)))
    r, c = p.incircle()
    assert p.area == pytest.approx(hull.volume, rel=1e-9)
    assert r <= 2 * p.area / hull.area * (1 + 1e-9)  # r <= 2A/P for every convex polygon
    assert -p.signed_distance(*c) == pytest.approx(r, rel=1e-6)


def test_composite_faces_take_their_own_parameters_positionally():
    """The parts of a derived union/difference are built, not passed: a positional call binds
    the first argument to the first physical parameter (it used to bind it to ``parts`` and
    leave the last parameter at its default, silently building another face)."""
    tc = cs.TwoCircles(10.0, 6.0, 13.0)
    assert (tc.radius1, tc.radius2, tc.distance) == (10.0, 6.0, 13.0)
    assert tc.bounds == (-16.5, -10.0, 12.5, 10.0)
    assert cs.Brush(2.0, 0.05).side == 2.0
    assert cs.SquareWithFaults(2.0).area == 4.0
    assert dataclasses.replace(tc, radius2=5.0).bounds[2] == 11.5


def test_mixed_brush_has_circular_and_square_columns_and_an_exact_area():
    b = cs.Brush(1.0, 0.07, layout="mixed", count=30, seed=1)
    kinds = {type(p) for p in b.parts}
    assert kinds == {cs.Circle, cs.Square} and len(b.parts) == 30 and b.area_is_exact
    h = 1.0 / 2048  # the raster's cell; boundary cells are the error
    perimeter = sum(2 * math.pi * p.radius if isinstance(p, cs.Circle) else 4 * p.side for p in b.parts)
    assert abs(raster_area(b) - b.area) <= perimeter * h
    assert cs.Brush(1.0, 0.07, layout="mixed", count=30, seed=1) == b
    with pytest.raises(cs.SceneError, match="indenter.layout"):
        cs.Brush(1.0, 0.07, layout="spiral")


@pytest.mark.parametrize(
    "build,field,says",
    [
        (lambda: cs.Circle(0.0), "indenter.radius", r"must be > 0 \(got 0\)"),
        (lambda: cs.Ellipse(1.0, 2.0), "indenter.semi_minor", r"must be in \(0, 1\] \(got 2\)"),
        (lambda: cs.Star(5, 1.0, 1.5), "indenter.inner_radius", r"must be in \(0, 1\]"),
        (lambda: cs.PowerLawStar(8, 0.5, 0.5), "indenter.outer_radius", r"must be > 0.5"),
        (lambda: cs.RegularPolygon(3.5, 1.0), "indenter.n_sides", r"whole number in \[3, 100000\]"),
        (lambda: cs.Square(1.0, center=(0.0,)), "indenter.center", "pair of numbers"),
        (lambda: cs.Rectangle(1.0, 2.0, rotation_deg=float("inf")), "indenter.rotation_deg", "finite number"),
        (lambda: cs.SquareWithFaults(2.0, v_cut_depth=2.0), "indenter.v_cut_depth", r"must be in \[0, 2\)"),
        (
            lambda: cs.SquareWithFaults(1.0, line_cuts=2, line_cut_length=0.5, cut_width=0.3),
            "indenter.cut_width",
            r"must be in \[0, 0.2\]",
        ),
        (lambda: cs.Brush(1.0, 0.1, pitch=0.2), "indenter.pitch", r"must be > 0.2"),
        (lambda: cs.Brush(1.0, 0.1, layout="spiral"), "indenter.layout", "'regular'"),
        (lambda: cs.Brush(1.0, 0.1, layout="random", count=0), "indenter.count", r"\[1, 100000\]"),
        (lambda: cs.TwoCircles(1.0, 1.0, -0.5), "indenter.distance", r"must be >= 0"),
        (lambda: cs.ImageMask(path="face.png", pixel_size=1.0, threshold=1.5), "indenter.threshold", r"in \[0, 1\]"),
        (lambda: cs.Circle(1.0).scaled(0.0), "scale", r"must be > 0"),
    ],
    ids=lambda v: v if isinstance(v, str) and "." in v else None,
)
def test_a_parameter_outside_its_range_is_refused_by_name(build, field, says):
    """Each declared range, including ranges set by another parameter (semi_minor <= semi_major,
    cut_width <= side / (2 line_cuts + 1)), names the field and the allowed values."""
    with pytest.raises(cs.SceneError, match=says) as exc:
        build()
    assert exc.value.field == field


def test_checked_parameters_are_stored_checked_and_conditional_ones_only_where_they_apply():
    # stored as floats (a scene's repr is the result cache's key: 1 and 1.0 must give one key)
    assert repr(cs.Circle(1, [0, 1])) == "Circle(radius=1.0, center=(0.0, 1.0))"
    assert repr(cs.TwoCircles(1, 1, 1)) == "TwoCircles(radius1=1.0, radius2=1.0, distance=1.0)"
    # a random brush has no lattice pitch, a regular one no count or seed: left at their
    # defaults they are not checked, given another value they are refused (not ignored)
    assert len(cs.Brush(1.0, 0.05, layout="random", count=3).parts) == 3
    assert len(cs.Brush(1.0, 0.05).parts) == 25
    with pytest.raises(cs.SceneError, match="indenter.pitch: only applies to layout 'regular'"):
        cs.Brush(1.0, 0.05, layout="random", count=3, pitch=0.0)
    with pytest.raises(cs.SceneError, match="indenter.count: only applies to layouts 'random' and 'mixed'"):
        cs.Brush(1.0, 0.05, count=-1, seed=-1)


def test_the_largest_allowed_regular_polygon_and_star_are_built_without_the_pairwise_edge_check():
    # corners at increasing angles around a centre make a simple polygon; checking every pair of
    # 100000 edges would need 5e9 pairs (a MemoryError of tens of GiB)
    polygon = cs.RegularPolygon(100_000, 1.0)
    assert polygon.area == pytest.approx(math.pi, rel=1e-8)
    star = cs.Star(10_000, 1.0, 0.5)
    assert 0 < star.area < math.pi
    # a polygon the user gives is still checked
    with pytest.raises(cs.SceneError, match="intersects itself"):
        cs.Polygon(((0, 0), (1, 1), (1, 0), (0, 1)))


def _placed_by_testing_every_pillar(brush: cs.Brush) -> list[tuple[float, float, float]]:
    """The random placement with its gap test against every pillar placed so far (quadratic)."""
    from contact_scene.shapes.brush import _ATTEMPTS_PER_PILLAR

    rng = np.random.default_rng(brush.seed)
    mixed = brush.layout == "mixed"
    radius, half_side = brush.pillar_radius, brush.side / 2
    placed: list[tuple[float, float, float]] = []
    for _ in range(_ATTEMPTS_PER_PILLAR * brush.count):
        if len(placed) == brush.count:
            break
        r = rng.uniform(0.5 * radius, radius) if mixed else radius
        c = rng.uniform(-half_side + radius, half_side - radius, 2)
        if all(max(abs(c[0] - q[0]), abs(c[1] - q[1])) > (r + q[2]) * 1.000001 for q in placed):
            placed.append((float(c[0]), float(c[1]), r))
    return placed


@pytest.mark.parametrize("layout", ["random", "mixed"])
def test_a_random_brush_places_the_pillars_the_test_against_every_pillar_would(layout):
    brush = cs.Brush(1.0, 0.012, layout=layout, count=400, seed=3)
    expected = _placed_by_testing_every_pillar(brush)
    got = [(p.centroid[0], p.centroid[1]) for p in brush.parts]
    assert np.allclose(got, [(x, y) for x, y, _ in expected], rtol=0, atol=1e-15)
    assert brush._disjoint


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(-2, 2), st.floats(-2, 2), st.floats(0.01, 1)), min_size=2, max_size=25))
def test_bounding_boxes_are_disjoint_exactly_when_every_pair_is(discs):
    from contact_scene.shapes.composite import _pairwise_disjoint

    def apart(a, b):  # the pair's definition: one box strictly beside the other
        ax0, ay0, ax1, ay1 = a.bounds
        bx0, by0, bx1, by1 = b.bounds
        return ax1 < bx0 or bx1 < ax0 or ay1 < by0 or by1 < ay0

    shapes = [cs.Circle(r, (x, y)) for x, y, r in discs]
    every_pair = all(apart(shapes[i], shapes[j]) for i in range(len(shapes)) for j in range(i + 1, len(shapes)))
    assert _pairwise_disjoint(shapes) == every_pair


def test_touching_bounding_boxes_are_not_disjoint():
    from contact_scene.shapes.composite import _pairwise_disjoint

    touching = [cs.Square(1.0), cs.Square(1.0, center=(1.0, 0.0)), cs.Square(1.0, center=(5.0, 5.0))]
    assert not _pairwise_disjoint(touching)
    assert _pairwise_disjoint([cs.Square(1.0), cs.Square(1.0, center=(1.0 + 1e-12, 0.0))])


def test_the_largest_random_brush_is_built():
    # 1e5 pillars, the documented maximum: the placement and the disjointness test used to be
    # quadratic (still running after a minute)
    brush = cs.Brush(1.0, 1e-4, layout="random", count=100_000)
    assert len(brush.parts) == 100_000 and brush._disjoint
    assert brush.area == pytest.approx(100_000 * math.pi * 1e-8, rel=1e-12)


_SCALED_EXTRA = {
    # a convex polygon without a closed-form incircle (the linear programme) and a non-convex one
    "pentagon": ((0.0, 0.0), (3.0, 0.0), (4.0, 2.0), (1.0, 3.0), (-0.5, 1.5)),
    "l_shape": ((0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0), (1.0, 2.0), (0.0, 2.0)),
}


def _image_face(s: float) -> cs.Shape:
    """A disc of 30 pixels and a 6 x 6 pixel island, pixels of side 0.02 s (an image made once)."""
    import tempfile

    import matplotlib.image as mpimg

    path = Path(tempfile.gettempdir()) / "adhesive_punch_test_scaled_image.png"
    if not path.exists():
        yy, xx = np.mgrid[0:100, 0:100]
        pixels = (xx + 0.5 - 40) ** 2 + (yy + 0.5 - 50) ** 2 <= 30**2
        pixels[47:53, 80:86] = True
        mpimg.imsave(path, np.where(pixels, 0.0, 1.0), cmap="gray", vmin=0, vmax=1)
    return cs.ImageMask(path=str(path), pixel_size=0.02 * s)


#: faces built in the unit s: the composites whose parts the suite's SHAPES does not cover
_SCALED_BUILT = {
    # boxes that meet, parts that overlap: one piece, its incircle from the raster
    "union_overlapping": lambda s: cs.Union((cs.Circle(s), cs.Circle(0.5 * s, (1.2 * s, 0.3 * s)))),
    # boxes that meet, parts that do not: a disc in a ring's hole, two islands
    "disc_in_ring": lambda s: cs.Union(
        (cs.Difference(cs.Circle(s), (cs.Circle(0.6 * s),)), cs.Circle(0.1 * s, (0.0123 * s, 0.0071 * s)))
    ),
    "transformed": lambda s: cs.Transformed(cs.Triangle.equilateral(2 * s), 30.0, True, 1.5, (0.2 * s, 0.1 * s)),
    "image": _image_face,
}


def _scaled_face(name: str, s: float) -> cs.Shape:
    if name in _SCALED_EXTRA:
        return cs.Polygon(tuple((s * x, s * y) for x, y in _SCALED_EXTRA[name]))
    if name in _SCALED_BUILT:
        return _SCALED_BUILT[name](s)
    face = SHAPES[name]
    fields = {f.name: getattr(face, f.name) for f in dataclasses.fields(face) if f.init}
    lengths = {"radius", "radius1", "radius2", "distance", "side", "width", "height", "semi_major", "semi_minor"}
    lengths |= {"outer_radius", "inner_radius", "pillar_radius", "pitch", "v_cut_depth", "v_cut_width"}
    lengths |= {"line_cut_length", "cut_width", "circumradius"}
    scaled = {k: s * v if k in lengths else v for k, v in fields.items()}
    if "center" in scaled:
        scaled["center"] = tuple(s * c for c in fields["center"])
    if "vertices" in scaled:
        scaled["vertices"] = tuple((s * x, s * y) for x, y in fields["vertices"])
    return type(face)(**scaled)


@pytest.mark.parametrize("s", [1e-120, 1e-30, 1e-9, 1e-6, 1e6, 1e120])
@pytest.mark.parametrize("name", sorted(SHAPES) + sorted(_SCALED_EXTRA) + sorted(_SCALED_BUILT))
def test_geometry_is_invariant_under_a_change_of_length_unit(name, s):
    # a face in nanometres (or any unit) is the same face: its area, centroid, incircle and raster
    # scale with the unit.  The incircle's linear programme, solved in the given units, gave a
    # pentagon of nanometres a radius 4 % too large and one of 1e-30 a radius of zero; the first
    # moments (lengths cubed) overflowed at 1e120, and the two circles' lens area underflowed
    one, face = _scaled_face(name, 1.0), _scaled_face(name, s)
    assert face.area / s**2 == pytest.approx(one.area, rel=1e-12)
    assert np.asarray(face.centroid) / s == pytest.approx(np.asarray(one.centroid), rel=1e-9, abs=1e-12 * one.size)
    for part in ("incircle", "smallest_part_incircle"):
        scaled, unit = getattr(face, part)(), getattr(one, part)()
        assert scaled.radius / s == pytest.approx(unit.radius, rel=1e-9)
        assert np.asarray(scaled.center) / s == pytest.approx(np.asarray(unit.center), rel=1e-6, abs=1e-6 * one.size)
    h = min(one.equivalent_radius / 24, 2 * one.smallest_part_incircle().radius / 4.5)  # every part resolved
    assert np.array_equal(cs.rasterise(face, s * h).mask, cs.rasterise(one, h).mask)


@pytest.mark.parametrize("s", [1e-200, 1e200])
def test_a_face_whose_area_leaves_floating_point_is_refused_by_name(s):
    for face in (cs.Square(2 * s), cs.Polygon(tuple((s * x, s * y) for x, y in _SCALED_EXTRA["l_shape"]))):
        with pytest.raises(cs.SceneError) as caught:
            cs.rasterise(face, 0.1 * s)
        assert caught.value.field == "indenter"
    # far from the origin the coordinates' rounding reaches the boundary tolerance: the raster of
    # a circle 1e14 sizes away lost cells; 1e12 sizes away it is the one at the origin
    at_origin = cs.rasterise(cs.Circle(1.0), 0.04).mask
    assert np.array_equal(cs.rasterise(cs.Circle(1.0, (1e12, 3e11)), 0.04).mask, at_origin)
    with pytest.raises(cs.SceneError) as caught:
        cs.rasterise(cs.Circle(1.0, (1e14, 3e13)), 0.04)
    assert caught.value.field == "indenter" and "origin" in str(caught.value)
    # a cut face whose base area underflowed is not a face the cuts removed
    if s < 1:
        with pytest.raises(cs.SceneError) as caught:
            cs.Difference(cs.Circle(s), (cs.Square(s),))
        assert caught.value.field == "indenter.base"


def test_a_layouts_unused_parameter_at_its_default_passes_in_any_numeric_type():
    # numpy's int64(0) is the default seed of a regular brush, not a value given for it
    assert cs.Brush(1.0, 0.05, seed=np.int64(0)).seed == 0
    with pytest.raises(cs.SceneError, match="indenter.seed"):
        cs.Brush(1.0, 0.05, seed=np.int64(3))


def test_a_polygon_whose_extent_overflows_is_refused_not_given_a_nan_area():
    with pytest.raises(cs.SceneError, match="indenter.vertices"):
        _ = cs.Polygon(((-1e308, 0.0), (1e308, 0.0), (0.0, 1e308))).area
