"""Discretisation and solver settings of the energy-minimisation BEM."""

from __future__ import annotations

from dataclasses import dataclass, field

from contact_scene import Grid, SceneError
from contact_scene.validation import check_fields, choice, flag, real, reals, whole

__all__ = ["EnergySettings", "ZeroRangeSettings"]


@dataclass(frozen=True)
class EnergySettings:
    """How one finite-range pull-off is discretised and solved.

    Parameters
    ----------
    grid : contact_scene.Grid, optional
        Element size, as for the Griffith solver (32 elements per radius by default).  The
        process zone l_c = E* rho^2 / w needs a potential's fewest elements
        (``bem_energy.potentials.PROCESS_ZONE_ELEMENTS``: one for the exponential potential,
        16 for Maugis-Dugdale; more on a graded body, ``process_zone_elements``); a coarser
        grid is run, but the result is not converged and its messages say which resolution
        suffices.  ``bem_energy.finite_range_grid`` picks a grid
        that resolves it.  A periodic grid is refused when solving: the method models the
        infinite half-space.
    minimiser : str, optional
        ``"pk"`` (default): a projected, Fourier-preconditioned conjugate-gradient iteration
        in the style of Polonsky-Keer and Rey et al.  ``"lbfgsb"``: scipy's bound-constrained
        L-BFGS-B on the surface displacement of the zero-padded grid (bounds = the hard wall on
        the face); the same answer about 20x slower (benchmarks/bench_energy.py).  ``"cvxpy"``:
        Newton's method on dense face matrices with the contact set from a convex QP solved
        by cvxpy, for small grids only (``max_face_elements_cvxpy``); a whole pull-off agrees
        with ``"pk"`` to the minimisers' tolerance (tests/test_energy_finite_range.py).
    steps : int, optional
        Continuation steps over the default pull range, in [2, 100000]; 40 by default.  The
        snap-off is then located by bisection to ``snap_tolerance``.
    snap_tolerance : float, optional
        The bisection's tolerance on the snap-off approach, relative to abs(d_c) of the circle
        of the face's area (Eq. 14; Eq. 38 graded) plus the range rho, in (0, 0.1]; 1e-3 by
        default (it is also Brent's tolerance on a smooth maximum).  1e-3 against 1e-4 took the
        256 x 256 circle from 27 s to 18 s for a change of 4e-8 in F_A (a smooth maximum,
        refined by Brent) and moved the suite's fold-limited cases by at most 3e-4
        (benchmarks/bench_energy.py, crossval regress).
    gtol : float, optional
        Stop when the projected gradient of the scaled energy is below this (scaled so that
        the adhesive stress and the elastic stiffness of one element are of order one), in
        (0, 1e-2]; 1e-6 by default.
    max_iterations : int, optional
        Iteration cap of each minimisation, >= 1; 50000 by default.
    memory : int, optional
        L-BFGS-B's correction pairs (also sizing the memory estimate of the grid), in [1, 100];
        10 by default.
    max_face_elements_cvxpy : int, optional
        The most face elements the ``"cvxpy"`` minimiser accepts (a larger face is refused when
        solving), >= 1; 700 by default.
    kernel : str, optional
        The discretisation of the half-space.  ``"collocation"`` (default): point-collocated
        Boussinesq coefficients (A_k Delta^2 / r^(1+k) for a graded body) with the lattice-
        consistent self term (``halfspace.collocation``), a discretisation of its own, so that
        agreement with the Griffith solver, which uses Love's element integrals, checks both
        kernels.  ``"love"``: Love's uniformly loaded squares (the graded analogue for a graded
        body), the Griffith solver's kernel: on the same grid the two methods then solve the
        same discrete elastic problem (same stiffness to the minimisers' tolerance).  The flat
        circle's stiffness converges like 1/N with both, about -0.16/N (collocation) and
        -0.12/N (Love) at the raster's area; on a common grid Love's squares are stiffer by
        0.045/N to 0.069/N over the faces measured (benchmarks/study_halfspace_kernels.py,
        tests/test_halfspace.py).
    locate_detachment : bool, optional
        Bisect the snap-off to ``snap_tolerance`` even once the recorded attached states
        bracket a smooth force maximum, for the detachment approach and the last stable state
        (True, the default).  False: stop there (the detachment approach is then known to the
        bracket's width only); the force maximum is refined by Brent either way, and a fold is
        still bisected.
    stop_peeling_trials : bool, optional
        Stop a pulling step whose contact falls below (1 - s) of its most during the
        minimisation, s = max(0.1, 10 l_c / a), and converge its detached state from U = 0
        (projected CG only; see ``Equilibria.pulling_trial``): a detaching minimisation
        otherwise creeps for about a hundred iterations and then peels one ring of cells per
        iteration.  True by default.
    restart_on_wall_change : bool, optional
        Projected CG only: restart the conjugate directions from steepest descent whenever the
        set of face cells held at the wall changes (Polonsky-Keer's rule).  False (the default)
        keeps the direction, projected onto the new free set: peeling states change that set
        at nearly every iteration, and the restarts were half of all iterations of a zero-range
        sequence.  The minima agree to the tolerance ``gtol``; a pull-off's path, and so its
        F_A, moves within the method's path noise (benchmarks/bench_energy_zero_range.py).
    single_precision_directions : bool, optional
        Projected CG only: the pressure of each search direction from single-precision FFTs
        (cheaper than double precision: ``benchmarks/bench_matvec.py``), with the pressure
        recomputed in double precision every 50 iterations and before a minimum is accepted,
        so that convergence is judged on the double-precision gradient.  On in
        :func:`sequence_energy_settings`, where the finest ranges dominate the time and their
        forces move far less than the method's path noise
        (``benchmarks/bench_energy_zero_range.py``).  False by default: single-precision
        rounding does not scale with the problem, so a problem scaled in its units then follows
        another path and its F_A agrees to the minimisers' tolerance instead of to
        double-precision round-off.
    peak_tolerance : float or None, optional
        Refine the force maximum to this fraction of it, in (0, 0.01], rather than to
        ``snap_tolerance`` in the approach alone.  The snap-off search (with
        ``locate_detachment=False``) then stops once the last three attached states flatten
        clearly (the last secant slope of the tension below half the one before) and the
        tension, assumed concave beyond them, cannot rise by more than this before the first
        detached state; its trials go close to where that bound is met rather than halfway
        (``bem_energy.peak.locate_snap_off``).  Brent's tolerance on a smooth maximum becomes
        the distance at which the parabola through the maximum's bracket loses this fraction,
        where that is the larger.  A tension that does not flatten, as toward a fold, is
        bisected to ``snap_tolerance``.  None (the default): the approach tolerance
        only.

    Raises
    ------
    contact_scene.SceneError
        Naming ``settings.<field>`` and its allowed values, for a value outside them;
        ``settings.grid`` when ``grid`` is not a :class:`~contact_scene.Grid`.
    """

    grid: Grid = field(default_factory=lambda: Grid(elements_per_radius=32))
    minimiser: str = choice("pk", ("lbfgsb", "pk", "cvxpy"))
    steps: int = whole(40, ge=2, le=100_000)
    snap_tolerance: float = real(1e-3, gt=0, le=0.1)
    gtol: float = real(1e-6, gt=0, le=1e-2)
    max_iterations: int = whole(50_000, ge=1)
    memory: int = whole(10, ge=1, le=100)
    max_face_elements_cvxpy: int = whole(700, ge=1)
    kernel: str = choice("collocation", ("collocation", "love"))
    locate_detachment: bool = flag(True)
    stop_peeling_trials: bool = flag(True)
    restart_on_wall_change: bool = flag(False)
    single_precision_directions: bool = flag(False)
    peak_tolerance: float | None = real(None, gt=0, le=0.01, optional=True)

    def __post_init__(self):
        # a type, not a range
        if not isinstance(self.grid, Grid):
            raise SceneError("settings.grid", "must be a contact_scene.Grid")
        check_fields(self, "settings")


