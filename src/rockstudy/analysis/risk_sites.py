"""The risk of an object at many sites, and the study's risk dataset.

:func:`risk_at_sites` answers "the risk of this object (one or several strategies' fragilities) at these
sites" (hazard curves, e.g. every site of a hazard file, :mod:`rockstudy.analysis.hazard`): a dataset
over strategies and sites of the annual rate of overturning (Eq. R1 of :mod:`rockstudy.analysis.risk`), its
probability in T years (Eq. R2), the share from outside each curve and, with band edges, the disaggregation.
``rockstudy risk`` and the workflow's :func:`risk_dataset` both call it. Every number it returns is checked
(:func:`check_risk_numbers`): rates finite and ≥ 0, probabilities in [0, 1].
"""
from __future__ import annotations

import json
import math
import warnings
from typing import NamedTuple

import numpy as np
import xarray as xr

from rockstudy.analysis.hazard import HazardSite
from rockstudy.analysis.risk import (
    DEFAULT_EXTENSION,
    TAIL_WARNING_SHARE,
    HazardExtensionWarning,
    LognormalFragility,
    RiskRangeError,
    annual_rate,
    check_target,
    fragility_from_dataset,
    median_meeting,
    scenario_probability,
    threshold_fit,
)
from rockstudy.core import validation
from rockstudy.core.constants import STANDARD_GRAVITY_UNITS as G_N
from rockstudy.core.risk_inputs import DEFAULT_GMM, DEFAULT_YEARS, RISK_INPUTS

BAND_EDGES_G = (0.05, 0.1, 0.2, 0.4, 0.8, 1.6)
"""Inner PGA band edges of the study's disaggregation (0 and inf added). [g]"""


def check_risk_numbers(rate, probability, what: str) -> None:
    """Refuse a rate that is not finite and ≥ 0 or a probability outside [0, 1] (NaN: no fragility, allowed).

    Parameters
    ----------
    rate, probability : array_like
        Annual rates [1/yr] and probabilities [-]; NaN where a strategy has no fitted fragility.
    what : str
        The inputs they come from, named in the message (a fragility, a hazard file and its site).
    """
    rate, probability = np.asarray(rate, dtype=float), np.asarray(probability, dtype=float)
    if np.any(np.isinf(rate)) or np.any(rate < 0):
        raise RiskRangeError(f"{what}: the rate of overturning is {rate[np.isinf(rate) | (rate < 0)].flat[0]}, not a "
                             "finite rate >= 0: the fragility or the hazard curve is outside what the integral holds")
    if np.any((probability < 0) | (probability > 1)) or np.any(np.isnan(probability) & ~np.isnan(rate)):
        raise RiskRangeError(f"{what}: a probability of overturning lies outside [0, 1]")


def _site_label(name: str, site: HazardSite, n_sites: int) -> str:
    return name if n_sites == 1 else f"{name}/{site.label}"


