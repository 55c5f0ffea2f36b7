"""The study workflow (Snakefile): config validation, the DAG of dry runs, the lint, and the tiny study's
spectra in chunks of one realisation (the whole tiny study runs in test_tiny_study.py)."""
import re
import shutil

import pytest
import yaml

from workflow_runs import ROOT, TEST_CONFIG, TINY, dry_run, snakemake

pytestmark = pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake is not installed")


def tiny_config():
    return yaml.safe_load(TEST_CONFIG.read_text())


def test_valid_tiny_config_dry_runs(tmp_path):
    res = dry_run(tiny_config(), tmp_path)
    assert res.returncode == 0, res.stderr + res.stdout
    assert "rule spectrum:" in res.stdout


def job_counts(stdout: str) -> dict:
    """Jobs per rule in a dry run's "Job stats" table."""
    table = stdout.split("Job stats:", 1)[1].split("\n\n", 1)[0]
    return {m.group(1): int(m.group(2)) for m in re.finditer(r"^(\w+)\s+(\d+)$", table, flags=re.MULTILINE)}


def test_default_study_writes_every_spectrum_in_its_simulation_job(tmp_path):
    """realisations_per_job >= realisations (config.yaml): one job per strategy writes its spectra at every
    noise level, no chunk and no gather job."""
    config = yaml.safe_load((ROOT / "config.yaml").read_text())
    assert config["realisations_per_job"] >= config["realisations"]
    res = dry_run(config, tmp_path, "--config", "results_dir=out")
    assert res.returncode == 0, res.stderr + res.stdout
    jobs = job_counts(res.stdout)
    n_levels, n_strategies = len(config["noise_levels"]), len(config["strategies"])
    assert jobs["spectrum"] == n_strategies
    job = re.search(r"rule spectrum:\n\s+input: [^\n]*\n\s+output: ([^\n]*)\n", res.stdout)
    assert job
    strategy = job.group(1).split(", ")[0].split("/")[-1].split("_")[0]
    files = sorted(f"out/spectra/{strategy}_{level}.nc" for level in config["noise_levels"])
    assert sorted(job.group(1).split(", ")) == files
    assert n_levels > 1
    # a strategy's timing sweep is one job, writing a spectrum per sampling time (per delay)
    assert jobs["spectrum_sampling"] == len(config["sampling_sweep"]["strategies"])
    assert jobs["spectrum_delay"] == len(config["delay_sweep"]["strategies"])
    sweep = re.search(r"rule spectrum_sampling:\n\s+input: [^\n]*\n\s+output: ([^\n]*)\n", res.stdout)
    assert sweep
    files = sweep.group(1).split(", ")
    strategy = files[0].split("/")[-1].split("_")[0]
    level = config["sampling_sweep"]["noise_level"]
    assert sorted(files) == sorted(f"out/timing/sampling/{strategy}_{level}_Ts{ts:g}.nc"
                                   for ts in config["sampling_sweep"]["sampling_times"])
    assert not {rule for rule in jobs if rule.startswith("gather_") or rule == "spectrum_chunk"}, jobs
    assert "spectra/chunks/" not in res.stdout


def test_the_compile_starts_first_then_the_longest_scans(tmp_path):
    """Snakemake priorities: both compile jobs of the threshold scans before anything else, then the scan jobs
    by how many noisy spectra each computes (the longest first: the last jobs leave no core idle long)."""
    config = yaml.safe_load((ROOT / "config.yaml").read_text())
    res = dry_run(config, tmp_path, "--config", "results_dir=out")
    assert res.returncode == 0, res.stderr + res.stdout
    priority = {}
    for rule, value in re.findall(r"rule (\w+):\n(?:\s+\w+: [^\n]*\n)*?\s+priority: (\d+)\n", res.stdout):
        priority.setdefault(rule, set()).add(int(value))
    assert priority["compile_engine"] == priority["compile_engine_parts"] == {100}
    noisy = len(config["noise_levels"]) - 1
    sampling, delays = len(config["sampling_sweep"]["sampling_times"]), len(config["delay_sweep"]["delays"])
    assert (priority["spectrum_sampling"], priority["spectrum"], priority["spectrum_delay"]) == (
        {1 + sampling}, {1 + noisy}, {1 + delays})
    assert sampling > noisy > delays
    assert all(p <= {0} for rule, p in priority.items() if rule.startswith(("figure_", "table")))


