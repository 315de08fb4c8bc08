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
    """What a method's ``resolution`` means on one scene, and the values it accepts."""

    meaning: str
    #: the axis label of a convergence plot, e.g. "N: elements/radius"
    label: str
    low: float
    high: float
    #: whether it counts BEM elements per equivalent radius sqrt(A/pi) (the grid methods share
    #: ``crossval compare --resolution``); else the method's own measure (mesh grading, elements
    #: per process zone)
    per_radius: bool
    #: why a value outside [low, high] is refused, when there is more to say than the range
    below: str = ""
    above: str = ""


@dataclass(frozen=True)
class Sweeps:
    """The resolutions the harness runs a method at (in the method's own ``resolution``)."""

    study: tuple[float, ...]  # ``crossval study`` unless told otherwise
    quick: tuple[float, ...]  # ``crossval report --quick``
    full: tuple[float, ...]  # ``crossval report``
    regression: float  # ``crossval regress``: one quick run per suite scene
    #: ``crossval compare --quick``: the method's own quick resolution where it does not count
    #: elements per radius (None: the shared ``--resolution``)
    compare_quick: float | None = None


@dataclass(frozen=True)
class Method:
    """A registered method: what it applies to and what its ``resolution`` means, stated by the
    method's own functions so that the harness never branches on a method's name.  Accuracy is
    not here: each result carries its method's error bars (``Result.error_bars``)."""

    name: str
    module: str
    description: str
    applies: Callable[[Scene], str | None]  # None when it applies, else the reason it does not
    resolution: Callable[[Scene], Resolution]
    sweeps: Sweeps
    #: how its results serve as a reference where no closed form exists: "bounded" (one result
    #: with a bound on its error), "sequence" (a limit extrapolated in 1/N over >= 3 grids), or
    #: "" (not a reference)
    reference_kind: str = ""
    #: whether the method models a finite interaction range (``adhesion.range``, ``--range``);
    #: the others are zero-range (Griffith) methods and would silently ignore it
    uses_range: bool = False
    #: the half-space discretisation of its single-grid solves (``halfspace``: "love" for Love's
    #: uniform-pressure squares, "collocation" for point-collocated Boussinesq coefficients), so
    #: that two methods' stiffnesses on one grid are held to their kernels' measured difference;
    #: None for a method without a grid
    grid_kernel: str | None = None

    def resolution_meaning(self, scene: Scene) -> str:
        """What ``resolution`` (``--resolution``) means for this method on this scene."""
        return self.resolution(scene).meaning

    def resolution_range(self, scene: Scene) -> tuple[float, float]:
        """The resolutions this method accepts for ``scene`` (the bounds its settings enforce,
        expressed as ``resolution``)."""
        r = self.resolution(scene)
        return r.low, r.high

    def resolution_is_grid(self, scene: Scene) -> bool:
        """Whether ``resolution`` means BEM elements per radius for this scene (the FEM's is
        a mesh grading, the zero-range energy method's elements per process zone)."""
        return self.resolution(scene).per_radius

    def check_resolution(self, scene: Scene, resolution: float | None, *, field: str = "resolution") -> None:
        """Raise SceneError, in terms of ``resolution``, if the method cannot run at it."""
        if resolution is None:
            return
        if isinstance(resolution, bool) or not isinstance(resolution, (int, float)):
            raise SceneError(field, f"must be a number > 0 (got {resolution!r})")
        if not (math.isfinite(resolution) and resolution > 0):
            raise SceneError(field, f"must be a number > 0 (got {resolution:g})")
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
_TOO_COARSE = "coarser grids put fewer than 4 elements across the face's incircle"


def _coarsest_grid(scene: Scene) -> float:
    from contact_scene.raster import MIN_INCIRCLE_CELLS

    shape = scene.indenter.shape
    return MIN_INCIRCLE_CELLS * shape.equivalent_radius / (2 * shape.incircle().radius)


def _griffith_applies(scene: Scene) -> str | None:
    return None  # any face, profile, homogeneous or power-law graded half-space


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

    return applies(scene)


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
    return Resolution(_PER_RADIUS, _N_PER_RADIUS, _coarsest_grid(scene), math.inf, True, below=_TOO_COARSE)


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
        # zero-range limit: elements per process zone (1.0: the coarse sequence)
        Sweeps(study=(1.0, 2.0, 3.0), quick=(1.0,), full=(1.0, 2.0), regression=1.0, compare_quick=1.0),
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
    if name not in METHODS:
        raise SceneError("method", f"unknown method {name!r}; available: {', '.join(sorted(METHODS))}")
    return METHODS[name]


def reference_method(scene: Scene, kind: str) -> Method | None:
    """The first registered method that applies to ``scene`` and serves as a reference of
    ``kind`` (``Method.reference_kind``: "bounded" or "sequence"), or None."""
    return next((m for m in METHODS.values() if m.reference_kind == kind and m.applies(scene) is None), None)


def applicable_methods(scene: Scene) -> list[Method]:
    return [m for m in METHODS.values() if m.applies(scene) is None]
