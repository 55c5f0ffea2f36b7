"""Tests for rockstudy.studies.expectations: what each dataset of a study must say about itself, from the
config and a job's wildcards."""
import pytest
import yaml

from rockstudy.core import io
from rockstudy.studies import datasets, expectations, parameters
from workflow_runs import ROOT, TEST_CONFIG


@pytest.fixture()
def tiny():
    return yaml.safe_load(TEST_CONFIG.read_text())


def test_a_spectrum_expects_its_strategy_timing_realisations_and_grids(tiny):
    expect = expectations.StudyExpectations(tiny)
    e = expect.spectrum("CS02", "R005", 0.1, 0.06)
    assert (e["control_strategy"], e["control_sampling_time_s"], e["control_delay_s"]) == ("CS02", 0.1, 0.06)
    assert e["noise_level"] == 0.05 and e["noise_seed"] == tiny["seed"]
    assert e["realisation"] == list(range(tiny["realisations"])) and e["frequency_ratio"] == [1.0, 2.0, 3.0]
    assert e["grid_amplitude_stop"] == tiny["amplitude_grid"]["stop"]
    assert expect.spectrum("FS", "R000")["realisation"] == [0]  # one realisation without noise


def test_chunks_expect_their_own_realisations(tiny):
    tiny["realisations_per_job"] = 1
    expect = expectations.StudyExpectations(tiny)
    assert [expect.chunk("FS", "R005", 0, 0, c)["realisation"] for c in (0, 1)] == [[0], [1]]
    with pytest.raises(IndexError):
        expect.chunk("FS", "R005", 0, 0, 2)


def test_the_noise_file_expects_no_device_and_matches_what_the_library_writes(tiny):
    """The expectation of a noise file is what rockstudy.studies.datasets.noise_dataset writes for the
    config's level (an independent path: the dataset built from the scenario the rule passes)."""
    expect = expectations.StudyExpectations(tiny)
    e = expect.noise("R005")
    assert not any(k.startswith(("control_", "anchorage_")) for k in e)
    spec = expectations.scenario_spec(tiny, "FS", "R005")
    ds = datasets.noise_dataset(parameters.scenario_from_dict(spec), [1.0, 2.0, 3.0], [0, 1], 1.0, 1)
    io.check_dataset(ds, "noise.nc", e)
    with pytest.raises(io.DatasetMismatch, match="noise.nc: noise_level is 0.05, expected 0.0"):
        io.check_dataset(ds, "noise.nc", expect.noise("R000"))


def test_beyond_and_design_expectations(tiny):
    config = yaml.safe_load((ROOT / "config.yaml").read_text())
    tiny["beyond"], tiny["design"] = config["beyond"], config["design"]
    expect = expectations.StudyExpectations(tiny)
    frag = expect.fragility("p695-far-field")
    assert frag["record_suite"] == "p695-far-field" and frag["strategy"] == config["beyond"]["fragility"]["strategies"]
    assert frag["block_alpha"] > 0 and "control_strategy" not in frag
    assert expect.probability("CS01", "R005")["n_realisations"] == tiny["realisations"]
    assert expect.record_set("selection", ["a:1", {"path": "x.csv"}])["record_set_members"] == \
        "['a:1', {'path': 'x.csv'}]"
    blocks = expect.design_blocks()
    assert blocks["R"] == sorted(config["design"]["blocks"]["R"])
    point = expect.design_block(config["design"]["blocks"]["R"][0], config["design"]["blocks"]["alpha"][0])
    assert point["R"] == config["design"]["blocks"]["R"][0] and point["record_suite"] == config["design"]["suite"]


def test_tables_expect_their_strategies_and_sweeps(tiny):
    expect = expectations.StudyExpectations(tiny)
    assert expect.table1()["strategy"] == tiny["table1"]["strategies"]
    assert expect.timing_table("sampling")["sampling_time"] == tiny["sampling_sweep"]["sampling_times"]
    assert expect.timing_table("delay")["delay"] == tiny["delay_sweep"]["delays"]
    assert "delay" not in expect.timing_table("sampling") and expect.table1()["block_alpha"] > 0
    with pytest.raises(ValueError, match="sampling or delay"):
        expect.timing_table("noise")


def test_calibration_and_readings_expectations(tiny):
    expect = expectations.StudyExpectations(tiny)
    cal = tiny["calibration"]
    assert len(expect.calibration_devices) == len(cal["kappa_max"]) * len(cal["damping_ratio"]) * len(
        cal["ultimate_rotation_ratio"]) * len(cal["kappa_min_ratio"])
    devices = [expect.calibration_device(i) for i in range(len(expect.calibration_devices))]
    assert {d["anchorage_kappa_max"] for d in devices} == set(cal["kappa_max"])
    assert len({tuple(sorted(d.items())) for d in devices}) == len(devices)  # one expectation per device
    assert expect.calibration_refined(0, "CS02", "R005")["control_strategy"] == "CS02"
    assert expect.readings_table()["reading"] == list(tiny["reproduction"]["readings"])


def test_paired_refuses_a_length_mismatch():
    assert expectations.paired(["a", "b"], [{}, {"x": 1}]) == {"a": {}, "b": {"x": 1}}
    with pytest.raises(ValueError, match="2 input files but 1 expectations"):
        expectations.paired(["a", "b"], [{}])
