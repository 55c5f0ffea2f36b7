"""Risk of overturning at a site: a fragility combined with the site's hazard.

**From a hazard curve.** With a lognormal fragility P(overturn | PGA = x) = Φ(ln(x/θ)/β) (median θ in g,
dispersion β; Eq. F1 of :mod:`rockstudy.analysis.fragility_fit`) and a hazard curve λ_IM(x), the mean
annual frequency of overturning is

    λ = ∫ P(overturn | x) |dλ_IM(x)|                                        (Eq. R1)

and the probability of at least one overturning in T years, occurrences being Poisson,
1 − exp(−λT) (Eq. R2). The hazard curve is a power law on each segment (log-log interpolation,
:mod:`rockstudy.analysis.hazard`), so Eq. R1 is integrated exactly segment by segment: on a piece
[a, b] where λ_IM = λ_c (x/x_c)^(−s), integrating by parts,

    ∫_a^b Φ(z) s λ_IM d(ln x) = Φ(z_a) λ_IM(a) − Φ(z_b) λ_IM(b)
                                + λ_IM(θ) e^(s²β²/2) [Φ(z_b + sβ) − Φ(z_a + sβ)],   z = ln(x/θ)/β,

which over one power law on (0, ∞) is Cornell et al.'s closed form λ = k0 θ^(−k) e^(k²β²/2) [1]_. The
share of λ from each PGA band is the disaggregation; the share from below the curve's first point
and beyond its last (where the end segments are extended, or nothing is counted) is reported and
warned about above :data:`TAIL_WARNING_SHARE`.

**Risk-targeted design** is the inverse: the median θ at which λ equals a target rate (or a
probability in T years, such as the 1 % in 50 years behind ASCE 7's risk-targeted ground motions),
for a dispersion β.

**For a scenario** (one earthquake), with the median PGA μ and its log standard deviation σ from a
ground-motion model (:mod:`rockstudy.analysis.ground_motion`),
P(overturn | scenario) = Φ((ln μ − ln θ)/√(β² + σ²)) (Eq. R3).

The fragility of a record set's dataset (:func:`fragility_from_dataset`) is the stripes' lognormal
fit in PGA: it estimates P(overturn | PGA = x) at each level, which is what Eq. R1 integrates. A fit
of the records' thresholds (the first overturning scale of each record) would estimate a different
curve, since overturning is not monotone in the scale: a record may overturn the block at one scale
and not at a higher one.

References
----------
.. [1] C. A. Cornell, F. Jalayer, R. O. Hamburger, D. A. Foutch (2002). Probabilistic basis for 2000
   SAC Federal Emergency Management Agency steel moment frame guidelines. Journal of Structural
   Engineering 128(4), 526–533.
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from scipy import optimize, special

from rockstudy.analysis.hazard import EXTENSIONS, HazardCurve
from rockstudy.core import validation
from rockstudy.core.risk_inputs import DEFAULT_GMM, DEFAULT_YEARS, RISK_INPUTS
from rockstudy.model.records import STANDARD_GRAVITY_UNITS as G_N  # PGA in units of standard gravity

if TYPE_CHECKING:
    import xarray as xr


TAIL_WARNING_SHARE = 0.01
"""Share of λ from outside the hazard curve's points above which :func:`annual_rate` warns. [-]"""
DEFAULT_EXTENSION = "loglog"
"""How a hazard curve is read outside its points (:data:`rockstudy.analysis.hazard.EXTENSIONS`)."""


class HazardExtensionWarning(UserWarning):
    """More than :data:`TAIL_WARNING_SHARE` of a rate of overturning comes from outside the hazard curve."""


