"""The readings study: which reading of the paper's loose noise model reproduces Table 1's FS row.

The FS row of Table 1 (J_OS of the free-standing block at R001, R005, R010 against the
noise-free block, Eq. 21) depends only on the block, J_OS and the noise model, so it is the
one row no unknown device can excuse. For each :class:`rockstudy.model.noise.NoiseReading` it is
computed from 40-realisation spectra and compared with the paper's: the largest absolute
difference and the root mean square difference, in points of J_OS.
"""
from __future__ import annotations

import math

import numpy as np
import xarray as xr

from rockstudy._version import __version__
from rockstudy.analysis.utility_index import utility_index
from rockstudy.core import validation
from rockstudy.model.noise import NoiseReading, reading_from_dict
from rockstudy.studies.claims import PAPER, PAPER_LEVELS, PAPER_TABLE1

PAPER_FS_ROW = dict(zip(PAPER_LEVELS, PAPER_TABLE1[("no_noise", "FS")]))
"""The paper's FS row of Table 1: J_OS against no noise at R001, R005, R010. [%]"""


def jos_against(system: xr.Dataset, reference: xr.Dataset, a_max0_g: float) -> tuple[float, int]:
    """J_OS [%] and N* of a spectrum against a reference spectrum on the same grid (Eq. 21).

    Parameters
    ----------
    system, reference : xarray.Dataset
        Overturning spectra (``threshold`` over ``frequency_ratio``) on the same frequencies; the block's α
        is read from the reference's ``block_alpha`` attribute.
    a_max0_g : float
        Protection level a_max,0. [g]
    """
    if not np.allclose(system["frequency_ratio"], reference["frequency_ratio"]):
        raise ValueError("J_OS needs the system and the reference on the same frequencies")
    ratio = float(a_max0_g) / math.tan(float(reference.attrs["block_alpha"]))
    return utility_index(system["threshold"].values, reference["threshold"].values, ratio)


def distance(ours, paper) -> tuple[float, float]:
    """Largest absolute difference and RMS difference between two rows of J_OS. [points of %]

    Parameters
    ----------
    ours, paper : array_like
        The two rows of J_OS, of equal length; a NaN in either gives NaN distances. [%]
    """
    d = np.asarray(ours, float) - np.asarray(paper, float)
    if d.size == 0 or np.any(np.isnan(d)):
        return math.nan, math.nan
    return float(np.max(np.abs(d))), float(np.sqrt(np.mean(d * d)))


