import sys
from pathlib import Path

import pytest

# examples/ are importable scripts (documentation that is tested)
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
pytest_plugins = ["pytester"]


@pytest.fixture
def count_calls(monkeypatch):
    """``count_calls(owner, *names)``: wrap the methods ``names`` of class ``owner`` for the
    test, counting each call; returns the live counts, {name: calls}.  The mirrored-transform
    tests use it to see which path the products took."""

    def count(owner, *names):
        calls = dict.fromkeys(names, 0)
        for name in names:
            original = getattr(owner, name)

            def wrapper(self, *args, _name=name, _original=original, **kwargs):
                calls[_name] += 1
                return _original(self, *args, **kwargs)

            monkeypatch.setattr(owner, name, wrapper)
        return calls

    return count