@dataclass(frozen=True)
class LognormalFragility:
    """P(overturn | PGA = x) = Φ(ln(x/θ)/β) (Eq. F1).

    Parameters
    ----------
    median_g : float
        θ, the PGA with 50 % probability of overturning. [g]
    dispersion : float
        β, the standard deviation of ln PGA at overturning (0: a step at θ). [-]
    label : str
        What the fragility is of (object, device, record set).
    """

    median_g: float
    dispersion: float
    label: str = ""

    def __post_init__(self):
        RISK_INPUTS["median_g"].check("median_g", self.median_g)
        RISK_INPUTS["dispersion"].check("dispersion", self.dispersion)

    def probability(self, pga_g) -> np.ndarray:
        """P(overturn | PGA = x). [-]

        Parameters
        ----------
        pga_g : float or array_like
            PGA x. [g]
        """
        x = np.asarray(pga_g, dtype=float)
        if self.dispersion == 0:
            return (x >= self.median_g).astype(float)
        with np.errstate(divide="ignore"):
            return special.ndtr(np.log(x / self.median_g) / self.dispersion)


def fragility_from_dataset(ds: xr.Dataset, strategy: str) -> LognormalFragility:
    """The lognormal fragility in PGA [g] of ``strategy`` in a fragility dataset (the stripes' fit).

    Parameters
    ----------
    ds : xarray.Dataset
        A record set's fragility (:func:`rockstudy.analysis.fragility.suite_fragility_dataset`, the
        workflow's ``fragility/<set>.nc``) with the intensity measure PGA/(g·tanα), whose median in g is
        ``fragility_median_physical``, or a dataset whose ``fragility_median`` is in g (a device point of
        the design study).
    strategy : str
        The control strategy, a value of the dataset's ``strategy`` coordinate.

    Raises
    ------
    ValueError
        (:class:`~rockstudy.core.validation.InputError`) if the strategy is not in the dataset, the
        fragility is not in PGA, or its fit has no finite median.
    """
    strategies = [str(s) for s in ds["strategy"].values]
    if strategy not in strategies:
        raise validation.InputError(f"strategy {strategy!r} is not in the fragility dataset (it has "
                                    f"{', '.join(strategies)})")
    in_g = (G_N, "g")  # PGA in units of standard gravity (files of rockstudy 0.2.0 wrote "g")
    if "fragility_median_physical" in ds and ds["fragility_median_physical"].attrs.get("units") in in_g:
        median = float(ds["fragility_median_physical"].sel(strategy=strategy))
    elif ds["fragility_median"].attrs.get("units") in in_g:
        median = float(ds["fragility_median"].sel(strategy=strategy))
    else:
        raise validation.InputError("the fragility dataset's median is not a PGA in g (intensity_measure "
                                    f"{ds.attrs.get('intensity_measure', '?')}); the hazard is in PGA")
    beta = float(ds["fragility_dispersion"].sel(strategy=strategy))
    if not (math.isfinite(median) and math.isfinite(beta)):
        status = str(ds["fit_status"].sel(strategy=strategy).values) if "fit_status" in ds else "?"
        raise validation.InputError(f"the fragility of {strategy} has no finite median and dispersion (fit status "
                                    f"{status!r})")
    return LognormalFragility(median, beta, label=f"{strategy} on {ds.attrs.get('record_suite', 'the records')}")


# --- Eq. R1 on a hazard curve -----------------------------------------------------------------------
@dataclass(frozen=True)
class RiskResult:
    """Mean annual frequency of overturning from a hazard curve (Eq. R1) and its disaggregation.

    Attributes
    ----------
    annual_rate : float
        λ, the mean annual frequency of overturning (with the extension's tails when ``extension`` is
        "loglog"). [1/yr]
    extension : str
        How the hazard curve is read outside its points (:data:`rockstudy.analysis.hazard.EXTENSIONS`).
    rate_below, rate_above : float
        The parts of λ from below the curve's first point and beyond its last, by the end segments' power
        laws (counted in ``annual_rate`` only with "loglog"). [1/yr]
    tail_share : float
        (rate_below + rate_above) / the rate with them. [-]
    band_edges_g : ndarray
        Edges of the PGA bands of the disaggregation, 0 first and inf last. [g]
    band_rate : ndarray
        Part of λ from each band (one fewer than the edges; outside the curve 0 with "none"). [1/yr]
    fragility : LognormalFragility
    hazard_source : str
    """

    annual_rate: float
    extension: str
    rate_below: float
    rate_above: float
    tail_share: float
    band_edges_g: np.ndarray
    band_rate: np.ndarray
    fragility: LognormalFragility
    hazard_source: str

    @property
    def band_share(self) -> np.ndarray:
        """Share of λ from each band (sums to 1). [-]"""
        return self.band_rate / self.annual_rate if self.annual_rate > 0 else np.zeros_like(self.band_rate)

    def probability(self, years: float = DEFAULT_YEARS) -> float:
        """Probability of overturning at least once in ``years`` (Eq. R2). [-]

        Parameters
        ----------
        years : float, default 50
            Exposure time T. [yr]
        """
        return probability_in_years(self.annual_rate, years)


