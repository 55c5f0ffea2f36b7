"""The study's labelled datasets (paper §5, Figs. 2–6): the noise realisations of a level, the
spectra gathered from realisation chunks, the convergence with the number of realisations, and
time histories. Every dataset is self-describing (units, long names, parameters, seed, paper
reference, the meaning of every NaN).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

from rockstudy._version import __version__
from rockstudy.core.constants import NOISE_DT, PAPER
from rockstudy.core.io import check_dataset

if TYPE_CHECKING:
    from rockstudy.analysis.scenario import Scenario

# The functions that regenerate noise or run the engine import it where they are called: gathering and the
# tables read datasets only, without loading the compiled model.

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
    :data:`MISSING_MEANINGS`; returns ``ds``.

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset; its variables' attributes are changed in place.
    """
    for name, meaning in MISSING_MEANINGS.items():
        if name in ds.variables:
            ds[name].attrs["missing_value_meaning"] = meaning
    return ds


def noise_dataset(scenario: Scenario, frequency_ratios, realisations, reference_frequency_ratio: float,
                  n_records: int) -> xr.Dataset:
    """The noise realisations of one level: seeds, spawn keys, energy and PGA ratios, unit records.

    Records are regenerated exactly by ``noisy_record(excitation, ω_p, level, k, seed, reading)``
    with ``SeedSequence(seed, spawn_key=(level_key, k))``; the first ``n_records`` unit records
    at ``reference_frequency_ratio`` are stored with the baseline for Fig. 4.

    Parameters
    ----------
    scenario : rockstudy.analysis.scenario.Scenario
        The scenario whose noise level, seed, reading, excitation and block make the records.
    frequency_ratios : array_like of float
        The frequency ratios ω_p/p at which the energy and PGA ratios are computed. [-]
    realisations : iterable of int
        The noise realisations k.
    reference_frequency_ratio : float
        The frequency ratio ω_p/p of the stored baseline and unit records. [-]
    n_records : int
        How many unit records to store (those of the first ``n_records`` realisations).
    """
    from rockstudy.model.noise import baseline_samples, level_key, noisy_record

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
         "baseline": ("t", base, {**ratio, "long_name": "unit-amplitude baseline excitation X_g/a_p",
                                     "frequency_ratio": reference_frequency_ratio}),
         "record": (("record_realisation", "t"), recs,
                    {**ratio, "long_name": "unit-amplitude noisy record X_g/a_p",
                     "frequency_ratio": reference_frequency_ratio})},
        coords={"realisation": ("realisation", np.array(ks, dtype=np.int64), {"long_name": "noise realisation k"}),
                "record_realisation": ("record_realisation", np.array(kept, dtype=np.int64),
                                       {"long_name": "noise realisation k of the stored records"}),
                "frequency_ratio": ("frequency_ratio", freqs, {"units": "1", "long_name": "omega_p/p"}),
                "t": ("t", np.arange(len(base)) * dt,
                      {"units": "s", "long_name": "time since the start of the ground motion"})},
        attrs={"title": f"Noise realisations, level {level:g} (noise energy / baseline energy)", "paper": PAPER,
               "paper_section": "5 (Fig. 4)", "rockstudy_version": __version__, "noise_level": level,
               "noise_seed": sc.seed, "noise_level_key": level_key(level), **sc.noise.to_attrs(),
               "excitation": sc.excitation, "reference_frequency_ratio": reference_frequency_ratio,
               "regenerate": "rockstudy.model.noise.noisy_record(excitation, frequency_ratio*block_p, noise_level, k, "
                             "noise_seed, NoiseReading(step=noise_step_s, rescale=noise_rescale, "
                             "level_means=noise_level_means, band=noise_band_hz or None, span=noise_span_s)); "
                             "SeedSequence(seed, spawn_key=(level_key, k))",
               **sc.block.to_attrs()})


PER_CHUNK_ATTRS = ("compute_time_s",)
DERIVED_ATTRS = ("title", "paper", "paper_equations", "rockstudy_version", "rockstudy_source_sha256")
"""Attributes that differ between the chunks of one spectrum."""
REALISATION_VARS = ("threshold_realisation", "last_safe", "n_simulations", "n_undetermined", "energy_ratio",
                    "pga_ratio")