def default_grid() -> Grid:
    """``EnergySettings``' default grid."""
    factory = EnergySettings.__dataclass_fields__["grid"].default_factory
    assert callable(factory)
    return factory()


#: the force tolerance of a zero-range sequence's ranges, relative to F_A: the smallest path
#: noise measured (benchmarks/study_energy_noise.py, docs/performance.md)
PEAK_TOLERANCE = 3e-4


def sequence_energy_settings() -> EnergySettings:
    """The finite-range settings of a zero-range sequence: each range contributes only its
    force maximum, so the snap-off is not bisected once a smooth maximum is bracketed
    (``locate_detachment=False``).  The snap tolerance, which is also Brent's on a smooth
    maximum, stays at the default: near the maximum F(d) is jagged at the 3e-4 to 1e-3 level
    (benchmarks/study_energy_noise.py), and a 4x looser one moved the coarse sequences'
    limits by 1e-3 where this keeps every range's force.  The search directions' pressures
    are computed in single precision (``single_precision_directions``): the finest ranges
    dominate a sequence's time, and this moves their forces far less than the path noise.
    The force maximum is refined to ``PEAK_TOLERANCE`` of itself (``peak_tolerance``): the
    smallest spread of F_A over continuation step counts measured (the circle at l_c = 0.04 a,
    docs/performance.md; the finest ranges spread more, docs/references.md), so that no
    refinement is paid for below the path noise.  On a circle it spares the snap-off search
    the trials that detach within a hair of the snap-off, the slowest of a sequence."""
    return EnergySettings(locate_detachment=False, single_precision_directions=True, peak_tolerance=PEAK_TOLERANCE)


