"""The tiny study (.test/config.yaml) run end to end with -j2, once for the module: its files, their CF
conventions, and the same numbers from an interrupted -j1 run resumed."""
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from workflow_runs import TEST_CONFIG, TINY, command, snakemake

pytestmark = [pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake is not installed"),
              pytest.mark.long_chain]  # started first (conftest.py)


@pytest.fixture(scope="module")
def tiny_run(tmp_path_factory):
    """The tiny study run once with -j2: (results folder, snakemake's work dir, the run)."""
    work = tmp_path_factory.mktemp("tiny")
    out = work / "out"
    res = snakemake("-j2", *TINY, "--config", f"results_dir={out}", workdir=work)
    return out, work, res


@pytest.mark.slow
def test_tiny_study_end_to_end(tiny_run):
    out, tmp_path, res = tiny_run
    assert res.returncode == 0, res.stderr[-5000:]
    import xarray as xr

    figures = sorted(p.name for p in (out / "figures").glob("*.png"))
    assert len(figures) == 8 and all((out / "figures" / f.replace(".png", ".pdf")).exists() for f in figures)
    for name in ("table1", "timing_sampling", "timing_delay"):
        assert all((out / "tables" / f"{name}.{ext}").stat().st_size > 0 for ext in ("nc", "csv", "md", "html"))
    for page in ("reproduction/claims.html", "reproduction/table1_vs_paper.html", "report/overview.html"):
        assert "<table" in (out / page).read_text(encoding="utf-8")  # the report's pages (rockstudy.report)
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


@pytest.mark.slow
def test_tiny_study_files_follow_cf_and_histories_have_one_value_per_time(tiny_run):
    """One netCDF file of each kind the tiny study writes (one per folder) passes the CF-1.11
    checker without a high-priority finding; every units attribute of every file parses with cf-units
    (and none is a mass); every history's time is strictly increasing."""
    from compliance import high_priority_findings

    out, _, res = tiny_run
    assert res.returncode == 0, res.stderr[-5000:]
    kinds = {}
    for path in sorted(out.rglob("*.nc")):
        kinds.setdefault(path.parent, path)
    assert len(kinds) >= 9, sorted(kinds)  # every spectrum written whole: no chunks/ folder
    findings = {str(path.relative_to(out)): high_priority_findings(path) for path in kinds.values()}
    assert all(not f for f in findings.values()), {k: f for k, f in findings.items() if f}
    from test_conventions import units_problems

    units = {str(path.relative_to(out)): units_problems(path) for path in sorted(out.rglob("*.nc"))}
    assert all(not u for u in units.values()), {k: u for k, u in units.items() if u}
    import xarray as xr

    histories = sorted((out / "histories").glob("*.nc"))
    assert histories
    for path in histories:
        with xr.open_dataset(path) as ds:
            assert np.all(np.diff(ds["t"].values) > 0), path.name
            assert ds["theta"].sel(t=2.0, method="nearest").size == 1


