"""Discretisation and solver settings of the Griffith BEM (kept apart from the scene's physics)."""

from __future__ import annotations

from dataclasses import dataclass, field

from contact_scene import Grid, SceneError
from contact_scene.validation import check_fields, choice, flag, real, whole
from halfspace.operator import default_workers

from .criterion import CRITERIA

__all__ = ["GriffithSettings"]


@dataclass(frozen=True)
class GriffithSettings:
    """How the Pohrt-Popov BEM discretises and drives a scene.

    Parameters
    ----------
    grid : contact_scene.Grid, optional
        Element size (``Grid.elements_per_radius`` across sqrt(A/pi), or ``Grid.spacing``);
        32 elements per radius by default.
    driver : str, optional
        ``"event"`` (default): with the contact set fixed the state is linear in the approach,
        so the next approach at which an element reaches sigma_c (or a gap closes) is computed
        exactly; the curve does not depend on any step.  ``"fixed_step"``: the paper's driver,
        pulling in steps of ``step``.
    step : float or None, optional
        The approach increment of the fixed-step driver (a length), > 0; required by that
        driver, unused by the event driver.  None by default.
    rtol : float, optional
        Conjugate-gradient tolerance (relative residual) per contact solve, in (0, 1e-2];
        1e-10 by default.
    maxiter : int, optional
        Conjugate-gradient iteration cap per contact solve, >= 1; 2000 by default.
    tie_tolerance : float, optional
        tau: a cascade pass detaches every element whose tension reaches sigma_c (1 - tau), so
        that symmetric partners (tensions equal up to floating-point round-off) leave
        together; in [1e-12, 1e-2], 1e-6 by default (at 0 an element that sits at sigma_c to
        round-off might never leave).  A larger tau merges events whose approaches lie within
        a relative tau into one cascade, at a bounded cost, for the event driver under
        ``criterion = "paper"`` (Eq. 22; Eq. 42 on graded bodies) on a flat face pulled
        without turning points on a non-periodic homogeneous or 0 <= k <= 0.95 half-space: the
        contact set at every approach d lies inside that of the exact pull (ties to round-off
        only, tau -> 0) at d and contains the exact pull's at d / (1 - tau), so F_A and the
        detachment approach (not the approach at F_A) lie between (1 - tau) times the exact
        values and the exact values, up to the CG tolerance (``tests/test_bem_griffith_ties.py``).
        Its premises, that tensions grow as elements leave (C_SS^-1 has no positive
        off-diagonal entry) and that no free gap closes, hold on every contact set when no
        off-diagonal coefficient of the infinite element lattice's C^-1 is positive, which is
        computed at seven exponents from 0 to 0.95, not proven (it fails at k = -0.1;
        docs/methods.md); and neither the early decisions nor the Eq. 14 cut changes where a
        cascade ends.  The fixed-step driver breaks the bound (tested); the stress-intensity
        criterion is not covered.  What tau = 1e-3 saves and moves on seven of the suite's flat
        faces and on the paper's 512^2 star is measured in docs/performance.md.
    stop_when_certainly_detached : bool, optional
        Flat faces only (True by default): a cascade at fixed approach d ends as soon as abs(d)
        exceeds (1 + m) times the upper-bound critical approach (Eq. 14) of the remaining
        contact area A', m = max(certainty_margin, 2 Delta / sqrt(A'/pi)): no face of that area
        holds there in the continuum, and the margin covers the discretisation error, which
        grows like Delta / a.  Saves the tail of the cascade; the pull-off force and the
        detachment approach are unchanged (tested against the uncut cascade).
    certainty_margin : float, optional
        The smallest margin m of ``stop_when_certainly_detached``, > 0; 0.02 by default.
    workers : int, optional
        FFT threads per solve, in [1, 256]; ``halfspace.operator.default_workers()`` (1) by
        default.
    max_memory_gb : float, optional
        Refuse grids whose estimated working memory (in GB) exceeds this, > 0; 8 by default.
    preconditioner : str, optional
        ``"fourier"`` (default): the inverse of the Fourier symbol of the element lattice
        (``halfspace.kernel.lattice_symbol``), applied on the padded grid in single precision; it cuts
        CG iterations several-fold (``bench_griffith_pulloff.py``) at the cost of one extra FFT pair each, also for
        elongated grids and k < 0, where the padded window's own symbol is a poor one.
        ``"none"``: plain conjugate gradients.
    shrink_window : bool, optional
        ``True`` (default): when the contact set has shrunk into a markedly smaller box of the
        grid (padded FFT size <= 90 %), its solves run on that box's padded grid, with the
        same coefficients C_SS (``HalfSpaceOperator.window``); one full-grid product per solve
        then gives the gaps of the whole face (not for the passes decided early while pulling
        where ``Problem.walk_bounds`` holds, which need no gaps).  Same contact sets, forces to round-off; it pays
        on faces whose contact shrinks early, like a star's, whose tips detach first
        (``bench_griffith_pulloff.py``); circles hardly shrink and are unaffected.
    decide_early : bool, optional
        Under the paper's criterion (True by default): within a cascade at a fixed
        approach, a contact set from which more elements leave is solved only until a bound on
        its error shows which elements detach and which gaps close (with the Fourier
        preconditioner, the error's energy norm from the preconditioned residual, times the
        lattice's inverse diagonal for the pressures and sqrt(C_00) for the displacements;
        without it, the CG residual over a lower bound of C_SS's eigenvalues); only the set
        that holds is solved to ``rtol``.  On a curved face the passing set is solved for its
        pressure at the cascade's approach alone (one CG run instead of x1 and xh), and the
        set that holds for both.  While pulling a flat face where ``Problem.walk_bounds`` holds (a
        property of the element lattice computed at seven exponents, not proven), the gaps are
        known to be open and are not checked, and only the tensions at or above the threshold
        must be certain: a pass may keep a cell that a full solve would detach, which leaves a
        pass later (tensions only grow as cells leave), so each cascade ends at the same
        contact set as with full solves.  Elsewhere each pass's decisions are those of a full
        solve.  Either way the contact sets and the curve are those of full solves (forces to
        the CG tolerance), with fewer CG iterations (``bench_griffith_pulloff.py``).
    local_warm_start : bool, optional
        True by default: a contact set that differs from the previous one by a few cells starts
        CG from the previous pressures corrected on the cells near the change (the residual
        there solved exactly with the dense C of those cells), which removes most of the
        residual the change leaves; the solution is the same to the CG tolerance, with fewer
        CG iterations (``bench_griffith_pulloff.py``).
    graded_criterion : str, optional
        Graded bodies only: ``"calibrated"`` (default) divides Eq. 42's sigma_c by r(k), the
        factor by which the flat circle's pull-off under it misses Eq. 39, relative to the
        homogeneous circle on the same grid (``bem_griffith.criterion``, -0.95 <= k <= 0.95);
        ``"eq42"`` keeps the theory sheet's constant (any k).
    criterion : str, optional
        The detachment rule of the pull.  ``"paper"`` (default): the paper's local criterion,
        an element detaches when its tension reaches sigma_c (Eq. 22; Eq. 42 for graded
        bodies).  ``"stress_intensity"``: a front cell detaches when the stress-intensity
        factor fitted to the pressure 8-24 or more cells behind it reaches sqrt(2 E* w)
        (``bem_griffith.stress_intensity``); it removes the staircase bias of Eq. 22 on
        curved and rotated edges, so it converges on smooth fronts (Kendall's circle), but
        on faces with corners its pull-off comes out low (square and triangle: 1-2 % below
        the energy BEM), because its fit over-estimates K while a detached corner is smaller
        than the fitting window and a detached cell never re-attaches.  ``"energy_release"``:
        Eq. 22's ranking of the front cells, with the threshold of each stretch of front set
        so that its most stressed cell leaves when the stretch's energy release rate, measured
        by a three-point difference of the solver's own stiffness, reaches w
        (``bem_griffith.energy_release``); no constant calibrated on a straight edge, so no
        staircase bias, and no fitting window, so it holds at corners; several times the
        paper rule's solves; homogeneous and graded bodies.  Both alternatives: flat punches on
        non-periodic half-spaces only, ``"stress_intensity"`` on homogeneous ones.

    Raises
    ------
    contact_scene.SceneError
        Naming ``settings.<field>`` and its allowed values, for a value outside them;
        ``settings.grid`` when ``grid`` is not a :class:`~contact_scene.Grid`;
        ``settings.step`` for the fixed-step driver without a step, or for a step given to the
        event driver; ``settings.criterion``
        for ``"stress_intensity"`` or ``"energy_release"`` on a periodic grid.
    """

    grid: Grid = field(default_factory=lambda: Grid(elements_per_radius=32))
    driver: str = choice("event", ("event", "fixed_step"))
    step: float | None = real(None, gt=0, optional=True, when=lambda s: s.driver == "fixed_step")
    rtol: float = real(1e-10, gt=0, le=1e-2)
    maxiter: int = whole(2000, ge=1)
    tie_tolerance: float = real(1e-6, ge=1e-12, le=1e-2)
    stop_when_certainly_detached: bool = flag(True)
    certainty_margin: float = real(0.02, gt=0)
    workers: int = whole(ge=1, le=256, factory=default_workers)
    max_memory_gb: float = real(8.0, gt=0)
    preconditioner: str = choice("fourier", ("none", "fourier"))
    shrink_window: bool = flag(True)
    decide_early: bool = flag(True)
    local_warm_start: bool = flag(True)
    graded_criterion: str = choice("calibrated", tuple(CRITERIA))
    criterion: str = choice("paper", ("paper", "stress_intensity", "energy_release"))

    def __post_init__(self):
        # a type, not a range
        if not isinstance(self.grid, Grid):
            raise SceneError("settings.grid", "must be a contact_scene.Grid")
        check_fields(self, "settings")
        # rules joining two fields, not ranges of one
        if self.driver == "fixed_step" and self.step is None:
            raise SceneError("settings.step", "the fixed-step driver needs step > 0")
        if self.driver == "event" and self.step is not None:
            # a step given to the event driver would be ignored without a word
            raise SceneError(
                "settings.step",
                "only the fixed-step driver takes a step (driver = 'fixed_step'); the event driver finds "
                "every event exactly and takes none",
            )
        if self.criterion in ("stress_intensity", "energy_release") and self.grid.periodic:
            why = (
                "its front windows do not wrap"
                if self.criterion == "stress_intensity"
                else "its pinned fronts need the ring of cells around the face"
            )
            raise SceneError(
                "settings.criterion",
                f"{self.criterion!r} does not support a periodic grid ({why}); "
                "use criterion = 'paper' or periodic = false",
            )
