"""On-disk cache of results, keyed by scene, method, resolution, package version and the
solvers' source code.

Each entry is one ``.npz`` file: the result's arrays, plus its scalars, strings and nesting as
JSON text.  Both are data only: loading an entry never runs code, so a cache directory copied
from elsewhere (or committed to a shared repository) is as safe to read as any data file.  An
entry that cannot be read, or that holds another key or another format, is a miss: the result
is recomputed and the entry overwritten, with one warning.

Writes are atomic (a temporary file renamed into place), so an interrupted run leaves either
the old entry or none, never half a file, and two runs sharing a directory each read whole
entries (both compute the same deterministic result; the last rename wins).
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import logging
import os
import tempfile
import zipfile
from importlib import metadata
from pathlib import Path
from typing import Any

import numpy as np

from contact_scene import Curve, ErrorBar, Result, Snapshot, SolverStats

__all__ = ["ResultCache", "package_version", "source_digest", "encode_result", "decode_result", "FORMAT"]

log = logging.getLogger("crossval")

#: bumped whenever the entry layout changes: older entries are then misses, not errors
FORMAT = 1

_TYPES = {cls.__name__: cls for cls in (Result, Curve, Snapshot, SolverStats, ErrorBar)}


def package_version() -> str:
    try:
        return metadata.version("adhesive-punch")
    except metadata.PackageNotFoundError:  # pragma: no cover - running from a source tree
        return "0+unknown"


#: the packages whose code decides a result, and the harness's mapping of resolutions to settings
_RESULT_SOURCES = ("contact_scene", "halfspace", "bem_griffith", "bem_energy", "fem_reference")


@functools.cache
def source_digest() -> str:
    """A digest of the source (``.py``) and data (``.json``) files of the packages that compute
    results, and of ``crossval/methods.py``.

    The package version alone does not change while a checkout is edited (an editable install):
    a solver changed in place reused every cached result computed before, so a broken solver
    passed a report.  Hashing the files makes any edit a cache miss.

    Returns
    -------
    str
        A hexadecimal digest.
    """
    import importlib.util

    h = hashlib.sha256()
    roots = []
    for name in _RESULT_SOURCES:
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.submodule_search_locations:
            roots.append(Path(next(iter(spec.submodule_search_locations))))
    files = [f for root in roots for pattern in ("*.py", "*.json") for f in root.rglob(pattern)]
    files.append(Path(__file__).with_name("methods.py"))
    for f in sorted(files):
        h.update(f.name.encode())
        h.update(f.read_bytes())
    return h.hexdigest()


def encode_result(result: Result) -> tuple[str, dict[str, np.ndarray]]:
    """JSON text and the arrays it refers to (by name), for :func:`decode_result`."""
    arrays: dict[str, np.ndarray] = {}

    def enc(obj):
        if isinstance(obj, np.ndarray):
            name = f"a{len(arrays)}"
            arrays[name] = obj
            return {"__array__": name}
        if dataclasses.is_dataclass(obj) and type(obj).__name__ in _TYPES:
            return {
                "__type__": type(obj).__name__,
                **{f.name: enc(getattr(obj, f.name)) for f in dataclasses.fields(obj)},
            }
        if isinstance(obj, dict):
            if not all(isinstance(k, str) and not k.startswith("__") for k in obj):
                raise TypeError(f"cannot cache a dict with keys {list(obj)!r}")
            return {k: enc(v) for k, v in obj.items()}
        if isinstance(obj, tuple):
            return {"__tuple__": [enc(v) for v in obj]}
        if isinstance(obj, list):
            return [enc(v) for v in obj]
        if isinstance(obj, (bool, np.bool_)):
            return bool(obj)
        if isinstance(obj, (int, np.integer)):
            return int(obj)
        if isinstance(obj, (float, np.floating)):
            v = float(obj)
            # JSON has no inf or nan: keep them exact as strings
            return v if np.isfinite(v) else {"__float__": repr(v)}
        if obj is None or isinstance(obj, str):
            return obj
        raise TypeError(f"cannot cache a {type(obj).__name__}")

    return json.dumps(enc(result), allow_nan=False), arrays


def decode_result(text: str, arrays) -> Result:
    """The inverse of :func:`encode_result`; only the package's own result types are built."""

    def dec(obj):
        if isinstance(obj, list):
            return [dec(v) for v in obj]
        if not isinstance(obj, dict):
            return obj
        if "__array__" in obj:
            return np.asarray(arrays[obj["__array__"]])
        if "__tuple__" in obj:
            return tuple(dec(v) for v in obj["__tuple__"])
        if "__float__" in obj:
            return float(obj["__float__"])
        if "__type__" in obj:
            cls = _TYPES[obj["__type__"]]
            return cls(**{k: dec(v) for k, v in obj.items() if k != "__type__"})
        return {k: dec(v) for k, v in obj.items()}

    out = dec(json.loads(text))
    if not isinstance(out, Result):
        raise TypeError(f"the entry holds a {type(out).__name__}, not a Result")
    return out


