"""The studies beyond the paper as the workflow runs them: the config's ``beyond:`` section
(probability of overturning over the noise realisations, fragility over a record suite) checked
across keys, before any job runs.
"""
from __future__ import annotations

from rockstudy.core import validation

SYNTHETIC_RANGES = {"envelope_shape": (0.0, 100.0), "filter_ratio": (0.0, 1.0),
                    "pga_g": (0.0, 100.0)}
"""Allowed (open low, closed high) ranges of the synthetic suite's dimensionless settings. [-]"""


def check_config(section: dict, config: dict) -> None:
    """The ``beyond:`` section agrees with the rest of the study ``config`` and stays within the limits of
    :mod:`rockstudy.core.validation`: strategies and levels of the study, grids, the synthetic suite (its
    records' duration, step and samples), record files that are regular files of bounded size, the
    intensity stripes, the bootstrap draws and seeds, and the workload of one job.

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) naming the key, the value and what is allowed.
    """
    levels = config["noise_levels"]
    prob, frag = section["probability"], section["fragility"]
    for level in prob["noise_levels"]:
        if level not in levels:
            raise validation.InputError(f"beyond.probability.noise_levels: {level!r} is not one of noise_levels "
                               f"({', '.join(levels)})")
    if "FS" not in frag["strategies"]:
        raise validation.InputError("beyond.fragility.strategies: FS is needed as the reference of the median shift")
    ag = prob["amplitude_grid"]
    sims = validation.check_amplitude_grid(ag["start"], ag["stop"], ag["step"], ag["resolution"],
                                  names=tuple(f"beyond.probability.amplitude_grid.{k}"
                                              for k in ("start", "stop", "step", "resolution")))
    fg = prob["frequency_grid"]
    n_freq = validation.check_grid("beyond.probability.frequency_grid", fg["start"], fg["stop"], fg["step"],
                          high=validation.MAX_FREQUENCY_RATIO)
    n_amp = validation.grid_size(ag["start"], ag["stop"], ag["step"])
    validation.check_workload("beyond.probability.frequency_grid.step", fg["step"], config["realisations"] * n_freq,
                     max(sims, n_amp), 0)
    records = frag["records"]
    if records == "synthetic":
        n_records = _check_synthetic(frag["synthetic"])
    elif isinstance(records, list):
        n_records = len(records)
        for i, entry in enumerate(records):
            if isinstance(entry, dict) and "path" in entry:
                validation.check_input_file(f"beyond.fragility.records[{i}].path", entry["path"],
                                            validation.MAX_RECORD_BYTES)
    else:
        n_records = 1
    validation.check_int_range("beyond.fragility.bootstrap", frag["bootstrap"], 0, validation.MAX_BOOTSTRAP)
    validation.check_int_range("beyond.fragility.seed", frag["seed"], 0, validation.MAX_INTEGER)
    il = frag["intensity_levels"]
    n_levels = validation.check_grid("beyond.fragility.intensity_levels", il["start"], il["stop"], il["step"],
                            high=validation.MAX_AMPLITUDE_RATIO)
    validation.check_workload("beyond.fragility.intensity_levels.step", il["step"],
                     n_records * n_levels * len(frag["strategies"]), 1, 0)


def _check_synthetic(syn: dict) -> int:
    """The synthetic suite's settings; returns its number of records."""
    key = "beyond.fragility.synthetic"
    n = validation.check_int_range(f"{key}.n_records", syn["n_records"], 1, validation.MAX_SUITE_RECORDS)
    validation.check_int_range(f"{key}.seed", syn["seed"], 0, validation.MAX_INTEGER)
    duration = validation.check_positive(f"{key}.duration", syn["duration"], "s", validation.MAX_TIME_SPAN)
    dt = validation.check_positive(f"{key}.dt", syn["dt"], "s", duration / 2)
    samples = duration / dt + 1
    if samples > validation.MAX_RECORD_SAMPLES:
        validation.fail(f"{key}.dt", dt, f"{key}.duration = {duration:g} s sampled every {dt:g} s gives {samples:.3g} "
                                f"samples per record, the limit is {validation.MAX_RECORD_SAMPLES:.0e}", "s")
    for name in ("ground_frequency_hz", "ground_damping", "peak_time"):
        lo, hi = syn[name]
        high = {"ground_frequency_hz": 0.5 / dt, "ground_damping": 1.0, "peak_time": duration}[name]
        for i, value in enumerate((lo, hi)):
            validation.check_positive(f"{key}.{name}[{i}]", value, high=high)
        if hi < lo:
            validation.fail(f"{key}.{name}", [lo, hi], "give [low, high] with low <= high")
    for name, (low, high) in SYNTHETIC_RANGES.items():
        validation.check_range(f"{key}.{name}", syn[name], low, high, low_open=True)
    return n
