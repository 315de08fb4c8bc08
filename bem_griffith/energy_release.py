"""The energy-release detachment rule: Eq. 22's local ranking of the front cells, with its level
set per stretch of front by the solver's own energy release rate.

The paper's rule (Eq. 22) lets a cell go when its tension reaches sigma_c, a constant exact for
a straight edge of the grid.  On a staircase edge the most stressed cells meet it at a slightly
different load, an O(1) bias of a few tenths of a per cent in the pull-off force that does not
shrink with the grid (theory sheet, section 6).  Griffith's condition itself is global in the
discrete model and needs no constant: at fixed approach d a flat punch stores U = d^2 S / 2
(S = sum(x1) Delta^2, the stiffness of the contact set), so the energy release rate of a stretch
of front is G = (d^2 / 2) dS / dA, and the stretch advances when G reaches w.

``"energy_release"`` measures dS / dA of each stretch by a difference of the solver's own
stiffness: the stretch's front cells peeled and the layer of cells ahead of it added, each set
re-solved from the current solution (``stress_intensity.free_front_release`` does the same for
a whole free front), and the derivative taken at the current set from the parabola through the
three (the central difference when both layers hold as many cells).  The two one-sided
differences carry opposite second-order terms, which cancel.  On Kendall's circle the whole
rim's release meets G = d^2 E* / (2 pi a), a the raster's equivalent radius, within 1.5 / N^2
at 16 ... 96 elements per radius, while each one-sided difference is off by about 0.7 % at 64
(tests/test_energy_release_rule.py).  Since G is
proportional to d^2 on a fixed set, the approach at which the stretch reaches w is exact,
d_R = -sqrt(w / (G / d^2)), and the rule sets the stretch's own threshold to
sigma_R = |d_R| max x1 over its cells: its most stressed cell leaves exactly when the stretch's
release reaches w, the others by Eq. 22's ranking of their tensions within it.

Stretches:

* free fronts: the contact cells with a 4-neighbour on the face outside the contact set,
  grouped by 8-connectivity (a detached corner's front, a notch); the layer ahead is the
  detached face cells touching them.  Their threshold is sigma_R.
* pinned fronts: the remaining contact cells with a 4-neighbour off the face (the face's own
  edge) and the free pieces too small to measure, grouped likewise; the layer ahead lies off the
  face (the raster keeps one empty ring of cells around the face, so it exists), a virtual
  advance that measures G at the edge.  A pinned stretch's mean G does not say where along it G
  is largest (at a square's corner it is singular), so its threshold is
  min(NUCLEATION_FACTOR sigma_c, sigma_R): the release lets the stretch go when its mean G
  reaches w, and Eq. 22 nucleates a detachment where the tension runs far above sigma_c (a
  corner) before that.  The factor (1.05) lies above Eq. 22's staircase bias, so that the most
  stressed cells of a staircase rim do not leave early by it: with factor 1 they do on Kendall's
  circle at 128 elements per radius (its error is -0.18 % there against -0.13 % at 96); with
  1.05 the circle's error falls at every step over 48 ... 128 and the square's pull-off is the
  same at 48 and 64 per radius.

A stretch with ends (a pinned edge between two detached corners, a corner's free front ending
on the face's edge) measures its ends as well: there the peeled and added layers are not each
other's mirror images, so the two one-sided differences' second-order terms do not cancel
there.  A pinned piece of ten cells between two detached corners of the square at 32 elements
per radius measures a release about 1.8 times the mean of Eq. 22's local values; left to Eq. 22
alone, such pieces give the same square pull-off at 32-64 per radius (to six digits), but on
Kendall's circle, once notches have opened, they are what lets the rest of the rim go.  The free
stretches' end effect shrinks as the stretch grows with the grid.

The pinned threshold is the stretch's mean release, so it is right where the release is
uniform along the pinned front (a circle) and late where it is not.  At a corner the cap is
meant to act first (Eq. 22 nucleates there); on a smooth front whose release varies along it,
it acts too, as a stand-in for the release: on the two overlapping circles the small
lobe's rim reaches the cap before the rim's mean release reaches w, and the pull-off is Eq. 22's
at NUCLEATION_FACTOR sigma_c (it moves with the factor: tests/test_energy_release_rule.py), 4.8 %
above the paper criterion's at 32 per radius; so is the square's at 32, where its corners
nucleate at its force maximum.  The rule notes at each event whether every cell that left was
held by the cap, and when that was the pull-off's event the result says so (its messages and
``info["pulloff_by_cap"]``).

A stretch of fewer than ``MIN_STRETCH_CELLS`` cells (a one-cell notch, the last cells of a
cascade) has no front for a difference to measure; its cells follow Eq. 22.

What it leaves: the stiffness S itself carries the raster's O(1/N) error, which passes into the
force smoothly (it does not zig-zag with the staircase), so the pull-off converges like 1/N and
can be extrapolated.  Each stretch costs two contact solves per contact solution the driver asks
about (``WorkCounters`` counts them with the others): several times the paper rule's solves.
The release is the stored energy's own derivative, so it needs no G-K relation: graded bodies
take it as they are.  Eq. 42's sigma_c still caps the pinned thresholds, so it must be the
calibrated one (``graded_criterion="eq42"`` is refused: its constant, 22 % low at k = -0.5, would
take over from the release).  On the graded
circle (k = -0.5, 0.5) the pull-off follows the discrete stiffness as on the homogeneous one
(tests/test_energy_release_rule.py).  Flat, non-periodic faces only: on a curved face the
released energy has the profile's terms and is not proportional to d^2.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import ndimage

from .contact_set import solve_contact_set
from .counters import WorkCounters
from .stress_intensity import PaperRule, pressure_roundoff

__all__ = ["MIN_STRETCH_CELLS", "EnergyReleaseRule", "front_stretches", "stretch_release"]

#: fewest cells of a stretch of front whose release the rule measures (smaller free pieces join
#: the pinned stretch they touch; smaller pinned ones follow Eq. 22)
MIN_STRETCH_CELLS = 8

#: a measured pinned stretch lets a cell go by Eq. 22 only once its tension exceeds this multiple
#: of sigma_c (module doc)
NUCLEATION_FACTOR = 1.05

_FOUR = ndimage.generate_binary_structure(2, 1)
_EIGHT = np.ones((3, 3), bool)

#: the symmetries of a square grid of square cells other than the identity (the kernel is
#: invariant under each)
_SYMMETRIES = (
    lambda a: a[::-1],
    lambda a: a[:, ::-1],
    lambda a: a[::-1, ::-1],
    lambda a: a.T,
    lambda a: a.T[::-1],
    lambda a: a.T[:, ::-1],
    lambda a: a.T[::-1, ::-1],
)


def _invariant(grid: np.ndarray, op) -> bool:
    image = op(grid)
    return image.shape == grid.shape and bool(np.array_equal(image, grid))


def front_stretches(
    face: np.ndarray, contact: np.ndarray, min_cells: int = MIN_STRETCH_CELLS
) -> list[tuple[np.ndarray, np.ndarray, bool]]:
    """The stretches of front of ``contact`` on ``face`` (module doc): a list of (cells, ahead,
    pinned), boolean grids of the stretch's contact cells and of the layer ahead of it.

    Parameters
    ----------
    face : numpy.ndarray
        Boolean grid of the face's cells.
    contact : numpy.ndarray
        Boolean grid of the contact set (a subset of ``face``).
    min_cells : int, optional
        Fewest cells of a free stretch; smaller free pieces join the pinned stretch they touch.

    Returns
    -------
    list of tuple
        (cells, ahead, pinned) per stretch: free stretches first, then pinned ones.
    """
    outside = ~contact
    detached = face & outside
    free = contact & ndimage.binary_dilation(detached, _FOUR)
    front = contact & ndimage.binary_dilation(outside, _FOUR)
    out = []
    labels, count = ndimage.label(free, _EIGHT)
    sizes = ndimage.sum_labels(free, labels, np.arange(1, count + 1))
    for index in np.flatnonzero(sizes >= min_cells):
        cells = labels == index + 1
        front &= ~cells
        out.append((cells, detached & ndimage.binary_dilation(cells, _FOUR), False))
    labels, count = ndimage.label(front, _EIGHT)
    for label in range(1, count + 1):
        cells = labels == label
        out.append((cells, outside & ndimage.binary_dilation(cells, _FOUR), True))
    return out


def stretch_release(problem, solution, cells, ahead, settings, counters: WorkCounters) -> float:
    """G / d^2 of one stretch of the front of ``solution``'s contact set: half of dS/dA at the
    current set, from the parabola through the stiffnesses of the set with ``cells`` peeled, the
    set itself and the set with ``ahead`` added (module doc).  Two contact solves, warm-started
    from ``solution``.

    Parameters
    ----------
    problem : bem_griffith.problem.Problem
        The discretised scene (flat face).
    solution : bem_griffith.contact_set.ContactSolution
        The solved contact set.
    cells, ahead : numpy.ndarray
        Boolean grids of the stretch's contact cells and of the cells ahead of it.
    settings : bem_griffith.GriffithSettings
        The solver settings (CG tolerance, windows).
    counters : bem_griffith.counters.WorkCounters
        Counts the two solves.

    Returns
    -------
    float
        G / d^2 (nan when the difference is not positive or either solve did not converge).
    """
    contact = solution.contact
    peeled = solve_contact_set(problem, contact & ~cells, settings, solution, counters)
    added = solve_contact_set(problem, contact | ahead, settings, solution, counters)
    stiffness = [float(x.pressure_per_approach.sum()) for x in (peeled, solution, added)]
    n_peel, n_add = int(cells.sum()), int(ahead.sum())
    # dS/dA at the current set from the parabola through the three sets (the central difference
    # when both layers hold as many cells); U = d^2 S / 2, so G / d^2 = (dS/dA) / 2
    behind = (stiffness[1] - stiffness[0]) / n_peel
    beyond = (stiffness[2] - stiffness[1]) / n_add
    release = 0.5 * (n_add * behind + n_peel * beyond) / (n_peel + n_add)
    return release if release > 0 and peeled.converged and added.converged else math.nan


class EnergyReleaseRule:
    """Eq. 22's ranking with each stretch's threshold set by its energy release (module doc).
    Caches the thresholds of the last contact solution it saw (the driver asks for the next
    event and then cascades on the same solution)."""

    def __init__(self, problem, settings, counters: WorkCounters, min_cells: int = MIN_STRETCH_CELLS):
        self.problem = problem
        self.settings = settings
        self.counters = counters
        self.min_cells = min_cells
        self.nucleation_factor = NUCLEATION_FACTOR
        self.paper = PaperRule(problem.critical_stress)
        self.work_of_adhesion = problem.work_of_adhesion
        self._last: tuple[object, np.ndarray, np.ndarray] | None = None
        #: releases measured (calls of ``stretch_release``; a symmetric image takes its
        #: stretch's), and those that could not be used (not positive, or a solve that did not
        #: converge): their stretches' cells followed Eq. 22
        self.measured = 0
        self.unmeasured = 0
        #: per approach at which cells detached (the first pass there): whether every one of
        #: them was held by the nucleation cap, not by its stretch's release (event driver only:
        #: its curve point at an event is the state the cells left from)
        self.by_cap: dict[float, bool] = {}
        self._face_symmetries = [op for op in _SYMMETRIES if _invariant(problem.face, op)]
        face = problem.face
        if face[0].any() or face[-1].any() or face[:, 0].any() or face[:, -1].any():
            # the layer ahead of a pinned edge would be cut short, not left empty
            raise ValueError("the energy-release rule needs a raster with an empty ring of cells around the face")

    def symmetries(self, contact: np.ndarray) -> list:
        """The grid symmetries (flips, transposes) that map the face and ``contact`` onto
        themselves: a stretch and its image under one of them release alike."""
        return [op for op in self._face_symmetries if _invariant(contact, op)]

    def thresholds(self, solution) -> np.ndarray:
        """sigma per contact cell (row-major order of the set): sigma_R on measured free
        stretches, min(NUCLEATION_FACTOR sigma_c, sigma_R) on measured pinned ones, sigma_c
        elsewhere.  A stretch that is the image of one already measured under a symmetry of
        the face and the contact set takes its release (same physics, half or a quarter of the
        solves on the built-in faces)."""
        return self._decide(solution)[0]

    def _decide(self, solution) -> tuple[np.ndarray, np.ndarray]:
        """(sigma per contact cell, whether the nucleation cap set it), cached per solution."""
        if self._last is not None and self._last[0] is solution:
            return self._last[1], self._last[2]
        contact = solution.contact
        x1 = np.zeros(contact.shape)
        x1[contact] = solution.pressure_per_approach
        sigma = np.full(contact.shape, self.paper.critical_stress)
        capped = np.zeros(contact.shape, bool)
        size = int(contact.sum())
        if self.work_of_adhesion > 0:
            symmetries = self.symmetries(contact)
            cap = self.nucleation_factor * self.paper.critical_stress
            known: dict[bytes, float] = {}
            for cells, ahead, pinned in front_stretches(self.problem.face, contact, self.min_cells):
                count = int(cells.sum())
                if count < self.min_cells or count == size or not ahead.any():
                    continue
                release = known.get(np.packbits(cells).tobytes())
                if release is None:
                    release = stretch_release(self.problem, solution, cells, ahead, self.settings, self.counters)
                    self.measured += 1
                    self.unmeasured += not release > 0
                    for op in symmetries:
                        known[np.packbits(op(cells)).tobytes()] = release
                if not release > 0:
                    continue  # Eq. 22 there (report says so)
                critical = math.sqrt(self.work_of_adhesion / release) * float(x1[cells].max())
                if pinned and cap < critical:
                    sigma[cells], capped[cells] = cap, True
                else:
                    sigma[cells] = critical
        out = sigma[contact], capped[contact]
        self._last = (solution, *out)
        return out

    def report(self, pulloff_approach: float) -> tuple[list[str], dict]:
        out = []
        if self.unmeasured:
            out.append(
                f"criterion 'energy_release': {self.unmeasured} of its {self.measured} release measurements were not "
                "usable (a stiffness difference that was not positive, or a solve that did not converge); those "
                "stretches of front followed Eq. 22"
            )
        if self.settings.driver != "event":
            return out, {}
        by_cap = self.by_cap.get(pulloff_approach, False)
        if by_cap:
            out.append(
                f"criterion 'energy_release': the cells that let go at the pull-off were held by the nucleation cap "
                f"({self.nucleation_factor:g} sigma_c, Eq. 22), not by a measured release (a pinned front's mean "
                "release had not reached w), so the pull-off is Eq. 22's at that tension and moves with the cap"
            )
        return out, {"pulloff_by_cap": by_cap}

    def critical_approaches(self, solution) -> np.ndarray:
        per_approach = solution.pressure_per_approach
        out = np.full(per_approach.shape, np.nan)
        loaded = per_approach > 0
        # tension -d x1 = sigma  <=>  d = -sigma / x1
        out[loaded] = -self.thresholds(solution)[loaded] / per_approach[loaded]
        return out

    def detaching(self, solution, approach: float, tie_tolerance: float) -> np.ndarray:
        sigma, capped = self._decide(solution)
        tension = -approach * solution.pressure_per_approach
        roundoff = pressure_roundoff(approach, solution.pressure_per_approach)
        out = tension >= sigma * (1 - tie_tolerance) - roundoff
        if self.settings.driver == "event" and out.any() and approach not in self.by_cap:
            self.by_cap[approach] = not (out & ~capped).any()
        return out
