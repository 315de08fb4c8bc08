"""The scene: what is pressed onto what, how it is loaded, and which outputs are wanted.

A scene is physics only; how finely a method discretises it is a separate settings object
(:mod:`contact_scene.discretisation`).  Every part is a frozen dataclass that validates
itself; make variants with :func:`dataclasses.replace`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .errors import SceneError
from .materials import Homogeneous, Material, PowerLawGraded
from .profiles import Flat, Profile, Sphere
from .shapes import Circle, PolygonalShape, Shape
from .validation import check_fields, choice, flag, real, reals

__all__ = ["Indenter", "Adhesion", "Loading", "Outputs", "Scene"]


#: a scene's main scales (its modulus E* or E0, the face's size, the work of adhesion, the range,
#: and the stiffness, force and approach the modulus, size and work make) must lie in this
#: range: the solvers form products and squares of them, which then stay well inside double
#: precision (about 1e-308 ... 1e308, with full precision above 2e-308 only), and so do their
#: ratios.  Lengths of the loading and the profile and a graded body's reference depth are not
#: checked here
SCALE_LIMITS = (1e-100, 1e100)


def _reach(shape: Shape, apex: tuple[float, float]) -> tuple[float, str]:
    """The largest distance from ``apex`` to a point of the face, and what it is measured on:
    exact for a circle and a polygon (its farthest vertex), else the bounding box's corners
    (an upper bound)."""
    ax, ay = apex
    if isinstance(shape, Circle):
        return math.hypot(shape.center[0] - ax, shape.center[1] - ay) + shape.radius, "the face"
    if isinstance(shape, PolygonalShape):
        v = np.asarray(shape.vertices, float)
        return float(np.max(np.hypot(v[:, 0] - ax, v[:, 1] - ay))), "the face"
    x0, y0, x1, y1 = shape.bounds
    return max(math.hypot(x - ax, y - ay) for x in (x0, x1) for y in (y0, y1)), "the face's bounding box"


@dataclass(frozen=True)
class Indenter:
    """A rigid punch: its face (where it may touch) and the profile of that face.

    Parameters
    ----------
    shape : contact_scene.Shape
        The face: the region of the plane where the punch may touch and adhere.
    profile : contact_scene.Profile, optional
        The height of the face above its lowest point; :class:`~contact_scene.Flat` by default.

    Raises
    ------
    contact_scene.SceneError
        ``indenter.shape`` or ``indenter.profile`` for an object of the wrong type;
        ``indenter.profile_radius`` for a sphere whose radius does not exceed the distance from
        its apex to the farthest corner of the face's bounding box.
    """

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
            rmax, what = _reach(self.shape, self.profile.apex)
            if rmax >= self.profile.radius:
                raise SceneError(
                    "indenter.profile_radius",
                    f"{what} reaches r = {rmax:g} from the apex; a sphere needs radius > that",
                )

    @property
    def is_circular_flat(self) -> bool:
        """Whether this is Kendall's punch: a circular face with a flat profile (Eqs. 1-8)."""
        return isinstance(self.shape, Circle) and self.profile.is_flat


@dataclass(frozen=True)
class Adhesion:
    """Work of adhesion w (energy per area, the paper's Delta-gamma_12).

    ``range`` is the interaction range of a finite-range potential (energy method only);
    ``None`` means the zero-range (JKR / Griffith) limit.

    Parameters
    ----------
    work_of_adhesion : float
        w (an energy per area), >= 0; 0 is a press and pull without adhesion.
    range : float or None, optional
        rho, the range of the adhesive potential (a length), in [1e-150, 1e150] (its square
        must stay a floating-point number); None (the default) for the zero-range limit.
    potential : str, optional
        The finite-range potential's form (:class:`bem_energy.Potential`): ``"exponential"``
        (the default) or ``"maugis_dugdale"``.  It shapes the interaction of the given
        ``range``, so another than the default needs a range.

    Raises
    ------
    contact_scene.SceneError
        Naming ``adhesion.<field>`` and its allowed values, for a value outside them;
        ``adhesion.potential`` for a potential other than the default without a range.
    """

    work_of_adhesion: float = real(ge=0)
    # the potential's curvature is w / rho^2: the square of the range must stay in floating point
    range: float | None = real(None, ge=1e-150, le=1e150, optional=True)
    potential: str = choice("exponential", ("exponential", "maugis_dugdale"))

    def __post_init__(self):
        check_fields(self, "adhesion")
        # a rule joining two fields: the zero-range limit has no potential, so one named without
        # a range would be ignored; the default passes, as it cannot be told from "not given"
        if self.range is None and self.potential != "exponential":
            raise SceneError(
                "adhesion.potential",
                "names the form of a finite-range interaction and needs a range; without one the scene is "
                f"the zero-range limit, which has no potential (got {self.potential!r}; dropping the range, "
                "set potential='exponential', the default, too)",
            )


