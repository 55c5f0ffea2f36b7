"""Design charts beyond the paper's one block: a sweep of block sizes and slendernesses, and a device sweep.

**Block sweep.** For a block of half diagonal R and slenderness α (:meth:`Block.slender`), every
strategy's noise-free overturning spectrum under the paper's excitation (Eq. 23) on a frequency grid
ω_p/p, its utility index J_OS over free standing (Eqs. 18–22, a_max,0 in g), and its fragility
median on a record suite (stripes at PGA levels in g; lognormal maximum likelihood, Eqs. F1–F2 of
:mod:`rockstudy.analysis.fragility`). In the rigid-block model the spectrum in a_p/(g·tanα) against
ω_p/p depends on α (and the dimensionless device, κ and ξ) only, not on R (Dimitrakopoulos and
DeJong 2012): J_OS maps vary along α, not R. Real records have their own time scale, so the
fragility median in g grows with R (the size effect).

**Device sweep.** For one block and suite, the fragility median of each strategy over a grid of
κ_max and ξ, and the smallest κ_max whose median reaches a target PGA.

Each point (one block, or one device) is one independent call, so the workflow runs one job each.

References
----------
.. [1] E. G. Dimitrakopoulos, M. J. DeJong (2012). Revisiting the rocking block: closed-form
   solutions and similarity laws. Proceedings of the Royal Society A 468, 2294–2318.
"""
from __future__ import annotations

import math
import time

import numpy as np
import xarray as xr

from rockstudy._version import __version__
from rockstudy.analysis.fragility_fit import ALWAYS_OVERTURNS, NEVER_OVERTURNS, fit_lognormal
from rockstudy.analysis.record_scan import RecordRun, grid_outcomes, is_overturned
from rockstudy.analysis.risk_devices import device_verdicts
from rockstudy.analysis.scenario import Scenario
from rockstudy.analysis.spectra import AmplitudeGrid, spectrum
from rockstudy.analysis.utility_index import utility_index
from rockstudy.core import validation
from rockstudy.core.quantities import check_arguments, declares
from rockstudy.engine.simulate import DEFAULT_FREE_TIME
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import Block
from rockstudy.model.control import Control
from rockstudy.model.records import STANDARD_GRAVITY, STANDARD_GRAVITY_UNITS


def gravity_comment(block: Block) -> str:
    """Both values of g a design point uses: the PGA levels are in units of standard gravity (the records'),
    the block's uplift acceleration g·tan(alpha) uses the block's own g.

    Parameters
    ----------
    block : rockstudy.model.block.Block
        The design point's block; its ``gravity`` is quoted.
    """
    return (f"PGA in units of standard gravity g_n = {STANDARD_GRAVITY:g} m s-2 (the records' g); the block's "
            f"model uses g = {block.gravity:g} m s-2 (block_gravity)")


@declares(start="design_pga_g", stop="design_pga_g", count="stripe_count")
def pga_levels(start: float = 0.05, stop: float = 3.0, count: int = 30) -> np.ndarray:
    """Geometric PGA levels of the stripes, from ``start`` to ``stop`` in ``count`` points. [g]

    Parameters
    ----------
    start, stop : float, default 0.05 and 3.0
        First and last level, start < stop, each in [1e-4, 100]. [g]
    count : int, default 30
        Number of levels, 2 to 200.
    """
    check_arguments("pga_levels", {"start": start, "stop": stop, "count": count})
    if not start < stop:
        raise ValueError(f"PGA levels need start < stop, got {start} and {stop} [g]")
    return np.geomspace(start, stop, int(count))


