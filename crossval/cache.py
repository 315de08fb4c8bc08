"""On-disk cache of results, keyed by scene, method, resolution and package version.

Writes are atomic (a temporary file renamed into place), so an interrupted run leaves either
the old entry or none, never half a file.
"""
from __future__ import annotations

import hashlib
import os
import pickle
import tempfile
from importlib import metadata
from pathlib import Path

__all__ = ["ResultCache", "package_version"]


def package_version() -> str:
    try:
        return metadata.version("adhesive-punch")
    except metadata.PackageNotFoundError:  # pragma: no cover - running from a source tree
        return "0+unknown"


class ResultCache:
    """``get``/``put`` results by key; in memory for the object's life, and on disk unless
    ``directory`` is None."""

    def __init__(self, directory: str | os.PathLike | None):
        self.directory = None if directory is None else Path(directory)
        self._memory: dict = {}

    @staticmethod
    def key(scene, method: str, resolution) -> str:
        text = "\n".join([repr(scene), method, repr(resolution), package_version()])
        return hashlib.sha256(text.encode()).hexdigest()[:32]

    def _path(self, key: str) -> Path:
        return self.directory / f"{key}.pkl"

    def get(self, key: str):
        if key in self._memory:
            return self._memory[key]
        if self.directory is None:
            return None
        try:
            with open(self._path(key), "rb") as f:
                return pickle.load(f)
        except (OSError, pickle.UnpicklingError, EOFError):
            return None

    def put(self, key: str, value) -> None:
        self._memory[key] = value
        if self.directory is None:
            return
        self.directory.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=self.directory, suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as f:
                pickle.dump(value, f, protocol=pickle.HIGHEST_PROTOCOL)
            os.replace(tmp, self._path(key))
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