def test_chunked_study_gathers_the_noisy_spectra(tmp_path):
    """realisations_per_job < realisations: the noisy spectra in chunks, gathered; the noise-free one (one
    realisation) still written by its job."""
    res = dry_run(tiny_config(), tmp_path, "--config", "results_dir=out", "realisations_per_job=1")
    assert res.returncode == 0, res.stderr + res.stdout
    jobs = job_counts(res.stdout)
    config = tiny_config()
    n_strategies, n_real = len(config["strategies"]), config["realisations"]
    n_sampling = len(config["sampling_sweep"]["strategies"]) * len(config["sampling_sweep"]["sampling_times"])
    n_delay = len(config["delay_sweep"]["strategies"]) * len(config["delay_sweep"]["delays"])
    assert jobs["spectrum"] == n_strategies  # the noise-free level
    assert jobs["gather_spectrum"] == n_strategies  # the one noisy level
    assert (jobs["gather_sampling"], jobs["gather_delay"]) == (n_sampling, n_delay)
    assert jobs["spectrum_chunk"] == n_real * (n_strategies + n_sampling + n_delay)
    assert "spectrum_sampling" not in jobs and "spectrum_delay" not in jobs
    assert re.search(r"rule gather_spectrum:\n\s+input: out/spectra/chunks/FS_R005_Ts0_d0_c0\.nc, "
                     r"out/spectra/chunks/FS_R005_Ts0_d0_c1\.nc\n\s+output: out/spectra/FS_R005\.nc", res.stdout)


@pytest.mark.parametrize("change, key", [
    (lambda c: c.update(unknown_key=1), "unknown_key"),
    (lambda c: c.update(realisations=-1), "realisations"),
    (lambda c: c["amplitude_grid"].update(step="0.1"), "step"),
    (lambda c: c["sampling_sweep"].update(frequency=1.0), "frequency"),
    (lambda c: c["delay_sweep"].update(noise_level="R999"), "delay_sweep.noise_level"),
    # refused by the config check before any job, not in the first job
    (lambda c: c.update(free_time=float("nan")), "free_time"),
    (lambda c: c.update(seed=2**70), "seed"),
    (lambda c: c.update(block={"width": 1.6, "height": 0.4, "depth": 1.0}), "block.restitution"),
    (lambda c: c["frequency_grid"].update(step=1e-9), "frequency_grid.step"),
])
def test_invalid_config_stops_before_any_job_naming_the_key(tmp_path, change, key):
    config = tiny_config()
    change(config)
    res = dry_run(config, tmp_path)
    assert res.returncode != 0
    assert key in res.stderr + res.stdout
    assert "Job stats" not in res.stdout and not (tmp_path / "results").exists()


def test_lint_is_clean(tmp_path):
    res = snakemake("--lint", workdir=ROOT)
    assert res.returncode == 0 and "Congratulations" in res.stdout + res.stderr, res.stdout + res.stderr


def reading_jobs(stdout: str) -> set:
    """The readings whose spectra a dry run would compute (``reading=<name>`` of the reading_spectrum jobs)."""
    return set(re.findall(r"wildcards: strategy=\w+, reading=(\w+), level=", stdout))


@pytest.mark.parametrize("change, computed", [
    (lambda c: None, {"rescale_none"}),  # step2p5ms is the tiny study's own reading: reused
    (lambda c: c["noise"].update(rescale="none"), {"step2p5ms"}),  # now rescale_none is the study's
    (lambda c: c["reproduction"].update(realisations=3), {"step2p5ms", "rescale_none"}),  # other records
    (lambda c: c["noise"].update(span=1.0), {"step2p5ms", "rescale_none"}),  # no reading equals the study's
])
def test_readings_study_reuses_the_study_spectra_of_its_own_reading(tmp_path, change, computed):
    config = tiny_config()
    change(config)
    res = dry_run(config, tmp_path, "reproduction", "--config", "results_dir=out")
    assert res.returncode == 0, res.stderr + res.stdout
    assert reading_jobs(res.stdout) == computed
    reused = {"step2p5ms", "rescale_none"} - computed
    if reused:  # the readings table reads the study's gathered spectrum instead
        assert re.search(r"rule readings_table:\n\s+input: [^\n]*out/spectra/FS_R005\.nc", res.stdout), res.stdout