def probability_in_years(annual_rate: float, years: float = DEFAULT_YEARS) -> float:
    """1 − exp(−λT), the Poisson probability of at least one occurrence in T years (Eq. R2). [-]

    Parameters
    ----------
    annual_rate : float
        λ, the annual rate of occurrence. [1/yr]
    years : float, default 50
        Exposure time T. [yr]
    """
    years = RISK_INPUTS["years"].check("years", years)
    return -math.expm1(-annual_rate * years)


def rate_for_probability(probability: float, years: float = DEFAULT_YEARS) -> float:
    """The annual rate whose probability in ``years`` is ``probability``: −ln(1 − p)/T (Eq. R2). [1/yr]

    Parameters
    ----------
    probability : float
        p, the probability of at least one occurrence in ``years``, in (0, 1). [-]
    years : float, default 50
        Exposure time T. [yr]
    """
    probability = RISK_INPUTS["target_probability"].check("target_probability", probability)
    years = RISK_INPUTS["years"].check("years", years)
    return -math.log1p(-probability) / years


def _log_phi_difference(lo, hi):
    """ln(Φ(hi) − Φ(lo)) for hi > lo, accurate in both tails."""
    lo, hi = np.broadcast_arrays(np.asarray(lo, dtype=float), np.asarray(hi, dtype=float))
    upper = lo > 0  # both in the upper tail: Φ(hi) − Φ(lo) = Φ(−lo) − Φ(−hi)
    big = np.where(upper, special.log_ndtr(-lo), special.log_ndtr(hi))
    small = np.where(upper, special.log_ndtr(-hi), special.log_ndtr(lo))
    with np.errstate(divide="ignore"):
        return big + np.log1p(-np.exp(small - big))


def _piece_rates(fragility: LognormalFragility, u_lo, u_hi, u_ref, log_rate_ref, slope) -> np.ndarray:
    """∫ P(overturn | x) |dλ_IM| over pieces [e^u_lo, e^u_hi] (u_lo may be −inf, u_hi +inf) on which
    λ_IM = exp(log_rate_ref − slope (u − u_ref)), exactly (the module's formula). [1/yr]"""
    log_theta, beta = math.log(fragility.median_g), fragility.dispersion
    with np.errstate(over="ignore", invalid="ignore"):
        log_rate_lo = np.where(np.isfinite(u_lo), log_rate_ref - slope * (u_lo - u_ref), np.inf)
        log_rate_hi = np.where(np.isfinite(u_hi), log_rate_ref - slope * (u_hi - u_ref), -np.inf)
    if beta == 0:  # a step at θ: the hazard's drop over the part of the piece above θ
        u_from = np.maximum(u_lo, log_theta)
        with np.errstate(over="ignore", invalid="ignore"):
            rate_from = np.where(u_from < u_hi, np.exp(log_rate_ref - slope * (u_from - u_ref)), 0.0)
        return np.clip(rate_from - np.where(u_from < u_hi, np.exp(log_rate_hi), 0.0), 0.0, None)
    z_lo, z_hi = (u_lo - log_theta) / beta, (u_hi - log_theta) / beta
    with np.errstate(over="ignore", invalid="ignore"):
        end_lo = np.where(np.isfinite(u_lo), np.exp(special.log_ndtr(z_lo) + log_rate_lo), 0.0)
        end_hi = np.where(np.isfinite(u_hi), np.exp(special.log_ndtr(z_hi) + log_rate_hi), 0.0)
        # λ_IM(θ) e^(s²β²/2) [Φ(z_hi + sβ) − Φ(z_lo + sβ)], in logs (each factor may over- or underflow)
        log_core = (log_rate_ref - slope * (log_theta - u_ref) + 0.5 * (slope * beta) ** 2
                    + _log_phi_difference(z_lo + slope * beta, z_hi + slope * beta))
    return np.clip(end_lo - end_hi + np.exp(log_core), 0.0, None)


