"""Sweeps: serial, processes and dask give identical results; caching; report; regress; study."""

import json
import logging
import sys
import warnings

import numpy as np
import pytest

import crossval
from crossval import runner
from crossval.cache import ResultCache
from crossval.runner import Job, run_jobs
from crossval.suite import SUITE

JOBS = [
    Job(SUITE["square"], "bem_griffith", 8),
    Job(SUITE["triangle"], "bem_griffith", 8),
    Job(SUITE["kendall_circle"], "bem_griffith", 10),
    Job(SUITE["incompressible_circle"], "fem_reference", 0.5),
]


def _same(a, b):
    assert a.pulloff_force == b.pulloff_force and a.pulloff_approach == b.pulloff_approach
    assert a.stiffness == b.stiffness
    assert np.array_equal(a.curve.force, b.curve.force)


def test_serial_processes_and_dask_are_identical():
    serial = run_jobs(JOBS)
    procs = run_jobs(JOBS, workers=2)
    for a, b in zip(serial, procs, strict=True):
        _same(a, b)
    distributed = pytest.importorskip("distributed")
    cl = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    try:
        with distributed.Client(cl) as client:
            for a, b in zip(serial, run_jobs(JOBS, scheduler=client), strict=True):
                _same(a, b)
    finally:
        # the cluster's close without a timeout has waited for ever once its workers had gone
        # (on a loaded machine, after the comparison had passed): bound it, and say so
        try:
            cl.close(timeout=60)
        except TimeoutError:
            warnings.warn("dask's LocalCluster did not close within 60 s", stacklevel=1)


def test_cache_is_reused_and_writes_are_atomic(tmp_path, monkeypatch):
    cache = ResultCache(tmp_path / "c")
    first = run_jobs(JOBS[:2], cache=cache)
    assert len(list((tmp_path / "c").glob("*.npz"))) == 2
    monkeypatch.setattr(runner, "_run", lambda job: pytest.fail("recomputed a cached result"))
    again = run_jobs(JOBS[:2], cache=ResultCache(tmp_path / "c"))
    for a, b in zip(first, again, strict=True):
        _same(a, b)
    # an interrupted write leaves the earlier entry whole and no temporary file
    key = ResultCache.key(JOBS[0].scene, JOBS[0].method, JOBS[0].resolution)

    def boom(*a, **k):
        raise KeyboardInterrupt

    monkeypatch.setattr(np, "savez", boom)
    with pytest.raises(KeyboardInterrupt):
        ResultCache(tmp_path / "c").put(key, "partial")
    monkeypatch.undo()
    _same(ResultCache(tmp_path / "c").get(key), first[0])
    assert not list((tmp_path / "c").glob("*.tmp"))


def _snapshot_job():
    import dataclasses

    import contact_scene as cs

    sc = dataclasses.replace(SUITE["square"], outputs=cs.Outputs(snapshots=(-0.5,), fields=True))
    return Job(sc, "bem_griffith", 8)


def test_cache_round_trip_keeps_every_field(tmp_path):
    """Arrays (curve, snapshots, fields), tuples, None, inf and nested info survive the data-only format."""
    import dataclasses

    job = _snapshot_job()
    (res,) = run_jobs([job])
    res = dataclasses.replace(res, accuracy_estimate=float("inf"), info={**res.info, "nested": {"t": (1, 2.5)}})
    key = ResultCache.key(job.scene, job.method, job.resolution)
    ResultCache(tmp_path).put(key, res)
    back = ResultCache(tmp_path).get(key)
    _same(res, back)
    assert back.accuracy_estimate == float("inf") and back.info["nested"] == {"t": (1, 2.5)}
    assert back.messages == res.messages and back.timings == res.timings
    assert len(back.snapshots) == len(res.snapshots) == 1
    for a, b in zip(res.snapshots + (res.last_stable,), back.snapshots + (back.last_stable,), strict=True):
        assert a.contact.dtype == b.contact.dtype and np.array_equal(a.contact, b.contact)
        assert np.array_equal(a.pressure, b.pressure) and a.origin == b.origin


NOT_AN_ARCHIVE = "is not a readable cache archive (not an .npz file"

#: damage -> what the warning must say, so that each reason is told apart from the others
DAMAGE_REASONS = {
    "truncate": "a damaged cache archive, truncated or corrupt",
    "text": NOT_AN_ARCHIVE,
    "hello": NOT_AN_ARCHIVE,
    "random": NOT_AN_ARCHIVE,
    "empty": NOT_AN_ARCHIVE,
    "pickle": NOT_AN_ARCHIVE,
    "no_meta": "an .npz archive without a cache entry's metadata",
    "old_format": "a cache entry of format 0 (this version reads format",
    "other_key": "a cache entry stored under another key",
}


