"""The one declaration of the study config: the checked-in schema is generated from it, it agrees with the
library's names, it accepts every config of the project and refuses bad keys in at most three lines."""
import copy
import time
from pathlib import Path

import jsonschema
import pytest
import yaml

from rockstudy.core import config_files
from rockstudy.core.validation import InputError
from rockstudy.studies import config_model as d

ROOT = Path(__file__).resolve().parents[2]
DEFAULT = yaml.safe_load((ROOT / "config.yaml").read_text())
TINY = yaml.safe_load((ROOT / ".test" / "config.yaml").read_text())


def test_checked_in_schema_is_the_generated_one():
    """Regenerate with ``python -m rockstudy.studies.config_model`` when this fails."""
    assert (ROOT / d.SCHEMA_PATH).read_text() == d.schema_text()


def test_generated_schema_is_a_valid_schema_accepting_the_project_configs():
    schema = d.config_schema()
    jsonschema.Draft202012Validator.check_schema(schema)
    for config in (DEFAULT, TINY):
        jsonschema.validate(config, schema)
        d.check_config(config)


def test_declared_names_are_the_library_names():
    from rockstudy.analysis.fragility import INTENSITY_MEASURES
    from rockstudy.engine.simulate import OVERTURN_CRITERIA
    from rockstudy.model.block import BLOCK_PRESETS
    from rockstudy.model.control import STRATEGIES
    from rockstudy.model.excitation import EXCITATIONS
    from rockstudy.model.noise import LEVEL_MEANINGS, RESCALES
    from rockstudy.model.record_suites import SUITES
    from rockstudy.model.records import UNITS

    assert set(d.STRATEGIES) == set(STRATEGIES)
    assert set(d.EXCITATIONS) == set(EXCITATIONS)
    assert set(d.OVERTURN_CRITERIA) == set(OVERTURN_CRITERIA)
    assert set(d.RESCALES) == set(RESCALES) and set(d.LEVEL_MEANINGS) == set(LEVEL_MEANINGS)
    assert set(d.BLOCK_PRESETS) == set(BLOCK_PRESETS)
    assert set(d.SUITES) == set(SUITES)
    assert set(d.RECORD_UNITS) == set(UNITS)
    assert set(d.INTENSITY_MEASURES) == set(INTENSITY_MEASURES)


def refusal(change) -> str:
    config = copy.deepcopy(DEFAULT)
    change(config)
    with pytest.raises(InputError) as info:
        d.check_config(config, name="my.yaml")
    text = str(info.value)
    assert len(text.splitlines()) <= 3, text
    assert text.startswith("my.yaml: ")
    return text


@pytest.mark.parametrize("change, needle", [
    (lambda c: c.update(realisatons=3), "realisatons: unknown key; did you mean `realisations`?"),
    (lambda c: c["anchorage"].update(kapa_max=1.0), "anchorage.kapa_max: unknown key; did you mean `kappa_max`?"),
    (lambda c: c["block"].update(preset="BLC07"), "block.preset = 'BLC07'"),
    (lambda c: c["block"].update(width=1.0, height=2.0, depth=1.0), "not both"),
    (lambda c: c["design"]["pga_levels_g"].update(start=1e-300, stop=1e300), "design.pga_levels_g.start = 1e-300"),
    (lambda c: c["design"]["blocks"].update(a_max0=1e9), "design.blocks.a_max0"),
    (lambda c: c["design"]["devices"].update(kappa_max=[2e6]), "design.devices.kappa_max[0] = 2000000.0"),
    (lambda c: c["design"]["blocks"]["amplitude_grid"].update(step=1e-9), "design.blocks.amplitude_grid.step"),
    (lambda c: c["anchorage"].update(kappa_max=True), "anchorage.kappa_max = True"),
    (lambda c: c["noise_levels"].update(R020=float("nan")), "noise_levels.R020 = nan"),
    (lambda c: c["beyond"]["fragility"].update(records=[{"path": "a.csv", "unit": "kg"}]),
     "beyond.fragility.records[0].unit = 'kg'"),
    (lambda c: c["table1"].update(strategies=["FS", "FS"]), "distinct"),
    (lambda c: c["sampling_sweep"].update(sampling_times=[0.01] * 10**5), "sampling_sweep.sampling_times"),
    (lambda c: c.pop("seed"), "seed: the key is missing"),
])
def test_refusal_names_key_value_and_rule(change, needle):
    assert needle in refusal(change)


def test_check_value_names_the_option():
    assert d.check_value("anchorage.kappa_max", 2.0, "--kappa-max") == 2.0
    with pytest.raises(InputError, match="--kappa-max = 20000.0 is not allowed"):
        d.check_value("anchorage.kappa_max", 2e4, "--kappa-max")
    with pytest.raises(InputError, match="--seed = True"):
        d.check_value("seed", True, "--seed")


def test_overlay_replaces_the_block_it_gives():
    merged = copy.deepcopy(DEFAULT)
    overlay = {"block": {"width": 0.5, "height": 2.5, "depth": 0.5}, "noise_levels": {"R000": 0.0, "R005": 0.05}}
    merged["block"].update(overlay["block"])  # Snakemake's deep merge
    merged["noise_levels"].update(overlay["noise_levels"])
    config_files.replace_sections(merged, overlay)
    assert merged["block"] == overlay["block"] and merged["noise_levels"] == overlay["noise_levels"]
    d.check_config(merged)


def test_alias_bomb_is_refused_at_once(tmp_path):
    lines = ["a0: &a0 [1, 2, 3, 4, 5, 6, 7, 8, 9]"]
    lines += [f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, 12)]
    bomb = tmp_path / "bomb.yaml"
    bomb.write_text("\n".join(lines) + "\n")
    t0 = time.perf_counter()
    with pytest.raises(InputError, match="alias bomb"):
        config_files.load_yaml(bomb)
    assert time.perf_counter() - t0 < 2.0


@pytest.mark.parametrize("text, needle", [("[1, 2]", "mapping"), ("a: [1,", "not valid YAML"), ("", "mapping")])
def test_load_yaml_refuses_what_is_not_a_config(tmp_path, text, needle):
    path = tmp_path / "c.yaml"
    path.write_text(text)
    with pytest.raises(InputError, match=needle):
        config_files.load_yaml(path)