def annual_rate(fragility: LognormalFragility, hazard: HazardCurve, *, band_edges_g=None,
                extension: str = DEFAULT_EXTENSION, warn: bool = True) -> RiskResult:
    """Mean annual frequency of overturning λ = ∫ P(overturn | x) |dλ_IM(x)| (Eq. R1), disaggregated.

    Parameters
    ----------
    fragility : LognormalFragility
        P(overturn | PGA) of the object.
    hazard : HazardCurve
        λ_IM of the site.
    band_edges_g : array_like, optional
        Inner edges of the PGA bands of the disaggregation, rising (0 and inf are added). Default: the
        hazard curve's points. [g]
    extension : {"loglog", "none"}
        Below the first and beyond the last point of the curve, extend its end segments' power laws, or
        count nothing.
    warn : bool
        Warn (:class:`HazardExtensionWarning`) when more than :data:`TAIL_WARNING_SHARE` of λ comes from
        outside the curve.

    Returns
    -------
    RiskResult
    """
    if extension not in EXTENSIONS:
        raise validation.InputError(f"extension must be one of {', '.join(EXTENSIONS)}, got {extension!r}")
    u_points = np.log(hazard.pga_g)
    edges = hazard.pga_g if band_edges_g is None else np.asarray(band_edges_g, dtype=float)
    if edges.ndim != 1 or np.any(~np.isfinite(edges)) or np.any(edges <= 0) or np.any(np.diff(edges) <= 0):
        raise validation.InputError("band_edges_g must be rising, finite and > 0 [g]")
    breaks = np.union1d(u_points, np.log(edges))
    u_lo = np.concatenate([[-np.inf], breaks])
    u_hi = np.concatenate([breaks, [np.inf]])
    # each piece lies on one segment of the curve (or an end segment's extension)
    middle = np.where(np.isfinite(u_lo), u_lo, u_hi - 1.0)
    seg = np.clip(np.searchsorted(u_points, middle, side="right") - 1, 0, u_points.size - 2)
    log_rates = np.log(hazard.annual_rate)
    rates = _piece_rates(fragility, u_lo, u_hi, u_points[seg], log_rates[seg], hazard.slopes[seg])
    below, above = u_hi <= u_points[0], u_lo >= u_points[-1]
    rate_below, rate_above = float(rates[below].sum()), float(rates[above].sum())
    with_tails = float(rates.sum())
    if extension == "none":
        rates = np.where(below | above, 0.0, rates)
    total = float(rates.sum())
    tail_share = (rate_below + rate_above) / with_tails if with_tails > 0 else 0.0
    if warn and tail_share > TAIL_WARNING_SHARE:
        where = "counted" if extension == "loglog" else "left out"
        warnings.warn(f"{100 * tail_share:.3g} % of the rate of overturning comes from outside the hazard curve "
                      f"({hazard.pga_g[0]:g}-{hazard.pga_g[-1]:g} g; below {100 * rate_below / with_tails:.2f} %, "
                      f"above {100 * rate_above / with_tails:.2f} %), {where} by extending its end segments' "
                      "power laws: give the curve over a wider range of PGA", HazardExtensionWarning, stacklevel=2)
    # the disaggregation over the bands [0, e_1], [e_1, e_2], ..., [e_n, inf)
    band_edges = np.concatenate([[0.0], edges, [np.inf]])
    band = np.searchsorted(np.log(edges), u_lo, side="right")
    band_rate = np.bincount(band, weights=rates, minlength=edges.size + 1)
    return RiskResult(annual_rate=total, extension=extension, rate_below=rate_below, rate_above=rate_above,
                      tail_share=tail_share, band_edges_g=band_edges, band_rate=band_rate, fragility=fragility,
                      hazard_source=hazard.source)


