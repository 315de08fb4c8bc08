"""The registry of methods: which solver applies to which scene.

A method is registered lazily by module path so that ``crossval scene check`` never imports a
solver, and a scene only runs through the methods that can represent it.
"""
from __future__ import annotations

import importlib
import math
from dataclasses import dataclass
from typing import Callable

from contact_scene import Scene, SceneError

__all__ = ["Method", "METHODS", "get_method", "applicable_methods"]


@dataclass(frozen=True)
class Method:
    name: str
    module: str
    description: str
    applies: Callable[[Scene], str | None]  # None when it applies, else the reason it does not
    #: whether the method models a finite interaction range (``adhesion.range``, ``--range``);
    #: the others are zero-range (Griffith) methods and would silently ignore it
    uses_range: bool = False

    def resolution_meaning(self, scene: Scene) -> str:
        """What ``resolution`` (``--resolution``) means for this method on this scene."""
        if self.name == "fem_reference":
            return "mesh refinement 1/grading (elements grow by at most 1/resolution x their distance from the punch edge)"
        if not self.resolution_is_grid(scene):
            return "elements per process zone l_c of each range of the zero-range sequence"
        return "elements per equivalent radius sqrt(A/pi)"

    def resolution_range(self, scene: Scene) -> tuple[float, float]:
        """The resolutions this method accepts for ``scene`` (the bounds its settings enforce,
        expressed as ``resolution``)."""
        if self.name == "fem_reference":
            from fem_reference.solver import MAX_ISOTROPIC_GRADING

            graded = getattr(scene.material, "exponent", 0.0) > 0    # the tensor mesh (fem_reference.model)
            return 1 / (4.0 if graded else MAX_ISOTROPIC_GRADING), 1 / 0.05   # FemSettings.grading in [0.05, 4]
        if not self.resolution_is_grid(scene):
            return 0.25, 64.0                             # ZeroRangeSettings.elements_per_process_zone
        from contact_scene.raster import MIN_INCIRCLE_CELLS

        shape = scene.indenter.shape
        lo = MIN_INCIRCLE_CELLS * shape.equivalent_radius / (2 * shape.incircle().radius)
        if self.name == "bem_griffith":
            from bem_griffith.solver import max_elements_per_radius

            return lo, float(max_elements_per_radius(scene))
        return lo, math.inf

    def check_resolution(self, scene: Scene, resolution: float | None, *, field: str = "resolution") -> None:
        """Raise SceneError, in terms of ``resolution``, if the method cannot run at it."""
        if resolution is None:
            return
        if isinstance(resolution, bool) or not isinstance(resolution, (int, float)):
            raise SceneError(field, f"must be a number > 0 (got {resolution!r})")
        if not (math.isfinite(resolution) and resolution > 0):
            raise SceneError(field, f"must be a number > 0 (got {resolution:g})")
        lo, hi = self.resolution_range(scene)
        if lo <= resolution <= hi:
            return
        what = self.resolution_meaning(scene)
        limits = f"from {_nice(lo, up=True)} to {_nice(hi, up=False)}" if math.isfinite(hi) else \
            f"{_nice(lo, up=True)} or more"
        why = ""
        if self.name == "bem_griffith" and resolution > hi:
            why = " (a finer grid needs more than the solver's memory limit)"
        elif resolution < lo and self.resolution_is_grid(scene) and self.name != "fem_reference":
            why = " (coarser grids put fewer than 4 elements across the face's incircle)"
        raise SceneError(field, f"{self.name} takes {limits} here{why}; it means {what} (got {resolution:g})")

    def resolution_is_grid(self, scene: Scene) -> bool:
        """Whether ``resolution`` means BEM elements per radius for this scene (the FEM's is
        a mesh grading, the zero-range energy method's elements per process zone)."""
        if self.name == "fem_reference":
            return False
        if self.name == "bem_energy":
            return not (scene.adhesion.range is None and scene.adhesion.work_of_adhesion > 0)
        return True

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


def _griffith_applies(scene: Scene) -> str | None:
    return None  # any face, profile, homogeneous or power-law graded half-space


def _fem_applies(scene: Scene) -> str | None:
    from fem_reference import applies

    return applies(scene)


def _energy_applies(scene: Scene) -> str | None:
    import contact_scene as cs

    if not isinstance(scene.material, cs.Homogeneous):
        return "the energy method is validated for homogeneous half-spaces only"
    if scene.adhesion.range is None and scene.adhesion.work_of_adhesion > 0 and not scene.indenter.profile.is_flat:
        return ("its zero-range extrapolation is calibrated on flat faces (the edge of a flat punch); "
                "give adhesion.range to run a finite range")
    return None


METHODS: dict[str, Method] = {
    "bem_griffith": Method(
        "bem_griffith", "bem_griffith",
        "FFT boundary elements with the Pohrt-Popov local Griffith detachment criterion",
        _griffith_applies,
    ),
    "bem_energy": Method(
        "bem_energy", "bem_energy",
        "FFT boundary elements minimising elastic + finite-range adhesive energy (zero-range limit by extrapolation)",
        _energy_applies,
        uses_range=True,
    ),
    "fem_reference": Method(
        "fem_reference", "fem_reference",
        "axisymmetric Taylor-Hood finite elements with a Griffith energy release rate (circular faces)",
        _fem_applies,
    ),
}


def get_method(name: str) -> Method:
    if name not in METHODS:
        raise SceneError("method", f"unknown method {name!r}; available: {', '.join(sorted(METHODS))}")
    return METHODS[name]


def applicable_methods(scene: Scene) -> list[Method]:
    return [m for m in METHODS.values() if m.applies(scene) is None]