#: the smallest quotient of two consecutive process-zone ratios of a zero-range sequence: the
#: error estimate divides the last step by t^q - 1, which vanishes as the quotient t -> 1
MIN_RATIO_STEP = 1.5


@dataclass(frozen=True)
class ZeroRangeSettings:
    """The JKR (zero-range) limit of the energy BEM: finite-range runs extrapolated to l_c -> 0.

    Finite-range runs at process zones l_c = r * a (a = sqrt(A/pi)) for r in ``ratios``, each
    on a grid with ``elements_per_process_zone`` elements per l_c (and at least
    ``minimum_elements_per_radius``), are extrapolated to l_c -> 0 by a least-squares fit of
    F0 + c l_c^p (see :func:`bem_energy.richardson`): p fitted when ``rate`` is None (the
    default; needs three ratios), else fixed.

    The default ratios reach l_c = 0.01 a: the circle's and the square's local rates still
    change below 0.04 a (benchmarks/study_energy_zero_range.py), and sequences stopping there
    missed the square's limit by 5 %.

    Parameters
    ----------
    ratios : tuple of float, optional
        The process-zone ratios l_c / a, each in (0, 1], at least two (three with a fitted rate),
        consecutive ones apart by a factor of at least ``MIN_RATIO_STEP`` (1.5); stored in
        decreasing order.  (0.08, 0.04, 0.02, 0.01) by default.
    elements_per_process_zone : float, optional
        Elements per l_c of each run's grid, in [0.25, 64]; 2 by default.  A graded body's
        grids get ``bem_energy.potentials.graded_zone_elements(k)`` times as many (4 at
        k = 0.5), which resolve its zone as well.
    rate : float or None, optional
        The exponent p of the fit, in (0, 4]; None (the default) to fit it.
    minimum_elements_per_radius : float, optional
        The fewest elements per radius a of any run's grid, in [4, 1e4]; 24 by default.
    potential : str, optional
        The finite-range potential of the runs, ``"exponential"`` (default) or
        ``"maugis_dugdale"``.
    normalise_area : bool, optional
        Scale each run's force to the nominal face area (the staircase area changes from grid
        to grid); True by default.
    energy : EnergySettings, optional
        The settings of each range (:func:`sequence_energy_settings` by default); their grid
        is replaced by each run's, so it must be left at its default.

    Raises
    ------
    contact_scene.SceneError
        Naming ``settings.<field>`` and its allowed values, for a value outside them;
        ``settings.ratios`` for fewer than two distinct ratios, fewer than three with a
        fitted rate, or two closer than a factor ``MIN_RATIO_STEP``; ``settings.energy.grid``
        for a grid other than the default.
    """

    ratios: tuple[float, ...] = reals((0.08, 0.04, 0.02, 0.01), gt=0, le=1)
    elements_per_process_zone: float = real(2.0, ge=0.25, le=64)
    rate: float | None = real(None, gt=0, le=4, optional=True)
    minimum_elements_per_radius: float = real(24.0, ge=4, le=1e4)
    potential: str = choice("exponential", ("exponential", "maugis_dugdale"))
    normalise_area: bool = flag(True)
    energy: EnergySettings = field(default_factory=sequence_energy_settings)

    @classmethod
    def coarse(cls, elements_per_process_zone: float = 1.0, **kw) -> ZeroRangeSettings:
        """The cheap sequence the harness sweeps (seconds, not minutes): l_c / a = 0.32 ... 0.04.

        The rate is fixed at 1/2, which the circle follows there (within 0.1 % of Kendall).
        Faces with corners converge faster than sqrt(l_c) below 0.04 a, so this sequence
        overshoots their limit: 0.935 and 0.864 of Eq. 13 for the square and the triangle
        against 0.881 and 0.810 from the default sequence
        (benchmarks/study_energy_zero_range.py).

        Parameters
        ----------
        elements_per_process_zone : float, optional
            Elements per l_c of each run's grid, in [0.25, 64]; 1 by default.
        **kw
            Other fields of :class:`ZeroRangeSettings`, overriding the sequence's
            (``ratios=(0.32, 0.16, 0.08, 0.04)``, ``rate=0.5``) where given.

        Returns
        -------
        ZeroRangeSettings
            The coarse sequence's settings.
        """
        kw.setdefault("ratios", (0.32, 0.16, 0.08, 0.04))
        kw.setdefault("rate", 0.5)
        return cls(elements_per_process_zone=elements_per_process_zone, **kw)

    def __post_init__(self):
        check_fields(self, "settings")
        if not isinstance(self.energy, EnergySettings):
            raise SceneError("settings.energy", "must be a bem_energy.EnergySettings")
        if self.energy.grid != default_grid():
            # a grid given here would be replaced by each range's without a word
            raise SceneError(
                "settings.energy.grid",
                "each range of the sequence runs on its own grid (elements_per_process_zone per l_c, at least "
                "minimum_elements_per_radius per radius); set those instead, and leave the grid at its default",
            )
        # how many ratios a fit needs depends on the rate: a rule on the sequence, not a range
        rs = self.ratios
        if len(rs) < 2 or len(set(rs)) != len(rs):
            raise SceneError("settings.ratios", "need at least two distinct process-zone ratios l_c / a")
        if self.rate is None and len(rs) < 3:
            raise SceneError(
                "settings.ratios",
                "a fitted rate (rate = None) needs at least three process-zone ratios; "
                "give three or more, or a fixed rate",
            )
        ordered = tuple(sorted(rs, reverse=True))
        closest = min(coarse / fine for coarse, fine in zip(ordered, ordered[1:], strict=False))
        if closest < MIN_RATIO_STEP * (1 - 1e-12):  # 0.3 / 0.2 is 1.4999999999999998
            # the error estimate rests on the last step F(l_n) - F(l_n-1) over t^q - 1 (t the two
            # finest ratios' quotient): as t -> 1 the step shrinks into the ranges' path noise and
            # the estimate says nothing; it is validated on halving sequences
            raise SceneError(
                "settings.ratios",
                f"consecutive process-zone ratios must differ by a factor of at least {MIN_RATIO_STEP:g} "
                f"(got {closest!r}); halving sequences such as 0.08, 0.04, 0.02, 0.01 are what the "
                "error estimate is validated on",
            )
        object.__setattr__(self, "ratios", ordered)