# --- the inverse: risk-targeted design --------------------------------------------------------------
MEDIAN_SEARCH_DECADES = 12
"""The median meeting a target is searched within this many decades of PGA around the hazard curve."""


def median_for_target(hazard: HazardCurve, dispersion: float, *, target_rate: float | None = None,
                      target_probability: float | None = None, years: float = DEFAULT_YEARS,
                      extension: str = DEFAULT_EXTENSION) -> float:
    """The fragility median θ [g] at which the rate of overturning λ (Eq. R1) equals a target.

    Parameters
    ----------
    hazard : HazardCurve
        λ_IM of the site.
    dispersion : float
        β of the fragility. [-]
    target_rate : float, optional
        Target λ. [1/yr]
    target_probability : float, optional
        Target probability in ``years`` instead (e.g. 0.01 in 50 years), turned into a rate by Eq. R2. [-]
    years : float
        Exposure time of ``target_probability``. [yr]
    extension : {"loglog", "none"}
        As for :func:`annual_rate`.

    Returns
    -------
    float
        θ: an object with a median at or above it meets the target. [g]
    """
    if (target_rate is None) == (target_probability is None):
        raise validation.InputError("give one target: target_rate or target_probability (with years)")
    if target_rate is None:
        target_rate = rate_for_probability(target_probability, years)
    target_rate = RISK_INPUTS["target_rate"].check("target_rate", target_rate)
    dispersion = RISK_INPUTS["dispersion"].check("dispersion", dispersion)

    def excess(log_median):  # ln λ(θ) − ln target: falls as θ rises
        fragility = LognormalFragility(math.exp(log_median), dispersion)
        rate = annual_rate(fragility, hazard, extension=extension, warn=False).annual_rate
        return (math.log(rate) if rate > 0 else -math.inf) - math.log(target_rate)

    span = MEDIAN_SEARCH_DECADES * math.log(10)
    low = max(math.log(hazard.pga_g[0]) - span, math.log(1e-12))
    high = min(math.log(hazard.pga_g[-1]) + span, math.log(RISK_INPUTS["median_g"].high) - 1e-9)
    if excess(low) < 0:
        raise validation.InputError(f"no median meets an annual rate of {target_rate:.4g}: even a median of "
                                    f"{math.exp(low):.3g} g overturns less often on this hazard curve")
    if excess(high) > 0:
        raise validation.InputError(f"no median up to {math.exp(high):.3g} g meets an annual rate of "
                                    f"{target_rate:.4g} on this hazard curve")
    return float(math.exp(optimize.brentq(excess, low, high, xtol=1e-12, rtol=1e-12)))


def devices_meeting(devices: xr.Dataset, median_g: float) -> list[dict]:
    """Which devices of a device sweep have a fragility median at or above ``median_g``, one row per
    (strategy, κ_max, ξ).

    Parameters
    ----------
    devices : xarray.Dataset
        A device sweep (:func:`rockstudy.studies.design.gather_devices`): ``fragility_median`` [g] over
        (strategy, kappa_max, damping_ratio).
    median_g : float
        The median a device must reach, e.g. from :func:`median_for_target`. [g]
    """
    rows = []
    for s in devices["strategy"].values:
        for k in devices["kappa_max"].values:
            for xi in devices["damping_ratio"].values:
                m = float(devices["fragility_median"].sel(strategy=s, kappa_max=k, damping_ratio=xi))
                rows.append({"strategy": str(s), "kappa_max": float(k), "damping_ratio": float(xi), "median_g": m,
                             "meets": bool(math.isfinite(m) and m >= median_g)})
    return rows


