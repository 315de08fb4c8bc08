"""The version has one source (pyproject.toml, read at run time from the package metadata);
CITATION.cff repeats it for citation tools, so it must not drift."""

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_citation_version_matches_the_package():
    version = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    cff = re.search(r"^version:\s*(\S+)\s*$", (ROOT / "CITATION.cff").read_text(), re.M)
    assert cff is not None, "CITATION.cff has no version line"
    assert cff.group(1).strip("\"'") == version


def test_the_cli_reports_the_installed_version():
    from crossval.cache import package_version

    version = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]
    assert package_version() == version
