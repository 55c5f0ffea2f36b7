"""The Markdown tables of a record set's fragility: the stripes' fits with their intervals, the two fits of
one object side by side, every record's threshold, the summary over record sets, and the fragility numbers
the docs quote (CSV).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import xarray as xr

NONE = "—"
"""What a table shows for a number that is not there (no fit, no overturning, no interval)."""


def _num(x, spec: str = ".3f") -> str:
    """``x`` formatted with ``spec``, or :data:`NONE` when it is not a finite number."""
    x = float(x)
    return format(x, spec) if np.isfinite(x) else NONE


def _ci(low, high, spec: str = ".3f") -> str:
    """An interval "(low–high)", or "(—)" when neither end is a finite number."""
    if not (np.isfinite(float(low)) or np.isfinite(float(high))):
        return f"({NONE})"
    return f"({_num(low, spec)}–{_num(high, spec)})"


def fragility_markdown(ds: xr.Dataset) -> str:
    """Markdown table of the fits: median (95 % interval), dispersion, median shift over FS (interval).

    Parameters
    ----------
    ds : xarray.Dataset
        A fragility dataset (``fragility/<record set>.nc``,
        :func:`rockstudy.analysis.fragility.suite_fragility_dataset`).
    """
    im = ds.attrs["intensity_measure_definition"]
    lines = [f"| strategy | median θ of {im} (95 % CI) | dispersion β (± se) | θ/θ_FS (bootstrap 95 % CI) "
             f"| median shift over FS | fit |", "|---|---|---|---|---|---|"]
    for s in ds.strategy.values:
        d = ds.sel(strategy=s)
        shift = _num(d.median_shift_percent, "+.1f")
        lines.append(f"| {s} | {_num(d.fragility_median)} {_ci(d.median_low, d.median_high)} "
                     f"| {_num(d.fragility_dispersion)} ± {_num(d.dispersion_se)} "
                     f"| {_num(d.median_ratio)} {_ci(d.median_ratio_low, d.median_ratio_high)}"
                     f" | {shift}{' %' if shift != NONE else ''} | {str(d.fit_status.values)} |")
    lines.append("")
    lines.append(f"{ds.attrs['n_records']} records, {ds.sizes['intensity']} IM levels "
                 f"({float(ds.intensity.min()):g}–{float(ds.intensity.max()):g}); "
                 f"{ds.attrs['n_bootstrap']} bootstrap draws over records.")
    return "\n".join(lines + _two_fits(ds)) + "\n"


def _two_fits(ds: xr.Dataset) -> list:
    """The two lognormal fits of one object in PGA [g], side by side: the stripes' fit (P(overturn) at each
    level, the table above, which the risk uses) and the fit of the records' thresholds (their first
    overturning); empty for a fragility without per-record thresholds in PGA."""
    if not {"threshold_pga", "fragility_median_physical"} <= set(ds.data_vars) or "record_pga" not in ds.coords:
        return []
    if ds.attrs.get("intensity_measure") != "pga_ratio":
        return []
    from rockstudy.analysis.risk import threshold_fit
    rows = ["", "Two fits of the same object, PGA in g: the stripes' (P(overturn) at each level, above; the risk "
                "uses it) and the records' thresholds' (the first overturning the upward scan finds along each "
                "record's scale, a record without one censored at the last level). They differ because "
                "overturning is not monotone in the scale: a record can overturn the block at one scale and not "
                "at a higher one.", "",
            "| strategy | stripes' fit θ [g] (β) | records' thresholds' fit θ [g] (β) |", "|---|---|---|"]
    for s in ds.strategy.values:
        d, fit = ds.sel(strategy=s), threshold_fit(ds, str(s))
        rows.append(f"| {s} | {_num(d.fragility_median_physical)} ({_num(d.fragility_dispersion, '.2f')}) "
                    f"| {_num(fit.median)} ({_num(fit.dispersion, '.2f')}) |")
    return rows


def suite_summary_markdown(rows) -> str:
    """Markdown table of :func:`rockstudy.analysis.fragility.suite_summary`.

    Parameters
    ----------
    rows : list of dict
        The rows of :func:`rockstudy.analysis.fragility.suite_summary`; empty: an empty string.
    """
    from rockstudy.analysis.fragility import INTENSITY_MEASURES
    if not rows:
        return ""
    r0 = rows[0]
    lines = [f"| suite | strategy | median {INTENSITY_MEASURES[r0['intensity_measure']]} (95 % CI) | median "
             f"[{r0['physical_unit']}] (95 % CI) | β ± se | median {INTENSITY_MEASURES[r0['other_measure']]} (95 % CI) "
             "| θ/θ_FS (bootstrap 95 % CI) | shift over FS | fit |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        shift = _num(r["median_shift_percent"], "+.1f")
        cells = [f"{_num(r[k])} {_ci(r[k + '_low'], r[k + '_high'])}" for k in ("median", "median_physical")]
        cells.append(f"{_num(r['dispersion'])} ± {_num(r['dispersion_se'])}")
        cells += [f"{_num(r[k])} {_ci(r[k + '_low'], r[k + '_high'])}" for k in ("median_other", "median_ratio")]
        lines.append(f"| {r['suite']} | {r['strategy']} | " + " | ".join(cells)
                     + f" | {shift}{' %' if shift != NONE else ''} | {r['fit']} |")
    return "\n".join(lines) + "\n"


def threshold_markdown(ds: xr.Dataset) -> str:
    """Markdown table of every record's threshold: the smallest PGA [g] (and scale) that overturns the block,
    per strategy; "—" where nothing up to the last level overturns it.

    Parameters
    ----------
    ds : xarray.Dataset
        A fragility dataset with per-record thresholds (``threshold_pga``, ``threshold_scale``, the
        ``record_*`` coordinates; :func:`rockstudy.analysis.fragility.suite_fragility_dataset`).
    """
    strategies = [str(s) for s in ds.strategy.values]
    lines = ["| record | event | station | PGA [g] | " + " | ".join(f"{s}: PGA [g] (scale)" for s in strategies)
             + " |", "|---" * (4 + len(strategies)) + "|"]
    for k, name in enumerate(ds.record.values):
        cells = []
        for s in strategies:
            g = float(ds.threshold_pga.sel(strategy=s).values[k])
            sc = float(ds.threshold_scale.sel(strategy=s).values[k])
            cells.append("—" if not np.isfinite(g) else f"{g:.3f} ({sc:.2f}{' *' if sc <= 1 else ''})")
        lines.append(f"| {name} | {ds.record_event.values[k]} | {ds.record_station.values[k]} | "
                     f"{float(ds.record_pga.values[k]):.3f} | " + " | ".join(cells) + " |")
    lines.append("")
    lines.append(f"Threshold: smallest scale that overturns the block, every lower stripe level shown safe, bisected "
                 f"to {ds.attrs['threshold_resolution']:g} in {ds.attrs['intensity_measure_definition']}: the first "
                 "overturning the upward scan finds. Overturning is not monotone in the scale, so a record may "
                 "leave the block standing at a higher scale, and narrower overturning windows between the stripe "
                 "levels below it are not searched. "
                 "* : the record as recorded (scale <= 1) already overturns the block.")
    return "\n".join(lines) + "\n"


RUN_NUMBERS = {"median": "fragility_median", "median_physical": "fragility_median_physical",
               "median_physical_low": "median_low_physical", "median_physical_high": "median_high_physical",
               "dispersion": "fragility_dispersion", "median_shift_percent": "median_shift_percent"}
"""Columns of ``docs/figures/run_numbers.csv`` (the fragility numbers the docs quote) and the variables
of a fragility dataset they come from."""


def run_numbers_csv(fragility: list) -> str:
    """The fragility numbers the docs quote, one row per (record set, strategy), at full precision,
    from the run's ``fragility/<record set>.nc`` datasets.

    Parameters
    ----------
    fragility : list of xarray.Dataset
        ``fragility/<record set>.nc`` of the run, each with the variables of :data:`RUN_NUMBERS` over
        ``strategy``.
    """
    lines = [",".join(["suite", "strategy", "n_records", *RUN_NUMBERS])]
    for ds in fragility:
        for s in ds["strategy"].values:
            values = [repr(float(ds[var].sel(strategy=s))) for var in RUN_NUMBERS.values()]
            lines.append(",".join([str(ds.attrs["record_suite"]), str(s), str(int(ds.attrs["n_records"])), *values]))
    return "\n".join(lines) + "\n"
