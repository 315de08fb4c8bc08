"""Small helpers shared by the benchmark scripts: thread settings and median timing."""

from __future__ import annotations

import os
import statistics
import time

# one BLAS thread: the solvers' parallelism is in the FFT workers, and oversubscribed BLAS
# threads have made small dot products orders of magnitude slower on this machine
for _v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
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


def provenance() -> str:
    """One line for a generated table: when, on what, from which commit."""
    import datetime
    import platform
    import subprocess

    import numpy
    import scipy

    try:
        commit = subprocess.run(
            ["git", "rev-parse", "--short", "HEAD"],
            capture_output=True,
            text=True,
            cwd=os.path.dirname(os.path.abspath(__file__)),
            check=True,
        ).stdout.strip()
        dirty = subprocess.run(
            ["git", "status", "--porcelain", "--untracked-files=no"],
            capture_output=True,
            text=True,
            cwd=os.path.dirname(os.path.abspath(__file__)),
        ).stdout.strip()
        commit += " (with uncommitted changes)" if dirty else ""
    except (OSError, subprocess.CalledProcessError):
        commit = "unknown"
    cpu = platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((line.split(":", 1)[1].strip() for line in f if line.startswith("model name")), cpu)
    except OSError:
        pass
    return (
        f"Generated {datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC on {cpu}, "
        f"{os.cpu_count()} cores, Python {platform.python_version()}, numpy {numpy.__version__}, "
        f"scipy {scipy.__version__}, commit {commit}; thread counts: OPENBLAS/OMP/MKL "
        f"{os.environ.get('OPENBLAS_NUM_THREADS')}/{os.environ.get('OMP_NUM_THREADS')}/"
        f"{os.environ.get('MKL_NUM_THREADS')}."
    )
