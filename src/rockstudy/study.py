"""The paper's study as data: parameters from plain dictionaries, realisation chunks,
noise bookkeeping, gathered spectra, J_OS tables and figure data (paper §4–5).

This module is the edge between the workflow (which reads and validates ``config.yaml``)
and the library: it takes plain ``dict``/``list`` values — never a file name of a config —
and returns the library's dataclasses or labelled :class:`xarray.Dataset` objects.
Amplitudes are ratios a_p/(g·tanα), frequencies ratios ω_p/p; a_max,0 is given in units of g.
"""
from __future__ import annotations

import hashlib
import logging
import math
from pathlib import Path

import numpy as np
import xarray as xr

from . import __version__
from . import validation as v
from .anchorage import Anchorage
from .block import BLOCK_PRESETS, Block
from .control import Control
from .excitation import excitation_duration
from .noise import NOISE_DT, baseline_samples, level_key, noisy_record, reading_from_dict
from .simulate import simulate
from .spectra import AmplitudeGrid, Scenario, convergence, frequency_grid
from .utility import utility_index

PAPER = "Use of overturning spectra in the performance evaluation of on-off control strategies for rocking objects"
REFERENCES = ("no_noise", "fs_same_noise")
"""Table 1's two references: the same strategy without noise, and FS at the same noise level."""


# --- parameters ------------------------------------------------------------------------------
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


def jos_of(system: xr.Dataset, reference: xr.Dataset, a_max0_g: float,
           a_max0_name: str = "a_max0") -> tuple[float, int, float]:
    """J_OS of ``system`` against ``reference`` (Eq. 21) with a_max,0 in units of g.

    The one rule used by the tables and by ``rockstudy jos``: a_max,0 must not lie above either
    spectrum's amplitude scan (a NaN threshold then means "safe up to a_max,0"). Where no
    frequency counts (N* = 0) J_OS is undefined and returned as NaN.

    Returns
    -------
    j_os : float
        Utility index, NaN when N* = 0. [%]
    n_star : int
        N*, the frequencies counted in Eq. (21).
    a_max0_ratio : float
        a_max,0 as an amplitude ratio a/(g·tanα). [-]
    """
    if system.sizes["frequency_ratio"] != reference.sizes["frequency_ratio"] or not np.allclose(
            system["frequency_ratio"], reference["frequency_ratio"]):
        raise ValueError("J_OS needs the system and the reference on the same frequencies")
    ratio = a_max0_ratio(system, a_max0_g, a_max0_name)
    a_max0_ratio(reference, a_max0_g, a_max0_name)
    j, n = utility_index(system["threshold"].values, reference["threshold"].values, ratio, undefined="nan")
    return j, n, ratio


MISSING_MEANINGS = {
    "threshold": "NaN: no overturning found up to the scan's top (grid_amplitude_stop) in any realisation",
    "threshold_realisation": "NaN: no overturning found up to the scan's top (grid_amplitude_stop) in this "
                             "realisation",
    "threshold_mean": "NaN: no realisation overturned up to the scan's top (grid_amplitude_stop)",
    "threshold_std": "NaN: no realisation overturned up to the scan's top (grid_amplitude_stop)",
    "threshold_convergence": "NaN: none of the first N realisations overturned up to the scan's top "
                             "(grid_amplitude_stop)",
    "last_safe": "NaN never: the highest amplitude ratio found safe (the scan's top when nothing overturned)",
    "j_os": "NaN where N* = 0: no frequency has a threshold below a_max,0 for the system or the reference, "
            "so J_OS (Eq. 21) is undefined",
}
"""What a NaN means in each variable that can hold one (the ``missing_value_meaning`` attribute)."""


def document_missing(ds: xr.Dataset) -> xr.Dataset:
    """Add ``missing_value_meaning`` (what a NaN means) to every variable of ``ds`` listed in
    :data:`MISSING_MEANINGS`; returns ``ds``."""
    for name, meaning in MISSING_MEANINGS.items():
        if name in ds.variables:
            ds[name].attrs["missing_value_meaning"] = meaning
    return ds