def gather_spectra(parts) -> xr.Dataset:
    """Concatenate realisation chunks of one spectrum and recompute the aggregates.

    ``threshold`` is the lowest threshold over all realisations (the paper's a_min,OVER),
    ``threshold_mean``/``threshold_std`` the mean and std over the realisations with a threshold.

    Parameters
    ----------
    parts : iterable of xarray.Dataset
        The realisation chunks of one spectrum (non-empty, in any order); they must share every setting and
        no realisation.
    """
    parts = sorted(parts, key=lambda d: int(d["realisation"].values[0]))
    first = parts[0]
    # the settings first, so that a mismatch names the setting rather than the title derived from it
    keys = sorted((k for k in first.attrs if k not in PER_CHUNK_ATTRS), key=lambda k: k in DERIVED_ATTRS)
    same = {k: first.attrs[k] for k in keys}
    same["frequency_ratio"] = first["frequency_ratio"].values.tolist()
    for part in parts[1:]:  # chunks of one spectrum share every setting; only their realisations differ
        check_dataset(part, part.encoding.get("source", "a chunk"), same)
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
    """Fig. 6a: the lowest threshold over the first N realisations, N = 1 … n.

    Parameters
    ----------
    ds : xarray.Dataset
        A gathered spectrum (:func:`gather_spectra`), with ``threshold_realisation`` and scalar ``strategy`` and
        ``noise_level`` coordinates.
    """
    from rockstudy.analysis.spectra import convergence

    out = convergence(ds).to_dataset()
    out["threshold_realisation"] = ds["threshold_realisation"]
    out.attrs = {**ds.attrs, "title": f"Convergence of a_min,OVER with the number of noise realisations, "
                                      f"{ds['strategy'].item()}", "paper_figure": "6a"}
    return document_missing(out.assign_coords(strategy=ds["strategy"], noise_level=ds["noise_level"]))


def history_dataset(result, scenario: Scenario, motion, frequency_ratio: float, amplitude_ratio: float,
                    realisation: int = 0, dt: float = NOISE_DT) -> xr.Dataset:
    """A :class:`SimulationResult` history as a labelled Dataset with the paper's normalisations
    (Figs. 2, 3, 5b): θ/α, θ̇/(p·α), κ/κ_max on a strictly increasing ``t`` [s] (the integrator's
    steps and events, each once, the state just after a jump), the velocities just before and
    after each impact on the ``impact`` dimension, and the ground motion Ẍ_g/(g·tanα) of
    ``motion`` sampled every ``dt`` [s] (on ``t_ground``); the layout of
    :meth:`SimulationResult.to_dataset` with the scenario's attributes.

    Parameters
    ----------
    result : rockstudy.engine.simulation_result.SimulationResult
        A run made with ``record_history=True``.
    scenario : rockstudy.analysis.scenario.Scenario
        The scenario of the run; its block, anchorage and attributes label the dataset.
    motion : rockstudy.model.excitation.GroundMotion
        The ground motion that drove the run.
    frequency_ratio : float
        The run's ω_p/p. [-]
    amplitude_ratio : float
        The run's a_p/(g·tanα). [-]
    realisation : int, default 0
        The run's noise realisation k.
    dt : float, default NOISE_DT
        Sampling step of the ground motion on ``t_ground``. [s]
    """
    from rockstudy.model.excitation import excitation_duration

    ds = result.to_dataset(scenario.block, scenario.anchorage, motion, dt)
    ds.attrs = {"title": f"Time history, {scenario.control.strategy}, omega_p/p={frequency_ratio:g}, "
                         f"a_p/(g tan alpha)={amplitude_ratio:g}", "paper": PAPER, "rockstudy_version": __version__,
                "frequency_ratio": frequency_ratio, "amplitude_ratio": amplitude_ratio,
                "noise_realisation": int(realisation), **ds.attrs,
                "excitation_end_s": excitation_duration(scenario.excitation, scenario.omega(frequency_ratio)),
                **scenario.to_attrs()}
    return ds


def time_history(scenario: Scenario, frequency_ratio: float, amplitude_ratio: float,
                 realisation: int = 0) -> xr.Dataset:
    """Simulate one (frequency, amplitude, realisation) case and return its labelled history.

    Parameters
    ----------
    scenario : rockstudy.analysis.scenario.Scenario
        The scenario to simulate.
    frequency_ratio : float
        Frequency ratio ω_p/p. [-]
    amplitude_ratio : float
        Amplitude ratio a_p/(g·tanα). [-]
    realisation : int, default 0
        Noise realisation k (0 without noise).
    """
    run = scenario.simulate(frequency_ratio, amplitude_ratio, realisation, record_history=True)
    return history_dataset(run.result, scenario, run.motion, frequency_ratio, amplitude_ratio, realisation)


