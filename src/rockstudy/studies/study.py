"""The edge between the workflow and the library: the one check of a whole study config
(:func:`check_study`, which calls each section's own check), the source fingerprints that make
Snakemake rerun what a code change affects, and job logging (paper §4–5).

It takes plain ``dict``/``list`` values, never a config file name; the parsers from dicts to the
library's dataclasses are in :mod:`rockstudy.studies.parameters`, the labelled datasets in
:mod:`rockstudy.studies.datasets`, the J_OS tables in :mod:`rockstudy.studies.tables`. Amplitudes are
ratios a_p/(g·tanα), frequencies ratios ω_p/p; a_max,0 is given in units of g.
"""
from __future__ import annotations

import atexit
import hashlib
import logging
import math
import os
import time
from pathlib import Path

try:
    import resource
except ImportError:  # not on Windows: the resources line then gives the run time only
    resource = None

from rockstudy.core import validation
from rockstudy.studies.parameters import (
    amplitude_grid,
    block_from_dict,
    frequency_ratios,
    grid_size_points,
    noise_free_level,
    scenario_from_dict,
)

SIMULATION_LAYERS = ("core", "model", "engine", "analysis")
"""The subpackages whose code can change a simulated number: the workflow reruns every simulation when
one of them changes (the study's bookkeeping, the figures and the CLI are fingerprinted on their own)."""

NOT_SIMULATED = ("engine/reference",)
"""Folders inside :data:`SIMULATION_LAYERS` that no study result runs: the scipy reference engine, which
the tests compare with the fast engine."""


def fingerprint_files(*parts: str) -> list[Path]:
    """The source files :func:`source_fingerprint` hashes, relative to the package, in a fixed order."""
    root = Path(__file__).resolve().parents[1]
    files = []
    for part in parts or SIMULATION_LAYERS:
        target = root / part
        if not target.exists():
            raise ValueError(f"source_fingerprint: {part!r} is not a folder or module of rockstudy")
        for path in sorted(target.rglob("*.py")) if target.is_dir() else [target]:
            name = path.relative_to(root).as_posix()
            if parts or not any(name.startswith(f"{skip}/") for skip in NOT_SIMULATED):
                files.append(Path(name))
    return files


def source_fingerprint(*parts: str) -> str:
    """SHA-256 of the package's sources under ``parts``: subpackage folders (``"engine"``) or module files
    (``"report.py"``), relative to the package; none given: :data:`SIMULATION_LAYERS` without
    :data:`NOT_SIMULATED`.

    Snakemake passes it to a rule as a parameter, so the rule reruns when that code changes. Folders,
    not file lists: a new module is covered by its layer's fingerprint without editing the workflow."""
    root = Path(__file__).resolve().parents[1]
    digest = hashlib.sha256()
    for name in fingerprint_files(*parts):
        digest.update(name.as_posix().encode())
        digest.update((root / name).read_bytes())
    return digest.hexdigest()


def log_to(path) -> logging.Logger:
    """Send the "rockstudy" logger (progress, ETA) to ``path``; when the job's process ends, its last
    line gives the job's resources (:func:`resources`: run time, CPU time, peak memory)."""
    handler = logging.FileHandler(path, mode="w")
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s"))
    logger = logging.getLogger("rockstudy")
    logger.addHandler(handler)
    logger.setLevel(logging.INFO)
    atexit.unregister(_log_resources)  # one resources line, however often a job calls log_to
    atexit.register(_log_resources, logger)
    return logger


def resources() -> dict:
    """What this process has used so far, from the operating system's own accounts (nothing sampled):
    ``wall_s`` since it started, ``cpu_s`` (user + system; ``user_s``, ``system_s``) and ``max_rss_mb``,
    its peak resident memory. [s, MB]"""
    if resource is None:
        return {"wall_s": _process_age(), "cpu_s": time.process_time(), "user_s": math.nan, "system_s": math.nan,
                "max_rss_mb": math.nan}
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return {"wall_s": _process_age(), "cpu_s": usage.ru_utime + usage.ru_stime, "user_s": usage.ru_utime,
            "system_s": usage.ru_stime, "max_rss_mb": usage.ru_maxrss / 1024.0}  # ru_maxrss: kB on Linux


_STARTED = time.monotonic()


def _process_age() -> float:
    """Seconds since this process started (Linux: from /proc; elsewhere since rockstudy was imported)."""
    try:
        with open("/proc/self/stat") as f:
            start_ticks = int(f.read().rsplit(")", 1)[1].split()[19])  # field 22, starttime
        with open("/proc/uptime") as f:
            uptime = float(f.read().split()[0])
        return max(0.0, uptime - start_ticks / os.sysconf("SC_CLK_TCK"))
    except (OSError, ValueError, IndexError):
        return time.monotonic() - _STARTED


