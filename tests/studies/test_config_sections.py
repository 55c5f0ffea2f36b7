"""The config check covers every section of the study config (beyond, reproduction, calibration, the
lists, results_dir): any number or list length anywhere is accepted within the limits or refused
before any job, naming the key (hypothesis over every numeric leaf and every list of config.yaml)."""
import copy
import math
import os
import time
from pathlib import Path

import jsonschema
import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rockstudy.core import validation as v
from rockstudy.studies import study

ROOT = Path(__file__).resolve().parents[2]
DEFAULT = yaml.safe_load((ROOT / "config.yaml").read_text())
SCHEMA = yaml.safe_load((ROOT / "workflow" / "schemas" / "config.schema.yaml").read_text())
EXAMPLES = int(os.environ.get("ROCKSTUDY_HYPOTHESIS_EXAMPLES", "60"))
PROPERTY = settings(max_examples=EXAMPLES, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])


def leaves(node, path=()):
    """(path, value) of every number and every list in a nested config."""
    if isinstance(node, dict):
        for k, item in node.items():
            yield from leaves(item, path + (k,))
    elif isinstance(node, list):
        yield path, node
        for i, item in enumerate(node):
            yield from leaves(item, path + (i,))
    elif isinstance(node, (int, float)) and not isinstance(node, bool):
        yield path, node


NUMBERS = [p for p, value in leaves(DEFAULT) if not isinstance(value, list)]
LISTS = [p for p, value in leaves(DEFAULT) if isinstance(value, list)]
SECTIONS = {p[0] for p in NUMBERS}
ANY_NUMBER = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-2**80, 2**80),
                       st.sampled_from([0, 1, -1, 1e-300, 1e300, 2**63 - 1, 2**63, 0.5, 1e-9, 1e9, 1e12]))


def key_name(path) -> str:
    out = ""
    for part in path:
        out += f"[{part}]" if isinstance(part, int) else (f".{part}" if out else str(part))
    return out


def config_error(config):
    """None when the schema and check_study accept ``config``, else the message."""
    try:
        study.check_sizes(config)  # the Snakefile's order: sizes, schema, the whole check
        jsonschema.validate(config, SCHEMA)
        study.check_study(config)
    except jsonschema.ValidationError as exc:
        return f"{key_name(exc.absolute_path)}: {exc.message}"
    except ValueError as exc:
        return str(exc)
    return None


def put(config, path, value):
    node = config
    for k in path[:-1]:
        node = node[k]
    node[path[-1]] = value


def test_every_section_has_numbers_to_change():
    assert {"beyond", "reproduction", "calibration", "frequency_grid", "amplitude_grid", "noise"} <= SECTIONS


RELATED = {"start", "stop", "step", "resolution", "a_max0", "realisations", "realisations_per_job", "kappa_min",
           "kappa_max", "noise_levels", "frequency_ratio", "candidates", "duration", "dt", "peak_time",
           "ground_frequency_hz", "frequency_grid", "sampling_times", "delays", "free_time", "span", "calibration",
           "config"}


@PROPERTY
@given(changes=st.lists(st.one_of(
    st.tuples(st.sampled_from(NUMBERS), ANY_NUMBER),
    st.tuples(st.sampled_from(LISTS), st.sampled_from([0, 1, 3, v.MAX_LIST_ITEMS + 1, 10**5]))),
    min_size=1, max_size=2))
def test_property_every_section_is_refused_naming_a_key_or_accepted_within_limits(changes):
    config = copy.deepcopy(DEFAULT)
    for path, value in changes:
        if path in LISTS:
            node = config
            for k in path:
                node = node[k]
            if not isinstance(node, list):  # an earlier change replaced it
                continue
            value = (node * (value // max(len(node), 1) + 1))[:value]
        try:
            put(config, path, value)
        except (KeyError, IndexError, TypeError):  # an earlier change removed the parent
            continue
    t0 = time.perf_counter()
    message = config_error(config)
    assert time.perf_counter() - t0 < 5.0, changes
    if message is None:
        for p, value in leaves(config):  # every number left is finite, every list within the limit
            if isinstance(value, list):
                assert len(value) <= v.MAX_LIST_ITEMS or p == ("beyond", "fragility", "records"), p
            else:
                assert math.isfinite(float(value)), p
    else:
        names = {str(p[-1]) for p, _ in changes} | {key_name(p) for p, _ in changes} | {
            str(part) for p, _ in changes for part in p if isinstance(part, str)}
        assert any(n in message for n in names | RELATED), (changes, message)


@pytest.mark.parametrize("path, value, needle", [
    (("results_dir",), "/", "root folder"),
    (("results_dir",), "/etc", "system folder"),
    (("results_dir",), "/proc/self", "system folder"),
    (("results_dir",), "/usr/share/x", "system folder"),
    (("results_dir",), "config.yaml", "existing file"),
    (("results_dir",), "out/{strategy}", "wildcards"),
    (("sampling_sweep", "sampling_times"), [0.01] * 10**5, "sampling_sweep.sampling_times"),
    (("delay_sweep", "delays"), [0.01] * 10**4, "delay_sweep.delays"),
    (("beyond", "fragility", "synthetic", "dt"), 1e-9, "beyond.fragility.synthetic.dt"),
    (("beyond", "fragility", "bootstrap"), 10**12, "beyond.fragility.bootstrap"),
    (("beyond", "fragility", "records"), [{"path": "/dev/zero"}], "not a regular file"),
    (("beyond", "probability", "frequency_grid", "step"), 1e-7, "beyond.probability.frequency_grid.step"),
    (("reproduction", "realisations"), 10**9, "reproduction.realisations"),
    (("reproduction", "readings", "fine"), {"step": 1e-7}, "reproduction.readings.fine.step"),
    (("calibration", "coarse_realisations"), 10**9, "calibration.coarse_realisations"),
    (("calibration", "candidates"), 10**4, "calibration.candidates"),
    (("noise", "span"), 3590.0, "noise.span"),
    (("noise", "step"), 1e-8, "noise.step"),
])
def test_config_check_names_key_value_and_limit(path, value, needle):
    config = copy.deepcopy(DEFAULT)
    put(config, path, value)
    t0 = time.perf_counter()
    message = config_error(config)
    assert message is not None and needle in message, message
    assert time.perf_counter() - t0 < 5.0
