"""The scene: what is pressed onto what, how it is loaded, and which outputs are wanted.

A scene is physics only; how finely a method discretises it is a separate settings object
(:mod:`contact_scene.discretisation`).  Every part is a frozen dataclass that validates
itself; make variants with :func:`dataclasses.replace`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from .errors import SceneError
from .materials import Homogeneous, Material, PowerLawGraded
from .profiles import Flat, Profile, Sphere
from .shapes import Circle, Shape
from .validation import check_fields, choice, flag, real, reals

__all__ = ["Indenter", "Adhesion", "Loading", "Outputs", "Scene"]


@dataclass(frozen=True)
class Indenter:
    """A rigid punch: its face (where it may touch) and the profile of that face."""

    shape: Shape
    profile: Profile = field(default_factory=Flat)

    def __post_init__(self):
        # the parts' types and a rule spanning both (the face must fit under the sphere) are
        # not ranges of one field, so they are checked here rather than declared
        if not isinstance(self.shape, Shape):
            raise SceneError("indenter.shape", f"must be a face shape (got {type(self.shape).__name__})")
        if not isinstance(self.profile, Profile):
            raise SceneError("indenter.profile", f"must be a profile (got {type(self.profile).__name__})")
        if isinstance(self.profile, Sphere):
            x0, y0, x1, y1 = self.shape.bounds
            ax, ay = self.profile.apex
            rmax = max(math.hypot(x - ax, y - ay) for x in (x0, x1) for y in (y0, y1))
            if rmax >= self.profile.radius:
                raise SceneError(
                    "indenter.profile_radius", f"the face reaches r = {rmax:g}; a sphere needs radius > that"
                )

    @property
    def is_circular_flat(self) -> bool:
        return isinstance(self.shape, Circle) and self.profile.is_flat


@dataclass(frozen=True)
class Adhesion:
    """Work of adhesion w (energy per area, the paper's Delta-gamma_12).

    ``range`` is the interaction range of a finite-range potential (energy method only);
    ``None`` means the zero-range (JKR / Griffith) limit.
    """

    work_of_adhesion: float = real(ge=0)
    range: float | None = real(None, gt=0, optional=True)
    potential: str = choice("exponential", ("exponential", "maugis_dugdale"))

    def __post_init__(self):
        check_fields(self, "adhesion")


@dataclass(frozen=True)
class Loading:
    """Press (without adhesion, as in the paper) to ``press_approach`` or ``press_force``,
    then pull.  ``turning_points`` optionally lists approaches at which the pull reverses
    direction (unload-reload: pull to t1, push back to t2, pull to t3, ...) before the
    final pull-off.  ``pull_limit`` ends the pull at that approach if the punch is still
    attached (a case of strong adhesion reported as such)."""

    press_approach: float | None = real(None, optional=True)
    press_force: float | None = real(None, ge=0, optional=True)
    turning_points: tuple[float, ...] = reals()
    pull_limit: float | None = real(None, lt=0, optional=True)

    def __post_init__(self):
        # two ways of stating the same press exclude each other: not a range of either field
        if self.press_approach is not None and self.press_force is not None:
            raise SceneError("loading.press_force", "give press_approach or press_force, not both")
        check_fields(self, "loading")


@dataclass(frozen=True)
class Outputs:
    """What the user wants back; methods compute only these.

    ``snapshots``: approaches at which the contact set is recorded (during the pull).
    ``fields``: pressure and displacement on the grid (or mesh) at those snapshots and at
    pull-off."""

    curve: bool = flag(True)
    snapshots: tuple[float, ...] = reals()
    fields: bool = flag(False)

    def __post_init__(self):
        check_fields(self, "outputs")


@dataclass(frozen=True)
class Scene:
    indenter: Indenter
    material: Material
    adhesion: Adhesion
    loading: Loading = field(default_factory=Loading)
    outputs: Outputs = field(default_factory=Outputs)
    name: str = ""

    def __post_init__(self):
        if not isinstance(self.indenter, Indenter):
            raise SceneError("indenter", "must be an Indenter")
        if not isinstance(self.material, (Homogeneous, PowerLawGraded)):
            raise SceneError("material", f"must be Homogeneous or PowerLawGraded (got {type(self.material).__name__})")
        if not isinstance(self.adhesion, Adhesion):
            raise SceneError("adhesion", "must be an Adhesion")
        if (
            not self.indenter.profile.is_flat
            and self.loading.press_approach is None
            and self.loading.press_force is None
        ):
            raise SceneError("loading.press_approach", "a curved profile needs press_approach > 0 or press_force > 0")
        if (
            not self.indenter.profile.is_flat
            and self.loading.press_approach is not None
            and self.loading.press_approach <= 0
        ):
            raise SceneError(
                "loading.press_approach", f"must be > 0 for a curved profile (got {self.loading.press_approach:g})"
            )

    @property
    def effective_modulus(self) -> float:
        """E* of a homogeneous material; for a graded one the k = 0 equivalent 4 E0 / 3 is not
        meaningful, so this raises."""
        if isinstance(self.material, Homogeneous):
            return self.material.effective_modulus
        raise SceneError("material", "a graded material has no single effective modulus")