class _Unusable(Exception):
    """Why an entry on disk is a miss, worded for the warning."""


#: how a zip archive (and so an ``.npz`` file) starts: a file header, or an empty archive's end record
_ZIP_MAGIC = (b"PK\x03\x04", b"PK\x05\x06")

_DAMAGED = (OSError, EOFError, ValueError, zipfile.BadZipFile)


def _read_entry(path: Path, key: str) -> Result:
    """The result in the entry ``path``, raising :class:`_Unusable` with the reason it is not one.

    The file is checked to be a zip archive before numpy reads it: ``np.load`` sniffs any other
    bytes as a pickle and, refusing it, would have the warning speak of pickled data and of
    loading the file unsafely, where the plain fact is that the file is no cache archive.
    """
    try:
        with open(path, "rb") as f:
            head = f.read(4)
    except OSError as exc:
        raise _Unusable(f"which cannot be opened ({exc.strerror or exc})") from exc
    if not head.startswith(_ZIP_MAGIC):
        what = "the file is empty" if not head else "it does not start as a zip archive does"
        raise _Unusable(f"which is not a readable cache archive (not an .npz file: {what})")
    try:
        with np.load(path, allow_pickle=False) as z:
            if "__meta__" not in z.files:
                raise _Unusable("an .npz archive without a cache entry's metadata (not written by this cache)")
            raw = bytes(z["__meta__"])
            try:
                meta = json.loads(raw.decode())
            except (UnicodeDecodeError, ValueError) as exc:
                raise _Unusable(f"a cache archive whose metadata is not readable ({exc})") from exc
            if not isinstance(meta, dict):
                raise _Unusable("a cache archive whose metadata is not a cache entry's")
            if meta.get("format") != FORMAT:
                raise _Unusable(f"a cache entry of format {meta.get('format')!r} (this version reads format {FORMAT})")
            if meta.get("key") != key:
                raise _Unusable(f"a cache entry stored under another key ({meta.get('key')!r})")
            try:
                return decode_result(meta["result"], z)
            except (KeyError, TypeError, ValueError) as exc:
                raise _Unusable(f"a cache entry whose result cannot be decoded ({type(exc).__name__}: {exc})") from exc
    except _DAMAGED as exc:
        # a zip's start but no readable archive behind it: cut short by a crash or a full disk.
        # zipfile's own words, "File is not a zip file", would deny what the first bytes showed
        detail = (
            "its zip directory is missing or unreadable"
            if isinstance(exc, zipfile.BadZipFile)
            else f"{type(exc).__name__}: {exc}"
        )
        raise _Unusable(f"a damaged cache archive, truncated or corrupt ({detail})") from exc


class ResultCache:
    """``get``/``put`` results by key; in memory for the object's life, and on disk unless
    ``directory`` is None."""

    def __init__(self, directory: str | os.PathLike | None):
        self.directory = None if directory is None else Path(directory)
        self._memory: dict = {}

    @staticmethod
    def key(scene, method: str, resolution) -> str:
        text = "\n".join([repr(scene), method, repr(resolution), package_version(), source_digest()])
        return hashlib.sha256(text.encode()).hexdigest()[:32]

    def path(self, key: str) -> Path:
        """The entry's file (the directory must be set)."""
        assert self.directory is not None
        return self.directory / f"{key}.npz"

    def get(self, key: str) -> Result | None:
        """The result stored under ``key``, or None on a miss.

        An entry on disk that cannot be used (not an ``.npz`` archive, a damaged one, another
        format or another key) is a miss, with one warning that says which.

        Parameters
        ----------
        key : str
            A key from :meth:`key`.

        Returns
        -------
        contact_scene.Result or None
            The stored result; None when there is none to use, so that the caller recomputes it.
        """
        if key in self._memory:
            return self._memory[key]
        if self.directory is None:
            return None
        path = self.path(key)
        if not path.exists():
            return None
        try:
            result = _read_entry(path, key)
        except _Unusable as exc:
            log.warning("crossval cache: ignoring %s, %s; recomputing it", path.name, exc)
            return None
        self._memory[key] = result
        return result

    def put(self, key: str, value: Result) -> None:
        self._memory[key] = value
        if self.directory is None:
            return
        try:
            text, arrays = encode_result(value)
        except TypeError as exc:
            log.warning("crossval cache: not storing %s (%s)", key, exc)
            return
        meta = json.dumps({"format": FORMAT, "key": key, "result": text})
        self.directory.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=self.directory, suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as f:
                # typed as Any: numpy's stub lets a str -> ndarray mapping reach savez's allow_pickle
                payload: dict[str, Any] = {"__meta__": np.frombuffer(meta.encode(), dtype=np.uint8), **arrays}
                np.savez(f, **payload)
            os.replace(tmp, self.path(key))
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
