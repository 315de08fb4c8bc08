"""Elastic half-spaces: homogeneous, and power-law graded E(z) = E0 (z/c0)^k (Eq. 32)."""

from __future__ import annotations

from dataclasses import dataclass

from .errors import check_real

__all__ = ["Material", "Homogeneous", "PowerLawGraded"]


class Material:
    kind = "material"


@dataclass(frozen=True)
class Homogeneous(Material):
    youngs_modulus: float
    poisson_ratio: float = 0.5
    kind = "homogeneous"

    def __post_init__(self):
        object.__setattr__(
            self, "youngs_modulus", check_real("material.youngs_modulus", self.youngs_modulus, lo=0, lo_open=True)
        )
        # nu = -1 would make E* infinite; nu > 1/2 is not positive definite
        object.__setattr__(
            self, "poisson_ratio", check_real("material.poisson_ratio", self.poisson_ratio, lo=-1, hi=0.5, lo_open=True)
        )

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

    surface_modulus: float
    reference_depth: float
    exponent: float
    kind = "power_law_graded"

    def __post_init__(self):
        object.__setattr__(
            self, "surface_modulus", check_real("material.surface_modulus", self.surface_modulus, lo=0, lo_open=True)
        )
        object.__setattr__(
            self, "reference_depth", check_real("material.reference_depth", self.reference_depth, lo=0, lo_open=True)
        )
        object.__setattr__(
            self, "exponent", check_real("material.exponent", self.exponent, lo=-1, hi=1, lo_open=True, hi_open=True)
        )

    @property
    def poisson_ratio(self) -> float:
        return 1.0 / (2.0 + self.exponent)
