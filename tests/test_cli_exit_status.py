"""The CLI's exit status is the harness's verdict for scripts and CI: 0 when every check holds,
1 when one fails, with the failing checks named.  Each command is run in-process on a real
solve; a check is made to fail by a wrong closed form, a wrong cached result or a wrong stored
value, the kinds of error the harness exists to catch."""

from __future__ import annotations

import dataclasses
import functools
import json
import sys

import pytest
from click.testing import CliRunner

from contact_scene import theory as T
from crossval.cache import ResultCache
from crossval.cli import main
from crossval.suite import SUITE

regress_module = sys.modules["crossval.regress"]  # the package's name `regress` is the function


def _run(*args):
    return CliRunner().invoke(main, list(args), catch_exceptions=False)


def test_compare_exits_1_and_names_the_check_when_the_closed_form_is_wrong(monkeypatch):
    """Kendall's force 5 % high: the Griffith and energy BEMs' pull-offs (checked against it with
    bars of a few per cent at 12 per radius) and the FEM's (1e-5) no longer match it."""
    ok = _run("compare", "kendall_circle", "--resolution", "12", "--quick")
    assert ok.exit_code == 0, ok.output
    assert "FAIL" not in ok.output

    kendall = T.kendall_adhesion_force
    monkeypatch.setattr(T, "kendall_adhesion_force", lambda **kw: 1.05 * kendall(**kw))
    bad = _run("compare", "kendall_circle", "--resolution", "12", "--quick")
    assert bad.exit_code == 1, bad.output
    failed = [line for line in bad.output.splitlines() if line.startswith("FAIL")]
    assert any("fem_reference" in line and "Kendall" in line for line in failed), bad.output


@pytest.fixture
def one_scene_report(monkeypatch):
    """``crossval report`` restricted to Kendall's circle (the suite's cheapest scene)."""
    report_module = sys.modules["crossval.report"]
    monkeypatch.setattr(report_module, "report", functools.partial(report_module.report, scenes=["kendall_circle"]))
    monkeypatch.setattr("crossval.cli.SUITE", {"kendall_circle": SUITE["kendall_circle"]})
    return report_module


def test_report_exits_1_and_names_a_failed_check(tmp_path, monkeypatch, one_scene_report):
    """A passing quick report exits 0; the same report over a cache whose energy-BEM result has a
    pull-off force 20 % off exits 1 and names the failed checks."""
    monkeypatch.chdir(tmp_path)
    ok = _run("report", "--quick", "--out", "first", "--workers", "1")
    assert ok.exit_code == 0, ok.output
    assert ", 0 failed," in ok.output and "FAIL" not in ok.output
    assert json.loads((tmp_path / "first" / "results.json").read_text())["passed"] is True

    scene = SUITE["kendall_circle"]
    cache = ResultCache(tmp_path / ".crossval-cache")
    key = ResultCache.key(scene, "bem_energy", one_scene_report.QUICK["bem_energy"][-1])
    stored = cache.get(key)
    assert stored is not None, "the report did not cache its finest energy-BEM result"
    cache.put(key, dataclasses.replace(stored, pulloff_force=1.2 * stored.pulloff_force))

    bad = _run("report", "--quick", "--out", "second", "--workers", "1")
    assert bad.exit_code == 1, bad.output
    failed = [line for line in bad.output.splitlines() if line.startswith("FAIL kendall_circle:")]
    assert failed and all("bem_energy" in line for line in failed), bad.output
    assert ", 0 failed," not in bad.output
    assert json.loads((tmp_path / "second" / "results.json").read_text())["passed"] is False


