"""Lognormal fragility fitted by maximum likelihood to counts of overturning runs, and its statistics.

A lognormal fragility function

    P(overturn | IM = x) = Φ( ln(x/θ) / β )                                  (Eq. F1)

with median θ and dispersion β is fitted by maximum likelihood, the stripes' counts being
binomial (Eq. 11 of Baker [1]_):

    ln L(θ, β) = Σ_j [ z_j ln Φ(ln(x_j/θ)/β) + (n_j − z_j) ln(1 − Φ(ln(x_j/θ)/β)) ].   (Eq. F2)

Uncertainty: standard errors of ln θ and β from the observed information matrix (the inverse
Hessian of −ln L at the maximum), and a bootstrap over records (records drawn with
replacement, every strategy refitted on the same draw) for the ratio of medians.

References
----------
.. [1] J. W. Baker (2015). Efficient analytical fragility function fitting using dynamic
   structural analysis. Earthquake Spectra 31(1), 579–599.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import special

from rockstudy.core import validation

BOOTSTRAP_KEY = 1302
"""Spawn key of the bootstrap's seed sequence."""

DISPERSION_BOUNDS = (0.01, 5.0)
"""Range of β searched; a fit at a bound is flagged (separated or flat data). [-]"""


NEVER_OVERTURNS = "no overturning"
"""Fit status of an object that no record overturns at any stripe: its median lies above the last stripe."""
ALWAYS_OVERTURNS = "all overturned"
"""Fit status of an object that every record overturns at every stripe: its median lies below the first."""


def median_reaches(median: float, status: str, target: float) -> bool:
    """Whether a fitted fragility's median reaches ``target``, its fit status deciding where the median is NaN:
    an object that never overturns on the stripes reaches every target, one that always overturns none.

    Parameters
    ----------
    median : float
        θ of the fit (NaN when the fit has none). [IM]
    status : str
        The fit's status (:class:`FragilityFit`).
    target : float
        The median to reach. [IM]

    Raises
    ------
    ValueError
        A NaN median with a status that does not say which side it lies on.
    """
    if status == NEVER_OVERTURNS:
        return True
    if status == ALWAYS_OVERTURNS:
        return False
    if not math.isfinite(median):
        raise ValueError(f"a fit with status {status!r} has no finite median: neither meets nor fails {target:g}")
    return bool(median >= target)


@dataclass(frozen=True)
class FragilityFit:
    """Lognormal fragility fitted by maximum likelihood (Eqs. F1–F2).

    Parameters
    ----------
    median : float
        θ, the IM with 50 % probability of overturning. [IM]
    dispersion : float
        β, the standard deviation of ln IM at overturning. [-]
    log_median_se, dispersion_se : float
        Standard errors of ln θ and β from the observed information matrix (NaN if singular). [-]
    covariance : ndarray, shape (2, 2)
        Inverse observed information of (ln θ, β). [-]
    log_likelihood : float
        ln L at the maximum. [-]
    status : str
        "ok"; "separated" (every stripe all safe below θ and all overturned above: β = 0, θ the
        geometric mean of the two stripes around the jump); "at bound" (β clipped to
        :data:`DISPERSION_BOUNDS`); "no curvature" (the observed information is not positive
        definite: no standard errors); "no overturning" / "all overturned" (θ undefined, NaN).
    """

    median: float
    dispersion: float
    log_median_se: float
    dispersion_se: float
    covariance: np.ndarray
    log_likelihood: float
    status: str

    def median_interval(self, level: float = 0.95) -> tuple[float, float]:
        """Wald interval exp(ln θ ± z·se) for the median. [IM]

        Parameters
        ----------
        level : float, default 0.95
            Confidence level of the interval, in (0, 1). [-]
        """
        z = special.ndtri(0.5 + level / 2)
        return (self.median * math.exp(-z * self.log_median_se), self.median * math.exp(z * self.log_median_se))

    def probability(self, x) -> np.ndarray:
        """Fitted P(overturn | IM = x), Eq. F1. [-]

        Parameters
        ----------
        x : float or array_like
            Intensity measure levels, > 0. [IM]
        """
        x = np.asarray(x, dtype=float)
        with np.errstate(divide="ignore"):
            return special.ndtr(np.log(x / self.median) / self.dispersion)


def negative_log_likelihood(params, im, n_total, n_overturned) -> float:
    """−ln L of Eq. F2 for params = (ln θ, β). [-]

    Parameters
    ----------
    params : (float, float)
        (ln θ, β); β <= 0 gives +inf.
    im : array_like
        IM levels x_j, > 0. [IM]
    n_total : array_like of int
        Records run at each level n_j. [-]
    n_overturned : array_like of int
        Records that overturned the block at each level z_j. [-]
    """
    return _nll_and_gradient(params, np.log(im), n_total, n_overturned)[0]


