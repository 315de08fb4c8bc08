"""Sweeps: serial, processes and dask give identical results; caching; report; regress; study."""
import json
import pickle

import numpy as np
import pytest

import crossval
from crossval import runner
from crossval.cache import ResultCache
from crossval.runner import Job, run_jobs
from crossval.suite import SUITE

JOBS = [Job(SUITE["square"], "bem_griffith", 8), Job(SUITE["triangle"], "bem_griffith", 8),
        Job(SUITE["kendall_circle"], "bem_griffith", 10), Job(SUITE["incompressible_circle"], "fem_reference", 0.5)]


def _same(a, b):
    assert a.pulloff_force == b.pulloff_force and a.pulloff_approach == b.pulloff_approach
    assert a.stiffness == b.stiffness
    assert np.array_equal(a.curve.force, b.curve.force)


def test_serial_processes_and_dask_are_identical():
    serial = run_jobs(JOBS)
    procs = run_jobs(JOBS, workers=2)
    for a, b in zip(serial, procs):
        _same(a, b)
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cl, \
            distributed.Client(cl) as client:
        for a, b in zip(serial, run_jobs(JOBS, scheduler=client)):
            _same(a, b)


def test_cache_is_reused_and_writes_are_atomic(tmp_path, monkeypatch):
    cache = ResultCache(tmp_path / "c")
    first = run_jobs(JOBS[:2], cache=cache)
    assert len(list((tmp_path / "c").glob("*.pkl"))) == 2
    monkeypatch.setattr(runner, "_run", lambda job: pytest.fail("recomputed a cached result"))
    again = run_jobs(JOBS[:2], cache=ResultCache(tmp_path / "c"))
    for a, b in zip(first, again):
        _same(a, b)
    # an interrupted write leaves the earlier entry whole and no temporary file
    key = ResultCache.key(JOBS[0].scene, JOBS[0].method, JOBS[0].resolution)

    def boom(*a, **k):
        raise KeyboardInterrupt
    monkeypatch.setattr(pickle, "dump", boom)
    with pytest.raises(KeyboardInterrupt):
        ResultCache(tmp_path / "c").put(key, "partial")
    monkeypatch.undo()
    _same(ResultCache(tmp_path / "c").get(key), first[0])
    assert not list((tmp_path / "c").glob("*.tmp"))


def test_study_fits_first_order_for_kendall():
    st = crossval.study(SUITE["incompressible_circle"], methods=["bem_griffith"],
                              resolutions={"bem_griffith": (8, 16, 32)})
    assert st.reference_name.startswith("Kendall")
    assert st.rates["bem_griffith"] > 0.7


def test_report_writes_a_self_contained_page(tmp_path):
    rep = crossval.report(tmp_path / "r", quick=True, cache_dir=None, scenes=["kendall_circle", "square"])
    assert rep.passed
    page = (tmp_path / "r" / "index.html").read_text()
    assert page.count("data:image/png;base64,") == 3 and "square" in page
    data = json.loads((tmp_path / "r" / "results.json").read_text())
    assert set(data["scenes"]) == {"kendall_circle", "square"}
    assert (tmp_path / "r" / "square.png").stat().st_size > 1000


def test_regress_passes_and_explains_a_change(tmp_path):
    from crossval.regress import REFERENCE_FILE, regress

    assert regress() == []
    data = json.loads(REFERENCE_FILE.read_text())
    data["cases"][0]["values"]["pulloff_force"] *= 1.001
    p = tmp_path / "ref.json"
    p.write_text(json.dumps(data))
    (bad,) = regress(path=p)
    assert bad.quantity == "pulloff_force" and "-9.99e-04" in bad.explain()


def test_full_report_includes_the_extreme_cases_table(tmp_path, monkeypatch):
    import crossval.extremes as ex

    row = ("nu = 0.5", "fem_reference", True, "+2.58e-05", 0, "1.90", "")
    monkeypatch.setattr(ex, "extreme_cases", lambda callback=None: [row])
    crossval.report(tmp_path / "r", quick=True, cache_dir=None, scenes=["kendall_circle"], extremes=True)
    page = (tmp_path / "r" / "index.html").read_text()
    assert "Stiff and extreme cases" in page and "+2.58e-05" in page
    data = json.loads((tmp_path / "r" / "results.json").read_text())
    assert data["extremes"] == [dict(zip(ex.HEADERS, row))]
