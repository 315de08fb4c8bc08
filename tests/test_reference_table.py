"""The reference table of the non-circular faces (``crossval/references/faces.json``).

Written by ``benchmarks/reference_table.py``: per face, F_A / F_A,upper, the approach at F_A
and the stiffness from the Griffith BEM extrapolated in 1/N and from the energy BEM's
zero-range limit, each with a relative bar.  Checked here without solving anything: every
bar is a positive finite number, F_A lies between the bounds of Eqs. 13 and 18, the square
and the same square at 45 degrees to the grid agree (the physics does not see the grid), and
two methods that disagree beyond their combined bars say so (``agreement: false`` with the
gap) instead of passing silently.  Each check is also run on a broken copy of the table (a
mutant) to show that it can fail.  The slow test re-runs the coarsest Griffith points.
"""

from __future__ import annotations

import copy
import importlib.util
import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from contact_scene import theory as T

ROOT = Path(__file__).resolve().parents[1]
FACES_JSON = ROOT / "crossval" / "references" / "faces.json"
FACES = ("square", "triangle", "rectangle", "square_45", "two_circles", "star")
QUANTITIES = ("pulloff_force", "pulloff_approach", "stiffness")
METHODS = ("bem_griffith", "bem_energy")


#: how closely a refit of stored runs repeats the stored fits: the energy BEM's limit takes a rate
#: found by a bounded minimisation over a flat misfit, whose argument follows the rounding of the
#: least-squares solves to about the square root of machine epsilon; on a machine with AVX-512
#: kernels the refit of the table computed on another one moved limits by 1.4e-9, bars by 1.0e-7
#: and relative gaps by 1.6e-7, while a 1 % change of one range moves a limit by about 1e-3
REFIT_RTOL = 1e-6