@dataclass(frozen=True)
class Loading:
    """The loading path: press without adhesion, then pull (through optional turning points).

    The press (without adhesion, as in the paper) goes to ``press_approach`` or
    ``press_force``; a flat face given neither touches with its whole face at d = 0, a curved
    profile needs one (:class:`Scene` checks).  ``turning_points`` optionally lists approaches
    at which the pull reverses direction (unload-reload: pull to t1, push back to t2, pull to
    t3, ...) before the final pull-off.  ``pull_limit`` ends the pull at that approach if the
    punch is still attached (a case of strong adhesion reported as such).

    Parameters
    ----------
    press_approach : float or None, optional
        The approach d to press to (a length; > 0 presses in), any finite number; None (the
        default) when pressing to a force or not at all.
    press_force : float or None, optional
        The compressive force to press to, >= 0; None (the default) when pressing to an
        approach or not at all.
    turning_points : tuple of float, optional
        Approaches at which the pull reverses direction, in order, each finite; none by
        default.
    pull_limit : float or None, optional
        The approach at which the pull ends if the punch is still attached, < 0; None (the
        default) for the method's own pull range, which reaches past the expected detachment.

    Raises
    ------
    contact_scene.SceneError
        ``loading.press_force`` when both press_approach and press_force are given;
        ``loading.turning_points`` for a turning point at or beyond ``pull_limit``; naming
        ``loading.<field>`` and its allowed range for a value out of that range.
    """

    press_approach: float | None = real(None, optional=True)
    press_force: float | None = real(None, ge=0, optional=True)
    turning_points: tuple[float, ...] = reals()
    pull_limit: float | None = real(None, lt=0, optional=True)

    def __post_init__(self):
        # two ways of stating the same press exclude each other: not a range of either field
        if self.press_approach is not None and self.press_force is not None:
            raise SceneError("loading.press_force", "give press_approach or press_force, not both")
        check_fields(self, "loading")
        t = self.turning_points
        # pull to t1, push back to t2, pull to t3, ...: a point that does not reverse the
        # direction is no turning point (the methods would just go on past it)
        for i in range(1, len(t)):
            if (t[i] <= t[i - 1]) if i % 2 else (t[i] >= t[i - 1]):
                given = ", ".join(f"{v:g}" for v in t)
                raise SceneError(
                    "loading.turning_points",
                    "must alternate: pull to the first, push back above it to the second, pull below that to "
                    f"the third, ... (got {given})",
                )
        if self.pull_limit is not None and any(t <= self.pull_limit for t in self.turning_points):
            # the pull ends at the limit: a turning point at or beyond it would never be reached
            # by that rule, and the methods would each go there anyway
            given = ", ".join(f"{t:g}" for t in self.turning_points)
            raise SceneError("loading.turning_points", f"must lie above pull_limit = {self.pull_limit:g} (got {given})")


@dataclass(frozen=True)
class Outputs:
    """What the user wants back; methods compute only these.

    Parameters
    ----------
    curve : bool, optional
        Return the force-approach curve (``Result.curve``); True by default.
    snapshots : tuple of float, optional
        Approaches at which the contact set is recorded (during the pull), each finite; none by
        default.
    fields : bool, optional
        Pressure and displacement on the grid (or mesh) at those snapshots and at pull-off;
        False by default.

    Raises
    ------
    contact_scene.SceneError
        Naming ``outputs.<field>`` and its allowed values, for a value outside them.
    """

    curve: bool = flag(True)
    snapshots: tuple[float, ...] = reals()
    fields: bool = flag(False)

    def __post_init__(self):
        check_fields(self, "outputs")


