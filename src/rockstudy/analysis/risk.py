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

The risk at many sites and the study's risk dataset are built in :mod:`rockstudy.analysis.risk_sites`; which
devices of a design sweep reach a risk-targeted median, in :mod:`rockstudy.analysis.risk_devices`. Every rate
leaving :func:`annual_rate` is finite and ≥ 0 (else :class:`RiskRangeError` names the fragility and the curve).

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
from dataclasses import InitVar, dataclass
from typing import TYPE_CHECKING

import numpy as np
from scipy import optimize, special

from rockstudy.analysis.hazard import EXTENSIONS, HazardCurve
from rockstudy.core import validation
from rockstudy.core.constants import STANDARD_GRAVITY_UNITS as G_N  # PGA in units of standard gravity
from rockstudy.core.risk_inputs import DEFAULT_GMM, DEFAULT_YEARS, GMMS, RISK_INPUTS

if TYPE_CHECKING:
    import xarray as xr


TAIL_WARNING_SHARE = 0.01
"""Share of λ from outside the hazard curve's points above which :func:`annual_rate` warns. [-]"""
DEFAULT_EXTENSION = "loglog"
"""How a hazard curve is read outside its points (:data:`rockstudy.analysis.hazard.EXTENSIONS`)."""


class HazardExtensionWarning(UserWarning):
    """More than :data:`TAIL_WARNING_SHARE` of a rate of overturning comes from outside the hazard curve."""


class HazardExtrapolationWarning(UserWarning):
    """A risk-targeted median lies outside the hazard curve's PGA range (it rests on the curve's extension)."""


class RiskRangeError(validation.InputError):
    """A computed rate or probability outside its range (the message names the inputs that caused it)."""