def _load_script():
    sys.path.insert(0, str(ROOT / "benchmarks"))  # the script imports its sibling _timing
    spec = importlib.util.spec_from_file_location("reference_table", ROOT / "benchmarks" / "reference_table.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def table() -> dict:
    return json.loads(FACES_JSON.read_text())


def values(doc: dict):
    """Every (face, quantity, method, entry) with a value in the table."""
    for face, entry in doc["faces"].items():
        for q, qentry in entry["quantities"].items():
            for key, v in qentry.items():
                if isinstance(v, dict) and "value" in v:
                    yield face, q, key, v


def bar_problems(doc: dict) -> list[str]:
    return [
        f"{face} {q} {key}: bar {v['relative_bar']!r}"
        for face, q, key, v in values(doc)
        if not (isinstance(v["relative_bar"], float) and math.isfinite(v["relative_bar"]) and v["relative_bar"] > 0)
        or not math.isfinite(v["value"])
    ]


def bound_problems(doc: dict) -> list[str]:
    """F_A / F_A,upper outside [F_A,lower / F_A,upper, 1] (Eqs. 18 and 13), the lower bound
    recomputed from the scene's incircle, each value allowed its bar."""
    script = _load_script()
    out = []
    for face, q, key, v in values(doc):
        if q != "pulloff_force":
            continue
        scene = script.face_scene(face)
        E, w, shape = scene.material.effective_modulus, scene.adhesion.work_of_adhesion, scene.indenter.shape
        low = T.lower_bound_force(E_star=E, work=w, incircle_radius=shape.incircle().radius) / T.upper_bound_force(
            E_star=E, work=w, area=shape.area
        )
        slack = v["relative_bar"] * v["value"]
        if not low - slack <= v["value"] <= 1 + slack:
            out.append(f"{face} {key}: {v['value']:.4f} outside [{low:.4f}, 1]")
    return out


def rotation_problems(doc: dict) -> list[str]:
    """The square and the square at 45 degrees: the methods behind the references (the reference
    criterion's Griffith values and the energy BEM's) agree within their combined bars in every
    quantity; another criterion's column may not, but then the table must say so
    (``rotation_check``), as it must say when it does."""
    a, b = doc["faces"]["square"]["quantities"], doc["faces"]["square_45"]["quantities"]
    stored = doc.get("rotation_check", {})
    out = []
    for q in QUANTITIES:
        for m in sorted(k for k in a[q] if k.startswith("bem_")):  # each method and criterion
            if m in b[q]:
                x, y = a[q][m], b[q][m]
                combined = x["relative_bar"] * abs(x["value"]) + y["relative_bar"] * abs(y["value"])
                agree = abs(x["value"] - y["value"]) <= combined
                if m in METHODS and not agree:
                    out.append(f"{q} {m}: {x['value']:.5f} vs {y['value']:.5f} (combined bar {combined:.2g})")
                elif stored.get(m, {}).get(q, {}).get("agreement") is not agree:
                    out.append(f"{q} {m}: rotation flag {stored.get(m, {}).get(q)!r}, measured agreement {agree}")
    return out


def agreement_problems(doc: dict) -> list[str]:
    """Where both methods give a value: the flag must match the gap against the combined bars,
    and a disagreement must carry its gap."""
    out = []
    for face, entry in doc["faces"].items():
        for q, qe in entry["quantities"].items():
            if not all(m in qe for m in METHODS):
                continue
            g, e = qe["bem_griffith"], qe["bem_energy"]
            gap = e["value"] - g["value"]
            combined = g["relative_bar"] * abs(g["value"]) + e["relative_bar"] * abs(e["value"])
            agree = abs(gap) <= combined
            if qe.get("agreement") is not agree:
                out.append(
                    f"{face} {q}: agreement flag {qe.get('agreement')!r}, measured gap {gap:+.4g} vs {combined:.3g}"
                )
            elif not agree and not math.isclose(qe.get("gap", math.nan), gap, rel_tol=1e-9):
                out.append(f"{face} {q}: disagreement without its gap ({qe.get('gap')!r}, measured {gap:+.4g})")
    return out


def test_table_is_well_formed(table):
    """Every face is there; a value missing from it is declared missing, with the reason."""
    for key in ("command", "revision", "date", "griffith_procedure", "energy_procedure", "check", "faces"):
        assert key in table, key
    assert set(table["faces"]) == set(FACES)
    for face, entry in table["faces"].items():
        declared = entry.get("not_computed", {})
        assert not declared or (declared["methods"] and declared["why"]), face
        assert set(entry["quantities"]) == set(QUANTITIES), face
        for q, qe in entry["quantities"].items():
            ref = qe.get("reference")
            if ref is None:
                assert "bem_griffith" not in qe and "bem_energy" not in qe, f"{face} {q}: values but no reference"
                assert f"bem_griffith ({table['reference_criterion']})" in declared.get("methods", ()), face
                continue
            assert ref["method"] in METHODS or (ref["method"].startswith("the interval") and not qe["agreement"])
        for criterion, sweep in entry["griffith"].items():
            assert len(sweep["resolutions"]) >= 4, f"{face} {criterion}: fewer than four grids behind the 1/N limit"
            assert sweep["all_converged"], f"{face} {criterion}"
        if entry["energy"] is None:
            assert "bem_energy" in declared.get("methods", ()), face
        else:
            assert entry["energy"]["converged"], face


def test_bars_are_positive_and_finite(table):
    assert not bar_problems(table)
    broken = copy.deepcopy(table)
    broken["faces"]["square"]["quantities"]["stiffness"]["reference"]["relative_bar"] = math.nan
    assert bar_problems(broken)


def test_pulloff_between_the_bounds(table):
    assert not bound_problems(table)
    broken = copy.deepcopy(table)
    broken["faces"]["triangle"]["quantities"]["pulloff_force"]["reference"]["value"] = 1.02
    assert bound_problems(broken)


def check_problems(doc: dict) -> list[str]:
    """The test of the procedure on Kendall's circle (every quantity exactly 1), recomputed from
    its stored points: each window's limit is the least-squares q0 + c/N over its finest four
    grids, the bias the largest |q0 - 1| over the windows, and every Griffith bar covers the
    bias of its criterion (the part of the error no extrapolation in N removes)."""
    out = []
    for key, check in doc["check"].items():
        points = {p["N"]: p["normalised"] for p in check["points"]}
        if len(check["windows"]) < 2:
            out.append(f"{key}: the bias is taken over a single window of grids")
        for q, bias in check["bias"].items():
            errors = []
            for w in check["windows"]:
                N = np.array(sorted(w["resolutions"])[-4:], float)
                y = np.array([points[n][q] for n in sorted(w["resolutions"])[-4:]])
                q0 = np.linalg.lstsq(np.c_[np.ones_like(N), 1 / N], y, rcond=None)[0][0]
                errors.append(abs(q0 - 1))
            if not math.isclose(bias, max(errors), rel_tol=1e-9, abs_tol=1e-12):
                out.append(f"{key} {q}: stored bias {bias:.3g}, its points give {max(errors):.3g}")
    for face, entry in doc["faces"].items():
        for criterion, sweep in entry["griffith"].items():
            for q, v in sweep["quantities"].items():
                bias = doc["check"][v["circle_check"]]["bias"][q]
                if v["relative_bar"] * abs(v["value"]) < bias * (1 - 1e-12):
                    out.append(f"{face} {criterion} {q}: bar below the circle's bias {bias:.3g}")
    return out


def test_procedure_check_on_kendall(table):
    assert not check_problems(table)
    broken = copy.deepcopy(table)
    check = next(iter(broken["check"].values()))
    check["bias"]["pulloff_force"] /= 2
    assert check_problems(broken)
    broken = copy.deepcopy(table)
    sweep = broken["faces"]["square"]["griffith"][table["reference_criterion"]]
    sweep["quantities"]["pulloff_force"]["relative_bar"] = 1e-5
    assert check_problems(broken)


def tail_problems(doc: dict) -> list[str]:
    """Every Griffith bar covers its sweep's tail estimate plus the circle's bias, recomputed
    from the stored points the fit kept: the larger distance from the limit to the two limits
    the finest step allows, q_f + (q_f - q_s) / (t^p - 1) with t = N_f / N_s, for p at either end
    of the script's rate bracket (no fast end: the finest value itself); and whether the sweep
    has shown the slow end's order (``order_seen``)."""
    script = _load_script()
    rates = script.GRIFFITH_RATES
    out = []
    for face, entry in doc["faces"].items():
        for criterion, sweep in entry["griffith"].items():
            kept = sorted((p for p in sweep["points"] if p["N"] in sweep["resolutions"]), key=lambda p: p["N"])
            (n_s, n_f), (a, b) = [p["N"] for p in kept[-2:]], [p["normalised"] for p in kept[-2:]]
            for q, v in sweep["quantities"].items():
                ends = [b[q] + (b[q] - a[q]) / ((n_f / n_s) ** r - 1) for r in rates]
                tail = max(abs(v["value"] - e) for e in ends)
                bias = doc["check"][v["circle_check"]]["bias"][q]
                if v["relative_bar"] * abs(v["value"]) < (tail + bias) * (1 - 1e-12):
                    out.append(f"{face} {criterion} {q}: bar {v['relative_bar']:.3g} below tail {tail:.3g} + bias")
                order = script.observed_order([p["N"] for p in kept], [p["normalised"][q] for p in kept])
                seen = order is not None and order >= rates[0]
                if v["order_seen"] is not seen:
                    out.append(f"{face} {criterion} {q}: order_seen {v['order_seen']!r}, finest grids' order {order}")
    return out


def test_griffith_bars_carry_the_tail_estimate(table):
    assert not tail_problems(table)
    broken = copy.deepcopy(table)
    # the bar before the tail estimate: the fits' spread and the circle's bias only
    v = broken["faces"]["square"]["griffith"]["energy_release"]["quantities"]["pulloff_force"]
    v["relative_bar"] = (v["model_spread"] + v["circle_bias"]) / v["value"]
    assert tail_problems(broken)
    broken = copy.deepcopy(table)
    v = broken["faces"]["square"]["griffith"]["energy_release"]["quantities"]["pulloff_force"]
    v["order_seen"] = not v["order_seen"]
    assert tail_problems(broken)


@pytest.mark.parametrize("grids", [(32, 45, 64, 90, 128), (45, 64, 90, 128), (64, 90, 128, 181, 256)])
def test_griffith_uncertainty_bounds_power_laws_in_its_rate_bracket(grids):
    """q = 1 +- N^-p: the extrapolation's uncertainty covers its error for every rate p from
    the slow end of GRIFFITH_RATES up (and, as a conditional bound, not for a slower one), while
    the fits' spread alone covers it only near p = 1 (and over five grids from p = 2 up; a pure
    N^-0.75: a factor 3.3 short over 32 ... 128 and 64 ... 256, 7.4 over 45 ... 128)."""
    script = _load_script()
    N = np.array(grids, float)
    lo, hi = script.GRIFFITH_RATES
    assert hi == math.inf
    for p in (*np.linspace(lo, 2.0, 7), 3.0, 4.0, 6.0):
        for sign in (1, -1):
            e = script.extrapolate(N, 1 + sign * N**-p)
            assert abs(e["value"] - 1) <= e["uncertainty"] * (1 + 1e-9), (p, sign)
            assert e["order_seen"]
    e = script.extrapolate(N, 1 + N**-0.75)
    assert abs(e["value"] - 1) > (7 if len(grids) == 4 else 3) * e["model_spread"]
    e = script.extrapolate(N, 1 + N ** -(lo / 2))
    assert abs(e["value"] - 1) > e["uncertainty"] and not e["order_seen"]


def test_observed_order_of_power_laws():
    """The order through the finest three grids is the power of a pure power law, negative for
    steps that grow, and None where the steps differ in sign."""
    script = _load_script()
    N = np.array([45, 64, 90, 128], float)
    for p in (-0.5, 0.5, 1.0, 2.5):
        assert script.observed_order(N, 0.8 + 0.3 * N**-p) == pytest.approx(p, abs=1e-8)
    assert script.observed_order(N, [1.0, 0.99, 0.995, 0.99]) is None
    assert script.observed_order(N, [1.0, 1.0, 1.0, 1.0]) is None
    with pytest.raises(ValueError, match="distinct grids"):
        script.observed_order([64, 128, 128], [1.0, 0.9, 0.8])


def test_tail_estimate_covers_kendall_where_the_criterion_converges(table):
    """On Kendall's circle the tail estimate alone covers the procedure's error in the pull-off
    force and the stiffness, in every window of the sweeps of the criteria that converge (the
    paper criterion's plateau is not a tail: it is the bias every bar adds)."""
    for key, check in table["check"].items():
        if key.startswith("paper"):
            continue
        for w in check["windows"]:
            for q in ("pulloff_force", "stiffness"):
                err = w["errors"][q]
                assert abs(err["error"]) <= err["tail_estimate"], (key, w["resolutions"], q)


def energy_check_problems(doc: dict) -> list[str]:
    """The energy BEM's procedure on Kendall's circle (F_A / F_A,upper exactly 1), once per
    sequence of process zones a face uses, recomputed from its stored sequence: the limit and bar
    are what ``bem_energy.richardson`` gives, the error is the limit less 1, and the bar covers it
    (else the faces' bars from the same procedure are not to be trusted).  The shared sequence is
    checked, and every face's sequence is one that was."""
    from bem_energy.zero_range import richardson

    checks = doc.get("energy_checks") or []
    if not checks:
        return ["no energy check on Kendall's circle"]
    out = []
    for check in checks:
        seq = check["sequence"]
        name = f"l_c/a to {seq['process_zone_ratios'][-1]:g}"
        F0, _, est = richardson(np.array(seq["process_zone_ratios"]), np.array(seq["forces_at_nominal_area"]))
        stored = (check["value"], check["estimate"])
        # the script fits this very sequence, so the refit repeats its arithmetic up to REFIT_RTOL; a
        # 1 % change of one range moves the limit by ~1e-3
        if not (
            math.isclose(F0, stored[0], rel_tol=REFIT_RTOL) and math.isclose(est / F0, stored[1], rel_tol=REFIT_RTOL)
        ):
            out.append(
                f"{name}: stored limit {stored[0]:.6g} +- {stored[1]:.3g}, "
                f"its sequence gives {F0:.6g} +- {est / F0:.3g}"
            )
        if not math.isclose(check["error"], check["value"] - 1.0, rel_tol=1e-9, abs_tol=1e-15):
            out.append(f"{name}: stored error {check['error']:.3g} is not the limit less 1")
        bar = check["relative_bar"] * abs(F0)
        if abs(F0 - 1.0) > bar:
            out.append(f"{name}: the bar {bar:.3g} does not cover the known error {F0 - 1:+.3g}")
        if check["covered"] is not (abs(F0 - 1.0) <= bar):
            out.append(f"{name}: the covered flag is wrong")
        if check.get("converged") is not True:
            out.append(f"{name}: not every run of the circle's sequence converged")
    checked = [c["sequence"]["process_zone_ratios"] for c in checks]
    if doc["energy_ratios"] not in checked:
        out.append("the shared sequence is not checked on the circle")
    for face, entry in doc["faces"].items():
        if entry["energy"] is not None:
            ratios = entry["energy"]["pulloff_force"]["sequence"]["process_zone_ratios"]
            if ratios not in checked:
                out.append(f"{face}: its energy sequence is not one checked on the circle")
            if ratios[: len(doc["energy_ratios"])] != doc["energy_ratios"]:
                out.append(f"{face}: its energy sequence does not continue the shared one")
    return out


def test_energy_procedure_check_on_kendall(table):
    from bem_energy.zero_range import richardson

    assert not energy_check_problems(table)
    for i in range(len(table["energy_checks"])):
        broken = copy.deepcopy(table)
        broken["energy_checks"][i]["sequence"]["forces_at_nominal_area"][-1] *= 0.99
        assert energy_check_problems(broken)
        broken = copy.deepcopy(table)
        broken["energy_checks"][i]["estimate"] /= 4
        assert energy_check_problems(broken)
        broken = copy.deepcopy(table)
        broken["energy_checks"][i]["relative_bar"] /= 4  # no longer covers the circle's known error
        assert energy_check_problems(broken)
    broken = copy.deepcopy(table)
    broken["energy_checks"] = broken["energy_checks"][:1]  # a face's finer sequence left unchecked
    longest = max(
        len(e["energy"]["pulloff_force"]["sequence"]["process_zone_ratios"])
        for e in table["faces"].values()
        if e["energy"]
    )
    assert bool(energy_check_problems(broken)) is (longest > len(table["energy_ratios"]))
    broken = copy.deepcopy(table)
    broken["faces"]["square"]["energy"]["pulloff_force"]["sequence"]["process_zone_ratios"][-1] /= 3
    assert energy_check_problems(broken)
    broken = copy.deepcopy(table)  # the shared sequence's check dropped
    broken["energy_checks"] = broken["energy_checks"][1:]
    assert energy_check_problems(broken)
    broken = copy.deepcopy(table)  # a face on a checked sequence that does not continue the shared one
    other = copy.deepcopy(broken["energy_checks"][0])
    other["sequence"]["process_zone_ratios"] = other["sequence"]["process_zone_ratios"][1:]
    other["sequence"]["forces_at_nominal_area"] = other["sequence"]["forces_at_nominal_area"][1:]
    F0, _, est = richardson(
        np.array(other["sequence"]["process_zone_ratios"]), np.array(other["sequence"]["forces_at_nominal_area"])
    )
    other.update(value=F0, estimate=est / F0, relative_bar=est / F0 * 1.5, error=F0 - 1.0)
    other["covered"] = abs(F0 - 1.0) <= other["relative_bar"] * abs(F0)
    broken["energy_checks"].append(other)
    assert energy_check_problems(broken) == []  # a check of its own is no problem while no face uses it
    seq = broken["faces"]["star"]["energy"]["pulloff_force"]["sequence"]
    seq["process_zone_ratios"] = other["sequence"]["process_zone_ratios"]
    assert energy_check_problems(broken) == ["star: its energy sequence does not continue the shared one"]
    broken = copy.deepcopy(table)
    broken["energy_checks"][-1]["converged"] = False
    assert energy_check_problems(broken)


def test_target_flags(table):
    """Whether each reference meets the bar issue #22 asks (0.3 %, 0.5 % for the star and two
    circles) is stated, and stated truly; an energy force bar whose path noise was not measured,
    or a Griffith bar whose sweep has not shown the order its tail estimate assumes, does not
    meet it."""
    for face, entry in table["faces"].items():
        for q, qe in entry["quantities"].items():
            if qe.get("reference"):
                within = qe["reference"]["relative_bar"] <= entry["target_bar"]
                if qe["reference"]["method"] == "bem_energy" and q == "pulloff_force":
                    within &= entry["energy"]["pulloff_force"]["path_noise"] is not None
                within &= qe["reference"].get("order_seen") is not False
                assert qe["within_target"] is within, (face, q)


def energy_bar_problems(doc: dict) -> list[str]:
    """Each energy force bar is the extrapolation's estimate plus the path noise where it was
    measured: the largest change of the limit over the stored step counts, recomputed."""
    out = []
    entries = [(face, e["energy"]["pulloff_force"]) for face, e in doc["faces"].items() if e["energy"]]
    entries += [("Kendall circle", check) for check in doc["energy_checks"]]
    for face, f in entries:
        noise = f["path_noise"]
        spread = 0.0
        if noise is not None:
            spread = max(abs(v - f["value"]) for v in noise["limits"].values()) / abs(f["value"])
            if not math.isclose(spread, noise["relative_spread"], rel_tol=1e-9):
                out.append(f"{face}: stored path noise {noise['relative_spread']:.3g}, its limits give {spread:.3g}")
        if not math.isclose(f["relative_bar"], f["estimate"] + spread, rel_tol=1e-9):
            out.append(
                f"{face}: bar {f['relative_bar']:.3g} is not the estimate {f['estimate']:.3g} + noise {spread:.3g}"
            )
    return out


def test_energy_bars_carry_the_path_noise(table):
    assert not energy_bar_problems(table)
    assert table["energy_checks"][0]["path_noise"] is not None  # measured where the answer is known
    broken = copy.deepcopy(table)
    for entry in broken["faces"].values():
        if entry["energy"] and entry["energy"]["pulloff_force"]["path_noise"]:
            entry["energy"]["pulloff_force"]["relative_bar"] = entry["energy"]["pulloff_force"]["estimate"]
            break
    assert energy_bar_problems(broken)


def test_square_is_rotation_invariant(table):
    assert not rotation_problems(table)
    broken = copy.deepcopy(table)
    ref = broken["faces"]["square_45"]["quantities"]["pulloff_force"]["bem_griffith"]
    ref["value"] *= 1 + 3 * ref["relative_bar"] + 0.01
    assert rotation_problems(broken)
    for m, flags in table["rotation_check"].items():  # a flag that says the opposite of its values
        broken = copy.deepcopy(table)
        broken["rotation_check"][m]["pulloff_force"]["agreement"] = not flags["pulloff_force"]["agreement"]
        assert rotation_problems(broken), m


def test_methods_agree_or_say_they_do_not(table):
    assert not agreement_problems(table)
    broken = copy.deepcopy(table)
    for entry in broken["faces"].values():
        qe = entry["quantities"]["pulloff_force"]
        if all(m in qe for m in METHODS):
            qe["bem_energy"]["value"] = qe["bem_griffith"]["value"] * 1.05
            break
    else:
        pytest.skip("no face has both methods")
    assert agreement_problems(broken)


@pytest.mark.slow
def test_square_sweep_reproduces_the_stored_points(table):
    """The two coarsest Griffith points of the square, re-run: the table is what the script computes."""
    script = _load_script()
    for criterion, sweep in table["faces"]["square"]["griffith"].items():
        for point in sweep["points"][:2]:
            row = script.griffith_point("square", criterion, point["N"])
            for q in QUANTITIES:
                # the Griffith solve reproduces to its CG tolerance's reach: 1.2e-9 between two
                # machines' BLAS/FFT builds (crossval regress)
                assert row["raw"][q] == pytest.approx(point["raw"][q], rel=1e-8, abs=0), (criterion, point["N"], q)
            assert row["face_area"] == pytest.approx(point["face_area"], rel=1e-12)


def rebuilt_problems(doc: dict, cache: Path) -> list[str]:
    """The table re-assembled from the runs it stores (``reference_table.py seed``, then the
    assembly ``write`` does) is the table: every value, bar and flag is what its runs give,
    so that a new part (a face's path noise) can be added without redoing the rest."""
    script = _load_script()
    script.seed(cache, doc)
    rebuilt = script.assemble(cache, doc["reference_criterion"], doc["energy_ratios"])
    out = []
    for face, entry in doc["faces"].items():
        for q, qe in entry["quantities"].items():
            again = rebuilt["faces"][face]["quantities"][q]
            for key, v in qe.items():
                w = again.get(key)
                if isinstance(v, dict) and "value" in v:
                    same = w is not None and all(
                        math.isclose(v[k], w[k], rel_tol=REFIT_RTOL) for k in ("value", "relative_bar")
                    )
                elif isinstance(v, float):
                    same = w is not None and math.isclose(v, w, rel_tol=REFIT_RTOL, abs_tol=1e-15)
                else:
                    same = v == w
                if not same:
                    out.append(f"{face} {q} {key}: stored {v!r}, its runs give {w!r}")
    if len(rebuilt["energy_checks"]) != len(doc["energy_checks"]):
        out.append(f"{len(doc['energy_checks'])} energy checks stored, its runs give {len(rebuilt['energy_checks'])}")
    for check, again in zip(doc["energy_checks"], rebuilt["energy_checks"], strict=False):
        for k in ("value", "relative_bar", "covered"):
            if check[k] != pytest.approx(again[k], rel=REFIT_RTOL):
                out.append(f"energy check {k}: stored {check[k]!r}, its runs give {again[k]!r}")
    return out


def test_table_is_its_own_cache(table, tmp_path):
    energy = [e["energy"] for e in table["faces"].values() if e["energy"]] + table["energy_checks"]
    if not all("runs" in e for e in energy):
        pytest.fail("faces.json does not store the energy runs it was assembled from")
    assert not rebuilt_problems(table, tmp_path / "cache")
    broken = copy.deepcopy(table)
    broken["faces"]["star"]["energy"]["runs"][-1]["pulloff_force"] *= 1.005
    assert rebuilt_problems(broken, tmp_path / "broken_energy")
    broken = copy.deepcopy(table)
    broken["faces"]["square"]["griffith"]["paper"]["points"][-1]["normalised"]["pulloff_force"] *= 1.005
    assert rebuilt_problems(broken, tmp_path / "broken_griffith")
    broken = copy.deepcopy(table)  # a path-noise run reaches the face's bar
    noisy = next(
        e["energy"]["pulloff_force"]
        for e in broken["faces"].values()
        if e["energy"] and e["energy"]["pulloff_force"]["path_noise"]
    )
    next(iter(noisy["path_noise"]["runs"].values()))[-1]["pulloff_force"] *= 1.01
    assert rebuilt_problems(broken, tmp_path / "broken_noise")


def test_a_finer_range_joins_a_face_only_with_its_check_and_its_noise(tmp_path):
    """A face's zero-range sequence continues past the shared one by a halving only when the cache
    holds converged runs of that range for the face and for Kendall's circle, each at the default
    step count and at every step count its own path noise was measured with: a window the circle
    has not checked, or a limit or check whose noise would go unmeasured, stays out."""
    script = _load_script()
    shared = (0.08, 0.04, 0.02, 0.01, 0.005)
    zone = script.ZeroRangeSettings().elements_per_process_zone

    def run(face, r, steps=None, converged=True):
        path = script.cache_file(tmp_path, face, "energy", r, zone, *([f"steps{steps}"] if steps else []))
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps({"converged": converged}))

    for face in ("square", script.CHECK):
        for r in shared:
            run(face, r)
            run(face, r, 36)
    for r in shared:
        run(script.CHECK, r, 44)  # the circle's noise also at a step count the square lacks
    assert script.energy_sequence("square", tmp_path, shared) == shared
    run("square", 0.0025)
    run("square", 0.0025, 36)
    assert script.energy_sequence("square", tmp_path, shared) == shared  # the circle has not run it
    run(script.CHECK, 0.0025)
    run(script.CHECK, 0.0025, 36)
    assert script.energy_sequence("square", tmp_path, shared) == shared  # nor its own 44-step noise
    run(script.CHECK, 0.0025, 44, converged=False)
    assert script.energy_sequence("square", tmp_path, shared) == shared  # which did not converge
    run(script.CHECK, 0.0025, 44)
    assert script.energy_sequence("square", tmp_path, shared) == (*shared, 0.0025)
    run("square", 0.0025, converged=False)
    assert script.energy_sequence("square", tmp_path, shared) == shared  # the face's own run unconverged
    run("square", 0.0025)
    for steps in (None, 36, 44):
        run(script.CHECK, 0.00125, steps)
    run("square", 0.00125, 36)
    assert script.energy_sequence("square", tmp_path, shared) == (*shared, 0.0025)  # noise alone is not a range
    run("square", 0.00125)
    assert script.energy_sequence("square", tmp_path, shared) == (*shared, 0.0025, 0.00125)  # two halvings
    for r in (0.02, 0.01, 0.005, 0.0025):
        run("triangle", r)
    assert script.energy_sequence("triangle", tmp_path, (0.02, 0.01, 0.005)) == (0.02, 0.01, 0.005, 0.0025)
    for r in shared:
        run("triangle", r, 44)
    assert script.energy_sequence("triangle", tmp_path, shared) == shared  # its noise at 0.0025 missing


