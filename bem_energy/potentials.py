"""Adhesive potentials of finite range: energy per area phi(g) of the gap g >= 0.

phi' > 0 is the attractive (tensile) stress; w is the work of adhesion (phi(0) = -w,
phi(inf) = 0) and rho the range.  The Tabor-like length l_c = E* rho^2 / w measures the
process zone; it must be resolved by the grid (l_c >= about one element) or the result is
trapped by the mesh.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contact_scene import SceneError
from contact_scene.errors import check_choice, check_real

__all__ = ["Potential", "process_zone_length", "process_zone_modulus"]


@dataclass(frozen=True)
class Potential:
    """``kind``: ``"exponential"`` phi = -w exp(-g/rho) (smooth, concave) or
    ``"maugis_dugdale"`` phi = -w max(0, 1 - g/rho) (constant stress w/rho up to rho;
    concave, with a kink at g = rho)."""

    work: float
    range: float
    kind: str = "exponential"

    def __post_init__(self):
        object.__setattr__(self, "work", check_real("adhesion.work_of_adhesion", self.work, lo=0))
        object.__setattr__(self, "range", check_real("adhesion.range", self.range, lo=0, lo_open=True))
        check_choice("adhesion.potential", self.kind, {"exponential", "maugis_dugdale"})

    def energy(self, g: np.ndarray) -> np.ndarray:
        w, r = self.work, self.range
        if self.kind == "exponential":
            return -w * np.exp(-g / r)
        return -w * np.maximum(0.0, 1.0 - g / r)

    def stress(self, g: np.ndarray) -> np.ndarray:
        """phi'(g): the attractive stress pulling the surface back toward the punch."""
        w, r = self.work, self.range
        if self.kind == "exponential":
            return (w / r) * np.exp(-g / r)
        return np.where(g < r, w / r, 0.0)

    def curvature(self, g: np.ndarray) -> np.ndarray:
        """phi''(g) (<= 0: the potential is concave)."""
        w, r = self.work, self.range
        if self.kind == "exponential":
            return -(w / r**2) * np.exp(-g / r)
        return np.zeros_like(np.asarray(g, float))


def process_zone_length(*, modulus: float, work: float, range: float) -> float:
    """l_c = E* rho^2 / w (infinite without adhesion)."""
    if work <= 0:
        return float("inf")
    if range <= 0:
        raise SceneError("adhesion.range", f"must be > 0 (got {range:g})")
    return modulus * range**2 / work


def process_zone_modulus(material) -> float:
    """The modulus in l_c: E* of a homogeneous body, the surface modulus E0 of a graded one."""
    from contact_scene import Homogeneous

    return material.effective_modulus if isinstance(material, Homogeneous) else material.surface_modulus
