"""Mutation study of the harness: does ``crossval report --quick``, the test suite (and, for
what both miss, the full report) notice a physics bug?

Each mutant is data: an id, the package, the file, the exact text it replaces (which must occur
exactly ``count`` times, asserted when applied), the new text, and what it breaks.  The bugs
are ones a contributor could plausibly introduce: a wrong constant, a dropped factor, a sign,
a unit, a boundary condition, a table entry.

For each mutant the repository is copied (from a clean clone, ``--base``), the text is
replaced in the copy, and the copy is run as the working directory and first on PYTHONPATH
(the virtualenv has the main tree installed editable; the run checks that the copy is what
gets imported):

1. ``crossval report --quick --no-cache``: exit status and the checks that fail in its
   results.json that did not fail without the mutant;
2. ``pytest -x -q -p no:cacheprovider`` over every test file, the mutated package's own files
   first (:data:`PACKAGE_TESTS`), then :data:`TEST_ORDER` (fast files that compare with closed
   forms first), so that a mutant the suite catches stops early: the first
   failing test, with a time limit per mutant; a test that also fails on the unmutated copy
   is deselected and the run repeated;
3. the full ``crossval report --no-cache`` only for mutants missed by both (``--full-for-missed``).

Writes docs/mutation_study.md (the table) and docs/mutation_study.json (raw results), with the
date, the machine and the base commit.

    git clone -q /work/main /tmp/mut/base
    python benchmarks/mutation_study.py --base /tmp/mut/base            # everything (about an hour or more)
    python benchmarks/mutation_study.py --only R2-raster-area --skip-tests
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import re
import shutil
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


@dataclass(frozen=True)
class Mutant:
    id: str
    package: str
    file: str
    old: str
    new: str
    breaks: str
    count: int = 1  # how often ``old`` occurs in ``file``; every occurrence is replaced


MUTANTS: tuple[Mutant, ...] = (
    # --- halfspace: the influence coefficients -------------------------------------------------
    Mutant(
        "H1-love-pi",
        "halfspace",
        "halfspace/kernel.py",
        "return _offset_layout(love_square_integral, nx, ny, spacing, padded) / (math.pi * E_star)",
        "return _offset_layout(love_square_integral, nx, ny, spacing, padded) / (3.11 * E_star)",
        "Love's coefficients with pi rounded to 3.11: the Griffith BEM's compliance +1 %, its stiffness and "
        "pull-off about -1 % and -0.5 %",
    ),
    Mutant(
        "H3-collocation-self-term",
        "halfspace",
        "halfspace/collocation.py",
        "self_term = -square_lattice_zeta(1.0 + k) * spacing ** (1.0 - k)",
        "self_term = 4.0 * math.asinh(1.0) * spacing ** (1.0 - k)",
        "the collocated kernel's self term from the element's own centre displacement (3.5255 Delta) "
        "instead of the lattice zeta (3.9003 Delta): the energy BEM's stiffness off by O(1/N)",
    ),
    Mutant(
        "H4-graded-kernel-exponent",
        "halfspace",
        "halfspace/kernel.py",
        "return t * hyp2f1(0.5, 0.5 * (1 + k), 1.5, -t * t)",
        "return t * hyp2f1(0.5, 0.5 * (1 - k), 1.5, -t * t)",
        "the graded square integral's hypergeometric parameter with (1 - k): wrong graded coefficients "
        "(exact at k = 0)",
    ),
    # --- moduli ---------------------------------------------------------------------------------
    Mutant(
        "M1-estar-square",
        "contact_scene",
        "contact_scene/materials.py",
        "return self.youngs_modulus / (1.0 - self.poisson_ratio**2)",
        "return self.youngs_modulus / (1.0 - self.poisson_ratio)",
        "E* = E / (1 - nu) instead of E / (1 - nu^2) everywhere (solvers and closed forms alike); only "
        "the FEM, which reads E and nu, disagrees",
    ),
    Mutant(
        "M2-griffith-E-not-Estar",
        "bem_griffith",
        "bem_griffith/problem.py",
        "E = material.effective_modulus",
        "E = material.youngs_modulus",
        "the Griffith BEM uses Young's modulus E where E* = E / (1 - nu^2) belongs (nu = 0.3: -9 % stiffness)",
    ),
    Mutant(
        "M3-fem-Estar-not-E",
        "fem_reference",
        "fem_reference/solver.py",
        "return Material(0.0, m.poisson_ratio), m.youngs_modulus",
        "return Material(0.0, m.poisson_ratio), m.effective_modulus",
        "the FEM scales its unit solution with E* where Young's E belongs: K x 1/(1 - nu^2)",
    ),
    # --- the Griffith criterion and its graded calibration -------------------------------------
    Mutant(
        "C1-element-energy-constant",
        "contact_scene",
        "contact_scene/theory.py",
        "(math.log(1.0 + math.sqrt(2.0)) - (math.sqrt(2.0) - 1.0) / 3.0)",
        "(math.log(1.0 + math.sqrt(2.0)) - (math.sqrt(2.0) - 1.0) / 2.0)",
        "Eq. 20's element energy constant 0.4293 instead of 0.4732: sigma_c and every Griffith pull-off +5 %",
    ),
    Mutant(
        "C3-calibration-table-digit",
        "bem_griffith",
        "bem_griffith/criterion.py",
        "0.25: (1.05020, 0.0016),",
        "0.25: (1.00520, 0.0016),",
        "two digits swapped in the graded calibration table at k = 0.25 (1.0502 -> 1.0052): graded "
        "pull-offs near k = 0.25 +4.5 %",
    ),
    Mutant(
        "C4-calibration-inverted",
        "bem_griffith",
        "bem_griffith/criterion.py",
        'return 1.0 / calibration(k)[0] if criterion == "calibrated" and k != 0 else 1.0',
        'return calibration(k)[0] if criterion == "calibrated" and k != 0 else 1.0',
        "the calibration factor multiplies Eq. 42's sigma_c instead of dividing it (k = 0.5: +14 %)",
    ),
    # --- the energy BEM: potentials and zero-range extrapolation -------------------------------
    Mutant(
        "E1-potential-work-half",
        "bem_energy",
        "bem_energy/potentials.py",
        "w, r = self.work, self.range",
        "w, r = 0.5 * self.work, self.range",
        "the adhesive potential's depth is w/2 (surface energy gamma confused with the work of adhesion "
        "w = 2 gamma), energy, stress and curvature alike: pull-off x 0.71",
        count=4,
    ),
    Mutant(
        "E2-range-for-process-zone",
        "bem_energy",
        "bem_energy/potentials.py",
        "return math.sqrt(work * length ** (1.0 - exponent) / (process_zone_factor(exponent) * modulus))",
        "return math.sqrt(work * length ** (1.0 - exponent) / (2.0 * process_zone_factor(exponent) * modulus))",
        "the range chosen for a process zone too short by sqrt(2): each range's true l_c is half the "
        "one its grid was sized for, so the zone is trapped by the mesh",
    ),
    Mutant(
        "E3-process-zone-length",
        "bem_energy",
        "bem_energy/potentials.py",
        "return (process_zone_factor(exponent) * modulus * range**2 / work) ** (1.0 / (1.0 - exponent))",
        "return (2.0 * process_zone_factor(exponent) * modulus * range**2 / work) ** (1.0 / (1.0 - exponent))",
        "l_c = 2 E* rho^2 / w: the resolution guard believes every zone twice as well resolved as it is",
    ),
    Mutant(
        "Z1-rate-bracket",
        "bem_energy",
        "bem_energy/zero_range.py",
        "RATE_BRACKET = (0.5, 1.5)",
        "RATE_BRACKET = (1.0, 1.5)",
        "the zero-range tail's rate bracket without the sqrt(l_c) tail of a smooth edge: the energy BEM's "
        "error bar too small to cover its error",
    ),
    # --- the FEM's weak form and boundary conditions -------------------------------------------
    Mutant(
        "F2-fem-axisymmetric-weight",
        "fem_reference",
        "fem_reference/model.py",
        # the default assembly (FemSettings.kernels="vectorised"); the scikit-fem forms it replaced
        # are kept and held equal to it by tests/test_fem_reference.py
        "WT = (T * rdx)",
        "WT = (T * ub.dx)",
        "the deviatoric form without the axisymmetric weight r (the pressure forms keep it)",
    ),
    Mutant(
        "F4-fem-bonded-punch",
        "fem_reference",
        "fem_reference/model.py",
        "fixed = np.unique(np.concatenate([axis, far, face]))",
        "fixed = np.unique(np.concatenate([axis, far, face, ub.get_dofs(lambda x: (x[1] < tol) & "
        '(x[0] < face_radius * (1 + 1e-12))).all("u^1")]))',
        "the punch holds u_r = 0 on its face (bonded, no slip) instead of the frictionless contact of Eqs. 1-6",
    ),
    Mutant(
        "F5-fem-radius-units",
        "fem_reference",
        "fem_reference/solver.py",
        "K = modulus_scale * a * u.stiffness",
        "K = modulus_scale * u.stiffness",
        "the FEM's stiffness not scaled by the punch radius (K = E K^ instead of E a K^): right only for a = 1",
    ),
    # --- rasterisation -------------------------------------------------------------------------
    Mutant(
        "R1-raster-half-cell",
        "contact_scene",
        "contact_scene/raster.py",
        "x = cx + (i0 + 0.5 + np.arange(nx)) * spacing",
        "x = cx + (i0 + np.arange(nx)) * spacing",
        "cell centres shifted by half a cell in x (corners taken for centres): a different staircase face",
    ),
    Mutant(
        "R2-raster-area",
        "contact_scene",
        "contact_scene/raster.py",
        "return float(np.count_nonzero(self.mask)) * self.spacing**2",
        "return float(self.mask.size) * self.spacing**2",
        "the raster's area counts every cell of its box, not the face's cells",
    ),
    # --- theory constants ----------------------------------------------------------------------
    Mutant(
        "T1-kendall-8pi",
        "contact_scene",
        "contact_scene/theory.py",
        "return math.sqrt(8.0 * math.pi * E_star * work * radius**3)",
        "return math.sqrt(2.0 * math.pi * E_star * work * radius**3)",
        "Kendall's F_A = sqrt(2 pi E* w a^3) instead of sqrt(8 pi ...) (Eq. 6): the closed form halved",
    ),
    Mutant(
        "T2-eq13-filling-factor",
        "contact_scene",
        "contact_scene/theory.py",
        "return math.sqrt(8.0 * math.pi * E_star * filling_factor * work * (area / math.pi) ** 1.5)",
        "return math.sqrt(8.0 * math.pi * E_star * work * (area / math.pi) ** 1.5)",
        "Eq. 13/24's upper bound without the filling factor phi (only faces with phi < 1: brushes, faults)",
    ),
    Mutant(
        "T3-eq34-cosine",
        "contact_scene",
        "contact_scene/theory.py",
        "return 4.0 * (2.0 + k) * math.cos(k * math.pi / 2)",
        "return 4.0 * (2.0 + k) * math.cos(k * math.pi / 4)",
        "Eq. 34's graded stiffness with cos(k pi/4) instead of cos(k pi/2) (k = 0.5: +31 %)",
    ),
    Mutant(
        "P1-paraboloid-factor-2",
        "contact_scene",
        "contact_scene/profiles.py",
        "return r2 / (2 * self.radius)",
        "return r2 / self.radius",
        "the paraboloid's height r^2/R instead of r^2/(2R): a sphere of half the radius",
    ),
    # --- sign conventions ----------------------------------------------------------------------
    Mutant(
        "S1-griffith-tension-sign",
        "bem_griffith",
        "bem_griffith/result.py",
        "tensile = -curve.force\n    peak = recorder.peak()",
        "tensile = abs(curve.force)\n    peak = int(tensile.argmax())",
        "the pull-off read as the largest |F| of the curve, compressive or tensile (sign convention)",
    ),
)

#: the test files in the order they run: fast files that compare with closed forms first, so
#: that a caught mutant stops within a minute or two; files not listed run after these
TEST_ORDER = (
    "tests/test_theory.py",
    "tests/test_halfspace.py",
    "tests/test_mutants.py",
    "tests/test_poisson_invariance.py",
    "tests/test_error_models.py",
    "tests/test_zero_range_estimator.py",
    "tests/test_fem_reference.py",
    "tests/test_bem_griffith.py",
    "tests/test_bem_graded.py",
    "tests/test_bem_energy.py",
    "tests/test_energy_finite_range.py",
    "tests/test_shapes.py",
    "tests/test_crossval.py",
    "tests/test_extreme.py",
    "tests/test_scene_files.py",
    "tests/test_harness.py",
    "tests/test_examples.py",
    "tests/test_report_view.py",
    "tests/test_cache_robustness.py",
)

#: the run order of the catalogue: the mutants whose catch depends on a tolerance first (a
#: partial run then says the most), the blunt ones after
RUN_ORDER = (
    "H1-love-pi",
    "M2-griffith-E-not-Estar",
    "C1-element-energy-constant",
    "H3-collocation-self-term",
    "C3-calibration-table-digit",
    "Z1-rate-bracket",
    "E3-process-zone-length",
    "R1-raster-half-cell",
    "R2-raster-area",
    "F5-fem-radius-units",
    "T2-eq13-filling-factor",
    "S1-griffith-tension-sign",
    "E2-range-for-process-zone",
    "M1-estar-square",
    "M3-fem-Estar-not-E",
    "F4-fem-bonded-punch",
    "F2-fem-axisymmetric-weight",
    "H4-graded-kernel-exponent",
    "E1-potential-work-half",
    "T1-kendall-8pi",
    "T3-eq34-cosine",
    "C4-calibration-inverted",
    "P1-paraboloid-factor-2",
)

#: test files that exercise a package most directly: they run first for a mutant of that package
#: (then :data:`TEST_ORDER`), so that the first failure comes early; the suite is the same
PACKAGE_TESTS = {
    "halfspace": ("tests/test_halfspace.py",),
    "contact_scene": ("tests/test_theory.py", "tests/test_shapes.py"),
    "bem_griffith": ("tests/test_bem_griffith.py", "tests/test_bem_graded.py", "tests/test_error_models.py"),
    "bem_energy": (
        "tests/test_bem_energy.py",
        "tests/test_energy_finite_range.py",
        "tests/test_zero_range_estimator.py",
    ),
    "fem_reference": ("tests/test_fem_reference.py", "tests/test_poisson_invariance.py"),
}

_print_lock = threading.Lock()


def log(msg: str) -> None:
    with _print_lock:
        print(f"[{datetime.datetime.now(datetime.UTC):%H:%M:%S}] {msg}", flush=True)


def _env(copy: Path) -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(copy) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    for v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        env[v] = "1"
    env["MPLBACKEND"] = "Agg"
    return env


def _run(cmd: list[str], copy: Path, timeout: float, log_path: Path) -> tuple[int | None, float, str]:
    """(exit status or None on timeout, seconds, combined output) of ``cmd`` run in ``copy``."""
    t0 = time.perf_counter()
    with open(log_path, "w") as f:
        proc = subprocess.Popen(
            cmd, cwd=copy, env=_env(copy), stdout=f, stderr=subprocess.STDOUT, start_new_session=True
        )
        try:
            rc = proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, 9)  # the run's own process group (pytest / report workers)
            proc.wait()
            rc = None
    return rc, time.perf_counter() - t0, log_path.read_text(errors="replace")


def make_copy(base: Path, dest: Path, mutant: Mutant | None) -> Path:
    """A copy of ``base`` without git metadata and build products, with ``mutant`` applied."""
    if dest.exists():
        shutil.rmtree(dest)
    shutil.copytree(
        base,
        dest,
        ignore=shutil.ignore_patterns(
            ".git", "build", "*.egg-info", "_build", "auto_examples", ".crossval-cache", "__pycache__", "report"
        ),
    )
    if mutant is not None:
        path = dest / mutant.file
        text = path.read_text()
        found = text.count(mutant.old)
        if found != mutant.count:
            raise ValueError(f"{mutant.id}: {mutant.file} holds the old text {found} times, expected {mutant.count}")
        path.write_text(text.replace(mutant.old, mutant.new))
    return dest


def check_import(copy: Path, package: str) -> str:
    out = subprocess.run(
        [sys.executable, "-c", f"import {package}, crossval; print({package}.__file__); print(crossval.__file__)"],
        cwd=copy,
        env=_env(copy),
        capture_output=True,
        text=True,
    )
    files = out.stdout.split()
    if out.returncode != 0 or len(files) != 2 or not all(f.startswith(str(copy)) for f in files):
        raise RuntimeError(f"the copy {copy} is not what gets imported: {out.stdout} {out.stderr[-500:]}")
    return files[0]


def _checks(results_json: Path) -> list[dict]:
    data = json.loads(results_json.read_text())
    out = []
    for scene, sd in data.get("scenes", {}).items():
        for c in sd.get("checks", []):
            out.append(
                {
                    "scene": scene,
                    **{
                        k: c.get(k) for k in ("method", "quantity", "value", "reference", "tolerance", "passed", "role")
                    },
                }
            )
    return out


def _key(c: dict) -> tuple:
    return (c["scene"], c["method"], c["quantity"], c.get("reference") is None)


def quick_report(copy: Path, timeout: float, *, full: bool = False) -> dict:
    out = copy / ("report_full" if full else "report_quick")
    cmd = [sys.executable, "-m", "crossval", "report", "--no-cache", "--out", str(out)] + ([] if full else ["--quick"])
    rc, secs, text = _run(cmd, copy, timeout, copy / ("report_full.log" if full else "report_quick.log"))
    res = {"exit": rc, "seconds": round(secs, 1), "checks": None, "tail": text.strip().splitlines()[-3:]}
    if (out / "results.json").exists() and rc is not None:
        res["checks"] = _checks(out / "results.json")
    return res


def _first_failure(text: str) -> tuple[str | None, str]:
    m = re.search(r"^(?:FAILED|ERROR) (\S+)(?: - (.*))?$", text, re.M)
    if m:
        return m.group(1), (m.group(2) or "")[:300]
    m = re.search(r"^(?:E\s+)(.+)$", text, re.M)
    return None, m.group(1)[:300] if m else ""


def _ordered_tests(copy: Path, package: str) -> list[str]:
    present = sorted(str(p.relative_to(copy)) for p in (copy / "tests").glob("test_*.py"))
    first = [t for t in dict.fromkeys(PACKAGE_TESTS.get(package, ()) + TEST_ORDER) if t in present]
    return first + [t for t in present if t not in first]


def test_suite(
    copy: Path, base_copy: Path, package: str, timeout: float, known_failures: dict, lock: threading.Lock
) -> dict:
    """Run the suite with -x; a first failure that also fails on the unmutated copy is
    deselected (and remembered) and the run repeated."""
    deselected = []
    t_start = time.perf_counter()
    while True:
        with lock:
            skip = [t for t, bad in known_failures.items() if bad]
        remaining = timeout - (time.perf_counter() - t_start)
        cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", *_ordered_tests(copy, package)]
        cmd += [f"--deselect={t}" for t in skip]
        rc, secs, text = _run(cmd, copy, max(remaining, 1.0), copy / "pytest.log")
        tail = text.strip().splitlines()[-1:] if text.strip() else []
        if rc is None:
            return {
                "exit": None,
                "seconds": round(time.perf_counter() - t_start, 1),
                "first_failure": None,
                "message": f"timeout after {timeout:.0f} s",
                "deselected_baseline_failures": deselected,
                "tail": tail,
            }
        test, message = _first_failure(text)
        if rc == 0 or test is None:
            return {
                "exit": rc,
                "seconds": round(time.perf_counter() - t_start, 1),
                "first_failure": test,
                "message": message if rc else "",
                "deselected_baseline_failures": deselected,
                "tail": tail,
            }
        with lock:
            known = known_failures.get(test)
        if known is None:
            brc, _, _ = _run(
                [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", test],
                base_copy,
                900.0,
                copy / "pytest_baseline_check.log",
            )
            known = brc not in (0, None) and brc != 5
            with lock:
                known_failures[test] = known
        if not known:
            return {
                "exit": rc,
                "seconds": round(time.perf_counter() - t_start, 1),
                "first_failure": test,
                "message": message,
                "deselected_baseline_failures": deselected,
                "tail": tail,
            }
        deselected.append(test)
        log(f"  {test} fails without the mutant too: deselected, rerunning")


def _report_verdict(res: dict, baseline: dict | None) -> dict:
    """Whether a report run catches the mutant: exit status differs from the baseline's, or a
    check fails that passed without the mutant, or a check is missing / new."""
    if res["checks"] is None:
        return {
            "caught": res["exit"] is not None and res["exit"] != 0,
            "how": "crashed (no results.json): " + " | ".join(res["tail"]) if res["exit"] else "timeout",
            "new_failures": [],
            "moves": [],
        }
    base_checks = {_key(c): c for c in (baseline or {}).get("checks") or []}
    new_fail = [c for c in res["checks"] if not c["passed"] and (base_checks.get(_key(c)) or {}).get("passed", True)]
    moves = []
    for c in res["checks"]:
        b = base_checks.get(_key(c))
        if b and b["value"] and c["value"] is not None:
            moves.append(
                {
                    "scene": c["scene"],
                    "method": c["method"],
                    "quantity": c["quantity"],
                    "moved": c["value"] / b["value"] - 1,
                    "difference": (c["value"] / c["reference"] - 1) if c["reference"] else None,
                    "tolerance": c["tolerance"],
                    "passed": c["passed"],
                }
            )
    moves.sort(key=lambda m: -abs(m["moved"]))
    caught = bool(new_fail) or (baseline is not None and (res["exit"] != 0) and baseline.get("exit") == 0)
    how = "; ".join(f"{c['scene']}: {c['method']} {c['quantity']}" for c in new_fail[:4])
    if len(new_fail) > 4:
        how += f"; ... ({len(new_fail)} checks)"
    return {"caught": caught, "how": how, "new_failures": new_fail, "moves": moves[:12]}


def run_one(mutant: Mutant | None, args, baseline_report: dict | None, known_failures: dict, lock) -> dict:
    name = mutant.id if mutant else "baseline"
    copy = make_copy(args.base, args.work / name, mutant)
    rec = {"id": name, "imported": check_import(copy, mutant.package if mutant else "contact_scene")}
    if mutant:
        rec.update(asdict(mutant))
    if not args.skip_report:
        log(f"{name}: quick report")
        rec["quick_report"] = quick_report(copy, args.report_timeout)
        if mutant is not None:
            rec["quick_report"].update(_report_verdict(rec["quick_report"], baseline_report))
        log(
            f"{name}: quick report exit {rec['quick_report']['exit']} in {rec['quick_report']['seconds']} s"
            + (f", caught: {rec['quick_report'].get('caught')} {rec['quick_report'].get('how', '')}" if mutant else "")
        )
    if not args.skip_tests and mutant is not None:
        log(f"{name}: tests")
        rec["tests"] = test_suite(copy, args.work / "baseline", mutant.package, args.test_timeout, known_failures, lock)
        rec["tests"]["caught"] = rec["tests"]["first_failure"] is not None or rec["tests"]["exit"] not in (0, None)
        log(
            f"{name}: tests exit {rec['tests']['exit']} in {rec['tests']['seconds']} s, first failure "
            f"{rec['tests']['first_failure']}"
        )
    return rec


def _part_commits(records: list[dict]) -> dict:
    """Which base commit(s) each part of the study ran on."""
    out: dict = {}
    for label, key in (("quick reports", "quick_report"), ("tests", "tests"), ("full reports", "full_report")):
        cs = {r[key]["commit"] for r in records if isinstance(r.get(key), dict) and "commit" in r[key]}
        if cs:
            out[label] = cs
    return out


def _md(text: str) -> str:
    """Plain text for a Markdown table cell (no column breaks, no stray emphasis)."""
    return str(text).replace("|", "/").replace("*", "\\*").replace("\n", " ")


def _yes(x: bool | None) -> str:
    return "n/a" if x is None else ("yes" if x else "**no**")


#: why a report cannot see a mutant (where the catalogue knows): what the bug changes and why
#: no result the report computes depends on it; the tests catch these
BLIND_SPOTS = {
    "T2-eq13-filling-factor": (
        "Eq. 24 is an upper bound; without phi it only grows, and a correct solver stays below a looser "
        "bound, so no bounds check can fail.  Only a converged reference for a face with phi < 1 would "
        "show it, and the suite has no such face."
    ),
    "E3-process-zone-length": (
        "l_c(rho) serves the resolution guard of explicit finite-range runs and the contact fraction at "
        "which a detaching trial is stopped (a lever chosen to leave answers unchanged); the zero-range "
        "sequence the report runs sizes its grids from the requested l_c (range_for_process_zone), so its "
        "numbers move by far less than any bar."
    ),
}


def write_outputs(records: list[dict], meta: dict, out_dir: Path) -> None:
    out_dir.mkdir(parents=True, exist_ok=True)
    (out_dir / "mutation_study.json").write_text(
        json.dumps({"meta": meta, "results": records}, indent=1, default=str) + "\n"
    )
    muts = [r for r in records if r["id"] != "baseline"]
    q = [r["quick_report"]["caught"] for r in muts if "quick_report" in r and "caught" in r["quick_report"]]
    t = [r["tests"]["caught"] for r in muts if "tests" in r]
    both = [r for r in muts if "quick_report" in r and "tests" in r]
    lines = [
        "# Mutation study: does the harness catch a physics bug?",
        "",
        f"Written by `python benchmarks/mutation_study.py` on {meta['date']} ({meta['machine']}); base commit(s): "
        + "; ".join(
            f"{label} on " + ", ".join(f"`{c}`" for c in sorted(cs)) for label, cs in _part_commits(records).items()
        )
        + f"; last command: {meta['command']}.",
        "",
        "Each mutant replaces one text of the package in a copy of the repository (exactly as listed in "
        "`benchmarks/mutation_study.py`), then runs `crossval report --quick --no-cache` (caught: a check fails "
        "that passes without the mutant, or the report crashes) and the test suite with `pytest -x`, the mutated "
        "package's own test files first (caught: a test fails that passes without the mutant; the first such test "
        f"is named; at most {meta['test_timeout_s']:.0f} s per mutant). "
        "The full report runs only for mutants both miss.",
        "",
        f"Quick report: caught {sum(q)} of {len(q)}"
        + (f" ({100 * sum(q) / len(q):.0f} %)" if q else "")
        + f"; tests: caught {sum(t)} of {len(t)}"
        + (
            "; quick report or tests: "
            f"{sum(r['quick_report'].get('caught', False) or r['tests']['caught'] for r in both)} "
            f"of {len(both)}"
            if both
            else ""
        )
        + ".",
        "",
        "| mutant | what it breaks | quick report | failing check(s) | tests | first failing test | full report |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in muts:
        qr, ts = r.get("quick_report", {}), r.get("tests", {})
        full = r.get("full_report")
        full_cell = "not run" if full is None else (f"{_yes(full.get('caught'))}: {full.get('how', '')}")
        test_cell = (ts.get("message") if ts else "not run") or "-"
        if ts.get("first_failure"):
            test_cell = f"`{ts['first_failure']}`" + (f" ({_md(ts['message'][:120])})" if ts.get("message") else "")
        else:
            test_cell = _md(test_cell)
        if r.get("error"):
            test_cell = _md("error: " + r["error"])
        lines.append(
            f"| `{r['id']}` ({r['file']}) | {_md(r['breaks'])} | {_yes(qr.get('caught')) if qr else 'not run'} | "
            f"{_md(qr.get('how', '') or '-')} | {_yes(ts.get('caught')) if ts else 'not run'} | "
            f"{test_cell} | {_md(full_cell)} |"
        )
    missed = [r for r in muts if r.get("quick_report", {}).get("caught") is False]
    if missed:
        lines += [
            "",
            "## Missed by the quick report: how far each quantity moved",
            "",
            "Relative change of each checked value from the unmutated run, its difference from the "
            "check's reference, and the check's tolerance (largest moves first).",
            "",
        ]
        for r in missed:
            lines.append(
                f"* `{r['id']}`: "
                + (
                    "; ".join(
                        f"{m['scene']} {m['method']} {m['quantity']} moved {m['moved']:+.3%} "
                        f"(now {m['difference']:+.3%} "
                        f"from its reference, tolerance {m['tolerance']:.3%})"
                        if m["difference"] is not None
                        else f"{m['scene']} {m['method']} {m['quantity']} moved {m['moved']:+.3%}"
                        for m in [m for m in r["quick_report"].get("moves", []) if abs(m["moved"]) > 1e-9][:4]
                    )
                    or "no checked value moved"
                )
                + (f".  Why: {BLIND_SPOTS[r['id']]}" if r["id"] in BLIND_SPOTS else "")
            )
    base = next((r for r in records if r["id"] == "baseline"), None)
    if base and "quick_report" in base:
        bad = [c for c in base["quick_report"].get("checks") or [] if not c["passed"]]
        lines += [
            "",
            f"Without a mutant the quick report exits {base['quick_report']['exit']} in "
            f"{base['quick_report']['seconds']:.0f} s"
            + (
                ": failing checks " + "; ".join(f"{c['scene']} {c['method']} {c['quantity']}" for c in bad)
                if bad
                else ", every check passing"
            )
            + ".",
        ]
    if meta.get("baseline_test_failures"):
        lines += [
            "",
            "Tests that fail without a mutant (deselected in the mutants' runs): "
            + ", ".join(f"`{x}`" for x in meta["baseline_test_failures"])
            + ".",
        ]
    (out_dir / "mutation_study.md").write_text("\n".join(lines) + "\n")


def combine(files: list[Path], out_dir: Path) -> None:
    """One table from several runs (e.g. the tests on one base, the quick reports on a later one):
    each mutant's parts are taken from the last file that has them."""
    results: dict[str, dict] = {}
    meta: dict = {}
    failures: set = set()
    for f in files:
        data = json.loads(f.read_text())
        meta = {**meta, **data["meta"]}
        failures |= set(data["meta"].get("baseline_test_failures", []))
        for r in data["results"]:
            results[r["id"]] = {**results.get(r["id"], {}), **r}
    order = {m.id: i for i, m in enumerate(MUTANTS)}
    meta["baseline_test_failures"] = sorted(failures)
    meta["commits"] = sorted(
        {
            p["commit"]
            for r in results.values()
            for k, p in r.items()
            if k in ("quick_report", "tests", "full_report") and isinstance(p, dict) and "commit" in p
        }
    )
    meta["command"] = "python benchmarks/mutation_study.py --combine " + " ".join(str(f) for f in files)
    write_outputs(
        sorted(results.values(), key=lambda r: -1 if r["id"] == "baseline" else order.get(r["id"], 999)), meta, out_dir
    )


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--base", type=Path, default=Path("/tmp/mut/base"), help="a clean clone of the repository")
    p.add_argument("--work", type=Path, default=Path("/tmp/mut/work"), help="where the mutated copies go")
    p.add_argument("--out", type=Path, default=REPO / "docs", help="where mutation_study.md / .json are written")
    p.add_argument("--only", nargs="+", metavar="ID", help="run these mutants only")
    p.add_argument("--skip-tests", action="store_true", help="the quick report only")
    p.add_argument("--skip-report", action="store_true", help="the tests only")
    p.add_argument(
        "--full-for-missed",
        action="store_true",
        help="run the full report for mutants that the quick report and the tests both miss",
    )
    p.add_argument("--jobs", type=int, default=1, help="mutants run at once (default 1: the machine is shared)")
    p.add_argument("--test-timeout", type=float, default=900.0, help="seconds per mutant's test run")
    p.add_argument("--report-timeout", type=float, default=1800.0, help="seconds per quick report")
    p.add_argument(
        "--baseline-report",
        type=Path,
        default=None,
        help="a quick report's directory (results.json) of the unmutated base, instead of running it",
    )
    p.add_argument(
        "--merge",
        action="store_true",
        help="update an existing mutation_study.json: parts not run now (quick report, tests) are kept, "
        "each labelled with the base commit it ran on",
    )
    p.add_argument(
        "--combine",
        nargs="+",
        type=Path,
        metavar="JSON",
        help="merge the parts of earlier runs' mutation_study.json files (later files win), write --out, exit",
    )
    p.add_argument("--list", action="store_true", help="print the catalogue and exit")
    args = p.parse_args(argv)
    if args.combine:
        combine(args.combine, args.out)
        return
    if args.list:
        for m in MUTANTS:
            print(f"{m.id:32s} {m.file:30s} {m.breaks}")
        return
    ids = {m.id for m in MUTANTS}
    if args.only and not set(args.only) <= ids:
        p.error(f"unknown mutant(s) {sorted(set(args.only) - ids)}; see --list")
    order = {i: n for n, i in enumerate(RUN_ORDER)}
    chosen = sorted(
        (m for m in MUTANTS if not args.only or m.id in args.only), key=lambda m: order.get(m.id, len(order))
    )
    args.base = args.base.resolve()
    args.work.mkdir(parents=True, exist_ok=True)
    for m in chosen:  # every text must exist before anything runs
        text = (args.base / m.file).read_text()
        if text.count(m.old) != m.count:
            raise SystemExit(f"{m.id}: {m.file} holds the old text {text.count(m.old)} times, expected {m.count}")
    commit = subprocess.run(
        ["git", "-C", str(args.base), "log", "-1", "--format=%h (%cs)"], capture_output=True, text=True
    ).stdout.strip()
    meta = {
        "date": f"{datetime.datetime.now(datetime.UTC):%Y-%m-%d %H:%M} UTC",
        "machine": f"{platform.node()}, {platform.processor() or platform.machine()}, {os.cpu_count()} cores "
        f"(shared), Python {platform.python_version()}",
        "commit": commit,
        "command": "python benchmarks/mutation_study.py " + " ".join(sys.argv[1:] if argv is None else argv),
        "test_order": list(TEST_ORDER),
        "test_timeout_s": args.test_timeout,
    }
    known_failures: dict = {}
    lock = threading.Lock()
    log(f"base {args.base} at {commit}; {len(chosen)} mutants")
    if args.baseline_report is not None:
        make_copy(args.base, args.work / "baseline", None)
        data = json.loads((args.baseline_report / "results.json").read_text())
        baseline = {
            "id": "baseline",
            "quick_report": {
                "exit": 0 if data.get("passed") else 1,
                "seconds": data.get("wall_time_s"),
                "checks": _checks(args.baseline_report / "results.json"),
                "tail": [f"reused from {args.baseline_report}"],
            },
        }
    else:
        baseline = run_one(None, args, None, known_failures, lock)
    for part in ("quick_report", "tests"):
        if part in baseline:
            baseline[part]["commit"] = commit
    results: dict[str, dict] = {}
    old = args.out / "mutation_study.json"
    if args.merge and old.exists():
        # parts (quick report, tests, full report) not run now are kept, each with its own base commit
        prev = json.loads(old.read_text())
        results = {r["id"]: r for r in prev["results"]}
        known_failures.update({t: True for t in prev.get("meta", {}).get("baseline_test_failures", [])})
        log(f"merging with {len(results)} records of an earlier run")
    order = {m.id: i for i, m in enumerate(MUTANTS)}

    def add(rec):
        merged = {**results.get(rec["id"], {}), **rec}
        if "error" not in rec and ("quick_report" in rec or "tests" in rec):
            merged.pop("error", None)
        results[rec["id"]] = merged
        meta["baseline_test_failures"] = sorted(t for t, bad in known_failures.items() if bad)
        meta["commits"] = sorted(
            {
                p["commit"]
                for r in results.values()
                for k, p in r.items()
                if k in ("quick_report", "tests", "full_report") and isinstance(p, dict) and "commit" in p
            }
        )
        records = sorted(results.values(), key=lambda r: -1 if r["id"] == "baseline" else order.get(r["id"], 999))
        write_outputs(records, meta, args.out)
        return records

    records = add(baseline)

    def job(m):
        try:
            rec = run_one(m, args, results["baseline"].get("quick_report"), known_failures, lock)
            for part in ("quick_report", "tests"):
                if part in rec:
                    rec[part]["commit"] = commit
            return rec
        except Exception as exc:  # a broken mutant is recorded, not fatal to the study
            log(f"{m.id}: {type(exc).__name__}: {exc}")
            return {"id": m.id, **asdict(m), "error": f"{type(exc).__name__}: {exc}"}

    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        for rec in pool.map(job, chosen):
            records = add(rec)
            shutil.rmtree(args.work / rec["id"], ignore_errors=True)
    if args.full_for_missed:
        for rec in list(records[1:]):
            if rec.get("quick_report", {}).get("caught") is False and rec.get("tests", {}).get("caught") is False:
                m = next(x for x in MUTANTS if x.id == rec["id"])
                copy = make_copy(args.base, args.work / m.id, m)
                log(f"{m.id}: missed by both; full report")
                if "full_baseline" not in meta:
                    meta["full_baseline"] = quick_report(args.work / "baseline", 4 * args.report_timeout, full=True)
                full = quick_report(copy, 4 * args.report_timeout, full=True)
                full.update(_report_verdict(full, meta["full_baseline"]), commit=commit)
                records = add({"id": m.id, "full_report": full})
                shutil.rmtree(copy, ignore_errors=True)
    log("done")


if __name__ == "__main__":
    main()
