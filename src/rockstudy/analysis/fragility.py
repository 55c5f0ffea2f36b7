"""Fragility of a controlled block over a suite of ground-motion records (multiple stripe analysis).

Every record is scaled to each level x_j of an intensity measure (IM), the block is run under it
for each strategy on the compiled engine, and the number z_j of the n records that overturn it is
counted; the lognormal fragility (median θ, dispersion β) is fitted to these counts by maximum
likelihood (:mod:`rockstudy.analysis.fragility_fit`, Eqs. F1–F2).

J_OS (Eqs. 18–22 of the paper) measures how far a device lifts the overturning spectrum above
free standing (FS); carried over to records, the measure is the **shift of the median**,
θ_device/θ_FS − 1, with its bootstrap interval (the same records drive every strategy, so
the ratio is far better determined than either median).

Intensity measures (each record is scaled to the IM level):

* ``pga_ratio``: PGA/(g·tanα), the amplitude ratio of the paper's spectra (default);
* ``pgv_ratio``: PGV·p/(g·tanα), the peak ground velocity in the rocking block's own scale
  (:func:`rockstudy.model.record_suites.peak_ground_velocity`).

The Markdown tables of these datasets are in :mod:`rockstudy.report.fragility_tables`.
"""
from __future__ import annotations

import math
import time
import warnings

import numpy as np
import xarray as xr

from rockstudy._version import __version__
from rockstudy.analysis.fragility_fit import BOOTSTRAP_KEY, bootstrap_median_ratios, fit_lognormal, fit_lognormal_points
from rockstudy.analysis.record_scan import RecordRun, grid_outcomes, is_overturned, stripes_and_thresholds
from rockstudy.core import validation
from rockstudy.core.quantities import check_arguments, declares
from rockstudy.engine.outcome import OUTCOME_MEANINGS
from rockstudy.engine.simulate import DEFAULT_FREE_TIME
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import Block
from rockstudy.model.record_suites import peak_ground_velocity
from rockstudy.model.records import STANDARD_GRAVITY, STANDARD_GRAVITY_UNITS, Record, unit_label

INTENSITY_MEASURES = {
    "pga_ratio": "PGA/(g tan(alpha))",
    "pgv_ratio": "PGV p/(g tan(alpha))",
}
"""Intensity measures a suite can be scaled to, with their definition (dimensionless)."""

SUITE_DEFAULTS = {"intensity_measure": "pga_ratio", "intensity_levels": {"start": 0.5, "stop": 12.0, "step": 0.25},
                  "threshold_resolution": 0.01, "bootstrap": 200, "seed": 20190101}
"""The study's settings of a record set's fragility (``beyond.fragility`` of config.yaml states the same
values): the intensity measure, its stripe levels, the threshold resolution [IM], the bootstrap draws and
their seed. ``rockstudy fragility`` takes them as its defaults."""


def intensity(record: Record, block: Block, measure: str = "pga_ratio") -> float:
    """The intensity measure of an unscaled record for ``block`` (see :data:`INTENSITY_MEASURES`). [-]

    Parameters
    ----------
    record : Record
        The unscaled record.
    block : rockstudy.Block
        The block, whose g·tanα (and p, for ``pgv_ratio``) make the measure dimensionless.
    measure : {"pga_ratio", "pgv_ratio"}, default "pga_ratio"
        The intensity measure.
    """
    if measure == "pga_ratio":
        return record.pga / block.uplift_acceleration
    if measure == "pgv_ratio":
        return peak_ground_velocity(record) * block.p / block.uplift_acceleration
    raise ValueError(f"intensity measure must be one of {', '.join(INTENSITY_MEASURES)}, got {measure!r}")