@pytest.mark.slow
def test_interrupted_j1_run_resumes_to_the_same_numbers_as_j2(tiny_run, tmp_path):
    """Ctrl-C in the middle of a -j1 run, then the same command again: it finishes without redoing (or
    touching) the jobs finished before (only the one job in flight at Ctrl-C may run again), and every
    netCDF file equals the -j2 run's (job order and -j do not change the numbers). The run asks for the
    netCDF files only: figures and pages are not numbers."""
    import signal
    import time

    import xarray as xr

    ref, _, first = tiny_run
    assert first.returncode == 0, first.stderr[-3000:]
    out = tmp_path / "out"
    ref_files = sorted(p.relative_to(ref) for p in ref.rglob("*.nc"))
    targets = [str(out / rel) for rel in ref_files]
    proc = subprocess.Popen(command("-j1", *TINY, "--config", f"results_dir={out}", "--", *targets, workdir=tmp_path),
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 600
    while time.monotonic() < deadline and proc.poll() is None:
        if len(list((out / "spectra").glob("*.nc"))) >= 2:
            break
        time.sleep(0.2)
    assert proc.poll() is None, "the run ended before it could be interrupted"
    proc.send_signal(signal.SIGINT)
    assert proc.wait(timeout=120) != 0
    done_before = {p: p.stat().st_mtime_ns for p in out.rglob("*.nc")}
    assert 2 <= len(done_before) < len(ref_files)
    res = snakemake("-j1", *TINY, "--config", f"results_dir={out}", "--", *targets, workdir=tmp_path)
    assert res.returncode == 0, res.stderr[-5000:]
    log = res.stdout + res.stderr
    jobs = {frozenset(Path(name) for name in line.split(", "))
            for line in re.findall(r"^\s+output: (.*)$", log, flags=re.MULTILINE)}
    redone_jobs = [outputs for outputs in jobs if outputs & set(done_before)]
    assert jobs and len(redone_jobs) <= 1, redone_jobs  # -j1: at most one job (of one or more files) was in flight
    redone = set().union(*redone_jobs)
    assert all(p.stat().st_mtime_ns == t for p, t in done_before.items() if p not in redone)

    assert sorted(p.relative_to(out) for p in out.rglob("*.nc")) == ref_files
    for rel in ref_files:
        with xr.open_dataset(ref / rel) as a, xr.open_dataset(out / rel) as b:
            a.attrs.pop("compute_time_s", None)
            b.attrs.pop("compute_time_s", None)
            xr.testing.assert_identical(a, b)


def _tampered_edit(path, edit):
    """Rewrite the netCDF file ``path`` with ``edit`` applied, every attribute kept."""
    from rockstudy.core import io

    ds = io.read_netcdf(path)
    edited = edit(ds)
    for name in edited.variables:
        if name in ds.variables:
            edited[name].attrs = ds[name].attrs
    edited.attrs = ds.attrs
    edited.to_netcdf(path)  # as a hand edit would: no check of rockstudy's own


def _copy_over(source):
    return lambda out, target: shutil.copyfile(out / source, out / target)


def _times(name, factor):
    return lambda out, target: _tampered_edit(out / target, lambda ds: ds.assign({name: ds[name] * factor}))


def _truncate(out, target):
    data = (out / target).read_bytes()
    (out / target).write_bytes(data[: len(data) // 2])


TAMPERED = {  # (intermediate, how, the step that reads it, what the refusal says after the file's name)
    "spectrum copied over another": ("spectra/FS_R005.nc", _copy_over("spectra/CS01_R005.nc"), "table1",
                                     "control_strategy is 'CS01', expected 'FS'"),
    "threshold x 1.5, attributes kept": ("spectra/FS_R000.nc", _times("threshold", 1.5), "table1",
                                         "threshold is not the lowest threshold_realisation"),
    "a realisation dropped": ("spectra/CS02_R005.nc",
                              lambda out, target: _tampered_edit(out / target, lambda ds: ds.isel(realisation=[0])),
                              "table1", "realisation is [0], expected [0, 1]"),
    "noise of another level": ("noise/R005.nc", _copy_over("noise/R000.nc"), "figure_excitation",
                               "noise_level is 0.0, expected 0.05"),
    "sampling time swapped": ("timing/sampling/CS01_R005_Ts0.1.nc",
                              _copy_over("timing/sampling/CS01_R005_Ts0.01.nc"), "timing_table_sampling",
                              "control_sampling_time_s is 0.01, expected 0.1"),
    "history of another realisation": ("histories/FS_R005_k1_w2_a1.4.nc",
                                       _copy_over("histories/FS_R005_k0_w2_a1.4.nc"), "figure_realisations",
                                       "noise_realisation is 0, expected 1"),
    "map of another strategy": ("maps/FS.nc", _copy_over("maps/CS01.nc"), "figure_maps",
                                "control_strategy is 'CS01', expected 'FS'"),
    "truncated file": ("convergence/FS_R005.nc", _truncate, "figure_noise_sensitivity", ""),
    "table swapped": ("tables/table1.nc", _copy_over("tables/timing_sampling.nc"), "claims",
                      "strategy is ['CS01', 'CS02'], expected ['FS', 'CS01', 'CS02']"),
}


@pytest.mark.slow
@pytest.mark.parametrize("case", sorted(TAMPERED))
def test_a_tampered_intermediate_is_refused_naming_the_file(tiny_run, tmp_path, case):
    """An intermediate of the tiny study swapped, edited or truncated by hand: the step that reads it (run
    alone, on the tampered copy) stops naming the file and what is wrong, and writes nothing."""
    ref, _, first = tiny_run
    assert first.returncode == 0, first.stderr[-3000:]
    out = tmp_path / "out"
    shutil.copytree(ref, out, ignore=shutil.ignore_patterns("logs"))
    target, tamper, rule, says = TAMPERED[case]
    tamper(out, target)
    res = snakemake("-j1", *TINY, "--config", f"results_dir={out}", "--allowed-rules", rule, "--forcerun", rule,
                    "--", rule, workdir=tmp_path)
    log = res.stdout + res.stderr
    assert res.returncode != 0, log[-3000:]
    assert f"{out / target}: {says}" in log if says else str(out / target) in log, log[-3000:]
    assert f"Error in rule {rule}" in log
