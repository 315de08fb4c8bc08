"""The faulted square of the paper (Fig. 7): a square face with a V notch and line cuts."""

from __future__ import annotations

from dataclasses import dataclass, field

from ..errors import SceneError
from ..validation import real, whole
from .base import Shape
from .composite import Difference
from .polygons import Polygon, Square

__all__ = ["SquareWithFaults"]


@dataclass(frozen=True)
class SquareWithFaults(Difference):
    """A square face with the faults of Fig. 7: a V notch and line cuts.

    An optional V-shaped notch is cut into the middle of the top edge, and ``line_cuts`` straight
    cuts of width ``cut_width`` run from the left edge inward by ``line_cut_length`` at evenly
    spaced heights.  The nominal area is the square's.

    Parameters
    ----------
    side : float, optional
        Side of the square, > 0; 1 by default.
    v_cut_depth : float, optional
        Depth of the V notch, 0 <= depth < side (0: no notch).
    v_cut_width : float, optional
        Width of the notch at the edge, 0 <= width <= side; > 0 exactly when the depth is.
    line_cuts : int, optional
        Number of line cuts, 0 <= n <= 1000.
    line_cut_length : float, optional
        How far the line cuts run in from the left edge, 0 <= length < side; > 0 with cuts.
    cut_width : float, optional
        Width of each line cut, 0 <= width <= side / (2 line_cuts + 1); > 0 with cuts.

    Raises
    ------
    contact_scene.SceneError
        Naming the parameter (``indenter.v_cut_width`` etc.) and its allowed range, or the rule
        it breaks.
    """

    base: Shape = field(default=None, init=False, repr=False)  # type: ignore[assignment]  # built by _complete
    cuts: tuple = field(default=(), init=False, repr=False)
    side: float = real(1.0, gt=0)
    v_cut_depth: float = real(0.0, ge=0, lt=lambda face: face.side)
    v_cut_width: float = real(0.0, ge=0, le=lambda face: face.side)
    line_cuts: int = whole(0, ge=0, le=1000)
    line_cut_length: float = real(0.0, ge=0, lt=lambda face: face.side)
    # the cuts and the gaps between them must fit in the side
    cut_width: float = real(0.0, ge=0, le=lambda face: face.side / max(2 * face.line_cuts + 1, 1))
    kind = "square_with_faults"

    def _complete(self):
        if (self.v_cut_depth > 0) != (self.v_cut_width > 0):
            raise SceneError("indenter.v_cut_width", "a V cut needs both v_cut_depth > 0 and v_cut_width > 0")
        if self.line_cuts and (self.line_cut_length <= 0 or self.cut_width <= 0):
            raise SceneError("indenter.cut_width", "line cuts need line_cut_length > 0 and cut_width > 0")
        side, half = self.side, self.side / 2
        cuts = []
        if self.v_cut_depth > 0:
            notch_half_width = self.v_cut_width / 2
            cuts.append(Polygon(((-notch_half_width, half), (0.0, half - self.v_cut_depth), (notch_half_width, half))))
        half_cut = self.cut_width / 2
        inner_end = -half + self.line_cut_length
        for i in range(self.line_cuts):
            y = -half + side * (i + 1) / (self.line_cuts + 1)
            cuts.append(
                Polygon(
                    ((-half, y - half_cut), (inner_end, y - half_cut), (inner_end, y + half_cut), (-half, y + half_cut))
                )
            )
        object.__setattr__(self, "base", Square(side))
        object.__setattr__(self, "cuts", tuple(cuts))