# --- Eq. R3: one scenario ---------------------------------------------------------------------------
@dataclass(frozen=True)
class ScenarioRisk:
    """P(overturn | scenario) (Eq. R3) and what it is made of.

    Attributes
    ----------
    gmm : str
        The ground-motion model.
    scenario : dict
        Every scenario value the model used, defaults included.
    median_pga_g : float
        μ, the model's median PGA. [g]
    ln_std : float
        σ, its standard deviation of ln PGA. [-]
    probability : float
        Φ((ln μ − ln θ)/√(β² + σ²)). [-]
    fragility : LognormalFragility
    """

    gmm: str
    scenario: dict
    median_pga_g: float
    ln_std: float
    probability: float
    fragility: LognormalFragility


def scenario_probability(fragility: LognormalFragility, median_pga_g: float, ln_std: float) -> float:
    """P(overturn | scenario) = Φ((ln μ − ln θ)/√(β² + σ²)) (Eq. R3). [-]

    Parameters
    ----------
    fragility : LognormalFragility
        θ and β of the object.
    median_pga_g : float
        μ, the scenario's median PGA. [g]
    ln_std : float
        σ, the standard deviation of ln PGA. [-]
    """
    spread = math.hypot(fragility.dispersion, ln_std)
    if spread == 0:
        return float(median_pga_g >= fragility.median_g)
    return float(special.ndtr((math.log(median_pga_g) - math.log(fragility.median_g)) / spread))


def scenario_risk(fragility: LognormalFragility, scenario: dict, gmm: str | None = None) -> ScenarioRisk:
    """P(overturn | scenario) from a ground-motion model (:func:`rockstudy.analysis.ground_motion.pga`).

    Parameters
    ----------
    fragility : LognormalFragility
        θ and β of the object.
    scenario : dict
        The earthquake scenario, as for :func:`rockstudy.analysis.ground_motion.check_scenario`.
    gmm : str or None, default None
        Ground-motion model, a key of :data:`rockstudy.core.risk_inputs.GMMS`; None: the default model.
    """
    from rockstudy.analysis.ground_motion import pga
    gmm = gmm or DEFAULT_GMM
    median, sigma, used = pga(scenario, gmm)
    return ScenarioRisk(gmm=gmm, scenario=used, median_pga_g=median, ln_std=sigma,
                        probability=scenario_probability(fragility, median, sigma), fragility=fragility)


# --- the study's dataset: every strategy of a record set at every site -------------------------------
BAND_EDGES_G = (0.05, 0.1, 0.2, 0.4, 0.8, 1.6)
"""Inner PGA band edges of the study's disaggregation (0 and inf added). [g]"""


