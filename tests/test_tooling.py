"""The contributor's tooling agrees with the project: pre-commit's ruff is the pinned ruff, its local hooks
run the commands the project runs, mypy is configured, pinned and run by CI, and CONTRIBUTING.md names
files and commands that exist."""
from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

tomllib = pytest.importorskip("tomllib")  # Python >= 3.11

ROOT = Path(__file__).resolve().parents[1]


def pins() -> dict[str, str]:
    lines = (ROOT / "constraints.txt").read_text().splitlines()
    return {a.lower(): b for a, _, b in (line.partition("==") for line in lines if "==" in line)}


def test_pre_commit_runs_the_pinned_ruff_snakemake_lint_and_mypy():
    config = yaml.safe_load((ROOT / ".pre-commit-config.yaml").read_text())
    ruff = next(r for r in config["repos"] if "ruff-pre-commit" in r["repo"])
    assert ruff["rev"] == f"v{pins()['ruff']}"
    local = {hook["id"]: hook for r in config["repos"] if r["repo"] == "local" for hook in r["hooks"]}
    assert "snakemake --lint" in local["snakemake-lint"]["entry"]
    assert local["mypy"]["entry"] == "python -m mypy"


def test_mypy_is_pinned_configured_and_run_by_ci():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())
    assert any(dep.startswith("mypy") for dep in project["project"]["optional-dependencies"]["test"])
    assert "mypy" in pins()
    assert {Path(f).name for f in project["tool"]["mypy"]["files"]} == {"core", "model", "analysis"}
    assert "python -m mypy" in (ROOT / ".ci" / "run").read_text()


def test_contributing_names_what_exists():
    text = (ROOT / "CONTRIBUTING.md").read_text()
    for path in re.findall(r"(?<![\w/])((?:tests|benchmarks|\.ci|src)/[\w./-]+\.py)", text):
        assert (ROOT / path).exists(), path
    for needed in ("kernel_fingerprint.py", "compare_results.py", "pre-commit install", "-n0 -x -q"):
        assert needed in text