NOT_IN_SIMULATIONS = ("cli.py", "plotting.py", "study.py", "validation.py",
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


# --- noise realisations ------------------------------------------------------------------------
def noise_dataset(scenario: Scenario, frequency_ratios, realisations, reference_frequency_ratio: float,
                  n_records: int) -> xr.Dataset:
    """The noise realisations of one level: seeds, spawn keys, energy and PGA ratios, unit records.

    Records are regenerated exactly by ``noisy_record(excitation, ω_p, level, k, seed, reading)``
    with ``SeedSequence(seed, spawn_key=(level_key, k))``; the first ``n_records`` unit records
    at ``reference_frequency_ratio`` are stored with the baseline for Fig. 4.
    """
    sc, freqs, ks = scenario, np.asarray(frequency_ratios, float), [int(k) for k in realisations]
    level = sc.noise_level

    def record(f, k):
        return noisy_record(sc.excitation, sc.omega(f), level, k, sc.seed, sc.noise)

    ratios = np.array([[(r.energy_ratio, r.pga_ratio) for r in (record(f, k) for f in freqs)] for k in ks])
    base, dt = baseline_samples(sc.excitation, sc.omega(reference_frequency_ratio), sc.noise.step)
    kept = ks[:n_records]
    recs = np.array([record(reference_frequency_ratio, k).values for k in kept]).reshape(len(kept), len(base))
    ratio = {"units": "1"}
    return xr.Dataset(
        {"energy_ratio": (("realisation", "frequency_ratio"), ratios[..., 0],
                          {**ratio, "long_name": "noisy record energy / baseline energy"}),
         "pga_ratio": (("realisation", "frequency_ratio"), ratios[..., 1],
                       {**ratio, "long_name": "noisy record PGA / baseline PGA"}),
         "spawn_key": (("realisation", "key"), np.array([[level_key(level), k] for k in ks], dtype=np.int64),
                       {"long_name": "SeedSequence spawn key (level_key, realisation)"}),
         "baseline": ("time", base, {**ratio, "long_name": "unit-amplitude baseline excitation X_g/a_p",
                                     "frequency_ratio": reference_frequency_ratio}),
         "record": (("record_realisation", "time"), recs,
                    {**ratio, "long_name": "unit-amplitude noisy record X_g/a_p",
                     "frequency_ratio": reference_frequency_ratio})},
        coords={"realisation": ("realisation", np.array(ks, dtype=np.int64), {"long_name": "noise realisation k"}),
                "record_realisation": ("record_realisation", np.array(kept, dtype=np.int64),
                                       {"long_name": "noise realisation k of the stored records"}),
                "frequency_ratio": ("frequency_ratio", freqs, {"units": "1", "long_name": "omega_p/p"}),
                "time": ("time", np.arange(len(base)) * dt, {"units": "s", "long_name": "time"})},
        attrs={"title": f"Noise realisations, level {level:g} (noise energy / baseline energy)", "paper": PAPER,
               "paper_section": "5 (Fig. 4)", "rockstudy_version": __version__, "noise_level": level,
               "noise_seed": sc.seed, "noise_level_key": level_key(level), **sc.noise.to_attrs(),
               "excitation": sc.excitation, "reference_frequency_ratio": reference_frequency_ratio,
               "regenerate": "rockstudy.noise.noisy_record(excitation, frequency_ratio*block_p, noise_level, k, "
                             "noise_seed, NoiseReading(step=noise_step_s, rescale=noise_rescale, "
                             "level_means=noise_level_means, band=noise_band_hz or None, span=noise_span_s)); "
                             "SeedSequence(seed, spawn_key=(level_key, k))",
               **sc.block.to_attrs()})


# --- spectra -------------------------------------------------------------------------------------
REALISATION_VARS = ("threshold_realisation", "last_safe", "n_simulations", "n_undetermined", "energy_ratio",
                    "pga_ratio")


def gather_spectra(parts) -> xr.Dataset:
    """Concatenate realisation chunks of one spectrum and recompute the aggregates.

    ``threshold`` is the lowest threshold over all realisations (the paper's a_min,OVER),
    ``threshold_mean``/``threshold_std`` the mean and std over the realisations with a threshold.
    """
    parts = sorted(parts, key=lambda d: int(d["realisation"].values[0]))
    ds = xr.concat([p[list(REALISATION_VARS)] for p in parts], dim="realisation", combine_attrs="override")
    if len(np.unique(ds["realisation"])) != ds.sizes["realisation"]:
        raise ValueError("the chunks overlap: a realisation appears twice")
    out = parts[0].drop_vars(list(REALISATION_VARS) + ["realisation"]).copy()
    out = out.assign_coords(realisation=ds["realisation"])
    for name in REALISATION_VARS:
        out[name] = ds[name]
    thr = ds["threshold_realisation"]
    out["threshold"] = thr.min("realisation", skipna=True).assign_attrs(parts[0]["threshold"].attrs)
    out["threshold_mean"] = thr.mean("realisation", skipna=True).assign_attrs(parts[0]["threshold_mean"].attrs)
    out["threshold_std"] = thr.std("realisation", skipna=True).assign_attrs(parts[0]["threshold_std"].attrs)
    out.attrs["compute_time_s"] = float(sum(p.attrs.get("compute_time_s", 0.0) for p in parts))
    out.attrs["n_realisations"] = int(ds.sizes["realisation"])
    return document_missing(out)


def convergence_dataset(ds: xr.Dataset) -> xr.Dataset:
    """Fig. 6a: the lowest threshold over the first N realisations, N = 1 … n."""
    out = convergence(ds).to_dataset()
    out["threshold_realisation"] = ds["threshold_realisation"]
    out.attrs = {**ds.attrs, "title": f"Convergence of a_min,OVER with the number of noise realisations, "
                                      f"{ds['strategy'].item()}", "paper_figure": "6a"}
    return document_missing(out.assign_coords(strategy=ds["strategy"], noise_level=ds["noise_level"]))


# --- J_OS tables ---------------------------------------------------------------------------------
def _jos(system: xr.Dataset, reference: xr.Dataset, a_max0_g: float) -> tuple[float, int]:
    j, n, _ = jos_of(system, reference, a_max0_g)
    return j, n


PROVENANCE_PREFIXES = ("block_", "anchorage_")
PROVENANCE_KEYS = ("noise_seed", "noise_match", "noise_dt_s", "excitation", "overturn_criterion", "free_time_s",
                   "grid_amplitude_start", "grid_amplitude_stop", "grid_amplitude_step", "grid_amplitude_resolution",
                   "noise_step_s", "noise_rescale", "noise_level_means", "noise_band_hz", "noise_span_s")


def provenance(spectra) -> dict:
    """Attributes a table inherits from the spectra it compares: the seed, the block, the device
    (anchorage), the excitation and scan, and the number of noise realisations of the noisy spectra."""
    first = spectra[0]
    attrs = {k: val for k, val in first.attrs.items() if k.startswith(PROVENANCE_PREFIXES) or k in PROVENANCE_KEYS}
    noisy = sorted({int(ds.sizes["realisation"]) for ds in spectra if float(ds["noise_level"]) > 0})
    attrs["n_realisations"] = noisy[0] if len(noisy) == 1 else str(noisy)
    attrs["n_realisations_note"] = "noise realisations of each noisy spectrum (a noise-free spectrum has one)"
    return attrs


def _find(datasets, **coords) -> xr.Dataset:
    for ds in datasets:
        if all(np.isclose(float(ds[k]), v) if not isinstance(v, str) else ds[k].item() == v
               for k, v in coords.items()):
            return ds
    raise KeyError(f"no spectrum with {coords}")


def _table(values: np.ndarray, n_star: np.ndarray, coords: dict, attrs: dict) -> xr.Dataset:
    dims = tuple(coords)
    return xr.Dataset(
        {"j_os": (dims, values, {"units": "percent", "long_name": "utility index J_OS, Eq. 21",
                                 "missing_value_meaning": MISSING_MEANINGS["j_os"]}),
         "n_star": (dims, n_star, {"units": "1", "long_name": "N*, frequencies counted in Eq. 21"})},
        coords={k: (k, list(v)) for k, v in coords.items()},
        attrs={"paper": PAPER, "rockstudy_version": __version__, **attrs})


def table1(spectra, strategies, noise_levels: dict, a_max0_g: float) -> xr.Dataset:
    """Table 1: J_OS of each strategy at each noisy level against (a) the same strategy without
    noise and (b) the free-standing block at the same noise level (for FS itself J_OS = 0 over the
    N* frequencies where it overturns below a_max,0, as ``rockstudy jos`` gives; NaN only where N* = 0)."""
    free = noise_free_level(noise_levels)
    noisy = [name for name in noise_levels if name != free]
    j = np.full((len(REFERENCES), len(strategies), len(noisy)), np.nan)
    n = np.zeros(j.shape, dtype=np.int64)
    for si, s in enumerate(strategies):
        for li, name in enumerate(noisy):
            system = _find(spectra, strategy=s, noise_level=noise_levels[name])
            refs = [_find(spectra, strategy=s, noise_level=0.0),
                    _find(spectra, strategy="FS", noise_level=noise_levels[name])]
            for ri, ref in enumerate(refs):
                j[ri, si, li], n[ri, si, li] = _jos(system, ref, a_max0_g)
    return _table(j, n, {"reference": REFERENCES, "strategy": strategies, "noise_level": noisy},
                  {"title": "Table 1: utility index J_OS at each noise level", "paper_table": "1",
                   "a_max0_g": a_max0_g, "reference_meanings": "no_noise: same strategy without noise (R000); "
                   "fs_same_noise: free-standing block at the same noise level",
                   "noise_level_values": str(noise_levels), **provenance(spectra)})


def timing_table(sweep, same_strategy, free_standing, variable: str, a_max0_g: float,
                 reference: str = "continuous_same_noise") -> xr.Dataset:
    """J_OS of sampled (or delayed) control against the same strategy without that timing
    (``same_strategy``: continuous control, or sampled without delay) and against the
    free-standing block, both at the sweep's noise level (§5.2, Figs. 7–8)."""
    strategies = sorted({ds["strategy"].item() for ds in sweep})
    values = sorted({float(ds[variable]) for ds in sweep})
    j = np.full((len(REFERENCES), len(strategies), len(values)), np.nan)
    n = np.zeros(j.shape, dtype=np.int64)
    for ds in sweep:
        s, si, vi = ds["strategy"].item(), strategies.index(ds["strategy"].item()), values.index(float(ds[variable]))
        level = float(ds["noise_level"])
        refs = [_find(same_strategy, strategy=s, noise_level=level), _find(free_standing, noise_level=level)]
        for ri, ref in enumerate(refs):
            j[ri, si, vi], n[ri, si, vi] = _jos(ds, ref, a_max0_g)
    out = _table(j, n, {"reference": (reference, "fs_same_noise"), "strategy": strategies,
                        variable: values},
                 {"title": f"J_OS against {variable} (§5.2)", "a_max0_g": a_max0_g,
                  "sampling_time_s": str(sorted({float(d['sampling_time']) for d in sweep})),
                  "noise_level": str(sorted({float(d['noise_level']) for d in sweep})),
                  **provenance(list(sweep) + list(same_strategy) + list(free_standing))})
    out[variable].attrs = {"units": "s"}
    return out


def table_markdown(table: xr.Dataset) -> str:
    """The table as Markdown: rows strategies, columns reference × last dimension, J_OS in %."""
    column = table["j_os"].dims[-1]
    head = ["strategy"] + [f"{r}: {c}" for r in table["reference"].values for c in table[column].values]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for s in table["strategy"].values:
        cells = [f"{v:+.2f}%" if np.isfinite(v) else "-"
                 for r in table["reference"].values for v in table["j_os"].sel(reference=r, strategy=s).values]
        lines.append("| " + " | ".join([str(s)] + cells) + " |")
    return f"{table.attrs.get('title', '')}\n\n" + "\n".join(lines) + "\n"


def table_csv(table: xr.Dataset) -> str:
    """The table in long form: one row per (reference, strategy, column) with J_OS [%] and N*."""
    return table.to_dataframe().reset_index().to_csv(index=False, float_format="%.4f")


# --- time histories -----------------------------------------------------------------------------
def history_dataset(result, scenario: Scenario, motion, frequency_ratio: float, amplitude_ratio: float,
                    realisation: int = 0, dt: float = NOISE_DT) -> xr.Dataset:
    """A :class:`SimulationResult` history as a labelled Dataset with the paper's normalisations
    (Figs. 2, 3, 5b): θ/α, θ̇/(p·α), κ/κ_max at the integrator's steps (``time``) and the ground
    motion Ẍ_g/(g·tanα) of ``motion`` sampled every ``dt`` [s] (``ground_time``)."""
    if result.history is None:
        raise ValueError("the simulation has no history: run it with record_history=True")
    h, b, an = result.history, scenario.block, scenario.anchorage
    ground_time = np.arange(0.0, result.end_time + dt, dt)
    kappa_ref = an.kappa_max if an.kappa_max > 0 else 1.0
    one = {"units": "1"}
    summary = result.summary()
    return xr.Dataset(
        {"theta": ("time", h["theta"], {"units": "rad", "long_name": "rotation theta"}),
         "theta_dot": ("time", h["theta_dot"], {"units": "rad/s", "long_name": "angular velocity"}),
         "kappa": ("time", h["kappa"], {**one, "long_name": "dimensionless stiffness 4Kb^2/(mgR)"}),
         "ground_acceleration": ("time", h["ground_acceleration"], {"units": "m/s^2", "long_name": "X_g"}),
         "rotation_ratio": ("time", h["theta"] / b.alpha, {**one, "long_name": "theta/alpha"}),
         "velocity_ratio": ("time", h["theta_dot"] / (b.p * b.alpha), {**one, "long_name": "theta_dot/(p alpha)"}),
         "stiffness_ratio": ("time", h["kappa"] / kappa_ref, {**one, "long_name": "K/K_max"}),
         "ground_ratio": ("ground_time", motion.horizontal(ground_time) / b.uplift_acceleration,
                          {**one, "long_name": "X_g/(g tan(alpha))"})},
        coords={"time": ("time", h["t"], {"units": "s", "long_name": "time (integrator steps)"}),
                "ground_time": ("ground_time", ground_time, {"units": "s", "long_name": "time (uniform)"})},
        attrs={"title": f"Time history, {scenario.control.strategy}, omega_p/p={frequency_ratio:g}, "
                        f"a_p/(g tan alpha)={amplitude_ratio:g}", "paper": PAPER, "rockstudy_version": __version__,
               "frequency_ratio": frequency_ratio, "amplitude_ratio": amplitude_ratio,
               "noise_realisation": int(realisation), "status": summary["status"],
               "overturned": int(summary["overturned"]), "n_impacts": summary["n_impacts"],
               "excitation_end_s": excitation_duration(scenario.excitation, scenario.omega(frequency_ratio)),
               **scenario.to_attrs()})


def time_history(scenario: Scenario, frequency_ratio: float, amplitude_ratio: float,
                 realisation: int = 0) -> xr.Dataset:
    """Simulate one (frequency, amplitude, realisation) case and return its labelled history."""
    motion, _ = scenario.motion(frequency_ratio, amplitude_ratio, realisation)
    result = simulate(scenario.block, scenario.anchorage, scenario.control, motion, record_history=True,
                      overturn_criterion=scenario.overturn_criterion, free_time=scenario.free_time)
    return history_dataset(result, scenario, motion, frequency_ratio, amplitude_ratio, realisation)


# --- checks across keys --------------------------------------------------------------------------
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
        reading_from_dict(config["noise"])
    except ValueError as exc:
        raise v.InputError(f"noise: {exc}") from None
    for name, spec in config["reproduction"]["readings"].items():
        try:
            reading_from_dict(spec)
        except ValueError as exc:
            raise v.InputError(f"reproduction.readings.{name}: {exc}") from None
    from .calibration import CalibrationDesign
    cal = config["calibration"]
    try:
        CalibrationDesign(cal["kappa_max"], cal["damping_ratio"], cal["ultimate_rotation"], cal["kappa_min"])
    except ValueError as exc:
        raise v.InputError(f"calibration: {exc}") from None


def grid_size_points(spec: dict) -> int:
    """Number of points of an amplitude grid ``{start, stop, step}`` (the simulations of one map row)."""
    return v.grid_size(spec["start"], spec["stop"], spec["step"])


def check_noise(noise: xr.Dataset, scenario: Scenario) -> None:
    """The noise file and the scenario describe the same realisations (seed, level, reading)."""
    expected = {"noise_seed": scenario.seed, "noise_level": scenario.noise_level,
                "excitation": scenario.excitation, **scenario.noise.to_attrs()}
    for attr, value in expected.items():
        if noise.attrs.get(attr) != value:
            raise ValueError(f"noise file has {attr}={noise.attrs.get(attr)!r}, the scenario {value!r}")