def risk_at_sites(fragilities: dict, sites, *, years: float = DEFAULT_YEARS, extension: str = DEFAULT_EXTENSION,
                  band_edges_g=BAND_EDGES_G, warn: bool = True, names: dict | None = None) -> xr.Dataset:
    """The risk of overturning of one object's strategies at every site.

    Parameters
    ----------
    fragilities : dict of str to LognormalFragility or None
        The object's fragility by strategy (None: no fitted fragility, NaN results).
    sites : dict of str to HazardSite or HazardCurve, or a callable returning one
        The sites by name (a :class:`~rockstudy.analysis.hazard.HazardCurve` is a site without coordinates); a
        callable (one that reads a hazard file) is called after ``years`` is checked.
    years : float, default 50
        Exposure time T of the probabilities. [yr]
    extension : {"loglog", "none"}
        How each hazard curve is read outside its points (:func:`rockstudy.analysis.risk.annual_rate`).
    band_edges_g : sequence of float or None, default :data:`BAND_EDGES_G`
        Inner edges of the disaggregation's PGA bands [g]; None: no disaggregation.
    warn : bool, default True
        Warn (:class:`~rockstudy.analysis.risk.HazardExtensionWarning`, naming the site) when more than
        :data:`~rockstudy.analysis.risk.TAIL_WARNING_SHARE` of a rate comes from outside its curve.
    names : dict, optional
        The caller's name of ``years`` in error messages (``{"years": "--years"}``).

    Returns
    -------
    xarray.Dataset
        Over ``strategy`` and ``site`` (with ``lon``, ``lat``, ``site_name``, ``hazard_source``): ``annual_rate``,
        ``probability``, ``rate_below``, ``rate_above``, ``tail_share``, the curves' points ``hazard_pga`` and
        ``hazard_rate`` over (site, hazard_point), and with band edges ``disaggregation`` over ``pga_band``.

    Raises
    ------
    ValueError
        (:class:`RiskRangeError`) when a rate or probability leaves its range, naming the fragility and site.
    """
    years = RISK_INPUTS["years"].check((names or {}).get("years", "years"), years)
    if callable(sites):
        sites = sites()
    sites = {n: s if isinstance(s, HazardSite) else HazardSite(curve=s) for n, s in dict(sites).items()}
    if not sites:
        raise validation.InputError("give at least one site (hazard curve)")
    strategies, labels = list(fragilities), list(sites)
    shape = (len(strategies), len(labels))
    out = {k: np.full(shape, math.nan) for k in ("annual_rate", "rate_below", "rate_above", "tail_share")}
    n_bands = None if band_edges_g is None else len(band_edges_g) + 1
    bands = None if n_bands is None else np.full(shape + (n_bands,), math.nan)
    for j, name in enumerate(labels):
        curve = sites[name].curve
        for i, s in enumerate(strategies):
            if fragilities[s] is None:
                continue
            result = annual_rate(fragilities[s], curve, band_edges_g=band_edges_g, extension=extension, warn=False)
            out["annual_rate"][i, j], out["tail_share"][i, j] = result.annual_rate, result.tail_share
            out["rate_below"][i, j], out["rate_above"][i, j] = result.rate_below, result.rate_above
            if bands is not None:
                bands[i, j] = result.band_share
            if warn and result.tail_share > TAIL_WARNING_SHARE:
                where = "counted" if extension == "loglog" else "left out"
                warnings.warn(f"{name}, {s}: {100 * result.tail_share:.3g} % of the rate of overturning comes from "
                              f"outside the hazard curve ({curve.pga_g[0]:g}-{curve.pga_g[-1]:g} g), {where} by "
                              "extending its end segments: give the curve over a wider range of PGA",
                              HazardExtensionWarning, stacklevel=2)
    probability = -np.expm1(-out["annual_rate"] * years)
    for j, name in enumerate(labels):
        for i, s in enumerate(strategies):
            f = fragilities[s]
            if f is not None:
                check_risk_numbers(out["annual_rate"][i, j], probability[i, j],
                                   f"the fragility of {s} (median {f.median_g:g} g, dispersion {f.dispersion:g}) at "
                                   f"{name} ({sites[name].curve.source or 'a hazard curve'})")
    return _sites_dataset(strategies, labels, sites, out, probability, bands, band_edges_g, years, extension)


class SiteTargets(NamedTuple):
    """The medians meeting one target at every site (:func:`targets_at_sites`)."""

    medians: dict
    """The :class:`~rockstudy.analysis.risk.TargetMedian` of each site, by name."""
    target_rate: float
    """The target annual rate of overturning. [1/yr]"""
    target_probability: float
    """Its probability in ``years`` (Eq. R2). [-]"""
    years: float
    """The exposure time. [yr]"""


