"""End-to-end tests of the study workflow (Snakefile): config validation and the tiny study."""
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[1]
TEST_CONFIG = ROOT / ".test" / "config.yaml"
pytestmark = pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake is not installed")


def snakemake(*args, workdir):
    cmd = ["snakemake", "--snakefile", str(ROOT / "Snakefile"), "--directory", str(workdir), *args]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=1800)


def run_with(config: dict, tmp_path, *args):
    path = tmp_path / "config.yaml"
    path.write_text(yaml.safe_dump(config))
    return snakemake("-n", "--configfile", str(path), "--replace-workflow-config", *args, workdir=tmp_path)


def tiny_config():
    return yaml.safe_load(TEST_CONFIG.read_text())


def test_valid_tiny_config_dry_runs(tmp_path):
    res = run_with(tiny_config(), tmp_path)
    assert res.returncode == 0, res.stderr + res.stdout
    assert "spectrum_chunk" in res.stdout


@pytest.mark.parametrize("change, key", [
    (lambda c: c.update(unknown_key=1), "unknown_key"),
    (lambda c: c.update(realisations=-1), "realisations"),
    (lambda c: c["amplitude_grid"].update(step="0.1"), "step"),
    (lambda c: c["sampling_sweep"].update(frequency=1.0), "frequency"),
    (lambda c: c["delay_sweep"].update(noise_level="R999"), "delay_sweep.noise_level"),
])
def test_invalid_config_stops_before_any_job_naming_the_key(tmp_path, change, key):
    config = tiny_config()
    change(config)
    res = run_with(config, tmp_path)
    assert res.returncode != 0
    assert key in res.stderr + res.stdout
    assert "Job stats" not in res.stdout and not (tmp_path / "results").exists()


def test_lint_is_clean(tmp_path):
    res = snakemake("--lint", workdir=ROOT)
    assert res.returncode == 0 and "Congratulations" in res.stdout + res.stderr, res.stdout + res.stderr


@pytest.mark.slow
def test_tiny_study_end_to_end(tmp_path):
    out = tmp_path / "out"
    res = snakemake("-j2", "--configfile", str(TEST_CONFIG), "--replace-workflow-config",
                    "--config", f"results_dir={out}", workdir=tmp_path)
    assert res.returncode == 0, res.stderr[-5000:]
    import xarray as xr

    figures = sorted(p.name for p in (out / "figures").glob("*.png"))
    assert len(figures) == 8 and all((out / "figures" / f.replace(".png", ".pdf")).exists() for f in figures)
    for name in ("table1", "timing_sampling", "timing_delay"):
        assert all((out / "tables" / f"{name}.{ext}").stat().st_size > 0 for ext in ("nc", "csv", "md"))
    with xr.open_dataset(out / "spectra" / "CS01_R005.nc") as ds:
        assert ds.sizes["realisation"] == 2 and ds["frequency_ratio"].attrs["units"] == "1"
        assert ds.attrs["rockstudy_version"] and len(ds.attrs["rockstudy_source_sha256"]) == 64
        assert float(ds["noise_level"]) == 0.05 and "threshold" in ds
    with xr.open_dataset(out / "tables" / "table1.nc") as t:
        assert set(t["reference"].values) == {"no_noise", "fs_same_noise"} and t["j_os"].attrs["units"] == "percent"
    assert list((out / "logs").rglob("*.log"))
    # nothing to do on a second run: outputs are up to date
    again = snakemake("-n", "--configfile", str(TEST_CONFIG), "--replace-workflow-config",
                      "--config", f"results_dir={out}", workdir=tmp_path)
    assert "Nothing to be done" in again.stdout + again.stderr, again.stdout[-3000:]


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-v"]))
