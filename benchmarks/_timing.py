"""Small helpers shared by the benchmark scripts: thread settings, median timing, and the JSON
that ``benchmarks/docs_tables.py`` renders into the docs (``write_doc_table``)."""

from __future__ import annotations

import datetime
import json
import os
import platform
import shlex
import statistics
import subprocess
import sys
import time
from pathlib import Path

# one BLAS thread: the solvers' parallelism is in the FFT workers, and oversubscribed BLAS
# threads have made small dot products orders of magnitude slower on a 2-core machine
_THREAD_VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
for _v in _THREAD_VARS:
    os.environ.setdefault(_v, "1")


def median_time(fn, *, repeat: int = 7, number: int = 1) -> float:
    """Median over ``repeat`` runs of the time of ``number`` calls, per call."""
    fn()  # warm up (plans, caches)
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        for _ in range(number):
            fn()
        ts.append((time.perf_counter() - t) / number)
    return statistics.median(ts)


def table(rows, headers) -> str:
    w = [max(len(str(h)), *(len(str(r[i])) for r in rows)) for i, h in enumerate(headers)]
    line = "  ".join(str(h).rjust(w[i]) for i, h in enumerate(headers))
    out = [line, "-" * len(line)]
    out += ["  ".join(str(r[i]).rjust(w[i]) for i in range(len(headers))) for r in rows]
    return "\n".join(out)


ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# what a benchmark's numbers depend on: a table's revision says "with uncommitted changes" only
# when these differ from the commit, not when an unrelated file (docs, tests) is being edited
MEASURED_PATHS = ("contact_scene", "halfspace", "bem_griffith", "bem_energy", "fem_reference", "crossval", "benchmarks")


def _git(*args: str) -> str:
    return subprocess.run(["git", *args], capture_output=True, text=True, cwd=ROOT, check=True).stdout.strip()


def revision() -> str:
    """The short commit, marked when the measured code differs from it."""
    try:
        commit = _git("rev-parse", "--short", "HEAD")
        dirty = _git("status", "--porcelain", "--untracked-files=no", "--", *MEASURED_PATHS)
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return commit + (" (with uncommitted changes)" if dirty else "")


def extract_revision(rev: str, paths, where) -> None:
    """Write ``paths`` (packages or files of the repository) as they were at git revision ``rev``
    into the directory ``where``: the earlier algorithm a benchmark compares against, in the
    same run as the current one."""
    archive = subprocess.run(["git", "-C", ROOT, "archive", rev, *paths], check=True, capture_output=True).stdout
    subprocess.run(["tar", "-x", "-C", str(where)], input=archive, check=True)


def provenance_record() -> dict:
    """When, on what and from which commit a run started: the ``date``, ``machine`` and
    ``revision`` of a docs table's JSON.  Taken at the start, so that the load average is the
    one the run met (the machine may be shared: compare times only within one run)."""
    return {
        "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "machine": {
            "platform": platform.platform(),
            "processor": platform.processor() or platform.machine(),
            "cpus": os.cpu_count(),
            "load_average_at_start": list(os.getloadavg()),
            "threads": {v: os.environ.get(v) for v in _THREAD_VARS},
        },
        "revision": revision(),
    }


def command() -> str:
    """The command line that ran this script, from the repository's root."""
    script = os.path.relpath(os.path.abspath(sys.argv[0]), ROOT)
    return shlex.join(["python", script, *sys.argv[1:]])


def cache_file(cache: Path, *key) -> Path:
    """The JSON file of one cached result: the key's parts joined by double underscores."""
    return cache / ("__".join(str(k) for k in key) + ".json")


def cached(cache: Path, key: tuple, compute) -> dict:
    """The cached row under ``key``, else ``compute()``'s dict, stamped with its wall and CPU
    time and the revision, written atomically (a run killed mid-write leaves no row)."""
    path = cache_file(cache, *key)
    if path.exists():
        return json.loads(path.read_text())
    t, c = time.perf_counter(), time.process_time()
    row = compute()
    row.update(wall_s=time.perf_counter() - t, cpu_s=time.process_time() - c, revision=revision())
    cache.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps(row, indent=1))
    os.replace(tmp, path)
    return row


def write_doc_table(name: str, headers, rows, record: dict, **extra) -> Path:
    """Write ``docs/<name>.json``, the table ``benchmarks/docs_tables.py`` renders into the docs.

    ``record`` is ``provenance_record()`` taken when the run started; ``extra`` holds raw
    numbers worth keeping beside the rounded table (full precision, per-case details)."""
    out = Path(ROOT) / "docs" / f"{name}.json"
    doc = {
        "written_by": command(),
        **record,
        "headers": [str(h) for h in headers],
        "rows": [[x if isinstance(x, int | str) else str(x) for x in row] for row in rows],
        **extra,
    }
    out.write_text(json.dumps(doc, indent=1) + "\n")
    print(f"wrote {os.path.relpath(out, ROOT)}", flush=True)
    return out


def provenance() -> str:
    """One line for a generated table: when, on what, from which commit."""
    import numpy
    import scipy

    cpu = platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), cpu)
    except OSError:
        pass
    return (
        f"Generated {datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC on {cpu}, "
        f"{os.cpu_count()} cores, Python {platform.python_version()}, numpy {numpy.__version__}, "
        f"scipy {scipy.__version__}, commit {revision()}; thread counts: OPENBLAS/OMP/MKL "
        f"{os.environ.get('OPENBLAS_NUM_THREADS')}/{os.environ.get('OMP_NUM_THREADS')}/"
        f"{os.environ.get('MKL_NUM_THREADS')}."
    )
