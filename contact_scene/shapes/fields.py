"""Declared shape parameters: each field states its allowed range once, where it is defined.

A shape writes ``radius: float = real(gt=0)`` instead of a line of validation in
``__post_init__``.  :func:`check_fields` (called by ``Shape.__post_init__``) walks the
declared fields in order, checks each value and stores the checked one (a float, an int or a
pair of floats), so a bad value raises ``SceneError(field, message)`` naming the field as the
scene file spells it (``indenter.radius``) and the allowed range.

A bound may be a number or a function of the shape, for ranges that depend on a parameter
declared earlier (``semi_minor: float = real(gt=0, le=lambda e: e.semi_major)``): fields are
checked in declaration order, so the earlier one is already checked when the bound is read.
``when`` makes a check conditional (a brush's ``pitch`` only matters for a regular layout).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import MISSING
from typing import Any

from ..errors import SceneError, check_choice, check_int, check_real

__all__ = ["real", "whole", "point", "choice", "check_fields"]

_SPEC = "contact_scene.check"

Bound = float | Callable[[Any], float] | None


def _value(bound: Bound, shape) -> float | None:
    return bound(shape) if callable(bound) else bound


@dataclasses.dataclass(frozen=True)
class _Spec:
    """How one field is checked: ``kind`` and its range (strict ``gt``/``lt`` or closed ``ge``/``le``)."""

    kind: str  # "real" | "whole" | "point" | "choice"
    gt: Bound = None
    ge: Bound = None
    lt: Bound = None
    le: Bound = None
    choices: tuple[str, ...] = ()
    name: str | None = None  # the error's field, when it is not "indenter.<field>"
    when: Callable[[Any], bool] | None = None

    def check(self, shape, name: str, value):
        if self.kind == "point":
            return _point(name, value)
        if self.kind == "choice":
            return check_choice(name, value, set(self.choices))
        lower = _value(self.gt, shape) if self.gt is not None else _value(self.ge, shape)
        upper = _value(self.lt, shape) if self.lt is not None else _value(self.le, shape)
        if self.kind == "whole":
            return check_int(name, value, lo=lower, hi=upper)
        return check_real(name, value, lo=lower, hi=upper, lo_open=self.gt is not None, hi_open=self.lt is not None)


def _declare(spec: _Spec, default) -> Any:
    if (spec.gt is not None and spec.ge is not None) or (spec.lt is not None and spec.le is not None):
        raise TypeError("give one lower bound (gt or ge) and one upper bound (lt or le)")
    return dataclasses.field(default=default, metadata={_SPEC: spec})


def real(
    default=MISSING,
    *,
    gt: Bound = None,
    ge: Bound = None,
    lt: Bound = None,
    le: Bound = None,
    name: str | None = None,
    when: Callable[[Any], bool] | None = None,
) -> Any:
    """A finite real number, optionally bounded (``gt``/``lt`` exclusive, ``ge``/``le`` inclusive)."""
    return _declare(_Spec("real", gt, ge, lt, le, name=name, when=when), default)


def whole(default=MISSING, *, ge: Bound = None, le: Bound = None, when: Callable[[Any], bool] | None = None) -> Any:
    """A whole number in [ge, le]."""
    return _declare(_Spec("whole", ge=ge, le=le, when=when), default)


def point(default=(0.0, 0.0)) -> Any:
    """A pair of finite numbers (x, y)."""
    return _declare(_Spec("point"), default)


def choice(default, choices: tuple[str, ...]) -> Any:
    """One of the given strings."""
    return _declare(_Spec("choice", choices=tuple(choices)), default)


def _point(name: str, value) -> tuple[float, float]:
    try:
        x, y = value
    except (TypeError, ValueError):
        raise SceneError(name, f"must be a pair of numbers (got {value!r})") from None
    return (check_real(name, x), check_real(name, y))


def check_fields(shape) -> None:
    """Check every declared field of ``shape`` in declaration order and store the checked value."""
    for f in dataclasses.fields(shape):
        spec = f.metadata.get(_SPEC)
        if spec is None or (spec.when is not None and not spec.when(shape)):
            continue
        name = spec.name or f"indenter.{f.name}"
        object.__setattr__(shape, f.name, spec.check(shape, name, getattr(shape, f.name)))