def fragility_medians_g(block: Block, anchorage: Anchorage, controls, records, levels_g, *,
                        overturn_criterion: str = "flat", free_time: float = DEFAULT_FREE_TIME):
    """Fragility median [g] of each control over ``records`` scaled to the PGA ``levels_g`` (stripes, MLE).

    Parameters
    ----------
    block : rockstudy.model.block.Block
        The block.
    anchorage : rockstudy.model.anchorage.Anchorage
        Its restrainers (the device).
    controls : sequence of rockstudy.model.control.Control
        The control laws compared, one median each.
    records : sequence of rockstudy.model.records.Record
        The record suite; each record is scaled to every level.
    levels_g : array_like of float
        PGA levels of the stripes, in units of standard gravity. [g]
    overturn_criterion : {"flat", "alpha"}, default "flat"
        When a run counts as overturned (:func:`rockstudy.engine.simulate.overturn_rotation`).
    free_time : float, default DEFAULT_FREE_TIME
        Free rocking allowed after each record. [s]

    Returns
    -------
    medians : ndarray, shape (control,)
        Median PGA [g] (NaN when nothing or everything overturns).
    dispersions : ndarray, shape (control,)
    fractions : ndarray, shape (control, level)
        Fraction of the records that overturn the block at each level.
    status : list of str
    intervals : ndarray, shape (control, 2)
        95 % Wald interval of each median [g] (NaN without a fit).
    """
    validation.check_items("controls", controls, what="control")
    validation.check_items("records", records, what="record")
    validation.check_items("levels_g", levels_g, low=2, what="level")
    levels_g = np.asarray(levels_g, dtype=float)
    ratio = levels_g * STANDARD_GRAVITY / block.uplift_acceleration  # PGA/(g tan(alpha)) of each level
    counts = np.zeros((len(controls), levels_g.size))
    for c, control in enumerate(controls):
        for record in records:
            run = RecordRun(block, anchorage, control, record, overturn_criterion=overturn_criterion,
                            free_time=free_time)
            counts[c] += is_overturned(grid_outcomes(run, ratio))
    fits = [fit_lognormal(levels_g, np.full(levels_g.size, len(records)), counts[c]) for c in range(len(controls))]
    intervals = np.array([f.median_interval() if math.isfinite(f.median) else (math.nan, math.nan) for f in fits])
    return (np.array([f.median for f in fits]), np.array([f.dispersion for f in fits]), counts / len(records),
            [f.status for f in fits], intervals.reshape(len(fits), 2))


@declares(R="half_diagonal", alpha="slenderness", amplitude_start="amplitude_ratio",
          amplitude_step="design_step", resolution="design_resolution", a_max0_g="a_max0_g", free_time="free_time")
