"""Elastic half-spaces: homogeneous, and power-law graded E(z) = E0 (z/c0)^k (Eq. 32)."""

from __future__ import annotations

from dataclasses import dataclass

from .validation import check_fields, real

__all__ = ["Material", "Homogeneous", "PowerLawGraded"]


class Material:
    """Base class of the elastic half-spaces: :class:`Homogeneous` and :class:`PowerLawGraded`.

    ``kind`` names the material as a scene file does (``model`` in ``[material]``).  A scene accepts
    these two only: every method and closed form is written for one of them.
    """

    kind = "material"


@dataclass(frozen=True)
class Homogeneous(Material):
    """A homogeneous, isotropic, linearly elastic half-space (formula sheet, sections 1-4).

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E (a stress), > 0.
    poisson_ratio : float, optional
        Poisson's ratio nu, in (-1, 0.5]; 0.5 (incompressible) by default.  nu = -1 would
        make E* = E / (1 - nu^2) infinite; nu > 1/2 is not positive definite.

    Raises
    ------
    contact_scene.SceneError
        Naming ``material.<field>`` and its allowed range, for a value out of that range.
    """

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

    Parameters
    ----------
    surface_modulus : float
        E0, Young's modulus at the depth ``reference_depth`` (a stress), > 0.
    reference_depth : float
        c0, the depth at which E = E0 (a length), > 0.
    exponent : float
        k, in (-1, 1): where the surface Green's function A_k / r^(1+k) exists (Eq. 32).

    Raises
    ------
    contact_scene.SceneError
        Naming ``material.<field>`` and its allowed range, for a value out of that range.
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
        """nu = 1/(2+k) (Eq. 33), in (1/3, 1): derived from the exponent."""
        return 1.0 / (2.0 + self.exponent)
