"""Config text read as written, generated over the whole config:

* every number of the project's config, written in each form YAML 1.1 does not read as written (``010`` is
  octal 8, ``0x1F``, ``0b11``, ``1:30`` sexagesimal 90), is refused naming the file and the line,
  or read as the decimal it shows -- never as another number;
* every mapping of names of the config model (noise levels, readings, scenarios, hazard curves ...) is
  replaced whole by an overlay that gives it, not merged, so a name the overlay leaves out does not stay.
"""
from __future__ import annotations

import copy
import typing
from pathlib import Path

import pytest
import yaml
from pydantic import BaseModel

from rockstudy.core import config_files
from rockstudy.core.validation import InputError
from rockstudy.studies import config_model as d

ROOT = Path(__file__).resolve().parents[2]
DEFAULT = yaml.safe_load((ROOT / "config.yaml").read_text())
FORMS = ("010", "-010", "0x1F", "0b11", "1:30")


def _numbers(node, path=()):
    if isinstance(node, dict):
        for key, item in node.items():
            yield from _numbers(item, (*path, key))
    elif isinstance(node, list):
        for i, item in enumerate(node):
            yield from _numbers(item, (*path, i))
    elif isinstance(node, (int, float)) and not isinstance(node, bool):
        yield path


def _set(config, path, value):
    out = copy.deepcopy(config)
    node = out
    for part in path[:-1]:
        node = node[part]
    node[path[-1]] = value
    return out


NUMBER_CASES = [pytest.param(path, form, id=f"{'.'.join(map(str, path))}={form}")
                for path in _numbers(DEFAULT) for form in FORMS]


def test_the_generation_covers_every_number():
    assert len(NUMBER_CASES) == len(FORMS) * len(list(_numbers(DEFAULT))) > 500


@pytest.mark.parametrize(("path", "form"), NUMBER_CASES)
def test_a_number_yaml_misreads_is_refused_or_read_as_written(path, form, tmp_path):
    marker = "NUMBER-MARKER"
    text = yaml.safe_dump(_set(DEFAULT, path, marker), sort_keys=False)
    line = next(i for i, row in enumerate(text.splitlines(), 1) if marker in row)
    text = text.replace(marker, form)
    file = tmp_path / "overlay.yaml"
    file.write_text(text)
    try:
        config = config_files.load_yaml(file)
    except InputError as exc:
        assert f"line {line}" in str(exc) and form in str(exc) and str(file) in str(exc), str(exc)
        assert f": {_key_path(path)}: {form} is not allowed" in str(exc), str(exc)  # the key, not only the line
        assert len(str(exc).splitlines()) <= 3
        return
    node = config
    for part in path:
        node = node[part]
    decimal = form.replace("_", "")
    assert node == decimal or (isinstance(node, (int, float)) and node == float(decimal)), (
        f"{form} read as {node!r}")


def _key_path(path) -> str:
    """``a.b[0].c`` of a path of keys and indices."""
    return "".join(f"[{p}]" if isinstance(p, int) else f".{p}" for p in path).lstrip(".")


@pytest.mark.parametrize(("path", "form"), NUMBER_CASES)
def test_the_command_line_refuses_or_reads_as_written_as_a_file_does(path, form):
    """The same number given on Snakemake's command line (``--config KEY=VALUE``, a section as a YAML flow
    mapping) as Snakemake parses it and the Snakefile reads it: refused naming the key path, or read as the
    decimal it shows (or kept as the text it is) -- never as another number; and refused whenever Snakemake
    would read it as a number a config file reads differently (``010``: 10 here, 8 in a file)."""
    cli = pytest.importorskip("snakemake.cli")
    marker = "NUMBER-MARKER"
    top = path[0]
    if len(path) == 1:
        word = f"{top}={form}"
    else:
        text = yaml.safe_dump(_set(DEFAULT, path, marker)[top], default_flow_style=True, width=10**6).strip()
        word = f"{top}={text.replace(marker, form)}"
    parsed = cli.parse_config([word])
    try:
        overlay = config_files.command_line_overlay(parsed, [word])
    except InputError as exc:
        assert str(exc).startswith(f"--config {_key_path(path)}: {form} is not allowed"), str(exc)
        assert len(str(exc).splitlines()) <= 3
        return
    node = overlay
    for part in path:
        node = node[part]
    decimal = form.replace("_", "")
    assert node == form or (isinstance(node, (int, float)) and node == float(decimal)), f"{word} read as {node!r}"
    file_reading = yaml.safe_load(form)
    assert not (isinstance(node, (int, float)) and node != file_reading), f"{word}: {node!r}, a file {file_reading!r}"


def _names_mappings(model, prefix=""):
    """Key paths of the model's fields that map free names to values (dict-typed)."""
    for name, field in model.model_fields.items():
        ann = field.annotation
        for arg in (ann, *typing.get_args(ann)):
            base = typing.get_args(arg)[0] if typing.get_origin(arg) is typing.Annotated else arg
            if typing.get_origin(base) is dict:
                yield f"{prefix}{name}"
            elif isinstance(base, type) and issubclass(base, BaseModel):
                yield from _names_mappings(base, f"{prefix}{name}.")


MAPPINGS = sorted(set(_names_mappings(d.Study)))


def test_the_model_has_mappings_of_names_to_generate_over():
    assert {"noise_levels", "reproduction.readings", "risk.scenarios", "risk.hazard_curves"} <= set(MAPPINGS)


@pytest.mark.parametrize("path", MAPPINGS)
def test_an_overlay_replaces_every_mapping_of_names(path):
    *parents, key = path.split(".")
    base = copy.deepcopy(DEFAULT)
    node = base
    for part in parents:
        node = node[part]
    if not node.get(key):  # no names in the default config: give it one, of the kind the overlay gives
        node[key] = {"defaultonly": "hazard.csv"}
    old = node[key]
    new_name = "overlayonly"
    overlay_value = {new_name: next(iter(old.values()))}
    overlay = {}
    target = overlay
    for part in parents:
        target = target.setdefault(part, {})
    target[key] = overlay_value
    merged = config_files.merge(copy.deepcopy(base), overlay)  # as Snakemake merges a --configfile
    config_files.replace_sections(merged, overlay)
    result = merged
    for part in path.split("."):
        result = result[part]
    assert set(result) == {new_name}, f"{path}: {sorted(set(old))} stayed after the overlay"
    assert path in config_files.REPLACED_BY_OVERLAY