def check_noise(noise: xr.Dataset, scenario: Scenario) -> None:
    """The noise file and the scenario describe the same realisations (seed, level, reading).

    Parameters
    ----------
    noise : xarray.Dataset
        A noise file (:func:`noise_dataset`).
    scenario : rockstudy.analysis.scenario.Scenario
        The scenario that uses it.
    """
    expected = {"noise_seed": scenario.seed, "noise_level": scenario.noise_level,
                "excitation": scenario.excitation, **scenario.noise.to_attrs()}
    for attr, value in expected.items():
        if noise.attrs.get(attr) != value:
            raise ValueError(f"noise file has {attr}={noise.attrs.get(attr)!r}, the scenario {value!r}")


NOISE_FILE_KEYS = ("noise_seed", "noise_level", "excitation")
"""Scenario attributes a noise file carries besides its block and reading (it has no device or control)."""


def expected_attrs(scenario: Scenario, kind: str = "spectrum", *, realisations=None, frequency_ratios=None,
                   amplitude_grid=None, **extra) -> dict:
    """What a dataset of ``kind`` made for ``scenario`` must say about itself (the expectations that
    :func:`rockstudy.core.io.check_dataset` compares), as plain JSON-able values.

    Parameters
    ----------
    scenario : rockstudy.analysis.scenario.Scenario
        The scenario the dataset is made for.
    kind : {"spectrum", "noise", "history", "map", "study"}, default "spectrum"
        ``"noise"``: seed, level, excitation, reading and block; ``"study"``: block, excitation, seed,
        criterion and free time (what a table inherits); the others: every attribute of the scenario.
    realisations : iterable of int, optional
        The ``realisation`` coordinate.
    frequency_ratios : iterable of float, optional
        The ``frequency_ratio`` coordinate. [-]
    amplitude_grid : rockstudy.analysis.spectra.AmplitudeGrid or dict, optional
        The amplitude scan, or a dict with ``start``, ``stop``, ``step``, ``resolution``. [-]
    **extra : dict
        More attributes (e.g. ``noise_realisation`` of a history).
    """
    attrs = scenario.to_attrs()
    if kind == "noise":
        keep = set(NOISE_FILE_KEYS) | set(scenario.noise.to_attrs()) | set(scenario.block.to_attrs())
        attrs = {k: val for k, val in attrs.items() if k in keep}
    elif kind == "study":
        keep = {"noise_seed", "excitation", "overturn_criterion", "free_time_s"} | set(scenario.block.to_attrs())
        attrs = {k: val for k, val in attrs.items() if k in keep}
    elif kind not in ("spectrum", "history", "map"):
        raise ValueError(f"kind must be noise, spectrum, history, map or study, got {kind!r}")
    out = {k: (val.item() if isinstance(val, np.generic) else val) for k, val in attrs.items()}
    if realisations is not None:
        out["realisation"] = [int(k) for k in realisations]
    if frequency_ratios is not None:
        out["frequency_ratio"] = [float(f) for f in frequency_ratios]
    if amplitude_grid is not None:
        grid = amplitude_grid if isinstance(amplitude_grid, dict) else amplitude_grid.__dict__
        out.update({f"grid_amplitude_{k}": float(grid[k]) for k in ("start", "stop", "step", "resolution")})
    out.update(extra)
    return out


# --- what a dataset says about itself -----------------------------------------------------------
class InconsistentDataset(ValueError):
    """A dataset contradicts itself (an edited or damaged file); the message names the file and the rule broken."""

    def __init__(self, path, rule: str):
        super().__init__(f"{path}: {rule}: this file contradicts itself (an edited or damaged file); delete it "
                         "and rerun to rebuild it")
        self.path, self.rule = str(path), rule


def _close(a, b) -> bool:
    return bool(np.allclose(a, b, rtol=1e-12, atol=0.0, equal_nan=True))


