"""The generated config schema and the study's check agree on every numeric key: generated over every number
of the project's config (every key, every list item), at each declared range end and just beyond it.

* just beyond a range end, :func:`check_study` refuses the value, naming the key;
* at a range end, :func:`check_study` does not refuse the value by a range of its own (a tighter bound than
  the schema's, the disagreement this guards against); it may still refuse it by a relation to another key
  (a grid's start above its stop, a time span), which the schema cannot express.
"""
from __future__ import annotations

import copy
import math
from pathlib import Path

import pytest
import yaml

from rockstudy.core.validation import InputError
from rockstudy.studies import config_model
from rockstudy.studies.study import check_study

ROOT = Path(__file__).resolve().parents[2]
DEFAULT = yaml.safe_load((ROOT / "config.yaml").read_text())
SCHEMA = config_model.config_schema()
BOUNDS = ("minimum", "exclusiveMinimum", "maximum", "exclusiveMaximum")


def _resolve(node: dict) -> dict:
    """The schema node itself (``$ref`` followed), and of an optional value (``anyOf`` with null) its value."""
    while True:
        if "$ref" in node:
            node = SCHEMA["$defs"][node["$ref"].rsplit("/", 1)[-1]]
        elif "anyOf" in node:
            kinds = [n for n in node["anyOf"] if n.get("type") != "null"]
            if len(kinds) != 1:
                return node
            node = kinds[0]
        else:
            return node


def _leaves(value, node: dict, path: list):
    """(key path, schema node) of every number of ``value``."""
    node = _resolve(node)
    if isinstance(value, dict):
        for key, item in value.items():
            child = node.get("properties", {}).get(key) or node.get("additionalProperties")
            if isinstance(child, dict):
                yield from _leaves(item, child, [*path, key])
    elif isinstance(value, list):
        if isinstance(node.get("items"), dict):
            for i, item in enumerate(value):
                yield from _leaves(item, node["items"], [*path, i])
    elif isinstance(value, (int, float)) and not isinstance(value, bool) and any(b in node for b in BOUNDS):
        yield path, node


def _name(path: list) -> str:
    out = ""
    for part in path:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else part)
    return out


def _with(config: dict, path: list, value) -> dict:
    out = copy.deepcopy(config)
    node = out
    for part in path[:-1]:
        node = node[part]
    node[path[-1]] = value
    return out


def _cases():
    for path, node in _leaves(DEFAULT, SCHEMA, []):
        integer = node.get("type") == "integer"
        for bound in BOUNDS:
            if bound not in node:
                continue
            end = node[bound]
            if abs(end) > 1e15:  # the int64 range: the schema's and the check's are one declaration
                continue
            upper = "aximum" in bound
            step = 1 if integer else max(abs(end) * 1e-6, 1e-12)
            inside = end if not bound.startswith("exclusive") else end - step if upper else end + step
            outside = end + step if upper and not bound.startswith("exclusive") else end if bound.startswith(
                "exclusive") else end - step
            if integer:
                inside, outside = int(inside), int(outside)
            yield pytest.param(path, inside, outside, id=f"{_name(path)}-{bound}")


CASES = list(_cases())
KEYS = ({_name(path[:n]) for path, _ in _leaves(DEFAULT, SCHEMA, []) for n in range(2, len(path) + 1)
         if not isinstance(path[n - 1], int)} | {key for key, value in DEFAULT.items() if isinstance(value, dict)})
"""The key paths a relation may name: every key below a section (``beyond.fragility.synthetic.dt``) and the
sections (``block``)."""


def test_the_generation_covers_every_section():
    sections = {path[0] for path, *_ in (c.values for c in CASES)}
    assert len(CASES) > 100
    assert {"anchorage", "noise", "frequency_grid", "beyond", "design", "risk", "calibration"} <= sections


@pytest.mark.parametrize(("path", "inside", "outside"), CASES)
def test_schema_bound_is_the_checks_bound(path, inside, outside):
    key = _name(path)
    with pytest.raises(InputError) as refused:
        check_study(_with(DEFAULT, path, outside))
    assert key in str(refused.value).split(" = ")[0].split(":")[0] or key in str(refused.value), str(refused.value)
    if isinstance(inside, float) and not math.isfinite(inside):
        return
    try:
        check_study(_with(DEFAULT, path, inside))
    except ValueError as exc:
        text = str(exc)
        # a relation to another key may refuse a range end (the message names that key); a range of the
        # check's own may not
        related = any(other in text for other in KEYS if other != key and not key.startswith(other))
        assert not (text.startswith(f"{key} = ") and "allowed is" in text and not related), (
            f"the schema allows {key} = {inside!r} but check_study refuses it by a range of its own:\n{text}")
