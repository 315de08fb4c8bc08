"""Brushes (Fig. 8): a square face whose adhering part is an array of separate pillars."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import SceneError
from ..validation import choice, real, whole
from .composite import Union
from .conics import Circle
from .polygons import Square

__all__ = ["Brush", "LAYOUTS", "LAYOUT_PARAMETERS", "unused_by_layout"]

_RANDOM_LAYOUTS = ("random", "mixed")
#: every layout a brush accepts
LAYOUTS = ("regular", *_RANDOM_LAYOUTS)
#: placement attempts per pillar before a random layout gives up
_ATTEMPTS_PER_PILLAR = 200


def _placed_at_random(layout: str) -> bool:
    return layout in _RANDOM_LAYOUTS


#: the layouts that use each layout-dependent parameter; the others refuse it (the scene reader
#: when the key is given at all, the class when it differs from its default)
LAYOUT_PARAMETERS: dict[str, tuple[str, ...]] = {
    "pitch": ("regular",),
    "count": _RANDOM_LAYOUTS,
    "seed": _RANDOM_LAYOUTS,
}


def unused_by_layout(parameter: str, layout: str, *, layout_given: bool = True) -> str:
    """Why ``parameter`` is refused for ``layout``: which layouts use it.

    Parameters
    ----------
    parameter : str
        A key of :data:`LAYOUT_PARAMETERS` (``"pitch"``, ``"count"`` or ``"seed"``).
    layout : str
        The brush's layout, one that does not use ``parameter``.
    layout_given : bool, optional
        False when ``layout`` is the default because none was given (the message says so).

    Returns
    -------
    str
        The message, e.g. "only applies to layout 'regular', not to layout 'random'".
    """
    users = LAYOUT_PARAMETERS[parameter]
    which = f"layout {users[0]!r}" if len(users) == 1 else "layouts " + " and ".join(map(repr, users))
    default = "" if layout_given else ", the default when no layout is given"
    return f"only applies to {which}, not to layout {layout!r}{default}"


def _layout_field(parameter: str) -> dict:
    """``when`` and ``unused`` of a layout-dependent field: checked where its layout uses it,
    refused (unless it keeps its default) where not."""
    return {
        "when": lambda brush: brush.layout in LAYOUT_PARAMETERS[parameter],
        # a brush's layout switched with dataclasses.replace keeps the old layout's values
        "unused": lambda brush: (
            unused_by_layout(parameter, brush.layout)
            + " (switching layouts with dataclasses.replace: give it its default too)"
        ),
    }


@dataclass(frozen=True)
class Brush(Union):
    """Circular pillars inside a square face (Fig. 8): the adhering part is the pillars.

    ``layout = "regular"`` puts them on a square lattice of pitch ``pitch``; ``"random"``
    places ``count`` non-overlapping pillars uniformly at random (reproducible by ``seed``);
    ``"mixed"`` places ``count`` columns at random too, alternately circular and square, each
    sized uniformly between half and all of ``pillar_radius`` (a square column of "radius" r
    has side r sqrt(pi), the area of the disc), as in the paper's mixed brushes (Fig. 8a).
    The nominal area is the square's, so area / nominal_area is the phi of Eq. 24.

    Parameters
    ----------
    side : float, optional
        Side of the square, > 0; 1 by default.
    pillar_radius : float, optional
        Radius of the pillars (the largest, for ``"mixed"``), 0 < r <= side/2; 0.05 by default.
    layout : {"regular", "random", "mixed"}, optional
        How the pillars are placed; ``"regular"`` by default.
    pitch : float, optional
        Distance between neighbouring pillars of the regular lattice, > 2 pillar_radius; 0.2 by
        default.  Regular layout only: another layout refuses a pitch other than the default.
    count : int, optional
        Number of pillars of a random or mixed layout, 1 <= count <= 100000 (no default for
        those); a regular layout refuses a count.
    seed : int, optional
        Seed of the random placement, >= 0; 0 by default.  Random and mixed layouts only: a
        regular layout refuses a seed other than 0.

    Raises
    ------
    contact_scene.SceneError
        Naming the parameter (``indenter.pitch`` etc.) and its allowed range;
        ``indenter.pitch``, ``indenter.count`` or ``indenter.seed`` given (other than its
        default) to a layout that does not use it; ``indenter.count`` when that many pillars do
        not fit.
    """

    parts: tuple = field(default=(), init=False, repr=False)
    side: float = real(1.0, gt=0)
    pillar_radius: float = real(0.05, gt=0, le=lambda brush: brush.side / 2)
    layout: str = choice("regular", LAYOUTS)
    pitch: float = real(0.2, gt=lambda brush: 2 * brush.pillar_radius, **_layout_field("pitch"))
    count: int = whole(0, ge=1, le=100_000, **_layout_field("count"))
    seed: int = whole(0, ge=0, **_layout_field("seed"))
    kind = "brush"

    def _complete(self):
        parts = self._random_parts() if _placed_at_random(self.layout) else self._lattice_parts()
        object.__setattr__(self, "parts", parts)

    def _lattice_parts(self) -> tuple:
        radius, pitch = self.pillar_radius, self.pitch
        per_row = int(math.floor((self.side - 2 * radius) / pitch + 1e-9)) + 1
        first = -(per_row - 1) * pitch / 2
        centres = [(first + i * pitch, first + j * pitch) for i in range(per_row) for j in range(per_row)]
        return tuple(Circle(radius, c) for c in centres)

    def _random_parts(self) -> tuple:
        rng = np.random.default_rng(self.seed)
        mixed = self.layout == "mixed"
        radius, half_side = self.pillar_radius, self.side / 2
        # the pillars' bounding boxes (side 2 r, r >= radius / 2 when mixed) lie apart inside the
        # square: more of them than the square's area holds cannot be placed, whatever the draw
        # (refused at once rather than after all the attempts)
        smallest_box = (radius if mixed else 2 * radius) ** 2
        if self.count * smallest_box > self.side**2:
            raise SceneError(
                "indenter.count",
                f"{self.count} pillars' bounding boxes ({smallest_box:.3g} each at least) exceed the square's area "
                f"{self.side**2:.3g}; lower count or pillar_radius",
            )
        placed: list[tuple[float, float, float]] = []  # (x, y, half-width of the bounding box)
        # pillars filed by square buckets of side ``reach``: two pillars closer than the gap test
        # below allows lie in neighbouring buckets, so each candidate is tested against those
        # alone (the same decisions as against every pillar, at a cost that does not grow with
        # the count)
        reach = 2 * radius * 1.00001  # above the test's largest distance, 2 radius 1.000001, by more than round-off
        buckets: dict[tuple[int, int], list[tuple[float, float, float]]] = {}
        for _ in range(_ATTEMPTS_PER_PILLAR * self.count):
            if len(placed) == self.count:
                break
            r = rng.uniform(0.5 * radius, radius) if mixed else radius
            c = rng.uniform(-half_side + radius, half_side - radius, 2)
            bx, by = math.floor(c[0] / reach), math.floor(c[1] / reach)
            near = (q for i in (-1, 0, 1) for j in (-1, 0, 1) for q in buckets.get((bx + i, by + j), ()))
            # a small gap keeps the pillars' bounding boxes apart, so the area stays exact
            if all(max(abs(c[0] - q[0]), abs(c[1] - q[1])) > (r + q[2]) * 1.000001 for q in near):
                pillar = (float(c[0]), float(c[1]), r)
                placed.append(pillar)
                buckets.setdefault((bx, by), []).append(pillar)
        if len(placed) < self.count:
            raise SceneError(
                "indenter.count",
                f"could place only {len(placed)} of {self.count} non-overlapping pillars; lower count or pillar_radius",
            )
        return tuple(
            Square(r * math.sqrt(math.pi), center=(x, y)) if mixed and i % 2 else Circle(r, (x, y))
            for i, (x, y, r) in enumerate(placed)
        )

    @property
    def nominal_area(self):
        return self.side**2

    @property
    def bounds(self):
        """The square's box, (-side/2, -side/2, side/2, side/2)."""
        half_side = self.side / 2
        return (-half_side, -half_side, half_side, half_side)
