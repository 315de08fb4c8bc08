"""The one error type a bad scene raises, and the checks that raise it.

Every message names the offending field (dotted, as in the scene file) and the
allowed range, so that the CLI can print it as is and exit with status 2.  Classes declare
their fields' ranges with :mod:`contact_scene.validation`, which calls these checks.
"""

from __future__ import annotations

import math
import numbers

__all__ = ["SceneError", "check_real", "check_int", "check_choice", "check_type"]


class SceneError(ValueError):
    """An invalid scene, scene file, discretisation or solver setting.

    The message names the offending entry and its allowed range, so that the CLI can print it
    as is (and exit with status 2); ``str(error)`` is ``"<field>: <message>"``.

    Parameters
    ----------
    field : str
        The dotted name of the offending entry, as a scene file spells it
        (``material.youngs_modulus``) or as the solver's settings are named
        (``settings.rtol``).
    message : str
        What is wrong, with the allowed values (``"must be > 0 (got -1)"``).

    Attributes
    ----------
    field : str
        The ``field`` given, for a caller that reacts to one entry.
    """

    def __init__(self, field: str, message: str):
        self.field = field
        super().__init__(f"{field}: {message}")


def _describe(lo, hi, lo_open, hi_open) -> str:
    """The allowed values as a phrase that follows "must be": "in [0, 1)", "> 0" ("" when unbounded)."""
    if lo is not None and hi is not None:
        return f"in {'(' if lo_open else '['}{lo:g}, {hi:g}{')' if hi_open else ']'}"
    if lo is not None:
        return f"{'>' if lo_open else '>='} {lo:g}"
    if hi is not None:
        return f"{'<' if hi_open else '<='} {hi:g}"
    return ""


def check_real(field: str, value, *, lo=None, hi=None, lo_open=False, hi_open=False) -> float:
    """Return ``value`` as a finite float inside the given interval, or raise SceneError.

    ``lo`` and ``hi`` are the lower and upper bounds (None: unbounded); ``lo_open`` and
    ``hi_open`` exclude them."""
    allowed = _describe(lo, hi, lo_open, hi_open)
    in_range = f" {allowed}" if allowed else ""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise SceneError(field, f"must be a number{in_range} (got {value!r})")
    v = float(value)
    if not math.isfinite(v):
        raise SceneError(field, f"must be a finite number{in_range} (got {value!r})")
    bad = (lo is not None and (v <= lo if lo_open else v < lo)) or (hi is not None and (v >= hi if hi_open else v > hi))
    if bad:
        raise SceneError(field, f"must be {allowed} (got {v:g})")
    return v


def check_int(field: str, value, *, lo=None, hi=None) -> int:
    """Return ``value`` as an int in [lo, hi] (None: unbounded), or raise SceneError."""
    allowed = _describe(lo, hi, False, False)
    in_range = f" {allowed}" if allowed else ""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise SceneError(field, f"must be a whole number{in_range} (got {value!r})")
    v = int(value)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        raise SceneError(field, f"must be a whole number{in_range} (got {v})")
    return v


def check_choice(field: str, value, choices) -> str:
    """Return ``value`` if it is one of the strings ``choices``, or raise SceneError listing them."""
    if not isinstance(value, str) or value not in choices:
        raise SceneError(field, f"must be one of {', '.join(map(repr, sorted(choices)))} (got {value!r})")
    return value


def check_type(field: str, value, expected: type | tuple[type, ...]):
    """Return ``value`` if it is an instance of ``expected``, or raise SceneError naming the types.

    A solver handed another solver's settings, or a string for a scene, would otherwise fail
    later with an AttributeError that names neither."""
    if not isinstance(value, expected):
        types = expected if isinstance(expected, tuple) else (expected,)
        names = " or ".join(f"{t.__module__.split('.')[0]}.{t.__name__}" for t in types)
        raise SceneError(field, f"must be a {names} (got {type(value).__name__})")
    return value