# --- the stripes -----------------------------------------------------------------------------------
def stripe_outcomes(block: Block, anchorage: Anchorage, controls, records, levels, *, measure: str = "pga_ratio",
                    overturn_criterion: str = "flat", free_time: float = DEFAULT_FREE_TIME):
    """Outcome of every (control, record, IM level) on the compiled engine, the record scaled so that its
    IM equals the level (the runs of :func:`rockstudy.analysis.record_scan.stripes_and_thresholds`
    without the thresholds).

    Parameters
    ----------
    block, anchorage : rockstudy.Block, rockstudy.Anchorage
        The block and its restrainers.
    controls : sequence of Control
        The strategies (with their timing).
    records : sequence of Record
        The unscaled records.
    levels : array_like
        IM levels x_j, increasing, at least 2, > 0. [IM]
    measure : str
        Intensity measure, a key of :data:`INTENSITY_MEASURES`.
    overturn_criterion, free_time : {"flat", "alpha"}, float
        As for :func:`rockstudy.engine.simulate.simulate` (free time in [s]).

    Returns
    -------
    outcome : ndarray of int8, shape (control, record, level)
        :class:`~rockstudy.engine.outcome.Outcome` codes.
    scale : ndarray, shape (record, level)
        Factor applied to each record. [-]
    """
    _check_fragility_inputs(controls, records, levels, reference=False)
    levels = np.asarray(levels, dtype=float)
    if levels.ndim != 1 or levels.size < 2 or np.any(levels <= 0) or np.any(np.diff(levels) <= 0):
        raise ValueError("levels must be an increasing 1-D list of at least 2 positive IM values")
    if len(records) < 1:
        raise ValueError("records must hold at least one record")
    base = np.array([intensity(r, block, measure) for r in records])
    scale = levels[None, :] / base[:, None]
    outcome = np.zeros((len(controls), len(records), levels.size), dtype=np.int8)
    for r, record in enumerate(records):
        per_level = record.pga / block.uplift_acceleration / base[r]  # PGA/(g tan(alpha)) per IM unit
        for c, control in enumerate(controls):
            run = RecordRun(block, anchorage, control, record, overturn_criterion=overturn_criterion,
                            free_time=free_time)
            outcome[c, r] = grid_outcomes(run, levels * per_level)
    return outcome, scale


def _outcome_variable(outcome) -> tuple:
    return (("strategy", "record", "intensity"), outcome,
            {"long_name": "outcome of the run at each level",
             "flag_values": np.arange(len(OUTCOME_MEANINGS), dtype=np.int8),
             "flag_meanings": " ".join(OUTCOME_MEANINGS)})


@declares(n_boot="bootstrap", seed="seed", free_time="free_time")
def fragility_dataset(block: Block, anchorage: Anchorage, controls, records, levels, *,
                      measure: str = "pga_ratio", n_boot: int = 200, seed: int = 0,
                      overturn_criterion: str = "flat", free_time: float = DEFAULT_FREE_TIME,
                      record_attrs=None) -> xr.Dataset:
    """Fragility of each strategy over a record suite: stripes (:func:`stripe_outcomes`), lognormal MLE
    fits, median shifts.

    Parameters
    ----------
    block, anchorage : rockstudy.Block, rockstudy.Anchorage
        The block and its restrainers.
    controls : sequence of Control
        The strategies; one must be FS (the reference of the median shift).
    records : sequence of Record
        The unscaled records.
    levels : array_like
        IM levels of the stripes. [IM]
    measure : str
        Intensity measure (:data:`INTENSITY_MEASURES`), PGA/(g·tanα) by default.
    n_boot : int
        Bootstrap draws over records for the interval of the median shift.
    seed : int
        Root seed of the bootstrap (``SeedSequence(seed, spawn_key=(BOOTSTRAP_KEY,))``).
    overturn_criterion, free_time : {"flat", "alpha"}, float
        As for :func:`rockstudy.engine.simulate.simulate` (free time in [s]).
    record_attrs : dict, optional
        Extra global attributes describing the suite (e.g. the synthetic model).

    Returns
    -------
    xarray.Dataset
        ``overturned`` and ``outcome`` (strategy, record, intensity); ``fraction``
        (strategy, intensity); ``fragility_median``, ``fragility_dispersion``, their standard errors and 95 %
        intervals, ``fit_status``; ``median_ratio`` θ/θ_FS with its bootstrap 95 % interval (NaN when no
        draw has a finite ratio) and ``median_shift_percent`` 100·(θ/θ_FS − 1), per strategy.
    """
    check_arguments("fragility_dataset", {"n_boot": n_boot, "seed": seed, "free_time": free_time})
    _check_fragility_inputs(controls, records, levels)
    levels = np.asarray(levels, dtype=float)
    t0 = time.perf_counter()
    outcome, scale = stripe_outcomes(block, anchorage, controls, records, levels, measure=measure,
                                     overturn_criterion=overturn_criterion, free_time=free_time)
    ds = fragility_from_stripes(block, anchorage, controls, records, levels, is_overturned(outcome), scale,
                                measure=measure, n_boot=n_boot, seed=seed, overturn_criterion=overturn_criterion,
                                free_time=free_time, record_attrs=record_attrs)
    ds["outcome"] = _outcome_variable(outcome)
    ds.attrs["compute_time_s"] = time.perf_counter() - t0
    return ds


