"""The documentation as a user meets it: the Sphinx build is clean, and the examples of the usage guide
(every Python block in order, every `rockstudy` command) and of the README run as printed."""
from __future__ import annotations

import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

import rockstudy
from rockstudy.core.constants import PAPER

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
FENCE = re.compile(r"^```(\w+)\n(.*?)^```", re.MULTILINE | re.DOTALL)


def blocks(path: Path, language: str) -> list[str]:
    return [body for lang, body in FENCE.findall(path.read_text(encoding="utf-8")) if lang == language]


def commands(path: Path, program: str = "rockstudy") -> list[list[str]]:
    """The `program ...` lines of the bash blocks, continuation lines joined, split as the shell would."""
    found = []
    for body in blocks(path, "bash"):
        for line in body.replace("\\\n", " ").splitlines():
            line = line.split("#", 1)[0].strip()
            if line.startswith(program + " "):
                found.append(shlex.split(line)[1:])
    return found


def run_python_blocks(path: Path, name: str) -> dict:
    """Every Python block of a page, in order and in one namespace (returned); a failure names the block."""
    namespace: dict = {"__name__": name}
    for i, code in enumerate(blocks(path, "python")):
        where = f"{path.parent.name}/{path.name}, python block {i + 1}"
        try:
            exec(compile(code, where, "exec"), namespace)
        except Exception as exc:  # name the block in the failure
            raise AssertionError(f"{where} failed: {exc!r}\n{code}") from exc
    return namespace


def env_with_package() -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(ROOT / "src"), env.get("PYTHONPATH", "")])
    return env


def test_docs_build_without_warnings(tmp_path):
    pytest.importorskip("sphinx")
    pytest.importorskip("myst_parser")
    pytest.importorskip("numpydoc")
    pytest.importorskip("myst_nb")  # runs docs/tutorial.md, the notebook
    # -W: a warning (broken reference, malformed docstring, missing image) is an error; dummy: read and
    # resolve everything as the html builder does, without writing pages
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-E", "-b", "dummy",
                          str(DOCS), str(tmp_path / "build")], capture_output=True, text=True,
                         env=env_with_package(), timeout=600)
    assert run.returncode == 0, run.stdout + run.stderr


def test_guide_has_every_topic():
    text = (DOCS / "usage.md").read_text(encoding="utf-8")
    for heading in ("## One case", "## A threshold", "## A spectrum", "## J_OS", "## An earthquake record",
                    "## A fragility study"):
        assert heading in text
    subcommands = {c[0] for c in commands(DOCS / "usage.md")}
    assert {"simulate", "threshold", "spectrum", "jos"} <= subcommands


def test_guide_examples_run(tmp_path, monkeypatch, capsys):
    """Every Python block of the usage guide, in order and in one namespace, then every `rockstudy` command
    (they read the files the blocks wrote: the guide is one session)."""
    monkeypatch.chdir(tmp_path)
    run_python_blocks(DOCS / "usage.md", "usage_guide")
    printed = capsys.readouterr().out
    assert "J_OS(CS01 vs FS) =" in printed and "samples, PGA 0.30 g" in printed
    for args in commands(DOCS / "usage.md"):
        run = subprocess.run([sys.executable, "-m", "rockstudy.cli", *args], capture_output=True, text=True,
                             env=env_with_package(), timeout=600)
        assert run.returncode == 0, f"rockstudy {shlex.join(args)}:\n{run.stdout}\n{run.stderr}"
    assert (tmp_path / "run.nc").exists() and (tmp_path / "cs01.nc").exists()


def test_readme_python_example_runs(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (code,) = blocks(ROOT / "README.md", "python")
    exec(compile(code, "README.md, python block", "exec"), {"__name__": "readme"})
    assert "J_OS(CS01 vs FS) =" in capsys.readouterr().out


def test_readme_commands_are_what_ci_runs():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    install = 'python -m pip install -c constraints.txt -e ".[all]"'
    lint_and_test = "ruff check . && python -m mypy && python -m pytest"
    assert f"{install} && snakemake -j2" in readme and lint_and_test in readme
    assert install in ci and lint_and_test in ci


@pytest.mark.parametrize("failing", ["ruff", "mypy", "pytest"])
def test_ci_stops_when_the_lint_or_the_tests_fail(tmp_path, failing):
    """.ci/run's lint-and-test line, with each of its three commands failing in turn, ends the script
    with an error (under `set -e` a failure inside an && list alone would not: the run went on, green)."""
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    line = next(ln for ln in ci.splitlines() if ln.startswith("ruff check . && python -m mypy"))
    stubs = {"ruff": "ruff() { return 0; }", "mypy": "mypy() { return 0; }", "pytest": "pytest() { return 0; }"}
    stubs[failing] = f"{failing}() {{ return 1; }}"
    script = "\n".join(["set -euo pipefail", *stubs.values(), "python() { shift; \"$@\"; }",
                        line, "echo went-on"])
    res = subprocess.run(["bash", "-c", script], capture_output=True, text=True, cwd=tmp_path)
    assert res.returncode != 0 and "went-on" not in res.stdout, (line, res.stdout, res.stderr)


def test_readme_cli_examples_parse():
    """The README's `rockstudy` lines are valid command lines (parsed, not run: they are full-size)."""
    from rockstudy import cli

    parser = cli.build_parser() if hasattr(cli, "build_parser") else None
    if parser is None:
        pytest.skip("rockstudy.cli has no build_parser()")
    for args in commands(ROOT / "README.md"):
        parser.parse_args(args)


def test_citation_matches_the_package():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert cff["cff-version"] == "1.2.0"
    assert cff["version"] == rockstudy.__version__
    assert cff["license"] == "MIT"
    assert " ".join(cff["references"][0]["title"].split()) == PAPER
    assert "MIT License" in (ROOT / "LICENSE").read_text(encoding="utf-8")


def test_the_version_is_written_once():
    """pyproject.toml reads the version from rockstudy._version, the one place it is written."""
    tomllib = pytest.importorskip("tomllib")
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert "version" not in project["project"] and "version" in project["project"]["dynamic"]
    assert project["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "rockstudy._version.__version__"}
    assert f'__version__ = "{rockstudy.__version__}"' in (ROOT / "src/rockstudy/_version.py").read_text()


def test_readme_is_a_guide_of_at_most_250_lines():
    assert len((ROOT / "README.md").read_text(encoding="utf-8").splitlines()) <= 250


def test_readme_records_exist_on_a_fresh_clone():
    """Every ``--record`` of the README's command lines is a record of a shipped suite or a file of the
    repository: nothing the reader has to find elsewhere."""
    from rockstudy.model import record_suites
    records = [args[args.index("--record") + 1] for args in commands(ROOT / "README.md") if "--record" in args]
    assert records
    for record in records:
        if record_suites.looks_like_suite_record(record):
            info, rec = record_suites.load_record(record, "--record")
            assert rec.acceleration.size > 100 and info.id
        else:
            assert (ROOT / record).is_file(), record