def _nll_and_gradient(params, log_im, n_total, n_overturned):
    """−ln L (Eq. F2) and its gradient in (ln θ, β)."""
    log_median, beta = params
    if not beta > 0:
        return math.inf, np.zeros(2)
    z = (log_im - log_median) / beta
    log_p, log_q = special.log_ndtr(z), special.log_ndtr(-z)
    log_pdf = -0.5 * z * z - 0.5 * math.log(2.0 * math.pi)
    # d(-ln L)/dz_j; dz/d(ln θ) = -1/β, dz/dβ = -z/β
    dz = -(n_overturned * np.exp(log_pdf - log_p) - (n_total - n_overturned) * np.exp(log_pdf - log_q))
    value = -float(np.sum(n_overturned * log_p + (n_total - n_overturned) * log_q))
    return value, np.array([-np.sum(dz) / beta, -np.sum(dz * z) / beta])


def _hessian(fun, x, steps):
    """Central-difference Hessian of a scalar function. [-]"""
    n = len(x)
    h = np.zeros((n, n))
    for i in range(n):
        for j in range(i, n):
            ei = np.zeros(n)
            ej = np.zeros(n)
            ei[i], ej[j] = steps[i], steps[j]
            h[i, j] = h[j, i] = (fun(x + ei + ej) - fun(x + ei - ej) - fun(x - ei + ej) + fun(x - ei - ej)) / (
                4 * steps[i] * steps[j])
    return h


def fit_lognormal(im, n_total, n_overturned) -> FragilityFit:
    """Maximum-likelihood lognormal fragility of stripe counts (Eqs. F1–F2, Baker [1]_).

    Parameters
    ----------
    im : array_like
        IM levels x_j, > 0. [IM]
    n_total : array_like of int
        Records run at each level n_j. [-]
    n_overturned : array_like of int
        Records that overturned the block at each level z_j (0 <= z_j <= n_j). [-]

    Returns
    -------
    FragilityFit
    """
    im = np.asarray(im, dtype=float)
    n_total = np.asarray(n_total, dtype=float)
    n_overturned = np.asarray(n_overturned, dtype=float)
    if im.ndim != 1 or im.size < 2 or im.shape != n_total.shape or im.shape != n_overturned.shape:
        raise ValueError(f"im, n_total and n_overturned must be 1-D arrays of one length >= 2, got shapes "
                         f"{im.shape}, {n_total.shape}, {n_overturned.shape}")
    if np.any(~np.isfinite(im)) or np.any(im <= 0):
        raise ValueError("im must hold positive finite intensity levels")
    if np.any(n_overturned < 0) or np.any(n_overturned > n_total):
        raise ValueError("n_overturned must lie between 0 and n_total at every level")
    nan2 = np.full((2, 2), np.nan)
    if n_overturned.sum() == 0:
        return FragilityFit(math.nan, math.nan, math.nan, math.nan, nan2, 0.0, "no overturning")
    if np.all(n_overturned == n_total):
        return FragilityFit(math.nan, math.nan, math.nan, math.nan, nan2, 0.0, "all overturned")
    fraction = n_overturned / np.maximum(n_total, 1)
    order = np.argsort(im)
    if np.all((fraction == 0) | (fraction == 1)) and np.all(np.diff(fraction[order]) >= 0):
        # every stripe all-safe below and all-overturned above: β → 0, θ anywhere in between
        first = int(np.argmax(fraction[order] == 1))
        median = math.sqrt(im[order][first - 1] * im[order][first])
        return FragilityFit(median, 0.0, math.nan, math.nan, nan2, 0.0, "separated")
    # start: the IM where the observed fraction first reaches 1/2, and a moderate dispersion
    start_median = im[np.argmax(fraction >= 0.5)] if np.any(fraction >= 0.5) else im[-1]
    log_im = np.log(im)

    def fun(x):
        return _nll_and_gradient(x, log_im, n_total, n_overturned)[0]

    def in_log_beta(x):  # (ln θ, ln β): unconstrained, so the quasi-Newton steps need no bounds
        value, grad = _nll_and_gradient((x[0], math.exp(x[1])), log_im, n_total, n_overturned)
        return value, np.array([grad[0], grad[1] * math.exp(x[1])])

    lo, hi = DISPERSION_BOUNDS
    from scipy import optimize

    res = optimize.minimize(in_log_beta, x0=[math.log(start_median), math.log(0.4)], jac=True, method="BFGS")
    log_median, beta = res.x[0], math.exp(res.x[1])
    if not lo < beta < hi:  # separated (β → 0) or flat (β → ∞) stripes: no interior maximum
        beta = min(max(beta, lo), hi)
    status = "ok" if lo < beta < hi else "at bound"
    cov = nan2
    se = (math.nan, math.nan)
    if status == "ok":
        hess = _hessian(fun, np.array([log_median, beta]), np.array([1e-4, 1e-4 * max(beta, 0.05)]))
        if np.all(np.linalg.eigvalsh(hess) > 0):
            cov = np.linalg.inv(hess)
            se = (math.sqrt(cov[0, 0]), math.sqrt(cov[1, 1]))
        else:
            status = "no curvature"
    return FragilityFit(float(math.exp(log_median)), float(beta), se[0], se[1], cov, -float(res.fun), status)