def block_point(R: float, alpha: float, anchorage: Anchorage, strategies, frequency_ratios, *,
                amplitude_start: float, amplitude_step: float, resolution: float, a_max0_g: float, records,
                levels_g, suite: str, excitation: str = "modulated", overturn_criterion: str = "flat",
                free_time: float = DEFAULT_FREE_TIME) -> xr.Dataset:
    """One point of the block sweep: spectra, J_OS over FS and fragility medians of every strategy.

    Parameters
    ----------
    R : float
        Half diagonal of the block. [m]
    alpha : float
        Slenderness angle. [rad]
    anchorage : rockstudy.model.anchorage.Anchorage
        The restrainers (the device), the same for every strategy.
    strategies : sequence of str
        FS among them (the reference of J_OS).
    frequency_ratios : array_like
        ω_p/p of the spectra. [-]
    amplitude_start, amplitude_step, resolution : float
        The amplitude scan a_p/(g·tanα); it stops one step above a_max,0 (thresholds above it are capped). [-]
    a_max0_g : float
        a_max,0 of J_OS. [g]
    records : sequence of rockstudy.model.records.Record
        The suite of the fragility.
    levels_g : array_like
        PGA levels of the stripes. [g]
    suite : str
        Name of the suite (stored).
    excitation : {"modulated", "one-sine"}, default "modulated"
        Baseline excitation of the spectra, as for :class:`rockstudy.analysis.scenario.Scenario`.
    overturn_criterion : {"flat", "alpha"}, default "flat"
        When a run counts as overturned.
    free_time : float, default DEFAULT_FREE_TIME
        Free rocking allowed after the excitation or record. [s]
    """
    check_arguments("block_point", {"R": R, "alpha": alpha, "amplitude_start": amplitude_start,
                                    "amplitude_step": amplitude_step, "resolution": resolution, "a_max0_g": a_max0_g,
                                    "free_time": free_time})
    if "FS" not in strategies:
        raise ValueError(f"strategies must include FS (the reference of J_OS), got {list(strategies)}")
    t0 = time.perf_counter()
    block = Block.slender(alpha, R)
    controls = [Control(s) for s in strategies]
    a_max0_ratio = a_max0_g * STANDARD_GRAVITY / block.uplift_acceleration
    grid = AmplitudeGrid(start=amplitude_start, stop=max(a_max0_ratio + amplitude_step, amplitude_start
                                                         + amplitude_step), step=amplitude_step,
                         resolution=resolution)
    freqs = np.asarray(frequency_ratios, dtype=float)
    thresholds = np.array([spectrum(Scenario(block, anchorage, c, excitation=excitation,
                                             overturn_criterion=overturn_criterion, free_time=free_time),
                                    freqs, grid=grid, progress_chunks=1)["threshold"].values for c in controls])
    fs = thresholds[list(strategies).index("FS")]
    jos = np.array([utility_index(t, fs, a_max0_ratio, undefined="nan")[0] for t in thresholds])
    medians, betas, _, status, _ = fragility_medians_g(block, anchorage, controls, records, levels_g,
                                                    overturn_criterion=overturn_criterion, free_time=free_time)
    ds = xr.Dataset(
        {"threshold": (("strategy", "frequency_ratio"), thresholds,
                       {"units": "1", "long_name": "minimum overturning amplitude ratio a_p/(g tan(alpha)), "
                        "noise-free; NaN: none up to the scan's end (one step above a_max,0)"}),
         "jos": ("strategy", jos, {"units": "percent", "long_name": "utility index J_OS over FS (Eqs. 18-22)"}),
         "fragility_median": ("strategy", medians, {
             "units": STANDARD_GRAVITY_UNITS, "long_name": f"fragility median PGA on {suite}",
             "comment": gravity_comment(block)}),
         "fragility_dispersion": ("strategy", betas, {"units": "1", "long_name": "fragility dispersion beta"}),
         "fit_status": ("strategy", status, {"long_name": "see rockstudy.analysis.fragility.FragilityFit"})},
        coords={"strategy": ("strategy", list(strategies)),
                "frequency_ratio": ("frequency_ratio", freqs, {"units": "1", "long_name": "omega_p/p"}),
                "R": ((), float(R), {"units": "m", "long_name": "half diagonal of the block"}),
                "alpha": ((), float(alpha), {"units": "rad", "long_name": "slenderness angle"})},
        attrs={"title": f"Design point: block R = {R:g} m, alpha = {alpha:g} rad", "rockstudy_version": __version__,
               "excitation": excitation, "a_max0_g": a_max0_g, "a_max0_ratio": a_max0_ratio,
               "record_suite": suite, "n_records": len(records), "pga_levels_g": list(map(float, levels_g)),
               "amplitude_grid": f"{grid.start:g}..{grid.stop:g} step {grid.step:g}, resolution {grid.resolution:g}",
               **block.to_attrs(), **anchorage.to_attrs(block)},
    )
    ds.attrs["compute_time_s"] = time.perf_counter() - t0
    return ds


