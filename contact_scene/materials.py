"""Elastic half-spaces: homogeneous, and power-law graded E(z) = E0 (z/c0)^k (Eq. 32)."""

from __future__ import annotations

from dataclasses import dataclass

from .validation import check_fields, real

__all__ = ["Material", "Homogeneous", "PowerLawGraded"]


class Material:
    kind = "material"


@dataclass(frozen=True)
class Homogeneous(Material):
    youngs_modulus: float = real(gt=0)
    # nu = -1 would make E* infinite; nu > 1/2 is not positive definite
    poisson_ratio: float = real(0.5, gt=-1, le=0.5)
    kind = "homogeneous"

    def __post_init__(self):
        check_fields(self, "material")

    @property
    def effective_modulus(self) -> float:
        """E* = E / (1 - nu^2), for a rigid indenter."""
        return self.youngs_modulus / (1.0 - self.poisson_ratio**2)


@dataclass(frozen=True)
class PowerLawGraded(Material):
    """E(z) = E0 (z/c0)^k with nu = 1/(2+k) (Eq. 33), -1 < k < 1.

    The closed forms of Section 11 hold only for nu = 1/(2+k), so the Poisson ratio is
    derived, not chosen.  k = 0 is the homogeneous incompressible half-space (E* = 4 E0/3).
    """

    surface_modulus: float = real(gt=0)
    reference_depth: float = real(gt=0)
    # -1 < k < 1 (Eq. 32): where the surface Green's function A_k / r^(1+k) exists
    exponent: float = real(gt=-1, lt=1)
    kind = "power_law_graded"

    def __post_init__(self):
        check_fields(self, "material")

    @property
    def poisson_ratio(self) -> float:
        return 1.0 / (2.0 + self.exponent)
