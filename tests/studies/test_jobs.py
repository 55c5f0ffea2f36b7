"""Tests for rockstudy.studies.jobs and rockstudy.studies.fingerprints: a job's log and resources line, its
checked reader and stamp, and the source fingerprints."""
import numpy as np
import pytest
import xarray as xr

from builders import BLC06, FREQS, fake_spectrum
from rockstudy.analysis.spectra import AmplitudeGrid, Scenario
from rockstudy.core import io
from rockstudy.model.control import Control
from rockstudy.studies import datasets, fingerprints, jobs


def test_source_fingerprint_is_a_stable_sha256():
    a, b = fingerprints.source_fingerprint(), fingerprints.source_fingerprint()
    assert a == b and len(a) == 64


def test_a_job_log_ends_with_the_jobs_resources(tmp_path):
    """log_to's last line, written as the process ends, gives what the operating system counted: a job
    that computes for 0.4 s of CPU and holds 300 MB shows at least that CPU time, memory and run
    time."""
    import re
    import subprocess
    import sys

    log = tmp_path / "job.log"
    code = ("import time, numpy as np\n"
            "from rockstudy.studies import jobs\n"
            f"jobs.log_to({str(log)!r})\n"
            "a = np.ones(300 * 2**20 // 8)\n"
            "t = time.process_time()\n"
            "while time.process_time() - t < 0.4:\n"
            "    pass\n")
    subprocess.run([sys.executable, "-c", code], check=True)
    last = log.read_text().strip().splitlines()[-1]
    m = re.search(r"resources: ([\d.]+) s run time, ([\d.]+) s CPU \(user [\d.]+, system [\d.]+\), "
                  r"peak memory (\d+) MB", last)
    assert m, last
    wall, cpu, mb = float(m[1]), float(m[2]), float(m[3])
    assert cpu >= 0.4 and mb >= 300 and wall >= 0.4



@pytest.mark.parametrize("fails, watched", [(False, False), (True, False), (False, True)])
def test_run_ends_a_finished_job_at_once_and_a_failed_one_as_usual(tmp_path, fails, watched):
    """jobs.run: a script whose main returns leaves its output, its flushed standard output and one
    resources line, and exits 0 before the interpreter's teardown (an exit handler never runs); one
    whose main raises ends the ordinary way, with its traceback, the resources line and status 1; so
    does one a profiler watches (it writes its results at the exit), with status 0."""
    import os
    import subprocess
    import sys

    log, out, mark = tmp_path / "job.log", tmp_path / "out.txt", tmp_path / "teardown.txt"
    code = ("import atexit, logging, sys\n"
            f"if {watched}:\n    sys.setprofile(lambda *args: None)\n"
            "from rockstudy.studies import jobs\n"
            f"atexit.register(lambda: open({str(mark)!r}, 'w').close())\n"
            f"class Job:\n    log = [{str(log)!r}]\n    threads = 1\n    params = None\n"
            "def main(snakemake):\n"
            "    jobs.open_job(snakemake)\n"
            "    logging.getLogger('rockstudy').info('computed')\n"
            f"    with open({str(out)!r}, 'w') as f:\n        f.write('written')\n"
            "    print('kept', end='')\n"
            f"    if {fails}:\n        raise ValueError('a job that fails')\n"
            "jobs.run(main, Job())\n")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}  # stdout buffered, as in a job
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    lines = log.read_text().strip().splitlines()
    assert [line.split("rockstudy: ")[1] for line in lines][0] == "computed"
    assert sum("resources:" in line for line in lines) == 1 and "resources:" in lines[-1]
    assert out.read_text() == "written" and res.stdout == "kept"
    assert res.returncode == (1 if fails else 0), res.stderr
    assert ("ValueError: a job that fails" in res.stderr) == fails
    assert mark.exists() == (fails or watched)

# --- the checked reader ------------------------------------------------------------------------------
class StandIn:
    """What a job reads of Snakemake's object: log, params (with ``expect``), threads."""

    def __init__(self, log, **params):
        self.log = [str(log)]
        self.params = type("Params", (), params)()
        self.threads = 1


def spectrum_file(tmp_path, name="FS_R005.nc", strategy="FS", level=0.05):
    thresholds = np.array([[1.5, 1.6, 1.7, 1.8], [1.4, 1.9, 1.7, 2.0]])
    ds = datasets.document_missing(fake_spectrum(strategy, level, thresholds))
    ds = datasets.gather_spectra([ds])
    return io.write_netcdf(ds, tmp_path / name), ds


