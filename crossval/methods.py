"""The registry of methods: which solver applies to which scene.

A method is registered lazily by module path so that ``crossval scene check`` never imports a
solver, and a scene only runs through the methods that can represent it.
"""
from __future__ import annotations

import importlib
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

    def resolution_is_grid(self, scene: Scene) -> bool:
        """Whether ``resolution`` means BEM elements per radius for this scene (the FEM's is
        a mesh grading, the zero-range energy method's elements per process zone)."""
        if self.name == "fem_reference":
            return False
        if self.name == "bem_energy":
            return not (scene.adhesion.range is None and scene.adhesion.work_of_adhesion > 0)
        return True

    def solve(self, scene: Scene, *, resolution: float | None = None, callback=None):
        mod = importlib.import_module(self.module)
        return mod.solve_with_resolution(scene, resolution, callback=callback)


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