@declares(kappa_max="kappa", damping_ratio="damping_ratio", kappa_min="kappa", free_time="free_time")
def device_point(block: Block, kappa_max: float, damping_ratio: float, strategies, records, levels_g, *,
                 suite: str, kappa_min: float = 0.0, overturn_criterion: str = "flat",
                 free_time: float = DEFAULT_FREE_TIME) -> xr.Dataset:
    """One point of the device sweep: the fragility median [g] of each strategy with this device.

    Parameters
    ----------
    block : rockstudy.model.block.Block
        The block.
    kappa_max : float
        Dimensionless restrainer stiffness κ_max = 4 K_max b²/(m g R) of the device. [-]
    damping_ratio : float
        Damping ratio ξ of the device. [-]
    strategies : sequence of str
        The control strategies (``"FS"``, ``"CS01"``, ...), one median each.
    records : sequence of rockstudy.model.records.Record
        The record suite of the fragility.
    levels_g : array_like of float
        PGA levels of the stripes. [g]
    suite : str
        Name of the suite (stored).
    kappa_min : float, default 0.0
        Dimensionless stiffness κ_min = 4 K_min b²/(m g R) of the device's "off" state. [-]
    overturn_criterion : {"flat", "alpha"}, default "flat"
        When a run counts as overturned.
    free_time : float, default DEFAULT_FREE_TIME
        Free rocking allowed after each record. [s]
    """
    check_arguments("device_point", {"kappa_max": kappa_max, "damping_ratio": damping_ratio, "kappa_min": kappa_min,
                                     "free_time": free_time})
    strategies = validation.check_items("strategies", strategies, what="strategy")
    t0 = time.perf_counter()
    anchorage = Anchorage(kappa_max=kappa_max, kappa_min=kappa_min, damping_ratio=damping_ratio)
    medians, betas, _, status, interval = fragility_medians_g(block, anchorage, [Control(s) for s in strategies],
                                                              records,
                                                    levels_g, overturn_criterion=overturn_criterion,
                                                    free_time=free_time)
    ds = xr.Dataset(
        {"fragility_median": ("strategy", medians, {
             "units": STANDARD_GRAVITY_UNITS, "long_name": f"fragility median PGA on {suite}",
             "comment": gravity_comment(block)}),
         "fragility_median_low": ("strategy", interval[:, 0], {
             "units": STANDARD_GRAVITY_UNITS, "long_name": "fragility median PGA, low end of its 95 % Wald interval"}),
         "fragility_median_high": ("strategy", interval[:, 1], {
             "units": STANDARD_GRAVITY_UNITS, "long_name": "fragility median PGA, high end of its 95 % Wald interval"}),
         "fragility_dispersion": ("strategy", betas, {"units": "1", "long_name": "fragility dispersion beta"}),
         "fit_status": ("strategy", status, {"long_name": "see rockstudy.analysis.fragility.FragilityFit"})},
        coords={"strategy": ("strategy", list(strategies)),
                "kappa_max": ((), float(kappa_max), {"units": "1", "long_name": "4 K_max b^2/(m g R)"}),
                "damping_ratio": ((), float(damping_ratio), {"units": "1", "long_name": "xi"})},
        attrs={"title": f"Device point: kappa_max = {kappa_max:g}, xi = {damping_ratio:g}",
               "rockstudy_version": __version__, "record_suite": suite, "n_records": len(records),
               "pga_levels_g": list(map(float, levels_g)), **block.to_attrs(), **anchorage.to_attrs(block)},
    )
    ds.attrs["compute_time_s"] = time.perf_counter() - t0
    return ds


def gather_blocks(points) -> xr.Dataset:
    """The block sweep over (R, alpha) from its points (:func:`block_point`).

    Parameters
    ----------
    points : iterable of xarray.Dataset
        The datasets of :func:`block_point`, one per (R, alpha), sharing strategies and settings; the
        first one's attributes label the result.
    """
    points = list(validation.check_items("points", points, what="block point"))
    Rs = sorted({float(p.R) for p in points})
    alphas = sorted({float(p.alpha) for p in points})
    strategies = list(points[0].strategy.values)
    shape = (len(strategies), len(Rs), len(alphas))
    jos, med = np.full(shape, np.nan), np.full(shape, np.nan)
    for p in points:
        i, j = Rs.index(float(p.R)), alphas.index(float(p.alpha))
        jos[:, i, j] = p.jos.sel(strategy=strategies).values
        med[:, i, j] = p.fragility_median.sel(strategy=strategies).values
    dims = ("strategy", "R", "alpha")
    return xr.Dataset(
        {"jos": (dims, jos, points[0].jos.attrs), "fragility_median": (dims, med, points[0].fragility_median.attrs)},
        coords={"strategy": strategies, "R": ("R", Rs, {"units": "m", "long_name": "half diagonal of the block"}),
                "alpha": ("alpha", alphas, {"units": "rad", "long_name": "slenderness angle"})},
        attrs={k: points[0].attrs[k] for k in ("excitation", "a_max0_g", "record_suite", "n_records",
                                               "rockstudy_version")}
        | {"title": "Block sweep: J_OS over FS and fragility median of every strategy over (R, alpha)",
           "compute_time_s": float(sum(p.attrs["compute_time_s"] for p in points))},
    )