def targets_at_sites(sites, dispersion: float, *, target_rate: float | None = None,
                     target_probability: float | None = None, years: float = DEFAULT_YEARS,
                     extension: str = DEFAULT_EXTENSION, allow_extrapolation: bool = False,
                     names: dict | None = None) -> SiteTargets:
    """The fragility median meeting a target at each site (:func:`~rockstudy.analysis.risk.target_median`), the
    target and the dispersion checked once, before the sites are read.

    Parameters
    ----------
    sites : dict of str to HazardSite or HazardCurve, or a callable returning one
        As for :func:`risk_at_sites`.
    dispersion, target_rate, target_probability, years, extension, allow_extrapolation : float or str or bool
        As for :func:`~rockstudy.analysis.risk.target_median`.
    names : dict, optional
        The caller's name of each numeric argument in error messages (``{"years": "--years"}``).

    Raises
    ------
    ValueError
        (:class:`~rockstudy.core.validation.InputError`) for a bad argument, or at a site where no median meets
        the target (the message starts with the site's name).
    """
    dispersion, rate, probability = check_target(dispersion, target_rate, target_probability, years, names)
    if callable(sites):
        sites = sites()
    medians = {}
    for name, site in dict(sites).items():
        curve = site.curve if isinstance(site, HazardSite) else site
        try:
            medians[name] = median_meeting(curve, dispersion, rate, extension=extension,
                                           allow_extrapolation=allow_extrapolation)
        except validation.InputError as exc:
            raise validation.InputError(f"{name}: {exc}") from None
    return SiteTargets(medians, rate, probability, float(years))


def _sites_dataset(strategies, names, sites, out, probability, bands, band_edges_g, years, extension) -> xr.Dataset:
    nan = math.nan
    n_points = max(s.curve.pga_g.size for s in sites.values())
    points = np.full((len(names), 2, n_points), nan)
    for j, name in enumerate(names):
        c = sites[name].curve
        points[j, 0, :c.pga_g.size], points[j, 1, :c.pga_g.size] = c.pga_g, c.annual_rate
    coords = {"strategy": ("strategy", strategies, {"long_name": "control strategy"}),
              "site": ("site", names, {"long_name": "site (hazard curve)"}),
              "lon": ("site", [nan if sites[n].lon is None else sites[n].lon for n in names],
                      {"units": "degrees_east", "long_name": "longitude (NaN: not in the hazard file)"}),
              "lat": ("site", [nan if sites[n].lat is None else sites[n].lat for n in names],
                      {"units": "degrees_north", "long_name": "latitude (NaN: not in the hazard file)"}),
              "site_name": ("site", [sites[n].name or "" for n in names], {"long_name": "site name in the file"}),
              "hazard_source": ("site", [sites[n].curve.source for n in names], {"long_name": "hazard file"})}
    ds = xr.Dataset(coords=coords)
    ds["hazard_notes"] = ("site", ["; ".join(sites[n].notes) for n in names],
                          {"long_name": "what reading the hazard file did (conversions, levels dropped)"})
    ds["hazard_pga"] = (("site", "hazard_point"), points[:, 0], {"units": G_N, "long_name": "PGA of the hazard "
                        "curve's points (NaN: padding)"})
    ds["hazard_rate"] = (("site", "hazard_point"), points[:, 1], {"units": "1/yr", "long_name": "annual rate of "
                         "exceedance of the hazard curve's points (NaN: padding)"})
    ends = "extended log-log" if extension == "loglog" else "not extended"
    ds["annual_rate"] = (("strategy", "site"), out["annual_rate"], {
        "units": "1/yr", "long_name": "mean annual frequency of overturning, integral of P(overturn|x) "
                                      f"|d lambda_IM(x)|, the curve's end segments {ends}"})
    ds["probability"] = (("strategy", "site"), probability, {
        "units": "1", "long_name": f"probability of overturning in {years:g} years, 1 - exp(-lambda T)"})
    ds["rate_below"] = (("strategy", "site"), out["rate_below"], {
        "units": "1/yr", "long_name": "part of the rate from below the curve's first point (end segment extended)"})
    ds["rate_above"] = (("strategy", "site"), out["rate_above"], {
        "units": "1/yr", "long_name": "part of the rate from beyond the curve's last point (end segment extended)"})
    ds["tail_share"] = (("strategy", "site"), out["tail_share"], {"units": "1", "long_name": "share of the annual "
                        "rate from below the curve's first point and beyond its last"})
    if bands is not None:
        edges = np.array((0.0,) + tuple(band_edges_g) + (np.inf,))
        ds = ds.assign_coords(pga_band_low=("pga_band", edges[:-1], {"units": G_N, "long_name": "PGA band, low"}),
                              pga_band_high=("pga_band", edges[1:], {"units": G_N, "long_name": "PGA band, high"}))
        ds["disaggregation"] = (("strategy", "site", "pga_band"), bands, {
            "units": "1", "long_name": "share of the annual rate of overturning from each PGA band"})
    ds.attrs.update(years=years, hazard_extension=extension)
    return ds


