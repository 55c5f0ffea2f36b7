"""The edge between the workflow and the library: the study's parameters from plain
dictionaries, the checks across config keys that a JSON schema cannot express, the source
fingerprints that make Snakemake rerun what a code change affects, and job logging (paper §4–5).

It takes plain ``dict``/``list`` values, never a config file name, and returns the library's
dataclasses. The labelled datasets are built in :mod:`rockstudy.datasets`, the J_OS tables in
:mod:`rockstudy.tables`. Amplitudes are ratios a_p/(g·tanα), frequencies ratios ω_p/p; a_max,0 is
given in units of g.
"""
from __future__ import annotations

import hashlib
import logging
import math
from pathlib import Path

import numpy as np
import xarray as xr

from . import validation as v
from .anchorage import Anchorage
from .block import BLOCK_PRESETS, Block
from .control import Control
from .excitation import excitation_duration
from .noise import reading_from_dict
from .scenario import Scenario
from .sensor import SENSOR_STEP, check_band
from .spectra import AmplitudeGrid, frequency_grid


def block_from_dict(spec: dict) -> Block:
    """A :class:`Block` from ``{"preset": name}`` or from its dimensions (``width``, ``height``, ...)."""
    spec = dict(spec)
    preset = spec.pop("preset", None)
    if preset is not None:
        if preset not in BLOCK_PRESETS:
            raise ValueError(f"block.preset must be one of {', '.join(BLOCK_PRESETS)}, got {preset!r}")
        if spec:
            raise ValueError(f"block: give either a preset or dimensions, not both (got {sorted(spec)})")
        return BLOCK_PRESETS[preset]
    try:
        return Block(**spec)
    except (TypeError, ValueError) as exc:
        raise v.InputError(str(exc).replace("Block.", "block.").replace("Block:", "block:")) from None


def scenario_from_dict(spec: dict) -> Scenario:
    """A :class:`Scenario` from ``block``, ``anchorage``, ``control``, ``noise`` dicts and scalar settings.

    ``noise`` is the noise reading (``step``, ``rescale``, ``level_means``, ``band``, ``span``;
    :class:`rockstudy.noise.NoiseReading`); absent: today's default reading."""
    spec = dict(spec)
    block = block_from_dict(spec.pop("block"))
    try:
        anchorage = Anchorage(**spec.pop("anchorage", {}))
    except ValueError as exc:
        raise v.InputError(str(exc).replace("Anchorage.", "anchorage.")) from None
    control = Control(**spec.pop("control", {}))
    noise = reading_from_dict(spec.pop("noise", None))
    return Scenario(block, anchorage, control, noise=noise, **spec)


def amplitude_grid(spec: dict) -> AmplitudeGrid:
    """:class:`AmplitudeGrid` from ``start``, ``stop``, ``step``, ``resolution`` (ratios a_p/(g·tanα)),
    refused (naming ``amplitude_grid.<key>``) beyond the limits of :mod:`rockstudy.validation`."""
    v.check_amplitude_grid(spec["start"], spec["stop"], spec["step"], spec["resolution"])
    return AmplitudeGrid(**spec)


def frequency_ratios(spec: dict) -> np.ndarray:
    """Frequency ratios ω_p/p from ``start``, ``stop``, ``step``, refused (naming ``frequency_grid.<key>``)
    above :data:`rockstudy.validation.MAX_GRID_POINTS` points before the grid is built. [-]"""
    v.check_grid("frequency_grid", spec["start"], spec["stop"], spec["step"], high=v.MAX_FREQUENCY_RATIO)
    return frequency_grid(**spec)


def realisation_chunks(n_realisations: int, per_job: int, noisy: bool = True) -> list[list[int]]:
    """Realisation indices split into jobs of at most ``per_job`` (one job [0] without noise)."""
    if n_realisations < 1 or per_job < 1:
        raise ValueError(f"n_realisations and per_job must be >= 1, got {n_realisations}, {per_job}")
    if not noisy:
        return [[0]]
    return [list(range(i, min(i + per_job, n_realisations))) for i in range(0, n_realisations, per_job)]


def noise_free_level(levels: dict) -> str:
    """Name of the noise level whose value is 0 (the paper's R000)."""
    names = [name for name, value in levels.items() if value == 0]
    if len(names) != 1:
        raise ValueError(f"noise_levels needs exactly one level equal to 0 (R000), got {levels!r}")
    return names[0]


def a_max0_ratio(ds: xr.Dataset, a_max0_g: float, name: str = "a_max0") -> float:
    """a_max,0 given in units of g as an amplitude ratio a/(g·tanα), refused (naming ``name``) when it is
    not positive or lies above the amplitude scan's top recorded in ``ds`` (see
    :func:`rockstudy.validation.check_a_max0`). [-]"""
    top = v.scan_top(ds.attrs["grid_amplitude_start"], ds.attrs["grid_amplitude_stop"], ds.attrs["grid_amplitude_step"])
    return v.check_a_max0(name, a_max0_g, float(ds.attrs["block_alpha"]), top,
                          "the spectrum's scan top, grid_amplitude_stop")