def gather_devices(points) -> xr.Dataset:
    """The device sweep over (kappa_max, damping_ratio) from its points (:func:`device_point`).

    Parameters
    ----------
    points : iterable of xarray.Dataset
        The datasets of :func:`device_point`, one per (kappa_max, damping_ratio), sharing strategies; the
        first one's block and suite label the result.
    """
    points = list(validation.check_items("points", points, what="device point"))
    kappas = sorted({float(p.kappa_max) for p in points})
    xis = sorted({float(p.damping_ratio) for p in points})
    strategies = list(points[0].strategy.values)
    names = [n for n in ("fragility_median", "fragility_median_low", "fragility_median_high") if n in points[0]]
    values = {n: np.full((len(strategies), len(kappas), len(xis)), np.nan) for n in names}
    for p in points:
        for n in names:
            values[n][:, kappas.index(float(p.kappa_max)), xis.index(float(p.damping_ratio))] = \
                p[n].sel(strategy=strategies).values
    status = np.full((len(strategies), len(kappas), len(xis)), "", dtype=object)
    for p in points:
        if "fit_status" in p:
            status[:, kappas.index(float(p.kappa_max)), xis.index(float(p.damping_ratio))] = \
                [str(v) for v in p["fit_status"].sel(strategy=strategies).values]
    attrs = {k: v for k, v in points[0].attrs.items() if k.startswith("block_") or k in ("record_suite", "n_records")}
    data = {n: (("strategy", "kappa_max", "damping_ratio"), values[n], points[0][n].attrs) for n in names}
    data["fit_status"] = (("strategy", "kappa_max", "damping_ratio"), status.astype(str), {
        "long_name": "fit status of each device's fragility (rockstudy.analysis.fragility_fit.FragilityFit): "
                     f"'{NEVER_OVERTURNS}' meets every target median, '{ALWAYS_OVERTURNS}' none"})
    return xr.Dataset(
        data,
        coords={"strategy": strategies,
                "kappa_max": ("kappa_max", kappas, {"units": "1", "long_name": "4 K_max b^2/(m g R)"}),
                "damping_ratio": ("damping_ratio", xis, {"units": "1", "long_name": "xi"})},
        attrs={**attrs, "title": "Device sweep: fragility median of every strategy over (kappa_max, xi)",
               "rockstudy_version": __version__,
               "compute_time_s": float(sum(p.attrs["compute_time_s"] for p in points))},
    )


def smallest_kappa(devices: xr.Dataset, strategy: str, damping_ratio: float, target_g: float) -> float:
    """Smallest κ_max of the sweep whose fragility median reaches ``target_g`` [g] (NaN: none does). [-]

    A device whose fit status is "no overturning" (no record overturns the block at any stripe) reaches every
    target, one with "all overturned" none (:func:`rockstudy.analysis.fragility_fit.median_reaches`); a sweep
    without ``fit_status`` counts a NaN median as not reaching.

    Parameters
    ----------
    devices : xarray.Dataset
        The device sweep (:func:`gather_devices`).
    strategy : str
        The strategy, a value of its ``strategy`` coordinate.
    damping_ratio : float
        The damping ratio ξ, a value of its ``damping_ratio`` coordinate. [-]
    target_g : float
        The target median PGA. [g]
    """
    reached = np.flatnonzero(device_verdicts(devices, target_g).sel(strategy=strategy,
                                                                      damping_ratio=damping_ratio).values)
    return float(devices.kappa_max.values[reached[0]]) if reached.size else math.nan


def design_markdown(devices: xr.Dataset, target_g: float, block_label: str) -> str:
    """The device table (median [g] per strategy, κ_max, ξ) and one sentence per strategy and ξ: the
    smallest κ_max that keeps the median at or above the target.

    Parameters
    ----------
    devices : xarray.Dataset
        The device sweep (:func:`gather_devices`).
    target_g : float
        The target median PGA. [g]
    block_label : str
        Words naming the block, put in the table's caption.
    """
    strategies = [str(s) for s in devices.strategy.values]
    lines = [f"Fragility median PGA [g] on {devices.attrs['record_suite']} ({devices.attrs['n_records']} records), "
             f"{block_label}.", "", "| κ_max | ξ | " + " | ".join(strategies) + " |",
             "|---|---|" + "---|" * len(strategies)]
    for k in devices.kappa_max.values:
        for xi in devices.damping_ratio.values:
            row = devices.fragility_median.sel(kappa_max=k, damping_ratio=xi)
            lines.append(f"| {k:g} | {xi:g} | " + " | ".join(_median_cell(devices, s, k, xi, float(row.sel(strategy=s)))
                                                           for s in strategies) + " |")
    lines += ["", f"Target: median PGA >= {target_g:g} g.", ""]
    for xi in devices.damping_ratio.values:
        for s in strategies:
            if s == "FS":
                continue
            k = smallest_kappa(devices, s, float(xi), target_g)
            if math.isnan(k):
                lines.append(f"- For this object, {s} with ξ = {xi:g} does not reach a median of {target_g:g} g "
                             f"with κ_max up to {float(devices.kappa_max.max()):g}"
                             f"{_interval_note(devices, s, math.nan, float(xi), target_g)}.")
            else:
                m = float(devices.fragility_median.sel(strategy=s, kappa_max=k, damping_ratio=xi))
                at = f"{m:.3f} g" if math.isfinite(m) else "no record overturns the block on any stripe"
                lines.append(f"- For this object, {s} with ξ = {xi:g} and κ_max ≥ {k:g} keeps the median above "
                             f"{target_g:g} g ({at} at κ_max = {k:g}, the smallest κ_max of the sweep that "
                             f"does{_interval_note(devices, s, k, float(xi), target_g)}).")
    return "\n".join(lines) + "\n"