# --- the study's dataset: every strategy of a record set at every site -------------------------------
def risk_dataset(fragility: xr.Dataset, *, scenarios=None, hazard_curves=None, years: float = DEFAULT_YEARS,
                 gmm: str = DEFAULT_GMM, outside_gmm_range: bool = False) -> xr.Dataset:
    """Risk of overturning of every strategy of a record set's fragility at every site.

    Parameters
    ----------
    fragility : xarray.Dataset
        A record set's fragility in PGA (:func:`rockstudy.analysis.fragility.suite_fragility_dataset`), FS
        among its strategies; each strategy's lognormal fit of the stripes is used
        (:func:`~rockstudy.analysis.risk.fragility_from_dataset`).
    scenarios : dict of str to dict, optional
        Named earthquake scenarios (:func:`rockstudy.analysis.ground_motion.check_scenario`).
    hazard_curves : dict of str to HazardCurve, HazardSite or list of HazardSite, optional
        Named hazard curves; a list (every site of a hazard file) gives one ``hazard`` entry per site,
        ``<name>/<site>``.
    years : float
        Exposure time T of the probabilities. [yr]
    gmm : str
        Ground-motion model of the scenarios.
    outside_gmm_range : bool, default False
        A scenario outside the model's published range is refused, or with True answered with the reason in
        ``scenario_warnings`` (:func:`rockstudy.analysis.ground_motion.check_range`).

    Returns
    -------
    xarray.Dataset
        Per strategy the fragility used; per scenario the model's median PGA and ln standard
        deviation and per (strategy, scenario) P(overturn | scenario) (Eq. R3) and its reduction over FS; per
        hazard curve (site, with ``lon`` and ``lat``) its points, and per (strategy, hazard) the annual rate
        (Eq. R1, :func:`risk_at_sites`), the probability in T years (Eq. R2), the reduction over FS, the share
        from outside the curve and the disaggregation over :data:`BAND_EDGES_G`.
    """
    from rockstudy._version import __version__
    scenarios, hazard_curves = dict(scenarios or {}), dict(hazard_curves or {})
    if not scenarios and not hazard_curves:
        raise validation.InputError("give at least one scenario or hazard curve")
    years = RISK_INPUTS["years"].check("years", years)
    strategies = [str(s) for s in fragility["strategy"].values]
    if "FS" not in strategies:
        raise validation.InputError(f"the fragility needs FS (the reference of the reduction), got {strategies}")
    fits = {s: fragility_from_dataset(fragility, s) if _finite_fit(fragility, s) else None for s in strategies}
    ds = _fragility_part(fragility, strategies, fits)
    if scenarios:
        ds = _scenario_part(ds, fits, strategies, scenarios, gmm, outside_gmm_range)
    if hazard_curves:
        ds = _hazard_part(ds, fits, strategies, hazard_curves, years)
    ds.attrs = {"title": f"Risk of overturning on {fragility.attrs.get('record_suite', 'a record set')}: every "
                         "strategy at every site",
                "rockstudy_version": __version__, "record_suite": fragility.attrs.get("record_suite", ""),
                "years": years, "gmm": gmm, "hazard_extension": DEFAULT_EXTENSION,
                "fragility_used": "the stripes' lognormal fit in PGA (P(overturn) at each PGA level, what the "
                                  "hazard integral needs); the fit of the records' thresholds describes their first "
                                  "overturning instead, and overturning is not monotone in the scale",
                "method": "Eq. R1: exact integral on the log-log interpolated hazard curve (Cornell et al. 2002); "
                          "Eq. R2: Poisson; Eq. R3: lognormal fragility and lognormal ground motion",
                **{k: v for k, v in fragility.attrs.items() if k.startswith(("block_", "anchorage_"))}}
    return ds


