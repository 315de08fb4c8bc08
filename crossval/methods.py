"""The registry of methods: which solver applies to which scene.

A method is registered lazily by module path so that ``crossval scene check`` never imports a
solver, and a scene only runs through the methods that can represent it.
"""

from __future__ import annotations

import importlib
import math
from collections.abc import Callable
from dataclasses import dataclass

from contact_scene import Scene, SceneError

__all__ = ["Method", "Resolution", "Sweeps", "METHODS", "reference_method", "get_method", "applicable_methods"]


@dataclass(frozen=True)
class Resolution:
    """What a method's ``resolution`` means on one scene, and the values it accepts.

    Attributes
    ----------
    meaning : str
        What the number counts, as the refusal of a value outside the range states it.
    label : str
        The axis label of a convergence plot, e.g. ``"N: elements/radius"``.
    low : float
        The smallest accepted resolution (inclusive; the bound the method's settings enforce).
    high : float
        The largest accepted resolution (inclusive); infinite where the method sets no bound.
    per_radius : bool
        Whether it counts BEM elements per equivalent radius sqrt(A/pi) (the grid methods share
        ``crossval compare --resolution``); else the method's own measure (mesh grading, elements
        per process zone).
    below : str
        Why a value below ``low`` is refused, when there is more to say than the range; empty
        otherwise.
    above : str
        Why a value above ``high`` is refused, likewise.
    """

    meaning: str
    label: str
    low: float
    high: float
    per_radius: bool
    below: str = ""
    above: str = ""


@dataclass(frozen=True)
class Sweeps:
    """The resolutions the harness runs a method at (in the method's own ``resolution``).

    Attributes
    ----------
    study : tuple of float
        ``crossval study`` unless told otherwise.
    quick : tuple of float
        ``crossval report --quick``.
    full : tuple of float
        ``crossval report``.
    regression : float
        ``crossval regress``: one quick run per suite scene.
    compare_quick : float or None
        ``crossval compare --quick``: the method's own quick resolution where it does not count
        elements per radius (None: the shared ``--resolution``).
    full_default : bool
        Whether ``crossval report`` (full) also runs the method at its default resolution
        (``resolution=None``) and checks that result as the method's finest.  For a method whose
        default is not a point of its sweep (the energy BEM's accurate zero-range sequence
        against the coarse sequences it sweeps), the sweep still gives the error against time
        and the default gives the answer the checks hold to its bars.
    """

    study: tuple[float, ...]
    quick: tuple[float, ...]
    full: tuple[float, ...]
    regression: float
    compare_quick: float | None = None
    full_default: bool = False


