"""The mutation study's catalogue (benchmarks/mutation_study.py) still applies to the code: each
mutant's text occurs in its file exactly as often as the catalogue says.  A rewritten line
would otherwise leave a mutant that can no longer be injected, and docs/mutation_study.md
would describe a check nobody can re-run."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _catalogue():
    spec = importlib.util.spec_from_file_location("mutation_study", ROOT / "benchmarks" / "mutation_study.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules.setdefault(spec.name, module)  # its dataclasses look their module up
    spec.loader.exec_module(module)
    return module.MUTANTS


@pytest.mark.parametrize("mutant", _catalogue(), ids=lambda m: m.id)
def test_each_mutant_still_applies(mutant):
    text = (ROOT / mutant.file).read_text()
    assert text.count(mutant.old) == mutant.count, (mutant.file, mutant.old)
    assert mutant.old != mutant.new