def _fragility_part(fragility: xr.Dataset, strategies, fits) -> xr.Dataset:
    nan = math.nan
    ds = xr.Dataset(coords={"strategy": ("strategy", strategies, {"long_name": "control strategy"})})
    ds["fragility_median"] = ("strategy", [f.median_g if f else nan for f in fits.values()], {
        "units": G_N, "long_name": "fragility median PGA used: the stripes' lognormal fit (MLE of P(overturn) at "
                                  "each stripe level)"})
    ds["fragility_dispersion"] = ("strategy", [f.dispersion if f else nan for f in fits.values()],
                                  {"units": "1", "long_name": "fragility dispersion beta used (the stripes' fit)"})
    if "fit_status" in fragility:
        ds["fit_status"] = ("strategy", [str(fragility["fit_status"].sel(strategy=s).values) for s in strategies],
                            {"long_name": "status of the stripes' fit (rockstudy.analysis.fragility_fit.FragilityFit); "
                                          "without a fitted median the strategy's risk is NaN"})
    for name in ("median_low_physical", "median_high_physical"):
        if name in fragility:
            ds[name.removesuffix("_physical")] = ("strategy", fragility[name].values.astype(float), {
                "units": G_N, "long_name": f"95 % Wald interval of the median, {name.split('_')[1]}"})
    if "threshold_pga" in fragility and "record_pga" in fragility.coords:
        thr = [threshold_fit(fragility, s) for s in strategies]
        ds["threshold_fit_median"] = ("strategy", [f.median for f in thr], {
            "units": G_N, "long_name": "median of the records' threshold PGA (lognormal MLE, censored where a record "
                                       "does not overturn the block up to the last level); not used by the risk"})
        ds["threshold_fit_dispersion"] = ("strategy", [f.dispersion for f in thr], {
            "units": "1", "long_name": "dispersion of the records' threshold PGA (lognormal MLE)"})
    return ds


def _scenario_part(ds: xr.Dataset, fits, strategies, scenarios: dict, gmm: str, outside: bool) -> xr.Dataset:
    from rockstudy.analysis.ground_motion import check_range, check_scenario, pga
    nan = math.nan
    names = list(scenarios)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        problems = [check_range(check_scenario(scenarios[n], n), gmm, n, outside) for n in names]
        ground = [pga(scenarios[n], gmm, name=n, outside_range=outside) for n in names]
    p = np.array([[scenario_probability(fits[s], g[0], g[1]) if fits[s] else nan for g in ground]
                  for s in strategies])
    ds = ds.assign_coords(scenario=("scenario", names, {"long_name": "earthquake scenario"}))
    ds["scenario_values"] = ("scenario", [json.dumps(g[2], sort_keys=True) for g in ground],
                             {"long_name": f"every scenario value {gmm} used (JSON), defaults included"})
    if any(problems):
        ds["scenario_warnings"] = ("scenario", ["; ".join(p) for p in problems], {
            "long_name": f"where the scenario lies outside {gmm}'s published range (empty: within it)"})
    ds["median_pga"] = ("scenario", [g[0] for g in ground], {"units": G_N, "long_name": f"median PGA ({gmm})"})
    ds["ln_std_pga"] = ("scenario", [g[1] for g in ground],
                        {"units": "1", "long_name": f"standard deviation of ln PGA ({gmm})"})
    ds["scenario_probability"] = (("strategy", "scenario"), p, {
        "units": "1", "long_name": "P(overturn | scenario) = Phi((ln mu - ln theta)/sqrt(beta^2 + sigma^2))"})
    lo, hi = _probability_range(fits, ds, strategies, lambda f: [scenario_probability(f, g[0], g[1])
                                                                 for g in ground], len(names))
    ds["scenario_probability_low"] = (("strategy", "scenario"), lo, {
        "units": "1", "long_name": "P(overturn | scenario) with the median at the high end of its 95 % interval"})
    ds["scenario_probability_high"] = (("strategy", "scenario"), hi, {
        "units": "1", "long_name": "P(overturn | scenario) with the median at the low end of its 95 % interval"})
    ds["scenario_reduction_percent"] = (("strategy", "scenario"), 100 * (1 - p / p[strategies.index("FS")]), {
        "units": "percent", "long_name": "reduction of P(overturn | scenario) over FS, 100 (1 - P/P_FS)"})
    return ds


