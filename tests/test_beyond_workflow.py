"""The optional `beyond:` section of the workflow: validated on load, targets in the DAG."""
import re
import shutil

import pytest
import yaml

from workflow_runs import ROOT, TEST_CONFIG, dry_run

pytestmark = pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake is not installed")


def tiny_with_beyond():
    config = yaml.safe_load(TEST_CONFIG.read_text())
    config["beyond"] = yaml.safe_load((ROOT / "config.yaml").read_text())["beyond"]
    return config


def test_targets_are_in_the_dag(tmp_path):
    res = dry_run(tiny_with_beyond(), tmp_path, "probability", "fragility")
    assert res.returncode == 0, res.stderr + res.stdout
    for rule in ("record_set", "fragility_stripes", "fragility_summary", "figure_record_thresholds",
                 "probability_surface", "figure_probability"):
        assert rule in res.stdout
    for name in ("p695-far-field", "p695-near-field-pulse"):  # the default record sets, one fragility each
        assert f"fragility/{name}.nc" in res.stdout and f"record_thresholds_{name}.png" in res.stdout
    assert "synthetic_suite" not in res.stdout


def test_the_synthetic_suite_and_a_selection_of_suite_records(tmp_path):
    config = tiny_with_beyond()
    config["beyond"]["fragility"]["records"] = ["synthetic", "p695-near-field-pulse:1a", "p695-far-field:3b"]
    res = dry_run(config, tmp_path, "fragility")
    assert res.returncode == 0, res.stderr + res.stdout
    assert "synthetic_suite" in res.stdout and "fragility/synthetic.nc" in res.stdout
    assert "fragility/selection.nc" in res.stdout


def test_user_record_files_replace_the_synthetic_suite(tmp_path):
    config = tiny_with_beyond()
    record = tmp_path / "quake.csv"
    record.write_text("time [s], acceleration [g]\n0, 0\n0.01, 0.1\n")
    config["beyond"]["fragility"]["records"] = [{"path": str(record)}]
    res = dry_run(config, tmp_path, "fragility")
    assert res.returncode == 0, res.stderr + res.stdout
    assert "fragility_stripes" in res.stdout and "synthetic_suite" not in res.stdout


@pytest.mark.parametrize("change, key", [
    (lambda b: b["fragility"].update(strategies=["CS01"]), "beyond.fragility.strategies"),
    (lambda b: b["probability"].update(noise_levels=["R999"]), "beyond.probability.noise_levels"),
    (lambda b: b["fragility"].update(intensity_measure="sa"), "intensity_measure"),
    (lambda b: b["fragility"].update(records=[{"path": "x.csv", "unit": "furlong"}]), "records"),
    (lambda b: b["fragility"].update(records=["p695-near-field-pulse:15a"]), "14b"),
    (lambda b: b["fragility"].update(records=["p695-nearfield"]), "p695-near-field-no-pulse"),
    (lambda b: b["fragility"].update(records="far-field"), "records"),
    (lambda b: b["fragility"].update(threshold_resolution=0), "threshold_resolution"),
])
def test_a_bad_beyond_section_stops_before_any_job(tmp_path, change, key):
    config = tiny_with_beyond()
    change(config["beyond"])
    res = dry_run(config, tmp_path, "fragility")
    assert res.returncode != 0 and key in res.stderr + res.stdout


# Rules whose scripts run the compiled engine: each must wait for the one compilation instead of compiling the
# engine itself alongside it; the spectra for its first part (rule compile_engine, the threshold scans), the
# others for both (rule compile_engine_more, which follows it).
SIMULATING_RULES = {"spectrum", "spectrum_sampling", "spectrum_delay", "spectrum_chunk", "overturning_map",
                    "time_history", "probability_surface", "fragility_stripes", "reading_spectrum", "calibration_fs",
                    "calibration_device", "calibration_refine_spectrum", "design_block", "design_device"}


def test_every_simulating_job_waits_for_the_one_compilation(tmp_path):
    config = tiny_with_beyond()
    config["design"] = yaml.safe_load((ROOT / "config.yaml").read_text())["design"]
    seen = set()
    for per_job in (config["realisations"], 1):  # every spectrum whole; the noisy ones in chunks
        config["realisations_per_job"] = per_job
        res = dry_run(config, tmp_path, "all", "probability", "fragility", "reproduction", "calibration", "design")
        assert res.returncode == 0, res.stderr + res.stdout
        jobs = re.findall(r"^( *)rule (\w+):\n((?:\1    .*\n)+)", res.stdout, flags=re.MULTILINE)  # grouped: indented
        seen |= {rule for _, rule, _ in jobs}
        for _, rule, body in jobs:
            if rule in SIMULATING_RULES:
                done = "compile_engine.done" if rule.startswith("spectrum") else "compile_engine_more.done"
                assert f"logs/{done}" in body, f"{rule} does not wait for {done}:\n{body}"
    assert SIMULATING_RULES <= seen, SIMULATING_RULES - seen
