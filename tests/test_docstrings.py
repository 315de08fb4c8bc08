"""The public API is documented in numpydoc style (issue #23), checked with ``numpydoc.validate``.

The API reference (docs/api/) is generated from these docstrings, so a parameter missing from
its ``Parameters`` section or a function that does not say what it returns is a hole in the
reference.  The walk covers what the reference shows: each package's ``__all__`` (and the
closed forms of :mod:`contact_scene.theory`), and the public methods and properties of every
exported class, including those it inherits from the package's own base classes.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib
import inspect
import re

# imported, not skipped when missing: numpydoc is in the test extra
import numpydoc.docscrape as docscrape
import numpydoc.validate as numpydoc_validate
import pytest

import contact_scene as cs

PACKAGES = ("contact_scene", "halfspace", "bem_griffith", "bem_energy", "fem_reference", "crossval")
#: modules offered as a name of a package's ``__all__``: their own ``__all__`` is public too
PUBLIC_MODULES = ("contact_scene.theory",)

#: what every public docstring must satisfy (numpydoc's codes, numpydoc.validate.ERROR_MSGS)
REQUIRED = {
    "GL08": "has a docstring",
    "SS01": "starts with a summary",
    "SS06": "the summary fits on one line",
    "GL06": "no unknown section",
    "GL07": "sections in numpydoc's order",
    "PR01": "every parameter documented",
    "PR02": "no parameter documented that the signature does not have",
    "PR03": "parameters documented in the signature's order",
    "PR04": "every documented parameter has a type",
    "PR07": "every documented parameter has a description",
    "PR10": "'name : type' spelled with a space before the colon",
    "RT01": "a Returns section where something is returned",
    "RT03": "the returned value has a description",
}

# public objects allowed to fail a check while their docstrings are written (empty: every
# public object passes); an entry that is no longer needed fails the staleness test
NOT_YET: dict[str, set[str]] = {}


#: members the reference shows as properties
PROPERTIES = (property, functools.cached_property)


def _own(obj) -> bool:
    return getattr(obj, "__module__", "").split(".")[0] in PACKAGES


def _public_objects():
    """(name, object) for every function and class of the public API, then each class's public
    methods and properties (those it inherits from this project's base classes included), once
    each, named after the public class that defines them."""
    seen: set[int] = set()
    classes: dict[type, str] = {}
    for modname in PACKAGES + PUBLIC_MODULES:
        mod = importlib.import_module(modname)
        for name in mod.__all__:
            obj = getattr(mod, name)
            if not (inspect.isclass(obj) or inspect.isroutine(obj)) or id(obj) in seen:
                continue  # constants, registries and submodules have no numpydoc sections
            seen.add(id(obj))
            yield f"{modname}.{name}", obj
            if inspect.isclass(obj):
                classes[obj] = f"{modname}.{name}"
    for cls, qualname in classes.items():
        for klass in cls.__mro__:
            if not _own(klass):
                continue  # object, NamedTuple, Exception: not this project's API
            for name, attr in vars(klass).items():
                if isinstance(attr, (staticmethod, classmethod)):
                    attr = attr.__func__
                if name.startswith("_") or not (inspect.isfunction(attr) or isinstance(attr, PROPERTIES)):
                    continue
                if id(attr) not in seen:
                    seen.add(id(attr))
                    yield f"{classes.get(klass, qualname)}.{name}", attr


def _inherited_from(cls_attr, name: str, owner: type):
    """The documented base-class member an undocumented override takes its docstring from (as
    the API reference shows it: Sphinx inherits docstrings), or None."""
    for base in owner.__mro__[1:]:
        if name in vars(base):
            base_attr = vars(base)[name]
            if isinstance(base_attr, (staticmethod, classmethod)):
                base_attr = base_attr.__func__
            if getattr(base_attr, "__doc__", None):
                return base_attr
    return None


def _owner(obj, qualname: str) -> type | None:
    """The class a member is defined in."""
    func = _function(obj)
    parts = getattr(func, "__qualname__", "").split(".")
    if len(parts) < 2:
        return None
    mod = inspect.getmodule(func)
    owner = mod
    for part in parts[:-1]:
        owner = getattr(owner, part, None)
    return owner if inspect.isclass(owner) else None


def _function(obj):
    """The function behind a member (a property's getter)."""
    if isinstance(obj, property):
        return obj.fget
    return obj.func if isinstance(obj, functools.cached_property) else obj


def _params(obj) -> list[str]:
    try:
        return list(inspect.signature(_function(obj)).parameters)
    except (TypeError, ValueError):
        return []


def _errors(qualname: str, obj) -> list[tuple[str, str]]:
    """numpydoc's errors of the docstring a reader of the API reference sees."""
    name = qualname.rsplit(".", 1)[-1]
    owner = _owner(obj, qualname)
    if not getattr(obj, "__doc__", None) and owner is not None:
        base = _inherited_from(obj, name, owner)
        if base is not None:
            # the reference shows the base's docstring: it is checked where the base is walked
            # (base classes are public here); the override must keep the documented parameters
            if _params(obj) != _params(base):
                return [("PR01", f"{_params(obj)} inherits the docstring written for {_params(base)}")]
            return []
    errors = [e for e in numpydoc_validate.validate(docscrape.get_doc_object(obj))["errors"] if e[0] in REQUIRED]
    if inspect.isclass(obj) and dataclasses.is_dataclass(obj):
        # a dataclass's fields are its constructor's parameters: a record the library fills and
        # the user reads documents them as Attributes, a class the user builds as Parameters
        parsed = docscrape.ClassDoc(obj, config={"show_class_members": False})
        documented = {p.name for p in parsed["Parameters"]} | {p.name for p in parsed["Attributes"]}
        missing = [f.name for f in dataclasses.fields(obj) if f.init and f.name not in documented]
        errors = [e for e in errors if e[0] != "PR01"]
        if missing:
            errors.append(("PR01", f"fields {missing} documented neither as Parameters nor as Attributes"))
    return errors


OBJECTS = dict(_public_objects())


@functools.cache
def _errors_of(qualname: str) -> tuple[tuple[str, str], ...]:
    return tuple(_errors(qualname, OBJECTS[qualname]))


def test_the_walk_reaches_the_api():
    """The walk sees the solvers, the closed forms, the shapes' methods and inherited members."""
    for name in (
        "bem_griffith.solve",
        "bem_energy.pull_off",
        "contact_scene.theory.kendall_adhesion_force",
        "contact_scene.Circle",
        "contact_scene.Shape.incircle",
        "contact_scene.Shape.area",
        "halfspace.HalfSpaceOperator.apply",
        "crossval.Reference.error_bar",
    ):
        assert name in OBJECTS, name
    assert len(OBJECTS) > 250


def test_public_docstrings_follow_numpydoc():
    problems = []
    for qualname in OBJECTS:
        allowed = NOT_YET.get(qualname, set())
        for code, message in _errors_of(qualname):
            if code not in allowed:
                problems.append(f"{qualname}: {code} {message}")
    assert not problems, f"{len(problems)} docstring problems:\n" + "\n".join(problems)


def test_the_exclusions_are_still_needed():
    """An exclusion that no longer applies is removed, so that it cannot hide a regression."""
    stale = []
    for qualname, allowed in NOT_YET.items():
        assert qualname in OBJECTS, f"{qualname} is no longer public: remove it from NOT_YET"
        found = {code for code, _ in _errors_of(qualname)}
        stale += [f"{qualname}: {code}" for code in sorted(allowed - found)]
    assert not stale, "remove from NOT_YET (now documented):\n" + "\n".join(stale)


def _half_documented(a, b):
    """Add two numbers.

    Parameters
    ----------
    a : float
        The first.

    Usage
    -----
    Not a numpydoc section.
    """
    return a + b


class _OverrideWithOtherParameters(cs.Circle):
    def contains(self, points):  # no docstring: the reference shows Shape.contains' (x, y)
        return super().contains(*points)


@dataclasses.dataclass(frozen=True)
class _RecordMissingAField:
    """A record.

    Attributes
    ----------
    kept : float
        Documented.
    """

    kept: float
    forgotten: float


def test_the_checks_catch_broken_docstrings():
    """The checker itself: each kind of hole is reported (a numpydoc that stopped parsing the
    sections would otherwise pass every docstring)."""
    with pytest.warns(UserWarning, match="Unknown section Usage"):  # numpydoc's parser says so too
        codes = {code for code, _ in _errors("tests._half_documented", _half_documented)}
    assert {"PR01", "RT01", "GL06"} <= codes
    override = _errors("tests._OverrideWithOtherParameters.contains", _OverrideWithOtherParameters.contains)
    assert [code for code, _ in override] == ["PR01"]
    record = _errors("tests._RecordMissingAField", _RecordMissingAField)
    assert [code for code, _ in record] == ["PR01"] and "forgotten" in record[0][1]
    assert _bars("the magnitude |d| of the approach") == ["|d|"]
    assert _bars("``x | y`` and float | None") == []


#: a magnitude written |x| outside an inline literal: reStructuredText reads it as a substitution
BARS = re.compile(r"(?<![|`])\|[^|\n]+\|(?![|`])")

# public docstrings allowed to write |x| (empty: all write abs(x))
BARS_NOT_YET: set[str] = set()


def _bars(text: str) -> list[str]:
    return BARS.findall(re.sub(r"``.*?``", "", text, flags=re.S))


def test_magnitudes_are_written_abs():
    """Docstrings write abs(x), not |x|, so that the API reference renders them as written."""
    found = {}
    for qualname, obj in OBJECTS.items():
        bars = _bars(getattr(obj, "__doc__", None) or "")
        if bars:
            found[qualname] = bars
    for modname in PACKAGES + PUBLIC_MODULES:
        bars = _bars(importlib.import_module(modname).__doc__ or "")
        if bars:
            found[modname] = bars
    assert set(found) == BARS_NOT_YET, (
        "write abs(x) (or remove from BARS_NOT_YET):\n"
        + "\n".join(f"{name}: {bars}" for name, bars in found.items() if name not in BARS_NOT_YET)
        + "".join(f"\n{name}: no bars left" for name in BARS_NOT_YET - set(found))
    )