DISPERSION_STEP = 1e-9
"""Below this dispersion β the fragility is integrated as a step at its median (the error is of order β²). [-]"""


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
    names : dict, optional
        The caller's name of ``median_g`` and ``dispersion`` in messages (``{"median_g": "--median"}``); not stored.
    """

    median_g: float
    dispersion: float
    label: str = ""
    names: InitVar[dict | None] = None

    def __post_init__(self, names):
        names = names or {}
        RISK_INPUTS["median_g"].check(names.get("median_g", "median_g"), self.median_g)
        RISK_INPUTS["dispersion"].check(names.get("dispersion", "dispersion"), self.dispersion)

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


def probability_in_years(annual_rate: float, years: float = DEFAULT_YEARS, *, names: dict | None = None) -> float:
    """1 − exp(−λT), the Poisson probability of at least one occurrence in T years (Eq. R2). [-]

    Parameters
    ----------
    annual_rate : float
        λ, the annual rate of occurrence. [1/yr]
    years : float, default 50
        Exposure time T. [yr]
    names : dict, optional
        The caller's name of ``years`` in error messages (``{"years": "--years"}``).
    """
    years = RISK_INPUTS["years"].check((names or {}).get("years", "years"), years)
    return _poisson_probability(annual_rate, years)


def rate_for_probability(probability: float, years: float = DEFAULT_YEARS, *, names: dict | None = None) -> float:
    """The annual rate whose probability in ``years`` is ``probability``: −ln(1 − p)/T (Eq. R2). [1/yr]

    Parameters
    ----------
    probability : float
        p, the probability of at least one occurrence in ``years``, in (0, 1). [-]
    years : float, default 50
        Exposure time T. [yr]
    names : dict, optional
        The caller's name of ``target_probability`` and ``years`` in error messages.
    """
    names = names or {}
    probability = RISK_INPUTS["target_probability"].check(names.get("target_probability", "target_probability"),
                                                          probability)
    years = RISK_INPUTS["years"].check(names.get("years", "years"), years)
    return -math.log1p(-probability) / years


def check_target(dispersion: float, target_rate: float | None = None, target_probability: float | None = None,
                 years: float = DEFAULT_YEARS, names: dict | None = None) -> tuple[float, float, float]:
    """Check a target of :func:`target_median` (one of ``target_rate`` and ``target_probability``, with ``years``)
    and its ``dispersion``; return (β, target λ [1/yr], its probability in T years).

    Parameters
    ----------
    dispersion, target_rate, target_probability, years, names : float, float, float, float, dict
        As for :func:`target_median` (``names``: the caller's name of each, ``{"years": "--years"}``).
    """
    names = names or {}
    if (target_rate is None) == (target_probability is None):
        raise validation.InputError("give one target: target_rate or target_probability (with years)")
    dispersion = RISK_INPUTS["dispersion"].check(names.get("dispersion", "dispersion"), dispersion)
    if target_probability is not None:
        rate = rate_for_probability(target_probability, years, names=names)
        return dispersion, rate, _poisson_probability(rate, years)
    rate = RISK_INPUTS["target_rate"].check(names.get("target_rate", "target_rate"), target_rate)
    return dispersion, rate, probability_in_years(rate, years, names=names)


def _poisson_probability(annual_rate: float, years: float) -> float:
    return -math.expm1(-annual_rate * years)


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
    if beta < DISPERSION_STEP:  # a step at θ: the hazard's drop over the part of the piece above θ
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
    if not (math.isfinite(with_tails) and total >= 0):
        side = "below its first point" if not math.isfinite(rate_below) else "beyond its last point"
        raise RiskRangeError(f"the rate of overturning of the fragility (median {fragility.median_g:g} g, "
                             f"dispersion {fragility.dispersion:g}) on {hazard.source or 'the hazard curve'} is "
                             f"{with_tails}, not a finite rate: the curve's end segment extended {side} outgrows "
                             "the fragility; give the curve over the fragility's range of PGA")
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


@dataclass(frozen=True)
class TargetMedian:
    """The fragility median meeting a target rate on a hazard curve, and where it lies against the curve.

    Attributes
    ----------
    median_g : float
        θ: an object with a median at or above it meets the target. [g]
    target_rate : float
        The target annual rate of overturning. [1/yr]
    extrapolated : bool
        θ lies below the curve's first PGA or beyond its last, where the curve is its extension.
    decades_outside : float
        How far: log10 of θ over the curve's last PGA (or of its first PGA over θ); 0 within. [-]
    """

    median_g: float
    target_rate: float
    extrapolated: bool
    decades_outside: float


def target_median(hazard: HazardCurve, dispersion: float, *, target_rate: float | None = None,
                  target_probability: float | None = None, years: float = DEFAULT_YEARS,
                  extension: str = DEFAULT_EXTENSION, allow_extrapolation: bool = False,
                  names: dict | None = None) -> TargetMedian:
    """The fragility median θ at which the rate of overturning λ (Eq. R1) equals a target, and whether it lies
    within the hazard curve's PGA range.

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
    allow_extrapolation : bool, default False
        A θ outside the curve's PGA range rests on the curve's extension (or its absence): refused unless
        allowed, and then answered with ``extrapolated`` and a :class:`HazardExtrapolationWarning` saying how far.
    names : dict, optional
        The caller's name of each numeric argument in error messages (:func:`check_target`).

    Raises
    ------
    ValueError
        (:class:`~rockstudy.core.validation.InputError`) when no median meets the target, or θ lies outside the
        curve and ``allow_extrapolation`` is False.
    """
    dispersion, target, _ = check_target(dispersion, target_rate, target_probability, years, names)
    return median_meeting(hazard, dispersion, target, extension=extension, allow_extrapolation=allow_extrapolation)


def median_meeting(hazard: HazardCurve, dispersion: float, target: float, *, extension: str = DEFAULT_EXTENSION,
                   allow_extrapolation: bool = False) -> TargetMedian:
    """:func:`target_median` of a dispersion and a target rate already checked (:func:`check_target`).

    Parameters
    ----------
    hazard, dispersion, target, extension, allow_extrapolation : HazardCurve, float, float, str, bool
        As for :func:`target_median`; ``target`` is the target annual rate of overturning. [1/yr]
    """
    def excess(log_median):  # ln λ(θ) − ln target: falls as θ rises
        fragility = LognormalFragility(math.exp(log_median), dispersion)
        try:
            rate = annual_rate(fragility, hazard, extension=extension, warn=False).annual_rate
        except RiskRangeError:  # an infinite rate far below the curve: above any target
            return math.inf
        return (math.log(rate) if rate > 0 else -math.inf) - math.log(target)

    span = MEDIAN_SEARCH_DECADES * math.log(10)
    low = max(math.log(hazard.pga_g[0]) - span, math.log(1e-12))
    top_median = RISK_INPUTS["median_g"].high  # declared: a finite upper bound [g]
    assert top_median is not None
    high = min(math.log(hazard.pga_g[-1]) + span, math.log(top_median) - 1e-9)
    if excess(low) < 0:
        raise validation.InputError(f"no median meets an annual rate of {target:.4g}: even a median of "
                                    f"{math.exp(low):.3g} g overturns less often on this hazard curve")
    if excess(high) > 0:
        raise validation.InputError(f"no median up to {math.exp(high):.3g} g meets an annual rate of "
                                    f"{target:.4g} on this hazard curve")
    median = float(math.exp(optimize.brentq(excess, low, high, xtol=1e-12, rtol=1e-12)))
    first, last = float(hazard.pga_g[0]), float(hazard.pga_g[-1])
    decades = math.log10(median / last) if median > last else math.log10(first / median) if median < first else 0.0
    if decades > 0:
        side = f"beyond the curve's last point, {last:g} g" if median > last else f"below its first point, {first:g} g"
        text = (f"the median meeting an annual rate of {target:.4g}, {median:.4g} g, lies {decades:.2g} decades "
                f"{side}: it rests on the curve's {'extension' if extension == 'loglog' else 'absence'} there")
        if not allow_extrapolation:
            raise validation.InputError(f"{text}; give the curve over a wider range of PGA (or allow extrapolation)")
        warnings.warn(text, HazardExtrapolationWarning, stacklevel=2)
    return TargetMedian(median, target, decades > 0, decades)


def median_for_target(hazard: HazardCurve, dispersion: float, *, target_rate: float | None = None,
                      target_probability: float | None = None, years: float = DEFAULT_YEARS,
                      extension: str = DEFAULT_EXTENSION, allow_extrapolation: bool = False) -> float:
    """The fragility median θ [g] at which the rate of overturning λ (Eq. R1) equals a target
    (:func:`target_median`, which says too whether θ lies within the hazard curve).

    Parameters
    ----------
    hazard, dispersion, target_rate, target_probability, years, extension, allow_extrapolation : object
        As for :func:`target_median`.

    Returns
    -------
    float
        θ: an object with a median at or above it meets the target. [g]
    """
    return target_median(hazard, dispersion, target_rate=target_rate, target_probability=target_probability,
                         years=years, extension=extension, allow_extrapolation=allow_extrapolation).median_g


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
    warnings : tuple of str
        Where the scenario lies outside the model's published range (answered on request only).
    """

    gmm: str
    scenario: dict
    median_pga_g: float
    ln_std: float
    probability: float
    fragility: LognormalFragility
    warnings: tuple[str, ...] = ()


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


def scenario_risk(fragility: LognormalFragility, scenario: dict, gmm: str | None = None, *,
                  outside_range: bool = False) -> ScenarioRisk:
    """P(overturn | scenario) from a ground-motion model (:func:`rockstudy.analysis.ground_motion.pga`).

    Parameters
    ----------
    fragility : LognormalFragility
        θ and β of the object.
    scenario : dict
        The earthquake scenario, as for :func:`rockstudy.analysis.ground_motion.check_scenario`.
    gmm : str or None, default None
        Ground-motion model, a key of :data:`rockstudy.core.risk_inputs.GMMS`; None: the default model.
    outside_range : bool, default False
        A scenario outside the model's published range is refused, or with True answered, the reasons in
        ``warnings`` (:func:`rockstudy.analysis.ground_motion.check_range`).
    """
    from rockstudy.analysis.ground_motion import check_range, check_scenario, pga
    gmm = gmm or DEFAULT_GMM
    if gmm not in GMMS:
        raise validation.InputError(f"gmm = {gmm!r} is not allowed: one of {', '.join(GMMS)}")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        problems = check_range(check_scenario(scenario), gmm, outside_range=outside_range)
    median, sigma, used = pga(scenario, gmm, outside_range=outside_range)
    return ScenarioRisk(gmm=gmm, scenario=used, median_pga_g=median, ln_std=sigma,
                        probability=scenario_probability(fragility, median, sigma), fragility=fragility,
                        warnings=tuple(problems))