@pytest.mark.slow
def test_reused_study_spectrum_equals_the_readings_study_own(tmp_path):
    """The study's gathered FS spectrum (two chunks of one realisation) that the readings study now reuses
    is bit for bit the spectrum the readings study would compute itself in one job, and the readings
    table's J_OS is the one of that spectrum."""
    import xarray as xr

    from rockstudy.studies import noise_readings as readings

    out = tmp_path / "out"
    own = out / "reproduction" / "readings" / "spectra" / "FS_step2p5ms_R005.nc"
    res = snakemake("-j2", *TINY, "--config", f"results_dir={out}", "realisations_per_job=1", "--",
                    "reproduction", str(own), workdir=tmp_path)
    assert res.returncode == 0, res.stderr[-5000:]
    with xr.open_dataset(own) as a, xr.open_dataset(out / "spectra" / "FS_R005.nc") as b:
        for name in ("threshold", "threshold_realisation", "energy_ratio", "pga_ratio", "n_undetermined"):
            assert a[name].values.tobytes() == b[name].values.tobytes(), name
        with xr.open_dataset(out / "spectra" / "FS_R000.nc") as ref, \
                xr.open_dataset(out / "reproduction" / "readings" / "readings.nc") as table:
            j, _ = readings.jos_against(a, ref, 1.0)
            assert float(table["j_os"].sel(reading="step2p5ms", noise_level="R005")) == j


@pytest.mark.slow
def test_a_swapped_chunk_stops_the_gather_naming_the_file_and_attribute(tmp_path):
    """A CS01 chunk copied over an FS chunk is not gathered into a right-looking FS spectrum: the gather
    stops naming the file and control_strategy, and writes no spectrum."""
    out = tmp_path / "out"
    chunked = ("--config", f"results_dir={out}", "realisations_per_job=1", "--")
    chunks = out / "spectra" / "chunks"
    made = snakemake("-j2", *TINY, *chunked, *(str(chunks / f"{s}_R005_Ts0_d0_c{c}.nc") for s in ("FS", "CS01")
                                              for c in (0, 1)), workdir=tmp_path)
    assert made.returncode == 0, made.stderr[-3000:]
    swapped = chunks / "FS_R005_Ts0_d0_c0.nc"
    shutil.copyfile(chunks / "CS01_R005_Ts0_d0_c0.nc", swapped)
    res = snakemake("-j1", *TINY, *chunked, str(out / "spectra" / "FS_R005.nc"), workdir=tmp_path)
    log = res.stdout + res.stderr
    assert res.returncode != 0
    assert f"{swapped}: control_strategy is 'CS01', expected 'FS'" in log, log[-3000:]
    assert not (out / "spectra" / "FS_R005.nc").exists()


RULE_HEADER = re.compile(r"^\s*(?:rule(?: (\w+))?|use rule (\w+) as (\w+) with):", re.M)


def rule_blocks() -> dict:
    """{rule: (its text, the rule it is derived from or None)} of every rule in workflow/rules/*.smk and the
    Snakefile, the text running from its header to the next rule's."""
    blocks = {}
    for path in [ROOT / "Snakefile", *sorted((ROOT / "workflow" / "rules").glob("*.smk"))]:
        text = path.read_text(encoding="utf-8")
        heads = list(RULE_HEADER.finditer(text))
        for k, m in enumerate(heads):
            end = heads[k + 1].start() if k + 1 < len(heads) else len(text)
            name = m.group(1) or m.group(3) or f"{path.name}:{text.count(chr(10), 0, m.start()) + 1}"  # rule: name:
            blocks[name] = (text[m.start():end], m.group(2))
    return blocks


def test_every_rule_writing_with_the_report_code_reruns_when_it_changes():
    """A rule whose script writes tables or pages with rockstudy.report carries the report package's
    fingerprint (``REPORT_CODE``) among its params, so that a change to that code rewrites what it wrote."""
    scripts = {p.name for p in (ROOT / "workflow" / "scripts").glob("*.py")
               if re.search(r"rockstudy\.report|from rockstudy import report", p.read_text(encoding="utf-8"))}
    blocks = rule_blocks()
    checked, missing = 0, []
    for name, (text, parent) in blocks.items():
        own = re.search(r'script:\s*\n\s*"\.\./scripts/(\w+\.py)"', text)
        script = own.group(1) if own else None
        if script is None and parent in blocks:
            inherited = re.search(r'script:\s*\n\s*"\.\./scripts/(\w+\.py)"', blocks[parent][0])
            script = inherited.group(1) if inherited else None
        if script not in scripts:
            continue
        checked += 1
        params = text if "params:" in text or parent is None else blocks[parent][0]
        if "REPORT_CODE" not in params:
            missing.append(f"{name} ({script})")
    assert checked >= 7 and not missing, f"{checked} rules checked; without REPORT_CODE: {missing}"
