"""pytest plugin (entry point ``pytest11``): reference results for testing your own solver.

def test_my_solver(adhesion_reference):
    ref = adhesion_reference("kendall_circle")           # or any contact_scene.Scene
    d, F = my_solver(...)                                 # your force-approach curve
    assert_matches_reference(ref, curve=(d, F), rtol=0.01)
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest


@pytest.fixture(scope="session")
def adhesion_reference():
    """Session fixture: reference results by scene or name, each computed once per session.

    Returns
    -------
    callable
        ``get(scene_or_name, *, resolution=64)`` -> :class:`crossval.Reference`, as
        :func:`crossval.reference` computes it (a built-in scene's name, a scene file's path or a
        :class:`contact_scene.Scene`; elements per radius of the Griffith BEM where the FEM does
        not apply); a name, a file (by its resolved path) or an equal Scene, at one resolution, is
        solved once per session.
    """
    from .reference import reference
    from .suite import BUILTIN

    cache: dict = {}
    # objects keyed by identity stay referenced here: an id is unique only while its object
    # lives, and a Path built inline in the call was collected and its id reused for another
    # file's, which then received the first file's reference
    pinned: list = []

    def key_of(scene_or_name):
        if isinstance(scene_or_name, str):
            # a built-in name is that scene wherever the test runs; any other string is a path,
            # resolved, so that two tests in different directories do not share "scene.toml"
            if scene_or_name in BUILTIN:
                return ("built-in", scene_or_name)
            return ("path", str(Path(scene_or_name).resolve()))
        if isinstance(scene_or_name, os.PathLike):
            return ("path", str(Path(scene_or_name).resolve()))
        try:
            hash(scene_or_name)
        except TypeError:
            pinned.append(scene_or_name)
            return ("object", id(scene_or_name))
        return ("scene", scene_or_name)  # equal scenes (frozen dataclasses) share a reference

    def get(scene_or_name, *, resolution: float = 64):
        key = (key_of(scene_or_name), resolution)
        if key not in cache:
            cache[key] = reference(scene_or_name, resolution=resolution)
        return cache[key]

    return get
