"""The built-in scenes: one TOML file per name in ``crossval/scenes/``, shipped with the package.

``SUITE`` is the set every method is checked on (the report, ``regress`` and the pytest
plugin's reference scenes); it is dimensionless (E* = 1, w = 1, unit size) except where a scene
exists to catch a scaling: the Kendall circle is compressible (nu = 0.3) so that E and E* differ,
the incompressible circle has radius 2 and w = 1/2, the k = 0.25 graded circle radius 1/2 and
c0 = 2, so that a length, an adhesion energy or a reference depth left out of a formula shows.
The ``paper_*`` scenes are the paper's fitted experiments in SI units (Figs. 13-15), shipped as
examples but not in the suite.
A scene's name is its file's stem, so a name means one scene wherever it appears.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

import contact_scene as cs

__all__ = ["SUITE", "BUILTIN", "SCENE_DIR", "scene", "load_scene_or_builtin"]

#: where the built-in scene files live (inside the installed package)
SCENE_DIR = Path(str(resources.files("crossval") / "scenes"))

_SUITE_NAMES = (
    "kendall_circle",
    "incompressible_circle",
    "graded_circle_k0.25",
    "graded_circle_k0.5",
    "square",
    "triangle",
    "star",
    "rectangle",
    "two_circles",
    "jkr_sphere",
)


def _load(path: Path) -> cs.Scene:
    sc = cs.load_scene(path)
    if sc.name != path.stem:
        raise cs.SceneError("name", f"built-in scene file {path.name} must be named {path.stem!r} (got {sc.name!r})")
    return sc


#: every shipped scene by name
BUILTIN: dict[str, cs.Scene] = {p.stem: _load(p) for p in sorted(SCENE_DIR.glob("*.toml"))}

SUITE: dict[str, cs.Scene] = {name: BUILTIN[name] for name in _SUITE_NAMES}


def scene(name: str) -> cs.Scene:
    """A built-in scene by name."""
    if name not in BUILTIN:
        raise cs.SceneError("scene", f"unknown built-in scene {name!r}; one of: {', '.join(BUILTIN)}")
    return BUILTIN[name]


def load_scene_or_builtin(file_or_name: str | Path) -> cs.Scene:
    """A built-in scene by name, or a scene file.

    The rule does not depend on what the current directory holds: a string that is a built-in
    scene's name (``crossval scene list``) is that scene, even when a file or directory of that
    name exists (write ``./star`` for a file called ``star``); anything else, and any
    :class:`os.PathLike`, is a scene file's path.

    Parameters
    ----------
    file_or_name : str or pathlib.Path
        A built-in scene's name, or a scene file's path.

    Returns
    -------
    contact_scene.Scene
        The built-in scene, or the scene read from the file.

    Raises
    ------
    contact_scene.SceneError
        With field ``file`` for a directory, for a name that is neither a file nor a built-in
        scene (listing them), or when the file cannot be read; naming the offending field of a
        bad scene file.
    """
    if isinstance(file_or_name, str) and file_or_name in BUILTIN:
        return BUILTIN[file_or_name]
    path = Path(file_or_name)
    if path.is_dir():
        raise cs.SceneError("file", f"{str(file_or_name)!r} is a directory, not a scene file")
    if not path.exists() and path.suffix != ".toml" and len(path.parts) == 1:
        raise cs.SceneError(
            "file",
            f"no file {str(file_or_name)!r} and no built-in scene of that name; built-in scenes: {', '.join(BUILTIN)}",
        )
    return cs.load_scene(path)