def readings_table(spectra: dict, reference: xr.Dataset, readings: dict, levels: dict, a_max0_g: float,
                   paper: dict = PAPER_FS_ROW) -> xr.Dataset:
    """The FS row of Table 1 for each reading, and its distance to the paper's.

    Parameters
    ----------
    spectra : dict
        {(reading name, level name): gathered spectrum dataset}.
    reference : xarray.Dataset
        The noise-free spectrum of the same strategy (the reference of the row).
    readings : dict
        {reading name: NoiseReading}, in the order of the table.
    levels : dict
        {level name: noise level} of the noisy levels (e.g. R001, R005, R010). [-]
    a_max0_g : float
        a_max,0 in units of g. [g]
    paper : dict, default PAPER_FS_ROW
        {level name: the paper's J_OS} [%]; levels absent from it get NaN differences.

    Returns
    -------
    xarray.Dataset
        ``j_os`` and ``n_star`` (reading, noise_level), ``paper`` (noise_level), ``difference``,
        ``max_abs_difference`` and ``rms_difference`` (reading) over the levels the paper has,
        ``energy_ratio`` and ``pga_ratio`` (mean achieved ratios of the records), and the
        reading's fields as coordinates along ``reading``.
    """
    names, level_names = list(readings), list(levels)
    j = np.full((len(names), len(level_names)), np.nan)
    n = np.zeros(j.shape, dtype=np.int64)
    e_ratio, p_ratio = np.full(j.shape, np.nan), np.full(j.shape, np.nan)
    for ri, name in enumerate(names):
        for li, level in enumerate(level_names):
            ds = spectra[(name, level)]
            j[ri, li], n[ri, li] = jos_against(ds, reference, a_max0_g)
            e_ratio[ri, li] = float(ds["energy_ratio"].mean())
            p_ratio[ri, li] = float(ds["pga_ratio"].mean())
    paper_row = np.array([paper.get(level, math.nan) for level in level_names])
    diff = j - paper_row
    compared = ~np.isnan(paper_row)
    dist = [distance(j[ri, compared], paper_row[compared]) for ri in range(len(names))]
    fields = [readings[name] for name in names]
    pct = {"units": "percent"}
    dims = ("reading", "noise_level")
    return xr.Dataset(
        {"j_os": (dims, j, {**pct, "long_name": "J_OS of FS against FS without noise (Table 1, Eq. 21)"}),
         "n_star": (dims, n, {"units": "1", "long_name": "N*, frequencies counted in Eq. 21"}),
         "paper": ("noise_level", paper_row, {**pct, "long_name": "the paper's Table 1 FS row"}),
         "difference": (dims, diff, {**pct, "long_name": "ours minus paper (points)"}),
         "max_abs_difference": ("reading", np.array([d[0] for d in dist]),
                                {**pct, "long_name": "largest |ours - paper| over the paper's levels (points)"}),
         "rms_difference": ("reading", np.array([d[1] for d in dist]),
                            {**pct, "long_name": "RMS of ours - paper over the paper's levels (points)"}),
         "energy_ratio": (dims, e_ratio, {"units": "1", "long_name": "mean record energy / baseline energy"}),
         "pga_ratio": (dims, p_ratio, {"units": "1", "long_name": "mean record PGA / baseline PGA"})},
        coords={"reading": ("reading", names),
                "noise_level": ("noise_level", level_names),
                "level_value": ("noise_level", [float(levels[lv]) for lv in level_names],
                                {"units": "1", "long_name": "noise level r"}),
                "step": ("reading", [r.step for r in fields], {"units": "s", "long_name": "record sampling step"}),
                "rescale": ("reading", [r.rescale for r in fields]),
                "level_means": ("reading", [r.level_means for r in fields]),
                "band": ("reading", [math.nan if r.band is None else r.band for r in fields],
                         {"units": "Hz", "long_name": "noise band limit (NaN: white)"}),
                "span": ("reading", [r.span for r in fields], {"units": "s", "long_name": "noise after T_d"}),
                "label": ("reading", [r.label() for r in fields])},
        attrs={"title": "Readings study: FS row of Table 1 under each reading of the noise model",
               "paper": PAPER, "paper_table": "1 (FS row)", "rockstudy_version": __version__,
               "a_max0_g": float(a_max0_g), "closest_reading": closest_reading_of(names, dist)})


def closest_reading_of(names, distances) -> str:
    """The name with the smallest RMS difference (ties: smallest max abs difference).

    Parameters
    ----------
    names : sequence of str
        The readings' names.
    distances : sequence of tuple of float
        (largest absolute difference, RMS difference) of each reading, as :func:`distance` gives them; NaN
        RMS differences are skipped. [%]
    """
    usable = [(d[1], d[0], i) for i, d in enumerate(distances) if not math.isnan(d[1])]
    return names[min(usable)[2]] if usable else ""


def closest_reading(table: xr.Dataset) -> str:
    """The reading of a :func:`readings_table` closest to the paper (smallest RMS difference).

    Parameters
    ----------
    table : xarray.Dataset
        A table of :func:`readings_table`.
    """
    names = list(table["reading"].values)
    dist = list(zip(table["max_abs_difference"].values, table["rms_difference"].values))
    return closest_reading_of(names, dist)