def _hazard_sites(hazard_curves: dict) -> dict:
    """Every site of the named hazard curves, by its ``hazard`` label."""
    sites = {}
    for name, value in hazard_curves.items():
        many = value if isinstance(value, (list, tuple)) else [value]
        for site in many:
            site = site if isinstance(site, HazardSite) else HazardSite(curve=site)
            sites[_site_label(name, site, len(many))] = site
    return sites


def _hazard_part(ds: xr.Dataset, fits, strategies, hazard_curves: dict, years: float) -> xr.Dataset:
    sites = _hazard_sites(hazard_curves)
    at = risk_at_sites(fits, sites, years=years, warn=False).rename(site="hazard")
    at["hazard"].attrs["long_name"] = "hazard curve (site)"
    rate = at["annual_rate"].values
    names = list(sites)
    ds = ds.merge(at.drop_vars(["rate_below", "rate_above"]), combine_attrs="drop_conflicts")
    ds = ds.set_coords([]).reset_coords("hazard_source")  # the hazard file stays a variable, as before
    lo, hi = _probability_range(fits, ds, strategies, lambda f: [
        -math.expm1(-annual_rate(f, sites[n].curve, warn=False).annual_rate * years) for n in names], len(names))
    ds["probability_low"] = (("strategy", "hazard"), lo, {
        "units": "1", "long_name": f"probability in {years:g} years with the median at the high end of its 95 % "
                                   "interval"})
    ds["probability_high"] = (("strategy", "hazard"), hi, {
        "units": "1", "long_name": f"probability in {years:g} years with the median at the low end of its 95 % "
                                   "interval"})
    ds["reduction_percent"] = (("strategy", "hazard"), 100 * (1 - rate / rate[strategies.index("FS")]), {
        "units": "percent", "long_name": "reduction of the annual rate of overturning over FS"})
    return ds


def _probability_range(fits, ds, strategies, probabilities, n_sites):
    """Probabilities with each fragility's median at the ends of its 95 % interval (NaN without one)."""
    lo, hi = np.full((len(strategies), n_sites), math.nan), np.full((len(strategies), n_sites), math.nan)
    if "median_low" not in ds:
        return lo, hi
    for i, s in enumerate(strategies):
        low, high = float(ds["median_low"].values[i]), float(ds["median_high"].values[i])
        if fits[s] is None or not (math.isfinite(low) and math.isfinite(high)):
            continue
        lo[i] = probabilities(LognormalFragility(high, fits[s].dispersion))
        hi[i] = probabilities(LognormalFragility(low, fits[s].dispersion))
    return lo, hi


def _finite_fit(ds: xr.Dataset, strategy: str) -> bool:
    return bool(np.isfinite(float(ds["fragility_dispersion"].sel(strategy=strategy)))
                and np.isfinite(float(ds["fragility_median"].sel(strategy=strategy))))


def risk_warnings_markdown(ds: xr.Dataset) -> str:
    """Lines to append to a risk table: each scenario answered outside its model's published range, and what
    reading each hazard file did (conversions, levels dropped); "" when there is nothing to say.

    Parameters
    ----------
    ds : xarray.Dataset
        A risk dataset (:func:`risk_dataset`).
    """
    lines = []
    if "scenario_warnings" in ds:
        lines += [f"- Warning: scenario {n}: {w}; the model is used outside its published range."
                  for n, w in zip(ds.scenario.values, ds.scenario_warnings.values) if str(w)]
    if "hazard_notes" in ds:
        lines += [f"- Hazard {n}: {w}." for n, w in zip(ds.hazard.values, ds.hazard_notes.values) if str(w)]
    return ("\n" + "\n".join(lines) + "\n") if lines else ""