def risk_dataset(fragility: xr.Dataset, *, scenarios=None, hazard_curves=None, years: float = DEFAULT_YEARS,
                 gmm: str = DEFAULT_GMM) -> xr.Dataset:
    """Risk of overturning of every strategy of a record set's fragility at every site.

    Parameters
    ----------
    fragility : xarray.Dataset
        A record set's fragility in PGA (:func:`rockstudy.analysis.fragility.suite_fragility_dataset`), FS
        among its strategies; each strategy's lognormal fit of the stripes is used (:func:`fragility_from_dataset`).
    scenarios : dict of str to dict, optional
        Named earthquake scenarios (:func:`rockstudy.analysis.ground_motion.check_scenario`).
    hazard_curves : dict of str to HazardCurve, optional
        Named hazard curves.
    years : float
        Exposure time T of the probabilities. [yr]
    gmm : str
        Ground-motion model of the scenarios.

    Returns
    -------
    xarray.Dataset
        Per strategy the fragility used; per scenario the model's median PGA and ln standard deviation and
        per (strategy, scenario) P(overturn | scenario) (Eq. R3) and its reduction over FS; per hazard curve
        its points, and per (strategy, hazard) the annual rate (Eq. R1), the probability in T years (Eq. R2),
        the reduction over FS, the share from outside the curve and the disaggregation over
        :data:`BAND_EDGES_G`.
    """
    import json

    import xarray as xr

    from rockstudy._version import __version__
    from rockstudy.analysis.ground_motion import pga
    scenarios, hazard_curves = dict(scenarios or {}), dict(hazard_curves or {})
    if not scenarios and not hazard_curves:
        raise validation.InputError("give at least one scenario or hazard curve")
    years = RISK_INPUTS["years"].check("years", years)
    strategies = [str(s) for s in fragility["strategy"].values]
    if "FS" not in strategies:
        raise validation.InputError(f"the fragility needs FS (the reference of the reduction), got {strategies}")
    fits = {s: fragility_from_dataset(fragility, s) if _finite_fit(fragility, s) else None for s in strategies}
    nan = math.nan
    ds = xr.Dataset(coords={"strategy": ("strategy", strategies, {"long_name": "control strategy"})})
    ds["fragility_median"] = ("strategy", [f.median_g if f else nan for f in fits.values()], {
        "units": G_N, "long_name": "fragility median PGA used: the stripes' lognormal fit (MLE of P(overturn) at "
                                  "each stripe level)"})
    ds["fragility_dispersion"] = ("strategy", [f.dispersion if f else nan for f in fits.values()],
                                  {"units": "1", "long_name": "fragility dispersion beta used (the stripes' fit)"})
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
    if scenarios:
        names = list(scenarios)
        ground = [pga(scenarios[n], gmm) for n in names]
        p = np.array([[scenario_probability(fits[s], g[0], g[1]) if fits[s] else nan for g in ground]
                      for s in strategies])
        ds = ds.assign_coords(scenario=("scenario", names, {"long_name": "earthquake scenario"}))
        ds["scenario_values"] = ("scenario", [json.dumps(g[2], sort_keys=True) for g in ground],
                                 {"long_name": f"every scenario value {gmm} used (JSON), defaults included"})
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
    if hazard_curves:
        names = list(hazard_curves)
        n_points = max(h.pga_g.size for h in hazard_curves.values())
        points = np.full((len(names), 2, n_points), nan)
        rate, tail = np.full((len(strategies), len(names)), nan), np.full((len(strategies), len(names)), nan)
        bands = np.full((len(strategies), len(names), len(BAND_EDGES_G) + 1), nan)
        for j, name in enumerate(names):
            h = hazard_curves[name]
            points[j, 0, :h.pga_g.size], points[j, 1, :h.pga_g.size] = h.pga_g, h.annual_rate
            for i, s in enumerate(strategies):
                if fits[s] is None:
                    continue
                result = annual_rate(fits[s], h, band_edges_g=BAND_EDGES_G, warn=False)
                rate[i, j], tail[i, j], bands[i, j] = result.annual_rate, result.tail_share, result.band_share
        edges = np.array((0.0,) + BAND_EDGES_G + (np.inf,))
        ds = ds.assign_coords(hazard=("hazard", names, {"long_name": "hazard curve"}),
                              pga_band_low=("pga_band", edges[:-1], {"units": G_N, "long_name": "PGA band, low"}),
                              pga_band_high=("pga_band", edges[1:], {"units": G_N, "long_name": "PGA band, high"}))
        ds["hazard_pga"] = (("hazard", "hazard_point"), points[:, 0], {"units": G_N, "long_name": "PGA of the "
                            "hazard curve's points (NaN: padding)"})
        ds["hazard_rate"] = (("hazard", "hazard_point"), points[:, 1], {"units": "1/yr", "long_name": "annual rate "
                             "of exceedance of the hazard curve's points (NaN: padding)"})
        ds["hazard_source"] = ("hazard", [hazard_curves[n].source for n in names], {"long_name": "hazard file"})
        ds["annual_rate"] = (("strategy", "hazard"), rate, {
            "units": "1/yr", "long_name": "mean annual frequency of overturning, integral of P(overturn|x) "
                                          "|d lambda_IM(x)|, the curve's end segments extended log-log"})
        ds["probability"] = (("strategy", "hazard"), -np.expm1(-rate * years), {
            "units": "1", "long_name": f"probability of overturning in {years:g} years, 1 - exp(-lambda T)"})
        lo, hi = _probability_range(fits, ds, strategies, lambda f: [
            -math.expm1(-annual_rate(f, hazard_curves[n], warn=False).annual_rate * years) for n in names], len(names))
        ds["probability_low"] = (("strategy", "hazard"), lo, {
            "units": "1", "long_name": f"probability in {years:g} years with the median at the high end of its 95 % "
                                       "interval"})
        ds["probability_high"] = (("strategy", "hazard"), hi, {
            "units": "1", "long_name": f"probability in {years:g} years with the median at the low end of its 95 % "
                                       "interval"})
        ds["reduction_percent"] = (("strategy", "hazard"), 100 * (1 - rate / rate[strategies.index("FS")]), {
            "units": "percent", "long_name": "reduction of the annual rate of overturning over FS"})
        ds["tail_share"] = (("strategy", "hazard"), tail, {"units": "1", "long_name": "share of the annual rate "
                            "from below the curve's first point and beyond its last"})
        ds["disaggregation"] = (("strategy", "hazard", "pga_band"), bands, {
            "units": "1", "long_name": "share of the annual rate of overturning from each PGA band"})
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