def _check_fragility_inputs(controls, records, levels, records_name: str = "records", reference: bool = True):
    """The strategies (FS among them when it is the ``reference`` of the median shift), a record or more and
    two levels or more; returns the strategies' names."""
    strategies = [c.strategy for c in validation.check_items("controls", controls, what="control")]
    validation.check_items(records_name, records, what="record")
    validation.check_items("levels", levels, low=2, what="level")
    if not reference:
        return strategies
    if "FS" not in strategies:
        raise ValueError(f"controls must include FS, the reference of the median shift, got {strategies}")
    return strategies


@declares(n_boot="bootstrap", seed="seed", free_time="free_time")
def fragility_from_stripes(block: Block, anchorage: Anchorage, controls, records, levels, overturned, scale, *,
                           measure: str = "pga_ratio", n_boot: int = 200, seed: int = 0,
                           overturn_criterion: str = "flat", free_time: float = DEFAULT_FREE_TIME,
                           record_attrs=None) -> xr.Dataset:
    """The fits, median shifts and dataset of :func:`fragility_dataset` from stripes already run.

    Parameters
    ----------
    block, anchorage : rockstudy.Block, rockstudy.Anchorage
        The block and its restrainers.
    controls : sequence of Control
        The strategies; one must be FS (the reference of the median shift).
    records : sequence of Record
        The unscaled records, in the order of ``overturned``.
    levels : array_like
        IM levels of the stripes. [IM]
    overturned : ndarray of bool, shape (control, record, level)
        Whether each run overturns the block (e.g. :func:`~rockstudy.analysis.record_scan.is_overturned`
        of :func:`stripe_outcomes`).
    scale : ndarray, shape (record, level)
        Factor applied to each record. [-]
    measure : str
        Intensity measure (:data:`INTENSITY_MEASURES`), stored in the attributes.
    n_boot : int
        Bootstrap draws over records for the interval of the median shift, >= 0 (0: no interval).
    seed : int
        Root seed of the bootstrap (``SeedSequence(seed, spawn_key=(BOOTSTRAP_KEY,))``).
    overturn_criterion, free_time : {"flat", "alpha"}, float
        The settings the stripes were run with, stored in the attributes (free time in [s]).
    record_attrs : dict, optional
        Extra global attributes describing the suite (e.g. the synthetic model).
    """
    check_arguments("fragility_from_stripes", {"n_boot": n_boot, "seed": seed, "free_time": free_time})
    strategies = _check_fragility_inputs(controls, records, levels)
    levels = np.asarray(levels, dtype=float)
    overturned = np.asarray(overturned, dtype=bool)
    dims3 = ("strategy", "record", "intensity")
    n_records = len(records)
    counts = overturned.sum(axis=1)
    fits = [fit_lognormal(levels, np.full(levels.size, n_records), counts[c]) for c in range(len(controls))]
    reference = strategies.index("FS")
    medians = np.array([f.median for f in fits])
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(BOOTSTRAP_KEY,)))
    boot = bootstrap_median_ratios(levels, overturned, reference, n_boot, rng) if n_boot else np.full((0, len(fits)),
                                                                                                       np.nan)
    with np.errstate(invalid="ignore"), warnings.catch_warnings():
        # a strategy none of whose draws has a finite ratio gets a NaN interval (fragility_dataset)
        warnings.filterwarnings("ignore", "All-NaN slice", RuntimeWarning)
        ci = np.nanpercentile(boot, [2.5, 97.5], axis=0) if n_boot else np.full((2, len(fits)), np.nan)
    intervals = np.array([f.median_interval() if f.status == "ok" else (math.nan, math.nan) for f in fits])
    ratio = medians / medians[reference]
    im_attrs = {"units": "1", "long_name": INTENSITY_MEASURES.get(measure, measure)}
    ds = xr.Dataset(
        {
            "overturned": (dims3, overturned.astype(np.int8), {"long_name": "the record scaled to the IM level "
                                                               "overturns the block",
                                                               "flag_values": np.array([0, 1], dtype=np.int8),
                                                               "flag_meanings": "not_overturned overturned"}),
            "scale": (("record", "intensity"), scale, {"units": "1", "long_name": "factor applied to the record"}),
            "fraction": (("strategy", "intensity"), counts / n_records,
                         {"units": "1", "long_name": "fraction of the records that overturn the block"}),
            "fragility_median": ("strategy", medians, {**im_attrs, "long_name": f"fragility median theta of "
                                             f"{im_attrs['long_name']} (MLE, Eq. F2)"}),
            "fragility_dispersion": ("strategy", [f.dispersion for f in fits],
                           {"units": "1", "long_name": "fragility dispersion beta (MLE, Eq. F2)"}),
            "log_median_se": ("strategy", [f.log_median_se for f in fits],
                              {"units": "1", "long_name": "standard error of ln(theta), observed information"}),
            "dispersion_se": ("strategy", [f.dispersion_se for f in fits],
                              {"units": "1", "long_name": "standard error of beta, observed information"}),
            "median_low": ("strategy", intervals[:, 0], {**im_attrs, "long_name": "95 % Wald interval of theta, low"}),
            "median_high": ("strategy", intervals[:, 1], {**im_attrs, "long_name": "95 % Wald interval of theta, "
                                                          "high"}),
            "log_likelihood": ("strategy", [f.log_likelihood for f in fits],
                               {"units": "1", "long_name": "maximum log-likelihood of the lognormal fit"}),
            "fit_status": ("strategy", [f.status for f in fits], {"long_name": "see FragilityFit.status"}),
            "median_ratio": ("strategy", ratio, {"units": "1", "long_name": "theta / theta_FS"}),
            "median_ratio_low": ("strategy", ci[0], {"units": "1", "long_name": "theta / theta_FS, bootstrap over "
                                                     "records, 2.5 % quantile"}),
            "median_ratio_high": ("strategy", ci[1], {"units": "1", "long_name": "theta / theta_FS, bootstrap over "
                                                      "records, 97.5 % quantile"}),
            "median_shift_percent": ("strategy", 100 * (ratio - 1), {"units": "percent", "long_name":
                                     "shift of the fragility median over FS, 100 (theta/theta_FS - 1)"}),
        },
        coords={
            "strategy": ("strategy", strategies, {"long_name": "control strategy"}),
            "record": ("record", [r.name for r in records], {"long_name": "record name"}),
            "intensity": ("intensity", levels, {**im_attrs, "long_name": f"intensity measure level, "
                                                f"{im_attrs['long_name']}"}),
            "record_intensity": ("record", [intensity(r, block, measure) for r in records],
                                 {**im_attrs, "long_name": "intensity measure of the unscaled record"}),
            "record_source": ("record", [r.source for r in records], {"long_name": "file or generator"}),
            "sampling_time": ("strategy", [c.sampling_time for c in controls],
                              {"units": "s", "long_name": "sampling time T_s of the controller"}),
            "delay": ("strategy", [c.delay for c in controls],
                      {"units": "s", "long_name": "actuation delay of the controller"}),
        },
        attrs={
            "title": "Fragility of the controlled block over a record suite (multiple stripe analysis)",
            "rockstudy_version": __version__,
            "method": "lognormal fragility, maximum likelihood on binomial stripe counts (Baker 2015, Eq. 11); "
                      "standard errors from the observed information; median ratio interval from a bootstrap "
                      "over records",
            "paper_equations": "Eqs. 1-17 (model); J_OS (Eqs. 18-22) carried over as the median shift over FS",
            "intensity_measure": measure,
            "intensity_measure_definition": INTENSITY_MEASURES.get(measure, measure),
            "n_records": n_records, "n_bootstrap": n_boot, "bootstrap_seed": seed,
            "overturn_criterion": overturn_criterion, "free_time_s": free_time,
            **block.to_attrs(), **anchorage.to_attrs(block), **(record_attrs or {}),
        },
    )
    return ds