@pytest.mark.parametrize("damage", list(DAMAGE_REASONS))
def test_damaged_cache_entry_is_a_miss_with_one_warning(tmp_path, monkeypatch, caplog, damage):
    from crossval import cache as cache_module

    cache = ResultCache(tmp_path)
    (first,) = run_jobs(JOBS[:1], cache=cache)
    key = ResultCache.key(JOBS[0].scene, JOBS[0].method, JOBS[0].resolution)
    path = cache.path(key)
    if damage == "truncate":
        path.write_bytes(path.read_bytes()[:200])
    elif damage == "text":
        path.write_text("not a cache entry")
    elif damage == "hello":
        path.write_bytes(b"hello")
    elif damage == "random":
        # bytes that no format claims; seeded, and never a zip's first bytes
        path.write_bytes(b"\x00" + np.random.default_rng(0).bytes(4096))
    elif damage == "empty":
        path.write_bytes(b"")
    elif damage == "no_meta":
        with open(path, "wb") as f:
            np.savez(f, x=np.arange(3.0))
    elif damage == "old_format":
        with monkeypatch.context() as m:
            m.setattr(cache_module, "FORMAT", 0)
            ResultCache(tmp_path).put(key, first)
    elif damage == "other_key":
        other = ResultCache.key(JOBS[1].scene, JOBS[1].method, JOBS[1].resolution)
        ResultCache(tmp_path).put(other, first)
        path.write_bytes(cache.path(other).read_bytes())
    else:  # a pickle whose loading would run code: it must never be unpickled

        class Evil:
            def __reduce__(self):
                return (pytest.fail, ("the cache unpickled an entry",))

        with open(path, "wb") as f:
            np.save(f, np.array([Evil()], dtype=object), allow_pickle=True)
    calls = []
    monkeypatch.setattr(runner, "_run", lambda job: calls.append(job) or first)
    with caplog.at_level(logging.WARNING, logger="crossval"):
        (again,) = run_jobs(JOBS[:1], cache=ResultCache(tmp_path))
    assert len(calls) == 1, "a damaged entry must be recomputed"
    warnings = [r for r in caplog.records if r.levelno == logging.WARNING]
    assert len(warnings) == 1 and path.name in warnings[0].getMessage()
    message = warnings[0].getMessage()
    assert DAMAGE_REASONS[damage] in message and message.endswith("recomputing it"), message
    # numpy's words for any bytes that are not an archive speak of pickled data and advise
    # loading the file unsafely: advice a user must never be given about a cache entry
    assert "pickle" not in message and "unsafe" not in message, message
    _same(again, first)
    monkeypatch.setattr(runner, "_run", lambda job: pytest.fail("the entry was not overwritten"))
    _same(ResultCache(tmp_path).get(key), first)


def test_study_fits_first_order_for_kendall():
    st = crossval.study(
        SUITE["incompressible_circle"], methods=["bem_griffith"], resolutions={"bem_griffith": (8, 16, 32)}
    )
    assert st.reference_name.startswith("Kendall")
    assert st.rates["bem_griffith"] > 0.7


def test_report_writes_a_self_contained_page(tmp_path):
    rep = crossval.report(tmp_path / "r", quick=True, cache_dir=None, scenes=["kendall_circle", "square"])
    assert rep.passed
    page = (tmp_path / "r" / "index.html").read_text()
    assert page.count("data:image/png;base64,") == 3 and "square" in page
    data = _strict_json((tmp_path / "r" / "results.json").read_text())
    assert set(data["scenes"]) == {"kendall_circle", "square"}
    assert (tmp_path / "r" / "square.png").stat().st_size > 1000


def _strict_json(text):
    """RFC 8259 JSON: NaN and Infinity tokens are refused, as JavaScript's JSON.parse does."""

    def refuse(token):
        raise ValueError(f"not valid JSON: bare {token}")

    return json.loads(text, parse_constant=refuse)


def test_report_json_is_strict_even_with_non_finite_values(tmp_path, monkeypatch):
    """A quantity with no value (a rate that could not be fitted) is null, never a bare NaN."""
    report_module = sys.modules["crossval.report"]
    real = report_module.study

    def study_with_nan_rate(*a, **k):
        st = real(*a, **k)
        st.rates["bem_griffith"] = float("nan")
        return st

    monkeypatch.setattr(report_module, "study", study_with_nan_rate)
    crossval.report(tmp_path / "r", quick=True, cache_dir=None, scenes=["kendall_circle"])
    data = _strict_json((tmp_path / "r" / "results.json").read_text())
    assert data["scenes"]["kendall_circle"]["rates"]["bem_griffith"] is None


def test_regress_passes_and_explains_a_change(tmp_path):
    from crossval.regress import MISSING, REFERENCE_FILE, STALE, regress

    assert regress() == []
    data = json.loads(REFERENCE_FILE.read_text())
    data["cases"][0]["values"]["pulloff_force"] *= 1.001
    p = tmp_path / "ref.json"
    p.write_text(json.dumps(data))
    (bad,) = regress(path=p)
    assert bad.quantity == "pulloff_force" and "-9.99e-04" in bad.explain()
    # a case the file lacks, and one it holds that the suite no longer computes, are named as
    # such (the first printed "= nan, stored nan"; the second passed unnoticed)
    data = json.loads(REFERENCE_FILE.read_text())
    dropped = data["cases"].pop(0)
    data["cases"].append(dict(dropped, scene="a_retired_scene"))
    p.write_text(json.dumps(data))
    found = {m.quantity: m for m in regress(path=p)}
    assert set(found) == {MISSING, STALE}
    assert found[MISSING].scene == dropped["scene"] and "not in the reference file" in found[MISSING].explain()
    assert found[STALE].scene == "a_retired_scene" and "no longer computed" in found[STALE].explain()
    assert "nan" not in found[MISSING].explain() + found[STALE].explain()