def _log_resources(logger: logging.Logger) -> None:
    r = resources()
    logger.info("resources: %.1f s run time, %.1f s CPU (user %.1f, system %.1f), peak memory %.0f MB",
                r["wall_s"], r["cpu_s"], r["user_s"], r["system_s"], r["max_rss_mb"])


def _non_finite(value, key=""):
    """(key path, value) of every NaN or inf number in a nested config."""
    if isinstance(value, dict):
        return [k for name, item in value.items() for k in _non_finite(item, f"{key}.{name}" if key else str(name))]
    if isinstance(value, (list, tuple)):
        return [k for i, item in enumerate(value) for k in _non_finite(item, f"{key}[{i}]")]
    if isinstance(value, float) and not math.isfinite(value):
        return [(key, value)]
    return []


def check_sizes(config: dict) -> None:
    """No list or mapping of the config has more than :data:`~rockstudy.core.validation.MAX_LIST_ITEMS`
    entries (a record suite :data:`~rockstudy.core.validation.MAX_SUITE_RECORDS`): run before the JSON
    schema, whose ``uniqueItems`` takes quadratic time on a long list.

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) naming the key path.
    """
    validation.check_sizes(config, limits={"beyond.fragility.records": validation.MAX_SUITE_RECORDS})


def check_study(config: dict) -> None:
    """Checks a JSON schema cannot express, before any job runs; the message names the offending key.

    Beyond the schema: no NaN or inf anywhere; integers that netCDF can store; a slender block
    (or an explicit restitution); the upper bounds of :mod:`rockstudy.core.validation` on every value
    that becomes an array size, a loop count or a time span (grid points, simulations and noise
    memory of one spectrum job, time span and integrator steps of one simulation, controller
    samples); and the cross-key rules (noise levels, strategies, a_max,0 within the scan).

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) naming the key, the value and what is allowed.
    """
    # the sections' checks and the model's limits, imported here: a job that only logs or fingerprints
    # (every workflow script) does not load the compiled model
    from rockstudy.model.excitation import check_time_span, excitation_duration
    from rockstudy.model.noise import reading_from_dict
    from rockstudy.model.sensor import SENSOR_STEP, check_band
    from rockstudy.studies import beyond, device_calibration, noise_readings

    check_sizes(config)
    validation.check_results_dir("results_dir", config["results_dir"])
    bad = _non_finite(config)
    if bad:
        key, value = bad[0]
        validation.fail(key, value, "every number must be finite (not NaN or inf)"
                        + (f"; also non-finite: {', '.join(k for k, _ in bad[1:])}" if len(bad) > 1 else ""))
    levels = config["noise_levels"]
    noise_free_level(levels)
    for key in ("convergence", "sampling_sweep", "delay_sweep", "example_point"):
        if config[key]["noise_level"] not in levels:
            raise validation.InputError(f"{key}.noise_level: {config[key]['noise_level']!r} is not one of noise_levels "
                                        f"({', '.join(levels)})")
    for key in ("table1", "maps", "control_histories", "sampling_sweep", "delay_sweep"):
        missing = set(config[key]["strategies"]) - set(config["strategies"])
        if missing:
            raise validation.InputError(f"{key}.strategies: {sorted(missing)} not in strategies {config['strategies']}")
    if "FS" not in config["strategies"]:
        raise validation.InputError("strategies: FS is needed as the reference of Table 1 and of the timing tables")
    n_real = validation.check_int_range("realisations", config["realisations"], 1, validation.MAX_REALISATIONS)
    per_job = validation.check_int_range("realisations_per_job", config["realisations_per_job"], 1,
                                         validation.MAX_REALISATIONS)
    validation.check_int_range("seed", config["seed"], 0, validation.MAX_INTEGER,
                               why="stored as a netCDF int64 attribute")
    validation.check_int_range("noise_records_stored", config["noise_records_stored"], 1, validation.MAX_REALISATIONS)
    too_high = [k for k in config["example_point"]["realisations"] if k >= n_real]
    if too_high:
        raise validation.InputError(f"example_point.realisations: {too_high} >= realisations ({n_real})")
    block = block_from_dict(config["block"])
    free_time = validation.check_nonnegative("free_time", config["free_time"], "s", validation.MAX_FREE_TIME)
    ag = config["amplitude_grid"]
    sims_per_case = validation.check_amplitude_grid(ag["start"], ag["stop"], ag["step"], ag["resolution"])
    top = amplitude_grid(ag).values()[-1]
    validation.check_a_max0("a_max0", config["a_max0"], block.alpha, top)
    fg = config["frequency_grid"]
    n_freq = validation.check_grid("frequency_grid", fg["start"], fg["stop"], fg["step"],
                                   high=validation.MAX_FREQUENCY_RATIO)
    an = config["anchorage"]
    for key, limit in (("kappa_max", validation.MAX_KAPPA), ("kappa_min", validation.MAX_KAPPA),
                       ("damping_ratio", validation.MAX_DAMPING_RATIO)):
        validation.check_nonnegative(f"anchorage.{key}", an[key], high=limit)
    scenario_from_dict({"block": config["block"], "anchorage": an})
    for key in ("control_histories", "example_point"):
        validation.check_positive(f"{key}.frequency_ratio", config[key]["frequency_ratio"],
                                  high=validation.MAX_FREQUENCY_RATIO)
        validation.check_positive(f"{key}.amplitude_ratio", config[key]["amplitude_ratio"],
                                  high=validation.MAX_AMPLITUDE_RATIO)
    validation.check_positive("noise_reference_frequency_ratio", config["noise_reference_frequency_ratio"],
                              high=validation.MAX_FREQUENCY_RATIO)
    for i, ts in enumerate(config["sampling_sweep"]["sampling_times"]):
        validation.check_positive(f"sampling_sweep.sampling_times[{i}]", ts, "s", validation.MAX_TIME_SPAN)
    validation.check_positive("delay_sweep.sampling_time", config["delay_sweep"]["sampling_time"], "s",
                              validation.MAX_TIME_SPAN)
    for i, d in enumerate(config["delay_sweep"]["delays"]):
        validation.check_positive(f"delay_sweep.delays[{i}]", d, "s", validation.MAX_TIME_SPAN)
    freqs = frequency_ratios(fg)
    grid_name = "frequency_grid.start" if fg["start"] < 1 else "frequency_grid.stop"
    span_freqs = [fg["start"], float(freqs[-1])]  # the user's start (the grid rounds to 10 decimals)
    try:
        reading = reading_from_dict(config["noise"], key="noise")
    except ValueError as exc:
        raise validation.InputError(str(exc)) from None
    # the noisy records last noise.span longer and have (duration + span) / noise.step samples
    check_time_span(block, config["excitation"], span_freqs, free_time, frequency_name=grid_name,
                    record_step=reading.step, record_span=reading.span)
    for key in ("control_histories.frequency_ratio", "example_point.frequency_ratio",
                "noise_reference_frequency_ratio"):
        node = config
        for part in key.split("."):
            node = node[part]
        check_time_span(block, config["excitation"], [node], free_time, frequency_name=key)
    for ts, name in ([(t, f"sampling_sweep.sampling_times[{i}]")
                      for i, t in enumerate(config["sampling_sweep"]["sampling_times"])]
                     + [(config["delay_sweep"]["sampling_time"], "delay_sweep.sampling_time")]):
        check_time_span(block, config["excitation"], span_freqs, free_time, ts, frequency_name=grid_name,
                          sampling_name=name)
    # one spectrum job: its realisations x frequencies, and the noise records it holds
    per_job = min(per_job, n_real)
    samples = validation.record_samples((excitation_duration(config["excitation"], f * block.p) for f in freqs),
                               reading.step, reading.span)
    validation.check_workload("realisations_per_job", config["realisations_per_job"], per_job * n_freq, sims_per_case,
                     per_job * samples * validation.RECORD_BYTES_PER_SAMPLE)
    n_chunks = -(-n_real // per_job)
    if n_chunks > validation.MAX_JOBS_PER_SPECTRUM:
        validation.fail("realisations_per_job", config["realisations_per_job"],
               f"realisations = {n_real} in jobs of {per_job} gives {n_chunks} jobs per spectrum, the limit is "
               f"{validation.MAX_JOBS_PER_SPECTRUM} (Snakemake's DAG would grow too large); use larger jobs")
    validation.check_workload("amplitude_grid.step", ag["step"], n_freq, grid_size_points(ag), 0)
    band = config["control"]["sensor_band"]
    if band is not None:  # the sensor reads the noisy records at noise.step, the analytic excitation at SENSOR_STEP
        try:
            check_band(band, max(reading.step, SENSOR_STEP), "control.sensor_band")
        except ValueError as exc:
            raise validation.InputError(str(exc)) from None
    noise_readings.check_config(config["reproduction"], {
        "block": block, "excitation": config["excitation"], "free_time": free_time, "frequency_ratios": freqs,
        "sims_per_case": sims_per_case})
    device_calibration.check_config(config["calibration"], block.alpha, sims_per_case)
    if config.get("beyond"):
        beyond.check_config(config["beyond"], config)
    if config.get("design"):
        from rockstudy.studies import design
        design.check_config(config["design"])