def _spectrum_problems(ds: xr.Dataset) -> list[str]:
    """The rules a spectrum (whole or a chunk), a convergence or a probability surface keeps."""
    problems = []
    if "threshold_realisation" not in ds or "realisation" not in ds["threshold_realisation"].dims:
        return problems
    per_realisation = ds["threshold_realisation"]
    n = per_realisation.sizes["realisation"]
    if "n_realisations" in ds.attrs and int(ds.attrs["n_realisations"]) != n:
        problems.append(f"n_realisations is {ds.attrs['n_realisations']} but the file holds {n} realisations")
    lowest = per_realisation.min("realisation", skipna=True)
    if "threshold" in ds and not np.array_equal(ds["threshold"].values, lowest.values, equal_nan=True):
        problems.append("threshold is not the lowest threshold_realisation over the realisations (a_min,OVER)")
    if "threshold_mean" in ds and not _close(ds["threshold_mean"], per_realisation.mean("realisation", skipna=True)):
        problems.append("threshold_mean is not the mean of threshold_realisation")
    if "threshold_convergence" in ds and not np.array_equal(
            ds["threshold_convergence"].isel({ds["threshold_convergence"].dims[0]: -1}).values, lowest.values,
            equal_nan=True):
        problems.append("threshold_convergence over all realisations is not the lowest threshold_realisation")
    stop, resolution = ds.attrs.get("grid_amplitude_stop"), ds.attrs.get("grid_amplitude_resolution")
    values = per_realisation.values
    if stop is not None and np.any(values[np.isfinite(values)] > stop * (1 + 1e-12)):
        problems.append(f"a threshold_realisation lies above the scan's top grid_amplitude_stop = {stop:g}")
    if np.any(values[np.isfinite(values)] <= 0):
        problems.append("a threshold_realisation is not positive")
    if "last_safe" in ds and resolution is not None:
        gap = (per_realisation - ds["last_safe"]).values
        bad = np.isfinite(gap) & ((gap < 0) | (gap > resolution * (1 + 1e-9) + 1e-12))
        if np.any(bad):
            problems.append(f"a threshold_realisation is not within grid_amplitude_resolution = {resolution:g} above "
                            "its last_safe amplitude (the bisection's bracket)")
    return problems


def _probability_problems(ds: xr.Dataset) -> list[str]:
    if "probability" not in ds or "n_overturned" not in ds or "n_realisations" not in ds.coords:
        return []
    n = int(ds["n_realisations"])
    if not _close(ds["probability"], ds["n_overturned"] / n):
        return [f"probability is not n_overturned / n_realisations ({n})"]
    return []


def _fragility_problems(ds: xr.Dataset) -> list[str]:
    problems = []
    if "overturned" not in ds or "record" not in ds.dims:
        return problems
    if "n_records" in ds.attrs and int(ds.attrs["n_records"]) != ds.sizes["record"]:
        problems.append(f"n_records is {ds.attrs['n_records']} but the file holds {ds.sizes['record']} records")
    if "fraction" in ds and not _close(ds["fraction"], ds["overturned"].mean("record")):
        problems.append("fraction is not the share of the records that overturn (overturned)")
    resolution = ds.attrs.get("threshold_resolution")
    if resolution is not None and "threshold_intensity" in ds and "last_safe_intensity" in ds:
        gap = (ds["threshold_intensity"] - ds["last_safe_intensity"]).values
        if np.any(np.isfinite(gap) & ((gap < 0) | (gap > resolution * (1 + 1e-9) + 1e-12))):
            problems.append(f"a threshold_intensity is not within threshold_resolution = {resolution:g} above its "
                            "last_safe_intensity")
    return problems


def _record_set_problems(ds: xr.Dataset) -> list[str]:
    if "acceleration" not in ds or "npts" not in ds or "pga" not in ds:
        return []
    from rockstudy.model.records import STANDARD_GRAVITY

    acc, npts = ds["acceleration"].values, ds["npts"].values.astype(int)
    if np.any(npts < 1) or np.any(npts > acc.shape[1]):
        return ["npts is not between 1 and the length of the sample dimension"]
    peaks = np.array([np.max(np.abs(row[:n])) for row, n in zip(acc, npts)]) / STANDARD_GRAVITY
    if not np.allclose(peaks, ds["pga"].values, rtol=1e-9, atol=0.0):
        return ["pga is not the peak of |acceleration| over each record's npts samples"]
    return []


def check_invariants(ds: xr.Dataset, path) -> xr.Dataset:
    """``ds`` (read from ``path``) keeps the rules its own variables imply; returns ``ds``.

    A spectrum's ``threshold`` is the lowest ``threshold_realisation`` (the paper's a_min,OVER) and
    ``threshold_mean`` their mean; every threshold lies inside the file's stated scan (positive, at most
    ``grid_amplitude_stop``) and within ``grid_amplitude_resolution`` above its ``last_safe`` amplitude;
    ``n_realisations`` counts the realisations. A probability surface's ``probability`` is
    ``n_overturned / n_realisations``. A fragility's ``fraction`` is the share of its records that
    overturn, ``n_records`` counts them, and each record's threshold lies within
    ``threshold_resolution`` above its last safe intensity. A record set's ``pga`` is the peak of each
    record's samples.

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset read from ``path``.
    path : str or pathlib.Path
        The file it was read from, named in the message.

    Raises
    ------
    InconsistentDataset
        Naming the file and the first rule it breaks.
    """
    for problems in (_spectrum_problems, _probability_problems, _fragility_problems, _record_set_problems):
        found = problems(ds)
        if found:
            raise InconsistentDataset(path, found[0])
    return ds