@dataclass(frozen=True)
class Method:
    """A registered method: what it applies to and what its ``resolution`` means.

    Both are stated by the method's own functions so that the harness never branches on a
    method's name.  Accuracy is not here: each result carries its method's error bars
    (``Result.error_bars``).

    Attributes
    ----------
    name : str
        The key in :data:`METHODS` and the name of ``--method``.
    module : str
        The module whose ``solve_with_resolution(scene, resolution, callback=...)`` runs it,
        imported only when a scene is solved.
    description : str
        One line for listings.
    applies : callable
        ``applies(scene)``: None when the method can represent the scene, else the reason it
        cannot.
    resolution : callable
        ``resolution(scene)``: the :class:`Resolution` (meaning and accepted range) on that scene.
    sweeps : Sweeps
        The resolutions the harness runs it at.
    reference_kind : str
        How its results serve as a reference where no closed form exists: ``"bounded"`` (one
        result with a bound on its error), ``"sequence"`` (a limit extrapolated in 1/N over >= 3
        grids), or ``""`` (not a reference).
    uses_range : bool
        Whether the method models a finite interaction range (``adhesion.range``, ``--range``);
        the others are zero-range (Griffith) methods and would silently ignore it.
    grid_kernel : str or None
        The half-space discretisation of its single-grid solves (:mod:`halfspace`: ``"love"`` for
        Love's uniform-pressure squares, ``"collocation"`` for point-collocated Boussinesq
        coefficients), so that two methods' stiffnesses on one grid are held to their kernels'
        measured difference; None for a method without a grid.
    """

    name: str
    module: str
    description: str
    applies: Callable[[Scene], str | None]
    resolution: Callable[[Scene], Resolution]
    sweeps: Sweeps
    reference_kind: str = ""
    uses_range: bool = False
    grid_kernel: str | None = None

    def resolution_meaning(self, scene: Scene) -> str:
        """What ``resolution`` (``--resolution``) means for this method on this scene.

        Parameters
        ----------
        scene : contact_scene.Scene
            The scene to be solved.

        Returns
        -------
        str
            E.g. "elements per equivalent radius sqrt(A/pi)".
        """
        return self.resolution(scene).meaning

    def resolution_range(self, scene: Scene) -> tuple[float, float]:
        """The resolutions this method accepts for ``scene``.

        Parameters
        ----------
        scene : contact_scene.Scene
            The scene to be solved.

        Returns
        -------
        tuple of float
            ``(low, high)``, inclusive: the bounds its settings enforce, expressed as
            ``resolution``; ``high`` may be infinite.
        """
        r = self.resolution(scene)
        return r.low, r.high

    def resolution_is_grid(self, scene: Scene) -> bool:
        """Whether ``resolution`` means BEM elements per radius for this scene.

        The FEM's is a mesh grading, the zero-range energy method's elements per process zone.

        Parameters
        ----------
        scene : contact_scene.Scene
            The scene to be solved.

        Returns
        -------
        bool
            True where it counts elements per equivalent radius sqrt(A/pi).
        """
        return self.resolution(scene).per_radius

    def check_resolution(self, scene: Scene, resolution: float | None, *, field: str = "resolution") -> None:
        """Raise SceneError, in terms of ``resolution``, if the method cannot run at it.

        Parameters
        ----------
        scene : contact_scene.Scene
            The scene to be solved.
        resolution : float or None
            The resolution asked for; None (the method's default) is always accepted.
        field : str, optional
            The name the error gives the value (e.g. a command-line option).

        Raises
        ------
        contact_scene.SceneError
            If ``resolution`` is not a finite number > 0 or lies outside
            :meth:`resolution_range`; the message states the range (rounded inward to two
            significant digits), why a value beyond it is refused where there is more to say,
            and what ``resolution`` means.
        """
        if resolution is None:
            return
        if isinstance(resolution, bool) or not isinstance(resolution, (int, float)):
            raise SceneError(field, f"must be a finite number > 0 (got {resolution!r})")
        if not (math.isfinite(resolution) and resolution > 0):
            raise SceneError(field, f"must be a finite number > 0 (got {resolution:g})")
        r = self.resolution(scene)
        if r.low <= resolution <= r.high:
            return
        limits = (
            f"from {_nice(r.low, up=True)} to {_nice(r.high, up=False)}"
            if math.isfinite(r.high)
            else f"{_nice(r.low, up=True)} or more"
        )
        why = r.above if resolution > r.high else r.below
        why = f" ({why})" if why else ""
        raise SceneError(field, f"{self.name} takes {limits} here{why}; it means {r.meaning} (got {resolution:g})")

    def solve(self, scene: Scene, *, resolution: float | None = None, callback=None):
        """Solve ``scene`` with this method at ``resolution``.

        The resolution is checked first (:meth:`check_resolution`), then the method's module is
        imported and its ``solve_with_resolution`` runs.

        Parameters
        ----------
        scene : contact_scene.Scene
            The scene to solve.
        resolution : float or None, optional
            In the method's own measure (:meth:`resolution_meaning`); None for its default.
        callback : callable, optional
            ``callback(approach, force, contact_area)`` at the points the method records
            (progress).

        Returns
        -------
        contact_scene.Result
            As the method's ``solve_with_resolution`` returns it.

        Raises
        ------
        contact_scene.SceneError
            If the resolution is refused, or the method's solver refuses a field of the scene.
        """
        self.check_resolution(scene, resolution)
        mod = importlib.import_module(self.module)
        return mod.solve_with_resolution(scene, resolution, callback=callback)


