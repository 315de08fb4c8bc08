"""Declared fields: each parameter of a scene part or solver setting states its allowed range once,
where it is defined.

A frozen dataclass writes ``youngs_modulus: float = real(gt=0)`` instead of a line of validation
in ``__post_init__``, and calls ``check_fields(self, "material")`` there.  :func:`check_fields`
walks the declared fields in order, checks each value and stores the checked one (a float, an
int, a bool, a string, a pair of floats or a tuple of floats), so that a bad value raises
``SceneError(field, message)`` naming the field as the user spells it (``material.youngs_modulus``
in a scene file, ``settings.rtol`` for a solver setting) and the allowed range.  One mechanism
for every class means one wording of every message, and a test can walk the declarations
(:func:`declared_fields`) to check every range of every class.

A bound may be a number or a function of the object, for ranges that depend on a field declared
earlier (``semi_minor: float = real(gt=0, le=lambda e: e.semi_major)``): fields are checked in
declaration order, so the earlier one is already checked when the bound is read.  ``when`` makes
a check conditional (a brush's ``pitch`` only matters for a regular layout); with ``unused``, a
value other than the field's default is refused while ``when`` is false, with that message, so
that a parameter the object does not use is not accepted and then ignored (the default itself
passes: a regular brush is built without a count).  ``optional`` lets ``None`` through unchanged
(``None`` means "not given" for such fields).  Rules that are not a range of one field (two
options that exclude each other, a value required by another) stay as explicit code in the
class's ``__post_init__``.
"""

from __future__ import annotations

import dataclasses
import numbers
from collections.abc import Callable
from dataclasses import MISSING
from typing import Any

from .errors import SceneError, check_choice, check_int, check_real

__all__ = [
    "real",
    "whole",
    "point",
    "choice",
    "flag",
    "reals",
    "check_fields",
    "declared_fields",
    "field_name",
    "FieldCheck",
]

_KEY = "contact_scene.check"

Bound = float | Callable[[Any], float] | None


def _value(bound: Bound, obj) -> float | None:
    return bound(obj) if callable(bound) else bound


@dataclasses.dataclass(frozen=True)
class FieldCheck:
    """How one field is checked: ``kind`` and its range (strict ``gt``/``lt`` or closed ``ge``/``le``).

    kind
        ``"real"`` (a finite float), ``"whole"`` (an int), ``"point"`` (a pair of finite floats),
        ``"choice"`` (one of ``choices``), ``"flag"`` (True or False) or ``"reals"`` (a tuple of
        finite floats, each in the range).
    name
        The error's field when it is not ``<prefix>.<field>`` (``indenter.profile_radius`` for a
        profile's ``radius``).
    when
        Check only when this function of the object is true.
    unused
        With ``when``: while ``when`` is false, a value other than the field's default is
        refused with this message (or the message this function of the object returns), e.g.
        "only applies to layout 'regular'".  Without it such a value is left unchecked.
    optional
        ``None`` is a valid value ("not given") and is stored as is.
    """

    kind: str
    gt: Bound = None
    ge: Bound = None
    lt: Bound = None
    le: Bound = None
    choices: tuple[str, ...] = ()
    name: str | None = None
    when: Callable[[Any], bool] | None = None
    optional: bool = False
    unused: str | Callable[[Any], str] | None = None

    def bounds(self, obj) -> tuple[float | None, bool, float | None, bool]:
        """(lower, lower is open, upper, upper is open) evaluated on ``obj``; None: unbounded."""
        lower = _value(self.gt, obj) if self.gt is not None else _value(self.ge, obj)
        upper = _value(self.lt, obj) if self.lt is not None else _value(self.le, obj)
        return lower, self.gt is not None, upper, self.lt is not None

    def check(self, obj, name: str, value):
        """The checked value to store, or SceneError naming ``name``."""
        if value is None and self.optional:
            return None
        if self.kind == "point":
            return _point(name, value)
        if self.kind == "choice":
            return check_choice(name, value, set(self.choices))
        if self.kind == "flag":
            if not isinstance(value, bool):
                raise SceneError(name, f"must be true or false (got {value!r})")
            return value
        lower, lower_open, upper, upper_open = self.bounds(obj)
        if self.kind == "whole":
            return check_int(name, value, lo=lower, hi=upper)
        if self.kind == "reals":
            # an ordered sequence: a dict or a set would give its keys in an order nobody chose
            if isinstance(value, (str, bytes, dict, set, frozenset)) or not hasattr(value, "__iter__"):
                raise SceneError(name, f"must be a list of numbers (got {value!r})")
            return tuple(check_real(name, v, lo=lower, hi=upper, lo_open=lower_open, hi_open=upper_open) for v in value)
        return check_real(name, value, lo=lower, hi=upper, lo_open=lower_open, hi_open=upper_open)