NOT_IN_SIMULATIONS = ("cli.py", "plotting.py", "study.py", "datasets.py", "tables.py", "validation.py",
                      "reference/__init__.py", "reference/controller.py", "reference/crossings.py",
                      "reference/dynamics.py", "reference/events.py", "reference/ground.py",
                      "reference/piece.py", "reference/recorder.py", "reference/run.py",
                      "records.py", "synthetic.py", "fragility.py", "probability.py",
                      "readings.py", "claims.py", "calibration.py")


"""Modules the compiled spectra and histories do not run (the scipy reference engine, the CLI,
figures, this bookkeeping module, whose outputs have their own tests, the input checks, which
refuse inputs but never change a result, the studies beyond the paper and the reproduction
bookkeeping (readings, claims, calibration), which the workflow fingerprints on their own)."""


def source_fingerprint(only=None) -> str:
    """SHA-256 of the package's simulation sources: changes whenever the physics code changes.

    ``only``: a list of module file names to hash instead (e.g. ``["study.py"]``, the
    bookkeeping that builds the gathered datasets and tables)."""
    digest = hashlib.sha256()
    root = Path(__file__).parent
    for path in sorted(root.rglob("*.py")):  # recursive: the compiled engine is a subpackage
        name = path.relative_to(root).as_posix()
        if (name in NOT_IN_SIMULATIONS) if only is None else (name not in only):
            continue
        digest.update(name.encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()


def log_to(path) -> logging.Logger:
    """Send the "rockstudy" logger (progress, ETA) to ``path``."""
    handler = logging.FileHandler(path, mode="w")
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s"))
    logger = logging.getLogger("rockstudy")
    logger.addHandler(handler)
    logger.setLevel(logging.INFO)
    return logger


def _non_finite(value, key=""):
    """(key path, value) of every NaN or inf number in a nested config."""
    if isinstance(value, dict):
        return [k for name, item in value.items() for k in _non_finite(item, f"{key}.{name}" if key else str(name))]
    if isinstance(value, (list, tuple)):
        return [k for i, item in enumerate(value) for k in _non_finite(item, f"{key}[{i}]")]
    if isinstance(value, float) and not math.isfinite(value):
        return [(key, value)]
    return []


def check_study(config: dict) -> None:
    """Checks a JSON schema cannot express, before any job runs; the message names the offending key.

    Beyond the schema: no NaN or inf anywhere; integers that netCDF can store; a slender block
    (or an explicit restitution); the upper bounds of :mod:`rockstudy.validation` on every value
    that becomes an array size, a loop count or a time span (grid points, simulations and noise
    memory of one spectrum job, time span and integrator steps of one simulation, controller
    samples); and the cross-key rules (noise levels, strategies, a_max,0 within the scan).

    Raises
    ------
    ValueError
        (:class:`rockstudy.validation.InputError`) naming the key, the value and what is allowed.
    """
    bad = _non_finite(config)
    if bad:
        key, value = bad[0]
        v.fail(key, value, "every number must be finite (not NaN or inf)"
               + (f"; also non-finite: {', '.join(k for k, _ in bad[1:])}" if len(bad) > 1 else ""))
    levels = config["noise_levels"]
    noise_free_level(levels)
    for key in ("convergence", "sampling_sweep", "delay_sweep", "example_point"):
        if config[key]["noise_level"] not in levels:
            raise v.InputError(f"{key}.noise_level: {config[key]['noise_level']!r} is not one of noise_levels "
                               f"({', '.join(levels)})")
    for key in ("table1", "maps", "control_histories", "sampling_sweep", "delay_sweep"):
        missing = set(config[key]["strategies"]) - set(config["strategies"])
        if missing:
            raise v.InputError(f"{key}.strategies: {sorted(missing)} not in strategies {config['strategies']}")
    if "FS" not in config["strategies"]:
        raise v.InputError("strategies: FS is needed as the reference of Table 1 and of the timing tables")
    n_real = v.check_int_range("realisations", config["realisations"], 1, v.MAX_REALISATIONS)
    per_job = v.check_int_range("realisations_per_job", config["realisations_per_job"], 1, v.MAX_REALISATIONS)
    v.check_int_range("seed", config["seed"], 0, v.MAX_INTEGER, why="stored as a netCDF int64 attribute")
    v.check_int_range("noise_records_stored", config["noise_records_stored"], 1, v.MAX_REALISATIONS)
    too_high = [k for k in config["example_point"]["realisations"] if k >= n_real]
    if too_high:
        raise v.InputError(f"example_point.realisations: {too_high} >= realisations ({n_real})")
    block = block_from_dict(config["block"])
    free_time = v.check_nonnegative("free_time", config["free_time"], "s", v.MAX_FREE_TIME)
    ag = config["amplitude_grid"]
    sims_per_case = v.check_amplitude_grid(ag["start"], ag["stop"], ag["step"], ag["resolution"])
    top = amplitude_grid(ag).values()[-1]
    v.check_a_max0("a_max0", config["a_max0"], block.alpha, top)
    fg = config["frequency_grid"]
    n_freq = v.check_grid("frequency_grid", fg["start"], fg["stop"], fg["step"], high=v.MAX_FREQUENCY_RATIO)
    an = config["anchorage"]
    for key, limit in (("kappa_max", v.MAX_KAPPA), ("kappa_min", v.MAX_KAPPA), ("damping_ratio", v.MAX_DAMPING_RATIO)):
        v.check_nonnegative(f"anchorage.{key}", an[key], high=limit)
    scenario_from_dict({"block": config["block"], "anchorage": an})
    for key in ("control_histories", "example_point"):
        v.check_positive(f"{key}.frequency_ratio", config[key]["frequency_ratio"], high=v.MAX_FREQUENCY_RATIO)
        v.check_positive(f"{key}.amplitude_ratio", config[key]["amplitude_ratio"], high=v.MAX_AMPLITUDE_RATIO)
    v.check_positive("noise_reference_frequency_ratio", config["noise_reference_frequency_ratio"],
                     high=v.MAX_FREQUENCY_RATIO)
    for i, ts in enumerate(config["sampling_sweep"]["sampling_times"]):
        v.check_positive(f"sampling_sweep.sampling_times[{i}]", ts, "s", v.MAX_TIME_SPAN)
    v.check_positive("delay_sweep.sampling_time", config["delay_sweep"]["sampling_time"], "s", v.MAX_TIME_SPAN)
    for i, d in enumerate(config["delay_sweep"]["delays"]):
        v.check_positive(f"delay_sweep.delays[{i}]", d, "s", v.MAX_TIME_SPAN)
    freqs = frequency_ratios(fg)
    grid_name = "frequency_grid.start" if fg["start"] < 1 else "frequency_grid.stop"
    span_freqs = [fg["start"], float(freqs[-1])]  # the user's start (the grid rounds to 10 decimals)
    v.check_time_span(block, config["excitation"], span_freqs, free_time, frequency_name=grid_name)
    for key in ("control_histories.frequency_ratio", "example_point.frequency_ratio",
                "noise_reference_frequency_ratio"):
        node = config
        for part in key.split("."):
            node = node[part]
        v.check_time_span(block, config["excitation"], [node], free_time, frequency_name=key)
    for ts, name in ([(t, f"sampling_sweep.sampling_times[{i}]")
                      for i, t in enumerate(config["sampling_sweep"]["sampling_times"])]
                     + [(config["delay_sweep"]["sampling_time"], "delay_sweep.sampling_time")]):
        v.check_time_span(block, config["excitation"], span_freqs, free_time, ts, frequency_name=grid_name,
                          sampling_name=name)
    # one spectrum job: its realisations x frequencies, and the noise records it holds
    per_job = min(per_job, n_real)
    samples = v.record_samples(excitation_duration(config["excitation"], f * block.p) for f in freqs)
    v.check_workload("realisations_per_job", config["realisations_per_job"], per_job * n_freq, sims_per_case,
                     per_job * samples * v.RECORD_BYTES_PER_SAMPLE)
    n_chunks = -(-n_real // per_job)
    if n_chunks > v.MAX_JOBS_PER_SPECTRUM:
        v.fail("realisations_per_job", config["realisations_per_job"],
               f"realisations = {n_real} in jobs of {per_job} gives {n_chunks} jobs per spectrum, the limit is "
               f"{v.MAX_JOBS_PER_SPECTRUM} (Snakemake's DAG would grow too large); use larger jobs")
    v.check_workload("amplitude_grid.step", ag["step"], n_freq, grid_size_points(ag), 0)
    try:
        reading = reading_from_dict(config["noise"])
    except ValueError as exc:
        raise v.InputError(f"noise: {exc}") from None
    band = config["control"]["sensor_band"]
    if band is not None:  # the sensor reads the noisy records at noise.step, the analytic excitation at SENSOR_STEP
        try:
            check_band(band, max(reading.step, SENSOR_STEP), "control.sensor_band")
        except ValueError as exc:
            raise v.InputError(str(exc)) from None
    for name, spec in config["reproduction"]["readings"].items():
        try:
            reading_from_dict(spec)
        except ValueError as exc:
            raise v.InputError(f"reproduction.readings.{name}: {exc}") from None
    from .calibration import CalibrationDesign
    cal = config["calibration"]
    try:
        design = CalibrationDesign(cal["kappa_max"], cal["damping_ratio"], cal["ultimate_rotation_ratio"],
                                   cal["kappa_min_ratio"])
        design.devices(block.alpha)
    except ValueError as exc:
        raise v.InputError(f"calibration: {exc}") from None


def grid_size_points(spec: dict) -> int:
    """Number of points of an amplitude grid ``{start, stop, step}`` (the simulations of one map row)."""
    return v.grid_size(spec["start"], spec["stop"], spec["step"])