def _nice(x: float, *, up: bool) -> str:
    """A bound as a user would type it: rounded inward to 2 significant digits."""
    if x == 0 or not math.isfinite(x):
        return f"{x:g}"
    scale = 10 ** (math.floor(math.log10(abs(x))) - 1)
    return f"{(math.ceil(x / scale) if up else math.floor(x / scale)) * scale:g}"


_PER_RADIUS = "elements per equivalent radius sqrt(A/pi)"
_N_PER_RADIUS = "N: elements/radius"
_TOO_COARSE = "coarser grids put fewer than 4 elements across the incircle of the face's smallest separate part"


def _coarsest_grid(scene: Scene) -> float:
    from contact_scene.raster import MIN_INCIRCLE_CELLS

    shape = scene.indenter.shape
    return MIN_INCIRCLE_CELLS * shape.equivalent_radius / (2 * shape.smallest_part_incircle().radius)


def _zero_range_only(scene: Scene, name: str) -> str | None:
    """Why a zero-range method does not represent a scene with a finite interaction range: it
    would solve the Griffith limit and ignore the range without a word."""
    rho = scene.adhesion.range
    if rho is not None and scene.adhesion.work_of_adhesion > 0:
        return f"{name} models zero-range (Griffith) adhesion; the scene's adhesion.range = {rho:g} is finite"
    return None


def _griffith_applies(scene: Scene) -> str | None:
    # any face, profile, homogeneous or power-law graded half-space, at zero range
    return _zero_range_only(scene, "bem_griffith")


def _griffith_resolution(scene: Scene) -> Resolution:
    from bem_griffith.solver import max_elements_per_radius

    return Resolution(
        _PER_RADIUS,
        _N_PER_RADIUS,
        _coarsest_grid(scene),
        float(max_elements_per_radius(scene)),
        True,
        below=_TOO_COARSE,
        above="a finer grid needs more than the solver's memory limit",
    )


def _fem_applies(scene: Scene) -> str | None:
    from fem_reference import applies

    return _zero_range_only(scene, "fem_reference") or applies(scene)


def _fem_resolution(scene: Scene) -> Resolution:
    from fem_reference.solver import MAX_ISOTROPIC_GRADING

    graded = getattr(scene.material, "exponent", 0.0) > 0  # the tensor mesh (fem_reference.model)
    # FemSettings.grading in [0.05, 4]; resolution = 1 / grading
    return Resolution(
        "mesh refinement 1/grading (elements grow by at most 1/resolution x their distance from the punch edge)",
        "N: 1/grading",
        1 / (4.0 if graded else MAX_ISOTROPIC_GRADING),
        1 / 0.05,
        False,
    )


def _energy_applies(scene: Scene) -> str | None:
    import contact_scene as cs

    if not isinstance(scene.material, cs.Homogeneous):
        return "the energy method is validated for homogeneous half-spaces only"
    if scene.adhesion.range is None and scene.adhesion.work_of_adhesion > 0 and not scene.indenter.profile.is_flat:
        return (
            "its zero-range extrapolation is calibrated on flat faces (the edge of a flat punch); "
            "give adhesion.range to run a finite range"
        )
    return None


def _energy_resolution(scene: Scene) -> Resolution:
    if scene.adhesion.range is None and scene.adhesion.work_of_adhesion > 0:
        # ZeroRangeSettings.elements_per_process_zone
        return Resolution(
            "elements per process zone l_c of each range of the zero-range sequence",
            "N: elements/process zone",
            0.25,
            64.0,
            False,
        )
    from bem_energy import EnergySettings
    from bem_energy.problem import max_elements_per_radius

    return Resolution(
        _PER_RADIUS,
        _N_PER_RADIUS,
        _coarsest_grid(scene),
        float(max_elements_per_radius(scene, memory=EnergySettings().memory)),
        True,
        below=_TOO_COARSE,
        above="a finer grid needs more than the solver's memory limit",
    )