def test_regress_writes_passes_and_exits_1_on_a_changed_value(tmp_path, monkeypatch):
    """``--update`` writes the store, a rerun matches it (exit 0), and a stored pull-off force
    0.1 % off is a mismatch (exit 1) named by case and quantity.  One case (the Griffith BEM on
    Kendall's circle) stands for the whole store."""
    jobs = [j for j in regress_module.regression_jobs() if j.scene.name == SUITE["kendall_circle"].name]
    jobs = [j for j in jobs if j.method == "bem_griffith"]
    assert len(jobs) == 1
    monkeypatch.setattr(regress_module, "regression_jobs", lambda: jobs)
    store = tmp_path / "regression.json"
    monkeypatch.setattr(regress_module, "REFERENCE_FILE", store)

    written = _run("regress", "--update", "--workers", "1")
    assert written.exit_code == 0 and str(store) in written.output, written.output
    ok = _run("regress", "--workers", "1")
    assert ok.exit_code == 0 and "0 mismatches" in ok.output, ok.output

    data = json.loads(store.read_text())
    data["cases"][0]["values"]["pulloff_force"] *= 1.001
    store.write_text(json.dumps(data))
    bad = _run("regress", "--workers", "1")
    assert bad.exit_code == 1, bad.output
    (line,) = [line for line in bad.output.splitlines() if line.startswith("MISMATCH")]
    assert "bem_griffith" in line and "pulloff_force" in line and "1 mismatches" in bad.output


def test_solve_exits_1_when_the_solve_did_not_converge():
    # a process zone below one element: the energy BEM says it did not converge, and the exit
    # status must say so too (it was 0, which a script takes for an answer)
    ok = _run("solve", "kendall_circle", "--method", "bem_energy", "--range", "0.5", "--resolution", "16")
    assert ok.exit_code == 0, ok.output
    bad = _run("solve", "kendall_circle", "--method", "bem_energy", "--range", "0.3", "--resolution", "8")
    assert bad.exit_code == 1, bad.output
    assert "converged         no" in bad.output or "converged         False" in bad.output
    as_json = _run("solve", "kendall_circle", "--method", "bem_energy", "--range", "0.3", "--resolution", "8", "--json")
    assert as_json.exit_code == 1 and json.loads(as_json.output)["converged"] is False


@pytest.mark.parametrize("adhesion", ["work_of_adhesion = 1.0\nrange = 0.5", "work_of_adhesion = 0.0"])
def test_compare_quick_takes_a_finite_range_or_no_adhesion(tmp_path, adhesion):
    # --quick gave the energy BEM its zero-range sequence's resolution (1 element per process
    # zone) where its resolution is elements per radius, and refused the user's scene for it
    scene = tmp_path / "circle.toml"
    scene.write_text(
        "[indenter]\nshape = 'circle'\nradius = 1.0\n[material]\nmodel = 'homogeneous'\n"
        f"youngs_modulus = 1.0\npoisson_ratio = 0.3\n[adhesion]\n{adhesion}\n"
    )
    r = _run("compare", str(scene), "--quick", "--resolution", "16")
    assert r.exit_code == 0, r.output
    assert "bem_energy" in r.output and "FAIL" not in r.output


def test_report_and_regress_refuse_bad_options_by_name_before_solving(tmp_path, monkeypatch):
    # an unusable --out ended in a NotADirectoryError traceback after the solves, and a
    # malformed --scheduler in a ValueError traceback, both with the status of a failed check
    monkeypatch.chdir(tmp_path)
    (tmp_path / "file").write_text("")
    for out in ("file/report", ""):
        r = _run("report", "--quick", "--out", out)
        assert r.exit_code == 2 and "--out" in r.output, r.output
    for cache in (["--no-cache"], []):  # with a warm cache no connection is made: still refused
        r = _run("report", "--quick", *cache, "--out", "rep", "--scheduler", "notanaddress")
        assert r.exit_code == 2 and "--scheduler" in r.output and "notanaddress" in r.output, r.output
    assert _run("regress", "--workers", "-5").exit_code == 2
    # local workers and a cluster exclude each other: --workers was silently ignored
    r = _run("report", "--quick", "--out", "rep", "--scheduler", "tcp://127.0.0.1:1", "--workers", "2")
    assert r.exit_code == 2 and "--workers" in r.output, r.output