def _declare(check: FieldCheck, default, factory) -> Any:
    if (check.gt is not None and check.ge is not None) or (check.lt is not None and check.le is not None):
        raise TypeError("give one lower bound (gt or ge) and one upper bound (lt or le)")
    if check.unused is not None and check.when is None:
        raise TypeError("unused says why a value is refused while `when` is false: give when too")
    if factory is not MISSING:
        return dataclasses.field(default_factory=factory, metadata={_KEY: check})
    return dataclasses.field(default=default, metadata={_KEY: check})


def real(
    default=MISSING,
    *,
    gt: Bound = None,
    ge: Bound = None,
    lt: Bound = None,
    le: Bound = None,
    name: str | None = None,
    when: Callable[[Any], bool] | None = None,
    optional: bool = False,
    unused: str | Callable[[Any], str] | None = None,
) -> Any:
    """A finite real number, optionally bounded (``gt``/``lt`` exclusive, ``ge``/``le`` inclusive),
    stored as a float."""
    return _declare(
        FieldCheck("real", gt, ge, lt, le, name=name, when=when, optional=optional, unused=unused), default, MISSING
    )


def whole(
    default=MISSING,
    *,
    ge: Bound = None,
    le: Bound = None,
    name: str | None = None,
    when: Callable[[Any], bool] | None = None,
    factory: Callable[[], int] | Any = MISSING,
    unused: str | Callable[[Any], str] | None = None,
) -> Any:
    """A whole number in [ge, le], stored as an int; ``factory`` computes the default at construction."""
    return _declare(FieldCheck("whole", ge=ge, le=le, name=name, when=when, unused=unused), default, factory)


def point(default=(0.0, 0.0), *, name: str | None = None) -> Any:
    """A pair of finite numbers (x, y), stored as a tuple of floats."""
    return _declare(FieldCheck("point", name=name), default, MISSING)


def choice(default, choices, *, name: str | None = None) -> Any:
    """One of the given strings."""
    return _declare(FieldCheck("choice", choices=tuple(choices), name=name), default, MISSING)


def flag(default, *, name: str | None = None) -> Any:
    """True or False (not a number standing for one)."""
    return _declare(FieldCheck("flag", name=name), default, MISSING)


def reals(
    default=(),
    *,
    gt: Bound = None,
    ge: Bound = None,
    lt: Bound = None,
    le: Bound = None,
    name: str | None = None,
) -> Any:
    """A sequence of finite numbers, each in the range, stored as a tuple of floats."""
    return _declare(FieldCheck("reals", gt, ge, lt, le, name=name), default, MISSING)


def _point(name: str, value) -> tuple[float, float]:
    try:
        x, y = value
    except (TypeError, ValueError):
        raise SceneError(name, f"must be a pair of numbers (got {value!r})") from None
    return (check_real(name, x), check_real(name, y))


def declared_fields(obj_or_class) -> tuple[tuple[str, FieldCheck], ...]:
    """The declared fields of a dataclass (or of an instance's class), in declaration order:
    (attribute name, its check)."""
    return tuple(
        (f.name, f.metadata[_KEY])
        for f in dataclasses.fields(obj_or_class)
        if isinstance(f.metadata.get(_KEY), FieldCheck)
    )


def field_name(prefix: str, attribute: str, check: FieldCheck) -> str:
    """The field an error names: the declared ``name``, else ``<prefix>.<attribute>``."""
    return check.name or f"{prefix}.{attribute}"


def _is_default(f: dataclasses.Field, value) -> bool:
    """Whether ``value`` is the field's default (of the same type: False is not a default 0)."""
    if f.default is not MISSING:
        default = f.default
    elif f.default_factory is not MISSING:
        default = f.default_factory()
    else:
        return False
    if value is default:
        return True
    if isinstance(value, bool) or isinstance(default, bool):
        return type(value) is type(default) and value == default  # False is not a default 0
    if isinstance(value, numbers.Real) and isinstance(default, numbers.Real):
        return bool(value == default)  # numpy's int64(0) is a default 0
    try:
        return type(value) is type(default) and bool(value == default)
    except Exception:  # an array or another object without a plain truth value
        return False


def check_fields(obj, prefix: str) -> None:
    """Check every declared field of the frozen dataclass ``obj`` in declaration order and store the
    checked value; an error names ``<prefix>.<field>`` (or the field's declared ``name``).  A
    field whose ``when`` is false is not checked, and, if it declares ``unused``, refused unless
    it holds its default."""
    fields = {f.name: f for f in dataclasses.fields(obj)}
    for attribute, check in declared_fields(obj):
        if check.when is not None and not check.when(obj):
            value = getattr(obj, attribute)
            if check.unused is not None and not _is_default(fields[attribute], value):
                why = check.unused(obj) if callable(check.unused) else check.unused
                raise SceneError(field_name(prefix, attribute, check), f"{why} (got {value!r})")
            continue
        value = check.check(obj, field_name(prefix, attribute, check), getattr(obj, attribute))
        object.__setattr__(obj, attribute, value)