METHODS: dict[str, Method] = {
    "bem_griffith": Method(
        "bem_griffith",
        "bem_griffith",
        "FFT boundary elements with the Pohrt-Popov local Griffith detachment criterion",
        _griffith_applies,
        _griffith_resolution,
        # quick: the finest is checked, and its bars shrink like 1/N (bem_griffith.error_model):
        # 32 per radius costs about twice 16 on the suite and halves the bars
        Sweeps(study=(8, 12, 16, 24, 32), quick=(16, 24, 32), full=(16, 24, 32, 48, 64), regression=16),
        reference_kind="sequence",
        grid_kernel="love",
    ),
    "bem_energy": Method(
        "bem_energy",
        "bem_energy",
        "FFT boundary elements minimising elastic + finite-range adhesive energy (zero-range limit by extrapolation)",
        _energy_applies,
        _energy_resolution,
        # zero-range limit: elements per process zone of the coarse sequence; the full report
        # checks the accurate default sequence (l_c down to 0.01 a), whose bars are a few times
        # narrower than the coarse sequence's
        Sweeps(
            study=(1.0, 2.0, 3.0), quick=(1.0,), full=(1.0, 2.0), regression=1.0, compare_quick=1.0, full_default=True
        ),
        uses_range=True,
        grid_kernel="collocation",  # EnergySettings.kernel's default
    ),
    "fem_reference": Method(
        "fem_reference",
        "fem_reference",
        "axisymmetric Taylor-Hood finite elements with a Griffith energy release rate (circular faces)",
        _fem_applies,
        _fem_resolution,
        # quick: one mesh; its own bound is its error bar, and as the reference it has no error to plot
        Sweeps(study=(0.5, 2 / 3, 1.0), quick=(0.5,), full=(0.5, 2 / 3, 1.0), regression=0.5),
        reference_kind="bounded",
    ),
}


def get_method(name: str) -> Method:
    """The registered method of that name.

    Parameters
    ----------
    name : str
        A key of :data:`METHODS`: ``"bem_griffith"``, ``"bem_energy"`` or ``"fem_reference"``.

    Returns
    -------
    crossval.methods.Method
        What it applies to, what its resolution means, and how to run it.

    Raises
    ------
    contact_scene.SceneError
        Field ``method``, if no method has that name; the message lists the available ones.
    """
    if name not in METHODS:
        raise SceneError("method", f"unknown method {name!r}; available: {', '.join(sorted(METHODS))}")
    return METHODS[name]


def reference_method(scene: Scene, kind: str) -> Method | None:
    """The first registered method that applies to ``scene`` and serves as a reference of ``kind``.

    Parameters
    ----------
    scene : contact_scene.Scene
        The scene a reference is needed for.
    kind : str
        ``Method.reference_kind``: ``"bounded"`` or ``"sequence"``.

    Returns
    -------
    crossval.methods.Method or None
        In registration order; None if no applicable method serves as that kind of reference.
    """
    return next((m for m in METHODS.values() if m.reference_kind == kind and m.applies(scene) is None), None)


def applicable_methods(scene: Scene) -> list[Method]:
    """The registered methods that can represent ``scene``.

    A scene runs only through these; each of the others states why not (``Method.applies``).

    Parameters
    ----------
    scene : contact_scene.Scene
        The scene to be solved.

    Returns
    -------
    list of crossval.methods.Method
        In registration order (:data:`METHODS`): those whose ``applies(scene)`` is None.
    """
    return [m for m in METHODS.values() if m.applies(scene) is None]