def threshold_fit(fragility: xr.Dataset, strategy: str):
    """Lognormal fit of a record set's per-record threshold PGA [g] for ``strategy``
    (:func:`rockstudy.analysis.fragility_fit.fit_lognormal_thresholds`), a record without a threshold
    censored at its PGA at the last stripe level.

    It describes the first overturning of each record along its scale, not P(overturn | PGA): a record
    may overturn the block at one scale and not at a higher one, so it differs from the stripes' fit
    that the risk uses.

    Parameters
    ----------
    fragility : xarray.Dataset
        A record set's fragility (:func:`rockstudy.analysis.fragility.suite_fragility_dataset`) with
        ``threshold_pga``, ``record_intensity`` and ``record_pga``.
    strategy : str
        The control strategy, a value of the dataset's ``strategy`` coordinate.
    """
    from rockstudy.analysis.fragility_fit import fit_lognormal_thresholds
    top_pga = (float(fragility["intensity"].values[-1]) / fragility["record_intensity"].values
               * fragility["record_pga"].values)
    return fit_lognormal_thresholds(fragility["threshold_pga"].sel(strategy=strategy).values, top_pga)


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


def check_config(section: dict, key: str = "risk") -> dict:
    """The config's ``risk:`` section: its declaration (:class:`rockstudy.core.declarations.Risk`: every value
    in range, no unknown key), at least one site, every hazard file readable. Returns the hazard curves by name.

    Parameters
    ----------
    section : dict
        The ``risk:`` section: ``scenarios``, ``hazard_curves`` (name: file path) and the other keys of
        :class:`rockstudy.core.declarations.Risk`.
    key : str, default "risk"
        Where the section sits in the config: errors name ``<key>.<entry>``.

    Raises
    ------
    ValueError
        (:class:`~rockstudy.core.validation.InputError`) naming ``<key>.<entry>``.
    """
    from rockstudy.analysis.hazard import read_hazard_curve
    from rockstudy.core import declarations
    declarations.check_config(section, declarations.Risk, key)
    scenarios, curves = section.get("scenarios") or {}, section.get("hazard_curves") or {}
    if not scenarios and not curves:
        raise validation.InputError(f"{key}: give at least one scenario or hazard curve")
    return {name: read_hazard_curve(path, f"{key}.hazard_curves.{name}") for name, path in curves.items()}
