"""Adhesive potentials of finite range: energy per area phi(g) of the gap g >= 0.

phi' > 0 is the attractive (tensile) stress; w is the work of adhesion (phi(0) = -w,
phi(inf) = 0) and rho the range.  The Tabor-like length l_c = E* rho^2 / w (graded bodies:
see :func:`process_zone_length`) measures the process zone; it must be resolved by the grid
(:data:`PROCESS_ZONE_ELEMENTS`) or the result is trapped by the mesh.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from contact_scene import SceneError
from contact_scene.validation import check_fields, choice, real

__all__ = [
    "Potential",
    "process_zone_length",
    "process_zone_factor",
    "process_zone_modulus",
    "process_zone_exponent",
    "range_for_process_zone",
    "PROCESS_ZONE_ELEMENTS",
    "GRADED_ZONE_ELEMENTS",
    "graded_zone_elements",
    "process_zone_elements",
]

#: Elements per process zone l_c of a finite-range pull-off, per potential: (the fewest for a
#: converged result, the default grid's count).  Measured on the flat circle, F_A scaled to
#: the nominal face area (benchmarks/study_energy_process_zone.py).  Exponential, against 4-16
#: per l_c at l_c / a = 0.16, 0.04, 0.02: half an element per l_c traps the zone (+33, +12,
#: +10 %), one is within 0.4-1.2 %, two within 0.2 % (the face's staircase included).
#: Maugis-Dugdale (a constant stress ending at g = rho) converges slowly, the change per
#: doubling shrinking by only about 0.6: extrapolated from 8, 16, 32 per l_c (l_c / a = 0.32,
#: 0.16; 4, 8, 16 at 0.08) it is +3 to +4 % high at 8 per l_c and +2 % at 16.
PROCESS_ZONE_ELEMENTS: dict[str, tuple[float, float]] = {"exponential": (1.0, 2.0), "maugis_dugdale": (16.0, 16.0)}

#: How many times the homogeneous count of elements per l_c a graded body (k > 0) needs, at
#: the k measured: the graded kernel is more local, so the opening rises more steeply across a
#: zone of the same l_c.  Exponential potential, flat circle, l_c = 0.08 a, F_A against 16 per
#: l_c (benchmarks/study_graded_shape_ratio.py --resolution): 2 per l_c is +0.46 % high at
#: k = 0.25, +2.0 % at 0.5, +5.8 % at 0.75; 4 per l_c +0.11, +0.17, +2.3 %; 8 per l_c +0.02,
#: +0.02, +0.30 %; k = 0: +0.19 % at 2.  Interpolated in log between the points,
#: extrapolated with the last slope past 0.75; k < 0 keeps the homogeneous count.
GRADED_ZONE_ELEMENTS: tuple[tuple[float, float], ...] = ((0.0, 1.0), (0.25, 1.5), (0.5, 2.0), (0.75, 4.0))


def graded_zone_elements(exponent: float) -> float:
    """The factor on a potential's elements per l_c for a body of grading ``exponent``
    (:data:`GRADED_ZONE_ELEMENTS`; 1 for a homogeneous one and k <= 0)."""
    if exponent <= 0:
        return 1.0
    ks = [k for k, _ in GRADED_ZONE_ELEMENTS]
    logm = [math.log(m) for _, m in GRADED_ZONE_ELEMENTS]
    if exponent >= ks[-1]:
        slope = (logm[-1] - logm[-2]) / (ks[-1] - ks[-2])
        return math.exp(logm[-1] + slope * (exponent - ks[-1]))
    return float(math.exp(np.interp(exponent, ks, logm)))


def process_zone_elements(kind: str, exponent: float = 0.0) -> tuple[float, float]:
    """(fewest, default) elements per l_c for the potential ``kind`` on a body of grading
    ``exponent`` (:data:`PROCESS_ZONE_ELEMENTS` times :func:`graded_zone_elements`)."""
    m = graded_zone_elements(exponent)
    fewest, default = PROCESS_ZONE_ELEMENTS[kind]
    return fewest * m, default * m


@dataclass(frozen=True)
class Potential:
    """An adhesive potential phi(g): energy per area of the gap g >= 0, phi(0) = -w.

    Parameters
    ----------
    work : float
        w, the work of adhesion (an energy per area), >= 0.
    range : float
        rho, the range (a length), > 0.
    kind : str, optional
        ``"exponential"`` (default) phi = -w exp(-g/rho) (smooth, concave) or
        ``"maugis_dugdale"`` phi = -w max(0, 1 - g/rho) (constant stress w/rho up to rho;
        concave, with a kink at g = rho).

    Raises
    ------
    contact_scene.SceneError
        Naming the scene's field the parameter comes from (``adhesion.work_of_adhesion``,
        ``adhesion.range``, ``adhesion.potential``) and its allowed values, for a value
        outside them.
    """

    # named as the scene's adhesion fields they come from
    work: float = real(ge=0, name="adhesion.work_of_adhesion")
    range: float = real(gt=0)
    kind: str = choice("exponential", ("exponential", "maugis_dugdale"), name="adhesion.potential")

    def __post_init__(self):
        check_fields(self, "adhesion")

    def energy(self, g: np.ndarray) -> np.ndarray:
        """phi(g), the adhesive energy per area (from -w at contact to 0 far away).

        Parameters
        ----------
        g : numpy.ndarray
            The gap, >= 0 (a length).

        Returns
        -------
        numpy.ndarray
            phi at each gap, in [-w, 0].
        """
        w, r = self.work, self.range
        if self.kind == "exponential":
            return -w * np.exp(-g / r)
        return -w * np.maximum(0.0, 1.0 - g / r)

    def evaluate(self, g: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """phi(g), phi'(g) and phi''(g) together, the exponential computed once.

        The same numbers as :meth:`energy`, :meth:`stress` and :meth:`curvature` (bit for bit):
        the projected CG needs all three at each accepted iterate, and the exponential is the
        costliest of the pointwise work.

        Parameters
        ----------
        g : numpy.ndarray
            The gap, >= 0 (a length).

        Returns
        -------
        energy, stress, curvature : numpy.ndarray
            phi, phi' and phi'' at each gap.
        """
        w, r = self.work, self.range
        if self.kind == "exponential":
            x = np.negative(g)
            x /= r
            # exp(-0) = 1 exactly: the cells at the wall (gap exactly zero, where the projection
            # puts them) skip the exponential, a libm call of about 10 ns per cell in double
            # precision without AVX-512, most of this function's time while the face holds
            e = np.ones_like(x)
            np.exp(x, out=e, where=g != 0)
            return -w * e, (w / r) * e, -(w / r**2) * e
        return self.energy(g), self.stress(g), self.curvature(g)

    def stress(self, g: np.ndarray) -> np.ndarray:
        """phi'(g): the attractive stress pulling the surface back toward the punch.

        Parameters
        ----------
        g : numpy.ndarray
            The gap, >= 0 (a length).

        Returns
        -------
        numpy.ndarray
            phi' at each gap, in [0, w/rho] (a stress).
        """
        w, r = self.work, self.range
        if self.kind == "exponential":
            return (w / r) * np.exp(-g / r)
        return np.where(g < r, w / r, 0.0)

    def curvature(self, g: np.ndarray) -> np.ndarray:
        """phi''(g) (<= 0: the potential is concave).

        Maugis-Dugdale's is 0 (its kink at g = rho is left out).

        Parameters
        ----------
        g : numpy.ndarray
            The gap, >= 0 (a length).

        Returns
        -------
        numpy.ndarray
            phi'' at each gap, in [-w/rho^2, 0].
        """
        w, r = self.work, self.range
        if self.kind == "exponential":
            return -(w / r**2) * np.exp(-g / r)
        return np.zeros_like(np.asarray(g, float))


def process_zone_factor(exponent: float) -> float:
    """The factor c_k = cos(k pi / 2) (2 / pi)^k of the graded process zone (1 at k = 0).

    Near the edge of a circular flat punch at the zero-range pull-off on a graded half-space
    the pressure is p = P0 (a^2 - r^2)^((k-1)/2) with the force 2 pi P0 a^(1+k) / (1+k) = F_A
    (Eq. 39); it equals the potential's largest stress w / rho at the distance s_k from the
    edge with pi s_k^(1-k) = pi^k c_k E_k rho^2 / w (psi(k) of Eq. 40 reduces the constants to
    cos(k pi / 2)).  Defining l_c by l_c^(1-k) = c_k E_k rho^2 / w makes l_c = pi s_k for every
    k, so that a grid with n elements per l_c resolves the zone of a graded body as it does a
    homogeneous one (at k = 0, l_c = E* rho^2 / w = pi s_0).  Without c_k the zone at k = 0.5
    is pi times shorter than l_c^(1-k) = E_k rho^2 / w says, and 2 elements per such l_c trap it
    (tests/test_graded_process_zone.py checks that length, and that a graded body on too few
    elements for its zone overshoots, by about 2 % at k = 0.5).
    """
    if exponent == 0:
        return 1.0
    return math.cos(exponent * math.pi / 2) * (2.0 / math.pi) ** exponent


def process_zone_length(*, modulus: float, work: float, range: float, exponent: float = 0.0) -> float:
    """l_c = E* rho^2 / w (infinite without adhesion); graded: l_c^(1-k) = c_k E_k rho^2 / w.

    On a graded half-space (surface Green's function A_k P / r^(1+k)) a cohesive zone of
    length l under the stress w / rho opens by about A_k (w / rho) l^(1-k); setting that to
    rho gives l^(1-k) ~ E_k rho^2 / w with E_k = 1 / (pi A_k) (``modulus``, units of
    stress / length^k; E* at k = 0, where this is the homogeneous l_c).  The constant c_k
    (:func:`process_zone_factor`) puts l_c at the same multiple of the distance where the
    zero-range edge field reaches the potential's strength for every k.

    Parameters
    ----------
    modulus : float
        E_k = 1 / (pi A_k), > 0 (:func:`process_zone_modulus`; E* of a homogeneous body).
    work : float
        w, the work of adhesion (an energy per area).
    range : float
        rho, the potential's range (a length), > 0 when ``work`` > 0.
    exponent : float, optional
        k of the Green's function, in (-1, 1) (:func:`process_zone_exponent`); 0 (homogeneous)
        by default.

    Returns
    -------
    float
        l_c (a length); infinite when ``work`` <= 0.

    Raises
    ------
    contact_scene.SceneError
        ``adhesion.range`` for range <= 0 with work > 0.
    """
    if work <= 0:
        return float("inf")
    if range <= 0:
        raise SceneError("adhesion.range", f"must be > 0 (got {range:g})")
    return (process_zone_factor(exponent) * modulus * range**2 / work) ** (1.0 / (1.0 - exponent))


def range_for_process_zone(*, modulus: float, work: float, length: float, exponent: float = 0.0) -> float:
    """The range rho whose process zone (:func:`process_zone_length`) is ``length``."""
    return math.sqrt(work * length ** (1.0 - exponent) / (process_zone_factor(exponent) * modulus))


def process_zone_modulus(material) -> float:
    """E_k = 1 / (pi A_k) of the surface Green's function A_k P / r^(1+k): E* of a
    homogeneous body; for a graded one (3+k) c0^k / (2 pi (1+k)(2+k) E0) inverted, which at
    k = 0 is E* = 4 E0 / 3 (nu = 1/2)."""
    from contact_scene import Homogeneous, theory

    if isinstance(material, Homogeneous):
        return material.effective_modulus
    A = theory.graded_green_coefficient(E0=material.surface_modulus, c0=material.reference_depth, k=material.exponent)
    return 1.0 / (math.pi * A)


def process_zone_exponent(material) -> float:
    """k of the Green's function r^-(1+k): 0 for a homogeneous body."""
    from contact_scene import Homogeneous

    return 0.0 if isinstance(material, Homogeneous) else float(material.exponent)