def _median_cell(devices: xr.Dataset, strategy: str, kappa_max, damping_ratio, median: float) -> str:
    """A table cell: the median [g], or what the fit status says where there is none."""
    if math.isfinite(median) or "fit_status" not in devices:
        return f"{median:.3f}"
    status = str(devices.fit_status.sel(strategy=strategy, kappa_max=kappa_max, damping_ratio=damping_ratio).values)
    return {NEVER_OVERTURNS: "never overturns", ALWAYS_OVERTURNS: "always overturns"}.get(status, f"— ({status})")


def _interval_note(devices: xr.Dataset, strategy: str, kappa_max: float, damping_ratio: float,
                   target_g: float) -> str:
    """``"; ..."`` when the answer κ_max rests on a median whose 95 % interval holds the target: its own
    (the median is above the target, the interval reaches below it), or that of the κ_max just below it
    (the median is below the target, the interval reaches above it); ``""`` when neither holds it or no
    interval is stored. ``kappa_max`` NaN: no κ_max of the sweep reaches the target (the largest is checked)."""
    if "fragility_median_low" not in devices:
        return ""
    kappas = [float(k) for k in devices.kappa_max.values]
    notes = []

    def interval(k):
        at = {"strategy": strategy, "kappa_max": k, "damping_ratio": damping_ratio}
        return tuple(float(devices[n].sel(**at)) for n in ("fragility_median", "fragility_median_low",
                                                              "fragility_median_high"))

    if math.isfinite(kappa_max):
        median, low, high = interval(kappa_max)
        if math.isfinite(low) and low < target_g:
            notes.append(f"its 95 % interval, {low:.3f}–{high:.3f} g, reaches below the target")
    below = [k for k in kappas if k < kappa_max] if math.isfinite(kappa_max) else kappas
    if below:
        median, low, high = interval(below[-1])
        if math.isfinite(high) and high >= target_g:
            notes.append(f"at κ_max = {below[-1]:g} the median, {median:.3f} g, is below the target but its 95 % "
                         f"interval, {low:.3f}–{high:.3f} g, reaches it")
    return ("; " + "; ".join(notes) + ": these records do not settle the smallest κ_max") if notes else ""


def check_config(section: dict) -> None:
    """The config's ``design:`` section is consistent (after the schema): FS among the strategies,
    increasing PGA levels, a suite whose records can be read.

    Parameters
    ----------
    section : dict
        The config's ``design:`` section (``suite``, ``strategies``, ``pga_levels_g``, ``blocks``, ``devices``).

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) naming the key, the value and what is allowed.
    """
    from rockstudy.core.validation import InputError
    from rockstudy.model import record_suites
    if "FS" not in section["strategies"]:
        raise InputError(f"design.strategies: FS is needed as the reference of J_OS, got {section['strategies']}")
    levels = section["pga_levels_g"]
    if not levels["start"] < levels["stop"]:
        raise InputError(f"design.pga_levels_g: start ({levels['start']}) must be below stop ({levels['stop']}) [g]")
    grid = section["blocks"]["amplitude_grid"]
    if grid["resolution"] > grid["step"]:
        raise InputError(f"design.blocks.amplitude_grid.resolution = {grid['resolution']} is not allowed: it must "
                         f"not exceed step ({grid['step']})")
    try:
        record_suites.record_ids(section["suite"])
    except record_suites.RecordSuiteError as exc:
        raise InputError(f"design.suite: {exc}") from None