def expectation(strategy="FS", level=0.05):
    return datasets.expected_attrs(Scenario(BLC06, control=Control(strategy), noise_level=level),
                                   realisations=[0, 1], frequency_ratios=FREQS, amplitude_grid=AmplitudeGrid())


def test_the_job_reads_a_dataset_that_is_what_its_rule_expects(tmp_path):
    path, ds = spectrum_file(tmp_path)
    job = jobs.open_job(StandIn(tmp_path / "job.log", expect={str(path): expectation()}, library="abc"))
    read = job.read(path)
    np.testing.assert_array_equal(read["threshold"].values, ds["threshold"].values)
    assert job.stamp(read).attrs["rockstudy_source_sha256"] == "abc"


def test_the_job_refuses_another_strategy_an_input_without_expectation_and_a_truncated_file(tmp_path):
    path, _ = spectrum_file(tmp_path, "CS01.nc", strategy="CS01")
    job = jobs.open_job(StandIn(tmp_path / "job.log", expect={str(path): expectation("FS")}))
    with pytest.raises(io.DatasetMismatch, match=rf"{path}: control_strategy is 'CS01', expected 'FS'"):
        job.read(path)
    with pytest.raises(KeyError, match="no expectation"):
        job.read(tmp_path / "other.nc")
    path, ds = spectrum_file(tmp_path)
    io.write_netcdf(ds.isel(realisation=[0]), path)  # one realisation dropped, attributes kept
    with pytest.raises(io.DatasetMismatch, match=rf"{path}: realisation is \[0\], expected \[0, 1\]"):
        jobs.open_job(StandIn(tmp_path / "job.log", expect={str(path): expectation()})).read(path)


@pytest.mark.parametrize("edit, rule", [
    (lambda ds: ds.assign(threshold=ds["threshold"] * 1.5), "threshold is not the lowest threshold_realisation"),
    (lambda ds: ds.assign(**{name: ds[name] * 1.5 for name in ("threshold", "threshold_realisation",
                                                               "threshold_mean")}),
     "within grid_amplitude_resolution"),
    (lambda ds: ds.assign(threshold_mean=ds["threshold_mean"] + 0.1), "threshold_mean is not the mean"),
    (lambda ds: ds.assign_attrs(n_realisations=3), "n_realisations is 3 but the file holds 2"),
])
def test_an_edited_spectrum_is_refused_by_its_own_invariants(tmp_path, edit, rule):
    """A threshold multiplied by 1.5 with its attributes kept is what the step expects by its attributes;
    the spectrum's own invariants refuse it."""
    path, ds = spectrum_file(tmp_path)
    edited = edit(ds)
    for name in ds.data_vars:
        edited[name].attrs = ds[name].attrs
    io.write_netcdf(edited, path)
    job = jobs.open_job(StandIn(tmp_path / "job.log", expect={str(path): expectation()}))
    with pytest.raises(datasets.InconsistentDataset, match=rf"{path}: .*{rule}"):
        job.read(path)


def test_invariants_of_a_probability_surface_and_a_record_set():
    from rockstudy.model import record_suites

    entries = record_suites.load_suite("p695-far-field")[:2]
    records = record_suites.suite_dataset(entries, title="two records")
    datasets.check_invariants(records, "set.nc")
    doubled = records.assign(acceleration=records["acceleration"] * 2)
    with pytest.raises(datasets.InconsistentDataset, match="set.nc: pga is not the peak"):
        datasets.check_invariants(doubled, "set.nc")
    surface = xr.Dataset({"probability": ("f", [0.0, 0.5]), "n_overturned": ("f", [0, 1])},
                         coords={"n_realisations": 2})
    datasets.check_invariants(surface, "p.nc")
    with pytest.raises(datasets.InconsistentDataset, match="probability is not n_overturned"):
        datasets.check_invariants(surface.assign(probability=("f", [0.0, 1.0])), "p.nc")


def test_write_bytecode_writes_what_a_later_import_loads():
    """The byte-code of a module whose cached copy is gone is written again, where the import system looks
    for it."""
    import importlib.util
    import os

    from rockstudy.core import frames

    cached = importlib.util.cache_from_source(frames.__file__)
    if os.path.exists(cached):
        os.remove(cached)
    assert jobs.write_bytecode()
    assert os.path.getmtime(cached) >= os.path.getmtime(frames.__file__)
    spec = importlib.util.spec_from_file_location("frames_again", frames.__file__)
    assert spec.cached == cached