# --- fragility over a named record suite, with every record's threshold -----------------------------
OTHER_MEASURE = {"pga_ratio": "pgv_ratio", "pgv_ratio": "pga_ratio"}


@declares(resolution="intensity_resolution", n_boot="bootstrap", seed="seed", free_time="free_time")
def suite_fragility_dataset(block: Block, anchorage: Anchorage, controls, entries, levels, *,
                            suite: str, measure: str = "pga_ratio", resolution: float = 0.01, n_boot: int = 200,
                            seed: int = 0, overturn_criterion: str = "flat",
                            free_time: float = DEFAULT_FREE_TIME, names: dict | None = None) -> xr.Dataset:
    """Fragility of each strategy over a record suite, and the threshold of every record.

    The stripes run on the compiled engine (:func:`rockstudy.analysis.record_scan.stripes_and_thresholds`);
    each record's threshold is the smallest intensity that overturns the block, found with the
    spectra's scan rules (every lower level of ``levels`` shown safe) and bisected to ``resolution``.
    Besides the fit in ``measure`` (:func:`fragility_from_stripes`), the dataset holds the median in
    physical units (PGA in g, or PGV in m/s) and a fit in the other measure of
    :data:`INTENSITY_MEASURES` from the same runs (each run one observation at its own intensity).

    Parameters
    ----------
    block, anchorage : rockstudy.Block, rockstudy.Anchorage
        The block and its restrainers.
    controls : sequence of Control
        The strategies, FS among them.
    entries : sequence of (RecordInfo, Record), or a callable returning one
        From :mod:`rockstudy.model.record_suites`; a callable (``lambda: load_suite(name)``) is called after
        the numeric arguments are checked, so a bad argument is refused before any record is read.
    levels : array_like
        Intensity levels of the stripes, in ``measure``. [IM]
    suite : str
        Name of the record set (stored, and in the title).
    resolution : float
        Resolution of the records' thresholds. [IM]
    measure, n_boot, seed, overturn_criterion, free_time : str, int, int, str, float
        As for :func:`fragility_dataset`.
    names : dict, optional
        The caller's name of ``resolution``, ``n_boot``, ``seed`` and ``free_time`` in error messages
        (``{"n_boot": "--bootstrap"}``).

    Returns
    -------
    xarray.Dataset
        The variables of :func:`fragility_from_stripes` plus ``outcome`` (strategy, record, intensity);
        ``threshold_intensity``, ``last_safe_intensity``, ``threshold_scale`` and ``threshold_pga``
        [g] (strategy, record); ``fragility_median_physical`` with its interval; ``fragility_median_other``,
        ``fragility_dispersion_other`` and the interval in the other measure; the records' catalogue as
        coordinates (suite, id, event, station, year, magnitude, distance, site class, PGA, PGV, pulse).
    """
    check_arguments("suite_fragility_dataset", {"resolution": resolution, "n_boot": n_boot, "seed": seed,
                                                "free_time": free_time}, names)
    if callable(entries):
        entries = entries()
    _check_fragility_inputs(controls, entries, levels, records_name="entries")
    if measure not in INTENSITY_MEASURES:
        raise ValueError(f"intensity measure must be one of {', '.join(INTENSITY_MEASURES)}, got {measure!r}")
    infos = [i for i, _ in entries]
    records = [r for _, r in entries]
    levels = np.asarray(levels, dtype=float)
    t0 = time.perf_counter()
    base = np.array([intensity(r, block, measure) for r in records])
    runs = stripes_and_thresholds(block, anchorage, controls, records, levels, base, resolution=resolution,
                                  overturn_criterion=overturn_criterion, free_time=free_time)
    overturned = is_overturned(runs["outcome"])
    ds = fragility_from_stripes(block, anchorage, controls, records, levels, overturned, runs["scale"],
                                measure=measure, n_boot=n_boot, seed=seed, overturn_criterion=overturn_criterion,
                                free_time=free_time, record_attrs={"record_suite": suite})
    dims2 = ("strategy", "record")
    ds["outcome"] = _outcome_variable(runs["outcome"])
    im_attrs = {"units": "1", "long_name": INTENSITY_MEASURES[measure]}
    threshold_scale = runs["threshold"] / base[None, :]
    pga_g = np.array([r.pga for r in records]) / STANDARD_GRAVITY
    ds["threshold_intensity"] = (dims2, runs["threshold"], {
        **im_attrs, "long_name": f"smallest {INTENSITY_MEASURES[measure]} that overturns the block",
        "description": "upward scan of the stripe levels (every lower level shown safe), then bisection to "
                       "threshold_resolution; NaN: no overturning up to the last level"})
    ds["last_safe_intensity"] = (dims2, runs["last_safe"], {**im_attrs, "long_name": "highest intensity shown "
                                                            "safe below the threshold"})
    ds["threshold_scale"] = (dims2, threshold_scale, {"units": "1", "long_name": "smallest factor on the "
                                                      "as-recorded motion that overturns the block"})
    ds["threshold_pga"] = (dims2, threshold_scale * pga_g[None, :], {
        "units": STANDARD_GRAVITY_UNITS, "long_name": "PGA of the record at its threshold scale (standard gravity)"})
    ds["n_simulations"] = (dims2, runs["n_simulations"], {"units": "1", "long_name": "runs of the stripes and "
                                                          "the threshold scan"})
    # the median in physical units: PGA [g] = ratio * g tan(alpha) / g_n; PGV [m/s] = ratio * g tan(alpha) / p
    unit_factor = (block.uplift_acceleration / STANDARD_GRAVITY if measure == "pga_ratio"
                   else block.uplift_acceleration / block.p)
    unit = STANDARD_GRAVITY_UNITS if measure == "pga_ratio" else "m/s"
    physical = "PGA" if measure == "pga_ratio" else "PGV"
    for name, source in (("fragility_median_physical", "fragility_median"), ("median_low_physical", "median_low"),
                         ("median_high_physical", "median_high")):
        ds[name] = ds[source] * unit_factor
        ds[name].attrs = {"units": unit, "long_name": f"{ds[source].attrs.get('long_name', source)}, as {physical} "
                          f"[{unit_label(unit)}]", "comment": f"from the block's g = {block.gravity:g} m s-2 "
                          f"(block_gravity); PGA in units of standard gravity g_n = {STANDARD_GRAVITY:g} m s-2"}
    # the other measure, from the same runs
    other = OTHER_MEASURE[measure]
    ratio_other = np.array([intensity(r, block, other) for r in records]) / base
    points = levels[None, :] * ratio_other[:, None]
    fits = [fit_lognormal_points(points, overturned[c]) for c in range(len(controls))]
    intervals = np.array([f.median_interval() if f.status == "ok" else (math.nan, math.nan) for f in fits])
    other_attrs = {"units": "1", "long_name": INTENSITY_MEASURES[other]}
    ds["fragility_median_other"] = ("strategy", [f.median for f in fits], {
        **other_attrs, "long_name": f"fragility median of {INTENSITY_MEASURES[other]}, MLE of the same runs "
                                    "(each run one observation at its own intensity)"})
    ds["fragility_dispersion_other"] = ("strategy", [f.dispersion for f in fits],
                                        {"units": "1", "long_name": f"fragility dispersion in {other}"})
    ds["median_low_other"] = ("strategy", intervals[:, 0], {**other_attrs, "long_name": "95 % Wald interval, low"})
    ds["median_high_other"] = ("strategy", intervals[:, 1], {**other_attrs, "long_name": "95 % Wald interval, high"})
    ds["fit_status_other"] = ("strategy", [f.status for f in fits], {"long_name": "see FragilityFit.status"})
    ds = ds.assign_coords(_catalogue_coordinates(infos, pga_g, base * ratio_other, other))
    ds.attrs.update(title=f"Fragility of the controlled block over the record suite {suite} (multiple stripe "
                          "analysis) and each record's threshold",
                    record_suite=suite, other_intensity_measure=other,
                    other_intensity_measure_definition=INTENSITY_MEASURES[other],
                    threshold_resolution=float(resolution),
                    threshold_rule="upward scan of the intensity levels, every lower level shown safe, then "
                                   "bisection (the overturning spectra's rule)",
                    engine="fast (compiled), energy bound on", compute_time_s=time.perf_counter() - t0)
    return ds