def fit_lognormal_points(im, overturned) -> FragilityFit:
    """Lognormal MLE (Eq. F2) of single runs at arbitrary intensities: each run is a stripe of one. [-]

    Parameters
    ----------
    im : array_like
        Intensity of each run, > 0 (any shape, flattened). [IM]
    overturned : array_like of bool
        Whether each run overturned the block, same shape as ``im``.
    """
    im = np.asarray(im, dtype=float).ravel()
    overturned = np.asarray(overturned, dtype=float).ravel()
    if overturned.size != im.size:
        raise validation.InputError(f"overturned has {overturned.size} values, im has {im.size}: give one per run")
    order = np.argsort(im, kind="stable")
    return fit_lognormal(im[order], np.ones(im.size), overturned[order])


def bootstrap_median_ratios(levels, overturned, reference: int, n_boot: int, rng: np.random.Generator):
    """Bootstrap over records of θ_c/θ_reference for every control c (records drawn with replacement).

    Parameters
    ----------
    levels : array_like, shape (level,)
        IM levels. [IM]
    overturned : ndarray of bool, shape (control, record, level)
        Whether each run overturned the block.
    reference : int
        Index of the reference control (FS).
    n_boot : int
        Number of bootstrap draws.
    rng : numpy.random.Generator
        Source of the record draws.

    Returns
    -------
    ndarray, shape (n_boot, control)
        Ratios of the medians; NaN for draws where either fit has no finite median.
    """
    n_controls, n_records, n_levels = overturned.shape
    ratios = np.full((n_boot, n_controls), np.nan)
    n_total = np.full(n_levels, n_records)
    for b in range(n_boot):
        pick = rng.integers(0, n_records, n_records)
        counts = overturned[:, pick, :].sum(axis=1)
        medians = np.array([fit_lognormal(levels, n_total, counts[c]).median for c in range(n_controls)])
        ratios[b] = medians / medians[reference]
    return ratios


def fit_lognormal_thresholds(thresholds, censored_above) -> FragilityFit:
    """Lognormal MLE of per-record thresholds, right-censored where a record has none.

    A threshold t_r is the smallest intensity at which record r overturns the block; where the scan
    found none (NaN) the threshold is only known to lie above ``censored_above[r]``, the highest level
    run. ln L = Σ_found [ln φ(z_r) − ln β − ln t_r] + Σ_censored ln(1 − Φ(z_r)), z = ln(t/θ)/β.

    Parameters
    ----------
    thresholds : array_like
        t_r, > 0, NaN where none was found. [IM]
    censored_above : array_like
        For each record, the level its threshold lies above when it is NaN. [IM]

    Returns
    -------
    FragilityFit
        θ and β of the thresholds' distribution (``status`` as for :func:`fit_lognormal`; "no overturning"
        when no record has a threshold, "separated" when all thresholds are equal).
    """
    t = np.asarray(thresholds, dtype=float).ravel()
    c = np.asarray(censored_above, dtype=float).ravel()
    if t.shape != c.shape or t.size < 1:
        raise ValueError("thresholds and censored_above must have one value per record")
    found = np.isfinite(t)
    if np.any(t[found] <= 0) or np.any(~np.isfinite(c[~found])) or np.any(c[~found] <= 0):
        raise ValueError("thresholds must be > 0 (or NaN) and every censoring level finite and > 0")
    nan2 = np.full((2, 2), np.nan)
    if not found.any():
        return FragilityFit(math.nan, math.nan, math.nan, math.nan, nan2, 0.0, "no overturning")
    log_t, log_c = np.log(t[found]), np.log(c[~found])
    if found.all() and np.ptp(log_t) == 0:
        return FragilityFit(float(t[found][0]), 0.0, math.nan, math.nan, nan2, 0.0, "separated")

    def nll(x):  # x = (ln θ, ln β)
        log_median, beta = x[0], math.exp(x[1])
        z = (log_t - log_median) / beta
        return -float(np.sum(-0.5 * z * z - 0.5 * math.log(2 * math.pi) - math.log(beta) - log_t)
                      + np.sum(special.log_ndtr(-(log_c - log_median) / beta)))

    from scipy import optimize

    start_beta = float(np.std(log_t)) if log_t.size > 1 and np.ptp(log_t) > 0 else 0.4
    res = optimize.minimize(nll, x0=[float(np.mean(log_t)), math.log(start_beta)], method="Nelder-Mead",
                            options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 4000})
    log_median, beta = float(res.x[0]), math.exp(float(res.x[1]))
    lo, hi = DISPERSION_BOUNDS
    status = "ok" if lo < beta < hi else "at bound"
    beta = min(max(beta, lo), hi)
    cov, se = nan2, (math.nan, math.nan)
    if status == "ok":
        def in_beta(x):
            return nll((x[0], math.log(x[1])))
        hess = _hessian(in_beta, np.array([log_median, beta]), np.array([1e-4, 1e-4 * beta]))
        if np.all(np.linalg.eigvalsh(hess) > 0):
            cov = np.linalg.inv(hess)
            se = (math.sqrt(cov[0, 0]), math.sqrt(cov[1, 1]))
        else:
            status = "no curvature"
    return FragilityFit(math.exp(log_median), beta, se[0], se[1], cov, -float(res.fun), status)
