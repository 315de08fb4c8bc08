"""The result cache under the conditions a real report meets: a run killed mid-way, two runs
sharing one cache directory, and a dask scheduler with worker processes.  Each must give the
numbers of a clean run."""

import json
import os
import shutil
import signal
import subprocess
import sys
import time

import pytest

SCENES = ["square"]
_REPORT = (
    "import sys, crossval; crossval.report(sys.argv[1], quick=True, cache_dir=sys.argv[2] or None, "
    "scenes=sys.argv[3].split(','), workers=1, scheduler=(sys.argv[4] if len(sys.argv) > 4 else None))"
)


def _report(out, cache, *extra):
    return subprocess.Popen(
        [sys.executable, "-c", _REPORT, str(out), str(cache), ",".join(SCENES), *extra],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def _numbers(out):
    """What a reader takes from a report: every run's value and every check (timings excluded)."""
    data = json.loads((out / "results.json").read_text())
    return {
        s: (
            [(r["method"], r["resolution"], r["pulloff_force"]) for r in v["runs"]],
            [(c["method"], c["quantity"], c["value"], c["reference"], c["passed"]) for c in v["checks"]],
        )
        for s, v in data["scenes"].items()
    }


def _finish(p):
    out, err = p.communicate(timeout=900)
    assert p.returncode == 0, err


@pytest.fixture(scope="module")
def clean(tmp_path_factory):
    out = tmp_path_factory.mktemp("clean")
    _finish(_report(out / "r", ""))
    return _numbers(out / "r")


def test_report_killed_mid_run_reruns_cleanly_from_its_cache(tmp_path, clean):
    cache = tmp_path / "cache"
    p = _report(tmp_path / "r", cache)
    deadline = time.monotonic() + 600
    while time.monotonic() < deadline and not list(cache.glob("*.npz")) and p.poll() is None:
        time.sleep(0.05)
    assert p.poll() is None, "the report finished before it could be killed"
    os.kill(p.pid, signal.SIGKILL)
    p.wait()
    assert list(cache.glob("*.npz")), "nothing was cached before the kill"
    _finish(_report(tmp_path / "r", cache))
    assert _numbers(tmp_path / "r") == clean
    assert not list(cache.glob("*.tmp"))


def test_two_reports_at_once_on_one_cache_agree(tmp_path, clean):
    cache = tmp_path / "cache"
    a, b = _report(tmp_path / "a", cache), _report(tmp_path / "b", cache)
    _finish(a)
    _finish(b)
    assert _numbers(tmp_path / "a") == _numbers(tmp_path / "b") == clean


@pytest.mark.slow
def test_report_on_a_dask_scheduler_with_two_workers(tmp_path, clean):
    pytest.importorskip("distributed")
    dask = shutil.which("dask", path=os.path.dirname(sys.executable)) or shutil.which("dask")
    if dask is None:
        pytest.skip("the dask command is not installed")
    sched_file = tmp_path / "scheduler.json"
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    procs = [
        subprocess.Popen(
            [
                dask,
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                "0",
                "--no-dashboard",
                "--scheduler-file",
                str(sched_file),
            ],
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
    ]
    try:
        deadline = time.monotonic() + 60
        while not sched_file.exists() and time.monotonic() < deadline:
            time.sleep(0.2)
        address = json.loads(sched_file.read_text())["address"]
        procs.append(
            subprocess.Popen(
                [dask, "worker", address, "--nworkers", "2", "--nthreads", "1", "--no-dashboard"],
                env=env,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
        )
        _finish(_report(tmp_path / "r", "", address))
        assert _numbers(tmp_path / "r") == clean
    finally:
        for p in reversed(procs):
            p.terminate()
            p.wait(timeout=30)