def _catalogue_coordinates(infos, pga_g, other_intensity, other: str) -> dict:
    """The records' catalogue as ``record`` coordinates (suite, id, event, station, year, magnitude, distance,
    site class, PGA [g], PGV, pulse, the other intensity measure of the unscaled record)."""
    coords = {
        "record_suite_name": [i.suite for i in infos], "record_id": [i.id for i in infos],
        "record_event": [i.event for i in infos], "record_station": [i.station for i in infos],
        "record_year": [i.year for i in infos], "record_magnitude": [i.magnitude for i in infos],
        "record_distance": [i.distance_km for i in infos], "record_site_class": [i.site_class for i in infos],
        "record_pga": pga_g, "record_pgv": [i.pgv for i in infos], "record_pulse": [i.pulse for i in infos],
        "record_other_intensity": other_intensity,
    }
    units = {"record_distance": "km", "record_pga": STANDARD_GRAVITY_UNITS, "record_pgv": "m/s",
             "record_magnitude": "1", "record_other_intensity": "1"}
    names = {"record_suite_name": "record suite", "record_id": "id within the suite", "record_event": "earthquake",
             "record_station": "recording station (component)",
             "record_year": "year of the event (0: not applicable)", "record_magnitude": "moment magnitude",
             "record_distance": "closest distance to the fault rupture plane", "record_site_class": "NEHRP site class",
             "record_pga": "peak ground acceleration of the unscaled record (standard gravity)",
             "record_pgv": "peak ground velocity of the unscaled record",
             "record_pulse": "velocity pulse (P695 classification)",
             "record_other_intensity": f"{INTENSITY_MEASURES[other]} of the unscaled record"}
    return {k: ("record", v, {**({"units": units[k]} if k in units else {}), "long_name": names[k]})
            for k, v in coords.items()}


