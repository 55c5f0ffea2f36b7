"""Every YAML, shell and Python block of README.md and docs/ runs as printed, found generically (fenced blocks
of any Markdown file): a YAML block that sets study keys is an overlay of config.yaml and passes the study's
check (merged as Snakemake merges a --configfile, then replaced as the Snakefile replaces); a `snakemake` line
runs as a dry run (-n) in a folder holding config.yaml and every YAML block named in its first comment
(``# tall.yaml: ...``); a `rockstudy` line parses; a Python block runs, unless tests/test_docs.py runs that
file's blocks already (the usage guide and the README's example, which take minutes)."""
from __future__ import annotations

import copy
import re
import shlex
import shutil
import subprocess
from pathlib import Path

import pytest
import yaml

from rockstudy.core import config_files
from rockstudy.studies import config_model

ROOT = Path(__file__).resolve().parents[1]
FENCE = re.compile(r"^```(\w+)[^\n]*\n(.*?)^```", re.MULTILINE | re.DOTALL)
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
SHELL = ("bash", "sh", "shell", "console")
PYTHON_RUN_ELSEWHERE = {"README.md", "docs/usage.md", "docs/risk.md"}  # test_docs(_risk).py run them in order
NOT_RUN_HERE = ("pip", "ruff", "pytest", "sphinx", "git", "cd", "open")
"""Shell commands these tests do not run: installs, the linter and test suite themselves, the docs build."""
DEFAULT = yaml.safe_load((ROOT / "config.yaml").read_text())


def fenced(language_set):
    found = []
    for page in PAGES:
        for i, (lang, body) in enumerate(FENCE.findall(page.read_text(encoding="utf-8"))):
            if lang in language_set:
                found.append((f"{page.relative_to(ROOT)}#{i + 1}", body))
    return found


YAML_BLOCKS = fenced({"yaml"})
NAMED = {m.group(1): body for _, body in YAML_BLOCKS if (m := re.match(r"#\s*([\w.-]+\.ya?ml)\b", body))}


def merge(base: dict, overlay: dict) -> dict:
    """Snakemake's deep merge of a --configfile over the config."""
    for key, value in overlay.items():
        if isinstance(value, dict) and isinstance(base.get(key), dict):
            merge(base[key], value)
        else:
            base[key] = value
    return base


@pytest.mark.parametrize("where, body", YAML_BLOCKS, ids=[w for w, _ in YAML_BLOCKS])
def test_yaml_block_is_a_valid_config_or_overlay(where, body):
    from rockstudy.studies import study

    data = yaml.safe_load(body)
    if not isinstance(data, dict) or not set(data) <= set(config_model.Study.model_fields):
        return  # not a config: parsed is enough
    config = config_files.replace_sections(merge(copy.deepcopy(DEFAULT), data), data)
    study.check_study(config)


def command_lines():
    found = []
    for where, body in fenced(set(SHELL)):
        for line in body.replace("\\\n", " ").splitlines():
            for part in line.split("#", 1)[0].split("&&"):
                words = shlex.split(part.strip())
                if words and words[0] not in NOT_RUN_HERE and words[:3] != ["python", "-m", "pip"] and not (
                        words[0] == "python" and len(words) > 2 and words[2] in NOT_RUN_HERE):
                    found.append((where, words))
    return found


COMMANDS = command_lines()
SNAKEMAKE = [(w, c) for w, c in COMMANDS if c[0] == "snakemake"]
ROCKSTUDY = [(w, c) for w, c in COMMANDS if c[0] == "rockstudy"]


def dry(words: list[str]) -> list[str]:
    """A snakemake command line as a dry run: -n, without --report (which needs finished results) and without
    a cluster profile, and with the software already installed (``--sdm conda`` would need conda; the environment
    file itself is checked by tests/test_environment.py)."""
    out, skip = [], False
    for word in words[1:]:
        if skip:
            skip = False
            continue
        if word in ("--report", "--profile", "--sdm", "--software-deployment-method"):
            skip = True
            continue
        if word.startswith(("--report=", "--profile=", "-j")) or word in ("--cores",):
            continue
        out.append(word)
    return ["-n", *out]


@pytest.mark.parametrize("where, words", SNAKEMAKE, ids=[f"{w}: {shlex.join(c)}" for w, c in SNAKEMAKE])
def test_snakemake_line_dry_runs(where, words, tmp_path):
    from workflow_runs import command

    shutil.copy(ROOT / "config.yaml", tmp_path / "config.yaml")
    for name, body in NAMED.items():
        (tmp_path / name).write_text(body)
    res = subprocess.run(command(*dry(words), workdir=tmp_path), cwd=tmp_path, capture_output=True, text=True,
                         timeout=600)  # in the folder, so that relative config files resolve as for a user
    assert res.returncode == 0, f"{where}: snakemake {shlex.join(dry(words))}\n{(res.stdout + res.stderr)[-2000:]}"


@pytest.mark.parametrize("where, words", ROCKSTUDY, ids=[f"{w}: {shlex.join(c)}" for w, c in ROCKSTUDY])
def test_rockstudy_line_parses(where, words, monkeypatch):
    from rockstudy.cli import build_parser
    from rockstudy.cli.options import _apply_config

    monkeypatch.chdir(ROOT)
    parser = build_parser(words[1:2])
    args = parser.parse_args(words[1:])
    if hasattr(args, "config"):
        _apply_config(args, words[1:], parser)


PYTHON_BLOCKS = [(w, b) for w, b in fenced({"python"}) if w.split("#")[0] not in PYTHON_RUN_ELSEWHERE]


@pytest.mark.parametrize("where, body", PYTHON_BLOCKS, ids=[w for w, _ in PYTHON_BLOCKS])
def test_python_block_runs(where, body, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    exec(compile(body, where, "exec"), {"__name__": "docs_block"})


def test_the_blocks_are_found():
    """The discovery sees the README's overlay and its commands (a changed fence syntax would hide them)."""
    assert "tall.yaml" in NAMED
    assert any("--configfile" in c for _, c in SNAKEMAKE) and ROCKSTUDY