@dataclass(frozen=True)
class Scene:
    """A whole problem: the punch, the half-space, the adhesion, the loading and the outputs.

    Physics only: how finely a method discretises it is that method's settings.

    Parameters
    ----------
    indenter : Indenter
        The rigid punch: face and profile.
    material : contact_scene.Homogeneous or contact_scene.PowerLawGraded
        The elastic half-space.
    adhesion : Adhesion
        The work of adhesion (and, for the energy method, the potential's range).
    loading : Loading, optional
        The press and pull; by default no press (a flat face touches at d = 0) and a pull
        until the punch detaches.
    outputs : Outputs, optional
        What to return; by default the curve, without snapshots or fields.
    name : str, optional
        A label for summaries and reports (a scene file's ``name``); empty by default.

    Raises
    ------
    contact_scene.SceneError
        ``indenter``, ``material``, ``adhesion``, ``loading``, ``outputs`` or ``name`` for an
        object of the wrong type; ``loading.press_approach`` for a curved profile without a
        press (press_approach > 0 or press_force > 0), with press_approach <= 0, or for a flat
        face with press_approach < 0; ``loading.press_force`` for a curved profile pressed to
        a force of 0.
    """

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
        if not isinstance(self.loading, Loading):
            raise SceneError("loading", f"must be a Loading (got {type(self.loading).__name__})")
        if not isinstance(self.outputs, Outputs):
            raise SceneError("outputs", f"must be an Outputs (got {type(self.outputs).__name__})")
        if not isinstance(self.name, str):
            raise SceneError("name", f"must be a string (got {type(self.name).__name__})")
        if (
            self.indenter.profile.is_flat
            and self.loading.press_approach is not None
            and self.loading.press_approach < 0
        ):
            # a flat face touches with its whole face at d = 0; at d < 0 it hangs above the surface,
            # and a pull from there starts detached (the methods disagreed on what that means)
            raise SceneError(
                "loading.press_approach",
                f"must be >= 0 for a flat face, which touches at d = 0 (got {self.loading.press_approach:g})",
            )
        if not self.indenter.profile.is_flat and self.loading.press_force == 0:
            raise SceneError("loading.press_force", "must be > 0 for a curved profile, which touches at one point")
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
        # the pull starts from the press, at press_approach (0 for a flat face pressed to no
        # approach); a first turning point at or above it would be a push
        start = self.loading.press_approach
        if start is None and self.indenter.profile.is_flat and self.loading.press_force is None:
            start = 0.0
        if start is not None and self.loading.turning_points and self.loading.turning_points[0] >= start:
            raise SceneError(
                "loading.turning_points",
                f"the first must lie below the press approach {start:g}, where the pull starts "
                f"(got {self.loading.turning_points[0]:g})",
            )
        self._check_scales()

    def _check_scales(self) -> None:
        """Refuse units in which the scene's scales leave the floating-point range the solvers
        need (:data:`SCALE_LIMITS`), naming the one value at fault or, for a combination, the
        material."""
        low, high = SCALE_LIMITS
        material = self.material
        if isinstance(material, Homogeneous):
            modulus, modulus_field, modulus_name = material.effective_modulus, "material.youngs_modulus", "E*"
        else:
            assert isinstance(material, PowerLawGraded)  # checked above
            modulus, modulus_field, modulus_name = material.surface_modulus, "material.surface_modulus", "E0"
        length = self.indenter.shape.size
        w = self.adhesion.work_of_adhesion
        single = [(modulus_field, modulus_name, modulus), ("indenter", "the face's size", length)]
        if w > 0:
            single.append(("adhesion.work_of_adhesion", "the work of adhesion", w))
        if self.adhesion.range is not None:
            single.append(("adhesion.range", "the range", self.adhesion.range))
        for name, what, value in single:
            if not low <= value <= high:
                raise SceneError(name, f"{what} ({value:.3g}) is outside [{low:g}, {high:g}]: rescale the units")
        M = modulus_name
        combined = [(f"stiffness {M} a", modulus * length)]
        if w > 0:
            combined += [
                (f"force sqrt({M} w a^3)", math.sqrt(modulus * w) * length**1.5),
                (f"approach sqrt(w a / {M})", math.sqrt(w * length / modulus)),
            ]
        for what, value in combined:
            if not low <= value <= high:
                raise SceneError(
                    "material",
                    f"the scene's {what} ({value:.3g}) is outside [{low:g}, {high:g}]: rescale lengths and moduli, "
                    f"e.g. to the face's size and {M}",
                )

    @property
    def effective_modulus(self) -> float:
        """E* = E / (1 - nu^2) of a homogeneous material.

        For a graded one the k = 0 equivalent 4 E0 / 3 is not meaningful, so this raises.

        Raises
        ------
        contact_scene.SceneError
            ``material``, for a graded material.
        """
        if isinstance(self.material, Homogeneous):
            return self.material.effective_modulus
        raise SceneError("material", "a graded material has no single effective modulus")