def test_points_decided_by_the_nucleation_cap_stay_out_of_the_fit(tmp_path):
    """A point flagged ``decided_by_cap`` (Eq. 22's pull-off at the energy-release rule's cap, not
    the criterion's) does not enter the limit, and a sweep it leaves short of four grids is
    reported as such, with its runs kept for ``seed``: synthetic sweeps q = q0 + c / N."""
    script = _load_script()
    grids = (32, 45, 64, 90, 128)

    def put(face, N, q0, capped=False):
        q = {k: q0 + 0.2 / N for k in QUANTITIES}
        row = {"face": face, "criterion": "energy_release", "N": N, "raw": q, "face_area": 1.0, "normalised": q}
        row |= {"converged": True, "messages": [], "decided_by_cap": capped}
        script.cache_file(tmp_path, face, "griffith", "energy_release", N).write_text(json.dumps(row))

    for N in grids:
        put(script.CHECK, N, 1.0)
        put("square", N, 0.88 if N > 32 else 0.95, capped=N == 32)  # the capped point is off the line
        put("star", N, 0.77, capped=N < 64)
    doc = script.assemble(tmp_path, "energy_release")
    square = doc["faces"]["square"]["griffith"]["energy_release"]
    assert square["excluded"] == [32] and square["resolutions"] == [45, 64, 90, 128]
    assert square["quantities"]["pulloff_force"]["value"] == pytest.approx(0.88, rel=1e-12)
    assert [p["decided_by_cap"] for p in square["points"]] == [True, False, False, False, False]
    star = doc["faces"]["star"]
    assert "energy_release" not in star["griffith"]
    assert "N = 32, 45 was Eq. 22's at the nucleation cap" in star["not_computed"]["why"]
    assert star["not_computed"]["why"].count("bem_griffith (energy_release)") == 1  # not also "did not finish"
    assert [r["N"] for r in star["capped_sweeps"]["energy_release"]] == list(grids)
    script.seed(tmp_path / "seeded", doc)
    seeded = script.load_sweep(tmp_path / "seeded", "star", "energy_release")
    stored = star["capped_sweeps"]["energy_release"]
    assert [{k: v for k, v in r.items() if k != "seeded_from"} for r in seeded] == stored
    # and without the flag the off-line point would have moved the limit
    for N in grids:
        put("square", N, 0.88 if N > 32 else 0.95)
    moved = script.assemble(tmp_path, "energy_release")["faces"]["square"]["griffith"]["energy_release"]
    assert abs(moved["quantities"]["pulloff_force"]["model_spread"]) > 1e-3