def test_full_report_includes_the_extreme_cases_table(tmp_path, monkeypatch):
    import crossval.extremes as ex

    row = ("nu = 0.5", "fem_reference", True, "+2.58e-05", 0, "1.90", "")
    monkeypatch.setattr(ex, "extreme_cases", lambda callback=None: [row])
    crossval.report(tmp_path / "r", quick=True, cache_dir=None, scenes=["kendall_circle"], extremes=True)
    page = (tmp_path / "r" / "index.html").read_text()
    assert "Stiff and extreme cases" in page and "+2.58e-05" in page
    data = _strict_json((tmp_path / "r" / "results.json").read_text())
    assert data["extremes"] == [dict(zip(ex.HEADERS, row, strict=True))]


def test_full_report_starts_the_methods_defaults_first():
    """The full report runs the energy BEM's accurate (default) zero-range sequence on every
    face it applies to, before the sweeps; the quick report does not."""
    from crossval.report import report_jobs

    full = report_jobs(["kendall_circle", "square", "graded_circle_k0.5"], quick=False)
    defaults = [(s, j.method) for s, j in full if j.resolution is None]
    assert defaults == [("kendall_circle", "bem_energy"), ("square", "bem_energy")]
    assert all(j.resolution is None for _, j in full[: len(defaults)])
    assert all(j.resolution is not None for _, j in report_jobs(["kendall_circle", "square"], quick=True))


def test_full_report_checks_the_default_result_not_the_sweeps_finest(tmp_path, monkeypatch):
    """The energy BEM's result at its default resolution is what the full report checks: a
    stored default with a pull-off force 20 % off fails the check against Kendall, while the
    coarse sweep's own finest would have passed (the quick report on the same cache)."""
    import dataclasses

    from crossval.methods import METHODS

    report_module = sys.modules["crossval.report"]
    monkeypatch.setattr(report_module, "FULL", report_module.QUICK)  # the quick sweeps, full rules
    scene = SUITE["kendall_circle"]
    cache = ResultCache(tmp_path / "cache")
    coarse = METHODS["bem_energy"].solve(scene, resolution=report_module.QUICK["bem_energy"][-1])
    cache.put(ResultCache.key(scene, "bem_energy", 1.0), coarse)
    wrong = dataclasses.replace(coarse, pulloff_force=1.2 * coarse.pulloff_force)
    cache.put(ResultCache.key(scene, "bem_energy", None), wrong)

    def energy_force_check(rep):
        (c,) = [c for c in rep.checks["kendall_circle"] if c.method == "bem_energy" and c.quantity == "pulloff_force"]
        return c

    quick = crossval.report(tmp_path / "q", quick=True, cache_dir=tmp_path / "cache", scenes=["kendall_circle"])
    assert energy_force_check(quick).passed and energy_force_check(quick).value == coarse.pulloff_force
    full = crossval.report(
        tmp_path / "f", quick=False, cache_dir=tmp_path / "cache", scenes=["kendall_circle"], extremes=False
    )
    assert energy_force_check(full).value == wrong.pulloff_force and not energy_force_check(full).passed
    data = _strict_json((tmp_path / "f" / "results.json").read_text())
    assert data["scenes"]["kendall_circle"]["finest"]["bem_energy"]["pulloff_force"] == wrong.pulloff_force


def test_an_edited_solver_is_a_cache_miss(monkeypatch):
    # the version of an editable install does not change while its code does: a solver broken
    # in place reused every cached result, and a report passed
    import crossval.cache as cache_module

    before = ResultCache.key(JOBS[0].scene, JOBS[0].method, JOBS[0].resolution)
    digest = cache_module.source_digest()
    assert len(digest) == 64 and digest == cache_module.source_digest()
    monkeypatch.setattr(cache_module, "source_digest", lambda: "0" * 64)
    assert ResultCache.key(JOBS[0].scene, JOBS[0].method, JOBS[0].resolution) != before


def test_the_source_digest_follows_an_edit_of_a_solver_file(tmp_path, monkeypatch):
    # the digest reads the packages' files, not a version: edit one and it changes
    import crossval.cache as cache_module

    package = tmp_path / "fake_solver"
    package.mkdir()
    (package / "__init__.py").write_text("")
    (package / "model.json").write_text('{"c": 0.5}')
    (package / "kernel.py").write_text("PI = 3.14159\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(cache_module, "_RESULT_SOURCES", ("fake_solver",))
    digests = []
    for edit in (None, ("kernel.py", "PI = 3.11\n"), ("model.json", '{"c": 0.6}')):
        if edit is not None:
            (package / edit[0]).write_text(edit[1])
        cache_module.source_digest.cache_clear()
        digests.append(cache_module.source_digest())
    cache_module.source_digest.cache_clear()
    assert len(set(digests)) == 3
