"""The study config's one check before any job runs (:func:`check_study`, which calls each section's
own check, and :func:`check_sizes`) (paper §4–5).

It takes plain ``dict``/``list`` values, never a config file name; the parsers from dicts to the
library's dataclasses are in :mod:`rockstudy.studies.parameters`, the labelled datasets in
:mod:`rockstudy.studies.datasets`, the J_OS tables in :mod:`rockstudy.studies.tables`; the source
fingerprints are in :mod:`rockstudy.studies.fingerprints` and a workflow job's log, checked reader and
stamp in :mod:`rockstudy.studies.jobs`. Amplitudes are ratios a_p/(g·tanα), frequencies ratios ω_p/p;
a_max,0 is given in units of g.
"""
from __future__ import annotations

from rockstudy.core import validation
from rockstudy.studies.parameters import (
    amplitude_grid,
    block_from_dict,
    frequency_ratios,
    grid_size_points,
    noise_free_level,
    scenario_from_dict,
)


def check_sizes(config: dict) -> None:
    """No list or mapping of the config is longer than declared (:mod:`rockstudy.studies.config_model`), and the
    config has at most :data:`~rockstudy.core.config_files.MAX_NODES` values (YAML aliases expanded).

    Parameters
    ----------
    config : dict
        The study config, as loaded from YAML (plain ``dict``/``list`` values).

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) naming the key path.
    """
    from rockstudy.core import config_files

    config_files.count_nodes(config)


def check_study(config: dict) -> None:
    """Checks a JSON schema cannot express, before any job runs; the message names the offending key.

    Beyond the schema: no NaN or inf anywhere; integers that netCDF can store; a slender block
    (or an explicit restitution); the upper bounds of :mod:`rockstudy.core.validation` on every value
    that becomes an array size, a loop count or a time span (grid points, simulations and noise
    memory of one spectrum job, time span and integrator steps of one simulation, controller
    samples); and the cross-key rules (noise levels, strategies, a_max,0 within the scan).

    Parameters
    ----------
    config : dict
        The whole study config (plain ``dict``/``list`` values, every key of config.yaml); each section is
        passed on to its own check.

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
    from rockstudy.studies import beyond, config_model, device_calibration, noise_readings

    # the model: every key's type, unit, range and size, and the relations between keys that need no
    # computation (its validators); then what needs the model's computations and bounds the work
    config_model.check_config(config)
    validation.check_results_dir("results_dir", config["results_dir"])
    levels = config["noise_levels"]
    noise_free_level(levels)
    n_real, per_job = config["realisations"], config["realisations_per_job"]
    block = block_from_dict(config["block"])
    free_time = config["free_time"]
    ag = config["amplitude_grid"]
    sims_per_case = validation.check_amplitude_grid(ag["start"], ag["stop"], ag["step"], ag["resolution"])
    top = amplitude_grid(ag).values()[-1]
    validation.check_a_max0("a_max0", config["a_max0"], block.alpha, top)
    fg = config["frequency_grid"]
    n_freq = validation.check_grid("frequency_grid", fg["start"], fg["stop"], fg["step"],
                                   high=validation.MAX_FREQUENCY_RATIO)
    scenario_from_dict({"block": config["block"], "anchorage": config["anchorage"]})  # the anchorage's relations
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