def suite_summary(datasets) -> "list[dict]":
    """One row per (suite, strategy): medians with 95 % intervals in every unit, dispersion, shift over FS.

    Parameters
    ----------
    datasets : iterable of xarray.Dataset
        Datasets of :func:`suite_fragility_dataset`, one per suite.
    """
    rows = []
    for ds in validation.check_items("datasets", datasets, what="dataset"):
        for s in ds.strategy.values:
            d = ds.sel(strategy=s)
            rows.append({"suite": ds.attrs["record_suite"], "strategy": str(s), "n_records": ds.attrs["n_records"],
                         "intensity_measure": ds.attrs["intensity_measure"],
                         "median": float(d.fragility_median), "median_low": float(d.median_low),
                         "median_high": float(d.median_high),
                         "median_physical": float(d.fragility_median_physical),
                         "median_physical_low": float(d.median_low_physical),
                         "median_physical_high": float(d.median_high_physical),
                         "physical_unit": unit_label(ds["fragility_median_physical"].attrs["units"]),
                         "dispersion": float(d.fragility_dispersion), "dispersion_se": float(d.dispersion_se),
                         "other_measure": ds.attrs["other_intensity_measure"],
                         "median_other": float(d.fragility_median_other),
                         "median_other_low": float(d.median_low_other),
                         "median_other_high": float(d.median_high_other),
                         "dispersion_other": float(d.fragility_dispersion_other),
                         "median_ratio": float(d.median_ratio), "median_ratio_low": float(d.median_ratio_low),
                         "median_ratio_high": float(d.median_ratio_high),
                         "median_shift_percent": float(d.median_shift_percent), "fit": str(d.fit_status.values)})
    return rows
