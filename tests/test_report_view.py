"""The report as a reader sees it: every figure is a real image, the page renders in a browser,
results.json is strict JSON, and a convergence order is printed only where a fit means one."""

import base64
import html
import io
import json
import math
import re
import shutil
import struct
import subprocess
import tempfile
from html.parser import HTMLParser
from pathlib import Path

import matplotlib.colors
import matplotlib.image
import numpy as np
import pytest

import crossval
from crossval.study import convergence, extrapolate_first_order

ROOT = Path(__file__).resolve().parents[1]

SCENES = ["kendall_circle", "square"]
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def rendered(tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    rep = crossval.report(out, quick=True, cache_dir=None, scenes=SCENES)
    return rep, out


class _Images(HTMLParser):
    def __init__(self):
        super().__init__()
        self.srcs = []

    def handle_starttag(self, tag, attrs):
        if tag == "img":
            self.srcs.append(dict(attrs).get("src", ""))


def _png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == PNG_MAGIC, "not a PNG"
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def _strict_json(text):
    def refuse(token):
        raise ValueError(f"not valid JSON: bare {token}")

    return json.loads(text, parse_constant=refuse)


def test_every_image_is_an_embedded_png_of_nonzero_size(rendered):
    _, out = rendered
    parser = _Images()
    parser.feed((out / "index.html").read_text())
    # the agreement map and one figure per scene
    assert len(parser.srcs) == 1 + len(SCENES)
    for src in parser.srcs:
        head, _, payload = src.partition(",")
        assert head == "data:image/png;base64" and payload
        data = base64.b64decode(payload, validate=True)
        w, h = _png_size(data)
        assert w > 100 and h > 100
        # the whole image decodes (a truncated stream keeps a valid header)
        pixels = matplotlib.image.imread(io.BytesIO(data), format="png")
        assert pixels.shape[:2] == (h, w) and pixels.std() > 0


def test_results_json_is_strict_and_never_measures_a_solver_against_its_own_finest_grid(rendered):
    _, out = rendered
    data = _strict_json((out / "results.json").read_text())
    kendall, square = data["scenes"]["kendall_circle"], data["scenes"]["square"]
    assert kendall["reference"]["name"].startswith("Kendall")
    # the square has no closed form and no FEM: its finest Griffith run must have a measured,
    # non-zero error (against the Griffith solver's own finest grid it would be exactly 0)
    finest = max(r["resolution"] for r in square["runs"] if r["method"] == "bem_griffith")
    (run,) = [r for r in square["runs"] if r["method"] == "bem_griffith" and r["resolution"] == finest]
    assert run["error"] is not None and run["error"] > 0
    # its reference is the reference table's converged value, with the table's bar
    assert square["reference"]["kind"] == "table"
    assert square["reference"]["uncertainty"] is not None and square["reference"]["uncertainty"] > 0
    for scene in data["scenes"].values():
        for m, c in scene["convergence"].items():
            assert (c["kind"] == "order") == (scene["rates"][m] is not None)


def test_the_page_prints_no_rate_the_errors_do_not_support(rendered):
    _, out = rendered
    page = (out / "index.html").read_text()
    data = _strict_json((out / "results.json").read_text())
    # a first- or second-order method: a fitted order outside (0, 5) is a fit through noise
    orders = [float(v) for v in re.findall(r"order (-?\d+(?:\.\d+)?)", page)]
    orders += [v for sc in data["scenes"].values() for v in sc["rates"].values() if v is not None]
    assert all(0 < v < 5 for v in orders), orders
    assert "time^--" not in page


def test_blank_cells_of_the_agreement_map_are_explained(rendered):
    rep, out = rendered
    page = html.unescape((out / "index.html").read_text())
    assert "Hatched cells have no value" in page and "'n/a' = method does not apply" in page
    from crossval.methods import METHODS
    from crossval.report import _agreement_row

    st = rep.studies["square"]
    fin = {
        m: st.results[(m, max(r.resolution for r in st.rows if r.method == m))]
        for m in dict.fromkeys(r.method for r in st.rows)
    }
    row, notes = _agreement_row(st.scene, st, fin, rep.checks["square"], list(METHODS))
    j = list(METHODS).index("fem_reference")
    assert math.isnan(row[j]) and notes[j] == "n/a"
    # measured against the reference table, not against its own extrapolated sequence
    assert "own extrap." not in notes[list(METHODS).index("bem_griffith")]
    # the table's square force is the energy BEM's own converged value: its cell says so, so that
    # its convergence error is not read as a disagreement between methods
    assert "own table value" in notes[list(METHODS).index("bem_energy")]
    assert "own table value" not in notes[list(METHODS).index("bem_griffith")]
    # a run without a force bar was held to nothing: its cell says so, whatever its colour
    for m, r in fin.items():
        j = list(METHODS).index(m)
        if not math.isnan(row[j]):
            assert ("no bar" in notes[j]) == (r.error_bars.get("pulloff_force") is None), (m, notes[j])
    assert "no bar" in notes[list(METHODS).index("bem_energy")]  # its quick sequence claims no force bar
    assert "'no bar'" in page


@pytest.mark.skipif(shutil.which("chromium") is None, reason="chromium is not installed")
def test_page_renders_in_headless_chromium_with_every_figure_loaded(rendered):
    _, out = rendered
    # an inline script writes each image's natural size into the DOM once the page has loaded
    probe = out / "probe.html"
    probe.write_text(
        (out / "index.html").read_text()
        + (
            "<script>window.addEventListener('load', () => {const p = document.createElement('pre');"
            "p.id = 'sizes'; p.textContent = JSON.stringify([...document.images].map("
            "i => [i.complete, i.naturalWidth, i.naturalHeight, i.getBoundingClientRect().right,"
            " document.documentElement.clientWidth])); document.body.appendChild(p);});</script>"
        )
    )
    with tempfile.TemporaryDirectory() as profile:
        r = subprocess.run(
            [
                "chromium",
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--disable-quic",
                "--no-first-run",
                "--disable-background-networking",
                "--disable-component-update",
                "--disable-sync",
                f"--user-data-dir={profile}",
                "--window-size=1000,800",
                "--virtual-time-budget=5000",
                "--dump-dom",
                probe.as_uri(),
            ],
            capture_output=True,
            text=True,
            timeout=120,
        )
    assert r.returncode == 0, r.stderr[-2000:]
    start = r.stdout.index('<pre id="sizes">') + len('<pre id="sizes">')
    sizes = json.loads(r.stdout[start : r.stdout.index("</pre>", start)])
    assert len(sizes) == 1 + len(SCENES)
    for complete, w, h, right, page_width in sizes:
        assert complete and w > 100 and h > 100
        # scaled to the page, not cut off at the window's edge (legends sit at the right)
        assert right <= page_width + 1


# --- the rate logic -----------------------------------------------------------------------

N = np.array([8, 12, 16, 24, 32])


def test_a_clean_first_order_sequence_gets_order_one():
    c = convergence(N, 0.4 / N * (1 + 0.3 / N))
    assert c.kind == "order" and abs(c.order - 1) < 0.05


def test_a_zig_zag_gets_an_envelope_not_a_rate():
    e = 0.3 / N * np.array([1, -0.4, 0.9, 0.2, -0.7])  # the staircase's sign changes
    c = convergence(N, e)
    assert c.kind == "envelope" and math.isnan(c.order)
    assert c.constant == pytest.approx(0.3) and "zig-zag" in c.text
    # unsigned, but not monotone either
    assert convergence(N, np.abs(e)).kind == "envelope"


def test_an_error_rising_with_resolution_gets_no_order():
    assert convergence([8, 12, 16], [0.001, 0.004, 0.01]).kind == "envelope"


def test_two_resolutions_are_not_a_rate():
    c = convergence([0.5, 2 / 3], [3e-5, 1e-8])
    assert c.kind == "envelope" and "needs 3" in c.text


def test_one_resolution_claims_neither_a_rate_nor_an_envelope():
    # c/N through a single run is that run's error times N: it bounds nothing
    c = convergence([1.0], [0.0788])
    assert c.kind == "none" and "c/N" not in c.text and "one resolution" in c.text


def test_errors_partly_inside_the_reference_bar_say_which():
    # only the finer two runs are unresolved; the coarsest (2.2 %) is not
    c = convergence([16, 24, 32], [0.022, 0.005, 0.003], floor=0.0074)
    assert c.kind == "envelope" and "N = 24, 32" in c.text and "16" not in c.reason


def test_a_collapse_through_zero_is_not_a_high_order():
    # |error| falls monotonically but the last point sits next to a sign change: a line
    # through three points with a collapsing end is not a power law
    assert convergence([8, 12, 16], [0.02, 0.015, 1e-4]).kind == "envelope"


def test_errors_inside_the_reference_error_bar_give_no_rate():
    c = convergence(N, 0.4 / N, floor=0.02)
    assert c.kind != "order"


def test_first_order_extrapolation_recovers_the_limit_and_bounds_its_error():
    lim, err = extrapolate_first_order(N, 2.0 + 0.5 / N)
    assert lim == pytest.approx(2.0, abs=1e-12) and err < 1e-12
    wiggly = 2.0 + 0.5 / N + 0.01 * np.array([1, -1, 1, -1, 1])
    lim, err = extrapolate_first_order(N, wiggly)
    assert abs(lim - 2.0) <= err and err > 0.005


def _windows(N, values):
    return [(N[i : i + 3], values[i : i + 3]) for i in range(len(N) - 2)]


def test_a_griffith_sequence_bar_covers_the_limits_error_where_the_answer_is_known():
    """``sequence_bar`` on the measured sweeps: Kendall's circle from 16 to 510 per radius
    (docs/accuracy_griffith_circle.json, forces at the raster's area) in every window of three
    grids, and the reference table's six faces over 32 ... 128 per radius (their stored
    Griffith points) against the energy BEM's converged value within its bar.  The
    leave-one-out spread alone fails on the circle (the staircase's zig-zag), the mutant."""
    from crossval.study import sequence_bar

    circle = json.loads((ROOT / "docs" / "accuracy_griffith_circle.json").read_text())
    N = np.array([r[0] for r in circle["rows"]], float)
    F = 1.0 + np.array([float(r[2]) for r in circle["rows"]])
    spread_alone_fails = 0
    for ns, vs in _windows(N, F):
        lim, spread = extrapolate_first_order(ns, vs)
        assert abs(lim - 1.0) <= sequence_bar(ns, vs, lim, spread), ns
        spread_alone_fails += abs(lim - 1.0) > spread
    assert spread_alone_fails >= 3
    faces = json.loads((ROOT / "crossval" / "references" / "faces.json").read_text())["faces"]
    for name, face in faces.items():
        points = face["griffith"]["paper"]["points"]
        N = np.array([p["N"] for p in points], float)
        F = np.array([p["normalised"]["pulloff_force"] for p in points])
        energy = face["quantities"]["pulloff_force"]["bem_energy"]
        for ns, vs in _windows(N, F):
            lim, spread = extrapolate_first_order(ns, vs)
            gap = abs(lim - energy["value"])
            assert gap <= sequence_bar(ns, vs, lim, spread) + energy["relative_bar"] * energy["value"], (name, ns)


def test_without_a_closed_form_a_circle_is_measured_against_the_fem(monkeypatch):
    """The FEM covers the circle: it is the reference (its estimate the error bar), its own
    runs are not measured, and the Griffith runs are measured against it."""
    import sys

    from crossval.suite import SUITE

    study_module = sys.modules["crossval.study"]  # the package's ``study`` is the function

    monkeypatch.setattr(study_module, "reference_values", lambda scene: {})
    st = study_module.study(
        SUITE["incompressible_circle"],
        methods=["bem_griffith", "fem_reference"],
        resolutions={"bem_griffith": (8, 12, 16), "fem_reference": (0.5,)},
    )
    ref = st.reference_info
    assert ref.kind == "bounded" and ref.own_method == "fem_reference" and 0 < ref.uncertainty < 1e-3
    fem = st.results[("fem_reference", 0.5)]
    assert st.reference == fem.pulloff_force
    assert all(math.isnan(r.error) for r in st.rows if r.method == "fem_reference")
    assert st.convergence["fem_reference"].kind == "none"
    # the FEM agrees with Kendall to 1e-5 (README), so the Griffith errors are Kendall's within that
    from crossval.compare import reference_values

    F_K = reference_values(SUITE["incompressible_circle"])["pulloff_force"]
    for r in st.rows:
        if r.method == "bem_griffith":
            assert r.error == pytest.approx(abs(r.value / F_K - 1), abs=1e-4)


def _labelled_ticks(axis):
    lo, hi = sorted(axis.get_view_interval())
    return [
        t.label1.get_text()
        for t in axis.get_major_ticks() + axis.get_minor_ticks()
        if t.label1.get_visible() and t.label1.get_text() and lo <= t.get_loc() <= hi
    ]


def _panel(rows, *, notes=None, scene="kendall_circle"):
    """The error panel of ``rows`` against a closed-form reference of 1, drawn."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from crossval import plotting
    from crossval.study import ErrorReference, Study
    from crossval.suite import SUITE

    ref = ErrorReference(1.0, "Kendall", "closed form")
    st = Study(SUITE[scene], "pulloff_force", 1.0, ref.name, tuple(rows), reference_info=ref)
    fig, ax = plt.subplots(layout="constrained")
    assert plotting.plot_error_vs_time(st, ax, notes=notes) is ax
    fig.canvas.draw()
    return fig, ax


def _markers(ax):
    """(x, y, marker) of each run's marker: the one-point lines the panel draws per run."""
    return [
        (float(line.get_xdata()[0]), float(line.get_ydata()[0]), line.get_marker())
        for line in ax.lines
        if len(line.get_xdata()) == 1
    ]


def _legend_texts(ax):
    # entries are wrapped to fit beside the panel: compare their words, not their line breaks
    return [" ".join(t.get_text().split()) for t in ax.get_legend().get_texts()]


@pytest.mark.parametrize("times", [(0.03, 0.05, 0.2), (0.6, 1.4, 3.0)])
def test_error_panel_labels_its_axes_and_its_legend_hides_no_point(times):
    """Errors within one decade (a few per cent) still get numbers on both axes, and the
    legend sits outside the data; short runs and long ones are both placed at their wall
    time (one axis in every panel), each with its resolution written beside it."""
    import matplotlib.pyplot as plt

    from crossval.study import StudyRow

    rows = [
        StudyRow("bem_griffith", n, t, 1 + e, e, e)
        for n, t, e in zip((8, 12, 16), times, (0.03, 0.02, 0.012), strict=True)
    ]
    fig, ax = _panel(rows)
    assert len(_labelled_ticks(ax.yaxis)) >= 2 and len(_labelled_ticks(ax.xaxis)) >= 2
    assert ax.get_xlabel().startswith("wall time")
    assert sorted(x for x, _, _ in _markers(ax)) == pytest.approx(times)
    written = {t.get_text() for t in ax.texts}
    assert {"8", "12", "16"} <= written, written
    legend = ax.get_legend().get_window_extent()
    points = ax.transData.transform([(line.get_xdata()[0], line.get_ydata()[0]) for line in ax.lines])
    assert not any(legend.contains(x, y) for x, y in points)
    assert not legend.overlaps(ax.get_window_extent())
    # short runs are not moved to another axis: the panel marks their timings as noise
    noise = [t for t in _legend_texts(ax) if "timings are noise" in t]
    assert bool(noise) == (min(times) < 0.5), _legend_texts(ax)
    plt.close(fig)


def test_error_panel_never_shares_a_resolution_axis_between_methods():
    """Elements per radius, elements per process zone and 1/grading are different measures: each
    method's runs sit at their wall times, never at their resolutions, and the legend names what
    the number beside each run of that method counts."""
    import matplotlib.pyplot as plt

    from crossval.study import StudyRow

    runs = {
        "bem_griffith": [(16, 0.06, 0.02), (24, 0.1, 0.001), (32, 0.09, 0.005)],
        "bem_energy": [(1, 0.6, 0.014), (2, 2.5, 0.008)],
        "fem_reference": [(0.5, 1.6, 6e-6), (1, 3.2, 3e-6)],
    }
    rows = [StudyRow(m, n, t, 1 + e, e, e) for m, rs in runs.items() for n, t, e in rs]
    fig, ax = _panel(rows)
    assert sorted(x for x, _, _ in _markers(ax)) == pytest.approx(sorted(t for rs in runs.values() for _, t, _ in rs))
    assert "resolution" not in ax.get_xlabel().split(";")[0]
    # each run's resolution is written in its method's colour beside it
    from crossval.plotting import METHOD_COLOURS

    written = {(t.get_text(), t.get_color()) for t in ax.texts}
    for m, rs in runs.items():
        colour = matplotlib.colors.to_rgba(METHOD_COLOURS[m])
        for n, _, _ in rs:
            assert any(text == f"{n:g}" and matplotlib.colors.to_rgba(c) == colour for text, c in written), (m, n)
    legend = _legend_texts(ax)
    for m, unit in (
        ("bem_griffith", "elements/radius"),
        ("bem_energy", "elements/process zone"),
        ("fem_reference", "1/grading"),
    ):
        assert any(t.startswith(m) and f"beside each run: {unit}" in t for t in legend), (m, legend)
    # the Griffith runs' times do not grow with their resolution: its entry says the times are noise
    (griffith,) = [t for t in legend if t.startswith("bem_griffith")]
    assert "does not grow with resolution" in griffith
    assert not any("does not grow" in t for t in legend if not t.startswith("bem_griffith"))
    plt.close(fig)


def test_error_panel_shows_on_which_side_of_the_reference_each_run_lies():
    """The axis is the error's magnitude; a run below the reference points down, one above
    points up, so that errors crossing zero (a dip on the log axis) are told apart from
    errors that fall."""
    import matplotlib.pyplot as plt

    from crossval.study import StudyRow

    signed = (0.03, -0.002, 0.004)
    times = (0.1, 0.2, 0.4)
    rows = [
        StudyRow("bem_griffith", n, t, 1 + e, abs(e), e) for n, t, e in zip((8, 12, 16), times, signed, strict=True)
    ]
    fig, ax = _panel(rows, notes={"bem_griffith": "calibration residual"})
    drawn = {x: marker for x, _, marker in _markers(ax)}
    assert drawn == {0.1: "^", 0.2: "v", 0.4: "^"}
    legend = _legend_texts(ax)
    assert {"above the reference", "below the reference"} <= set(legend)
    assert any(t.startswith("bem_griffith") and t.endswith("; calibration residual") for t in legend), legend
    plt.close(fig)


def test_page_explains_the_error_panels_axis_and_labels(rendered):
    """The reader is told once what the panels' axis is and what the numbers beside runs mean."""
    from crossval.report import ERROR_PANEL_CAPTION

    _, out = rendered
    page = html.unescape((out / "index.html").read_text())
    assert ERROR_PANEL_CAPTION in page
    for words in ("wall time", "elements per radius", "elements per process zone", "1/grading", "hatched"):
        assert words in ERROR_PANEL_CAPTION


def test_scene_tables_name_each_reference_value_and_show_no_pull_off_for_a_press(rendered):
    """A value from the reference table is named as such (a converged number with a bar, not a
    closed form beside the bounds), and a same-grid run without adhesion shows no pull-off."""
    _, out = rendered
    page = html.unescape((out / "index.html").read_text())
    square = page[page.index("id='square'") :]
    square = square[: square.index("<img")]
    assert re.search(r"<td>pulloff_force</td><td>[\d.]+ ± [\d.]+%</td><td>reference table, square: bem_", square)
    assert "<td>upper_force</td>" in square and "bounds (Eqs. 13, 18)" in square
    presses = re.findall(r"<tr><td>[^<]*\(w = 0\)</td>.*?</tr>", square)
    assert presses and all("<td>- (w = 0)</td><td>-</td>" in row for row in presses)


def test_values_without_a_check_are_listed_not_passed_over():
    # the quick report checks the energy BEM's stiffness on the square but not its F_A (its
    # coarse sequence gives no bar): "all checks passed" must not read as covering it
    from types import SimpleNamespace

    from crossval.report import unchecked_values

    finest = {
        "bem_griffith": SimpleNamespace(pulloff_force=5.29, pulloff_approach=-2.5, stiffness=2.26),
        "bem_energy": SimpleNamespace(pulloff_force=5.70, pulloff_approach=-2.4, stiffness=2.27),
        "bem_energy on bem_griffith's grid (w = 0)": SimpleNamespace(pulloff_force=0.0, stiffness=2.26),
    }
    checks = [
        SimpleNamespace(method="bem_griffith", quantity="pulloff_force"),
        SimpleNamespace(method="bem_griffith", quantity="stiffness"),
        SimpleNamespace(method="bem_energy", quantity="stiffness"),
        SimpleNamespace(method="bem_energy", quantity="pulloff_force bracket"),
    ]
    theory = {"pulloff_force": 5.29, "pulloff_approach": -2.39, "stiffness": 2.30, "upper_force": 6.0}
    assert unchecked_values(finest, checks, theory) == [
        ("bem_griffith", "pulloff_approach"),
        ("bem_energy", "pulloff_approach"),
    ]
    # no reference for a quantity: nothing to check it against, so not listed
    assert unchecked_values(finest, checks[:3], {"stiffness": 2.3}) == []
    assert ("bem_energy", "pulloff_force") in unchecked_values(finest, checks[:3], theory)