def readings_markdown(table: xr.Dataset) -> str:
    """The readings table as Markdown, closest reading first.

    Parameters
    ----------
    table : xarray.Dataset
        A table of :func:`readings_table`.
    """
    levels = list(table["noise_level"].values)
    order = np.argsort(np.where(np.isnan(table["rms_difference"].values), np.inf, table["rms_difference"].values),
                       kind="stable")
    head = ["reading", "what"] + [f"{lv} J_OS (diff)" for lv in levels] + ["max abs diff", "RMS diff",
                                                                            "energy ratio", "PGA ratio"]
    lines = [f"{table.attrs.get('title', '')}", "",
             "Paper: " + ", ".join(f"{lv} {p:+.2f} %" for lv, p in zip(levels, table["paper"].values)) + ".",
             f"Closest: **{table.attrs.get('closest_reading', '')}**.", "",
             "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for i in order:
        t = table.isel(reading=int(i))
        cells = [f"{float(v):+.2f} ({float(d):+.2f})" for v, d in zip(t["j_os"].values, t["difference"].values)]
        e = "/".join(f"{float(v):.3f}" for v in t["energy_ratio"].values)
        pg = "/".join(f"{float(v):.3f}" for v in t["pga_ratio"].values)
        lines.append("| " + " | ".join([str(t["reading"].item()), str(t["label"].item())] + cells +
                                       [f"{float(t['max_abs_difference']):.2f}", f"{float(t['rms_difference']):.2f}",
                                        e, pg]) + " |")
    return "\n".join(lines) + "\n"


def readings_csv(table: xr.Dataset) -> str:
    """One row per (reading, noise level): the reading, J_OS, paper, difference and the reading's distance.

    Parameters
    ----------
    table : xarray.Dataset
        A table of :func:`readings_table`.
    """
    rows = ["reading,label,step_s,rescale,level_means,band_hz,span_s,noise_level,j_os_percent,paper_percent,"
            "difference_points,n_star,energy_ratio,pga_ratio,max_abs_difference_points,rms_difference_points"]
    for name in table["reading"].values:
        t = table.sel(reading=name)
        for level in table["noise_level"].values:
            c = t.sel(noise_level=level)
            rows.append(",".join([
                str(name), f"\"{t['label'].item()}\"", f"{float(t['step']):g}", str(t["rescale"].item()),
                str(t["level_means"].item()), f"{float(t['band']):g}", f"{float(t['span']):g}", str(level),
                f"{float(c['j_os']):.4f}", f"{float(c['paper']):.2f}", f"{float(c['difference']):.4f}",
                str(int(c["n_star"])), f"{float(c['energy_ratio']):.6f}", f"{float(c['pga_ratio']):.6f}",
                f"{float(t['max_abs_difference']):.4f}", f"{float(t['rms_difference']):.4f}"]))
    return "\n".join(rows) + "\n"


def reading_dict(reading: NoiseReading) -> dict:
    """The config form of a reading (the keys of the ``noise:`` section).

    Parameters
    ----------
    reading : rockstudy.model.noise.NoiseReading
        The reading.
    """
    return {"step": reading.step, "rescale": reading.rescale, "level_means": reading.level_means,
            "band": reading.band, "span": reading.span}


def check_config(section: dict, study=None) -> None:
    """The config's ``reproduction:`` section: every reading of ``reproduction.readings`` is a valid
    :class:`NoiseReading`, ``reproduction.realisations`` is within the limits and, given ``study``, every
    reading's records fit one simulation (span, samples) and its spectrum job (all realisations at once)
    fits the workload and memory limits.

    Parameters
    ----------
    section : dict
        The config's ``reproduction:`` section (``realisations``, ``readings``).
    study : dict, optional
        The study's ``block`` (a :class:`~rockstudy.model.block.Block`), ``excitation``, ``free_time`` [s],
        ``frequency_ratios`` [-] and ``sims_per_case``; None: only the readings and the number of
        realisations are checked.

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) naming ``reproduction.<key>``.
    """
    from rockstudy.model.excitation import check_time_span, excitation_duration
    n_real = validation.check_int_range("reproduction.realisations", section["realisations"], 1,
                                        validation.MAX_REALISATIONS)
    for name, spec in section["readings"].items():
        try:
            reading = reading_from_dict(spec, key=f"reproduction.readings.{name}")
        except ValueError as exc:
            raise validation.InputError(str(exc)) from None
        if study is None:
            continue
        key = f"reproduction.readings.{name}"
        freqs, block = study["frequency_ratios"], study["block"]
        check_time_span(block, study["excitation"], [min(freqs), max(freqs)], study["free_time"],
                        frequency_name="frequency_grid", record_step=reading.step, record_span=reading.span,
                        step_name=f"{key}.step", span_name=f"{key}.span")
        samples = validation.record_samples((excitation_duration(study["excitation"], f * block.p) for f in freqs),
                                   reading.step, reading.span)
        validation.check_workload("reproduction.realisations", n_real, n_real * len(freqs), study["sims_per_case"],
                         n_real * samples * validation.RECORD_BYTES_PER_SAMPLE)
