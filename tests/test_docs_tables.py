"""Measured numbers in the docs are generated, not typed.

A table between ``<!-- table: name -->`` and ``<!-- end table -->`` is what
``benchmarks/docs_tables.py`` renders from ``docs/<name>.json``, the output of the benchmark
named in it: a re-run changes it, a hand edit makes it differ from its JSON and fails here.
The accuracy and speed pages carry no measured percentage or timing outside such tables, so a
number cannot go stale in the prose while its table moves on.
"""

from __future__ import annotations

import importlib.util
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
REQUIRED_KEYS = ("headers", "rows", "written_by", "date", "machine", "revision")
MEASURED_PAGES = ("accuracy.md", "performance.md")


def _load_docs_tables():
    spec = importlib.util.spec_from_file_location("docs_tables", ROOT / "benchmarks" / "docs_tables.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


docs_tables = _load_docs_tables()
BLOCKS = [
    pytest.param(page.name, m, id=f"{page.name}:{m.group('name')}")
    for page in sorted(DOCS.glob("*.md"))
    for m in docs_tables.BLOCK.finditer(page.read_text())
]


@pytest.mark.parametrize(("page", "block"), BLOCKS)
def test_table_has_its_benchmark_json(page, block):
    source = DOCS / f"{block.group('name')}.json"
    assert source.exists(), f"{page} shows table {block.group('name')}, but no benchmark wrote {source.name}"
    doc = json.loads(source.read_text())
    missing = [k for k in REQUIRED_KEYS if k not in doc]
    assert not missing, f"{source.name} lacks {missing}"
    assert doc["rows"], f"{source.name} has no rows"
    assert all(len(row) == len(doc["headers"]) for row in doc["rows"]), f"{source.name}: ragged rows"
    script = re.search(r"benchmarks/\w+\.py", doc["written_by"])
    assert script and (ROOT / script.group(0)).exists(), f"{source.name}: written_by names no benchmark script"


@pytest.mark.parametrize(("page", "block"), BLOCKS)
def test_table_is_rendered_from_its_json(page, block):
    doc = json.loads((DOCS / f"{block.group('name')}.json").read_text())
    expected = block.group(1) + docs_tables.render(doc) + block.group(3)
    assert block.group(0) == expected, (
        f"{page}: table {block.group('name')} differs from docs/{block.group('name')}.json; "
        "re-run its benchmark with --update and `python benchmarks/docs_tables.py`, never edit it"
    )


# What counts as a measurement in prose: a percentage, a time, a speed-up factor, a memory size.
MEASURED = re.compile(
    r"\d\s*%"  # 0.5 %, 12%
    r"|\b\d+(?:[.,]\d+)*\s*(?:s|ms|min|h|seconds?|minutes?|hours?)\b"  # 424 s, 13 min
    r"|\b\d+(?:\.\d+)?x\b"  # 2.3x
    r"|\b\d+(?:\.\d+)?\s*[GM]B\b"  # 0.42 GB
)
# Closed-form facts and tolerances quoted in prose that the pattern would flag, each with why it
# is not a measurement.  Keep this short: a tolerance reads better as a code span (`... <= 0.01`).
ALLOWED: dict[str, str] = {}


def prose(text: str) -> str:
    """The page without generated tables, fenced code, inline code and math."""
    text = docs_tables.BLOCK.sub("", text)
    text = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)
    text = re.sub(r"`[^`\n]*`", "", text)
    text = re.sub(r"\$\$.*?\$\$|\$[^$\n]+\$", "", text, flags=re.S)
    return text


def measured_in_prose(text: str) -> list[str]:
    found = []
    for m in MEASURED.finditer(prose(text)):
        context = prose(text)[max(0, m.start() - 40) : m.end() + 10].replace("\n", " ")
        if not any(allowed in context for allowed in ALLOWED):
            found.append(context)
    return found


@pytest.mark.parametrize("page", MEASURED_PAGES)
def test_no_measured_number_outside_tables(page):
    found = measured_in_prose((DOCS / page).read_text())
    assert not found, f"{page} quotes measurements outside generated tables:\n" + "\n".join(found)


def test_the_prose_check_sees_what_it_must():
    # a measurement in prose is found; the same text inside a table block, a code span or an
    # equation is not
    assert measured_in_prose("The pull-off took 424 s and was +0.54 % off, 2.3x slower, 0.42 GB.")
    assert len(measured_in_prose("took 424 s; +0.54 %; 2.3x; 0.42 GB")) == 4
    assert not measured_in_prose("<!-- table: x -->\n| 424 s | 0.5 % |\n<!-- end table -->\n")
    assert not measured_in_prose("tested: `|F_A/F_K - 1| <= 1 %`, $e < 1\\%$")
    assert not measured_in_prose("at 32 elements per radius, k = 0.5, Eq. 13, 1.021, 0.5/N, 2 cores")


def test_a_hand_edited_table_differs_from_its_rendering():
    doc = {"headers": ["N", "err"], "rows": [[16, "+0.5"]], "written_by": "python benchmarks/x.py"}
    doc |= {"date": "d", "machine": {"cpus": 2}, "revision": "r"}
    block = "<!-- table: t -->\n" + docs_tables.render(doc) + "<!-- end table -->"
    m = docs_tables.BLOCK.search(block)
    assert m.group(0) == m.group(1) + docs_tables.render(doc) + m.group(3)
    edited = docs_tables.BLOCK.search(block.replace("+0.5", "+0.4"))
    assert edited.group(0) != edited.group(1) + docs_tables.render(doc) + edited.group(3)
