"""Lognormal fragility by maximum likelihood (Eqs. F1-F2): recovery of known parameters, coverage of the
Wald interval, the likelihood's gradient and the degenerate stripes."""
import math

import numpy as np
import pytest
from scipy import optimize, stats

from rockstudy.analysis.fragility_fit import _nll_and_gradient, fit_lognormal

LEVELS = np.round(np.arange(0.5, 12.01, 0.5), 3)


def _sample(median, dispersion, n, rng, levels=LEVELS):
    p = stats.norm.cdf(np.log(levels / median) / dispersion)
    return rng.binomial(n, p)


@pytest.mark.parametrize("median, dispersion", [(4.0, 0.35), (2.5, 0.6), (7.0, 0.2)])
def test_fit_recovers_known_median_and_dispersion(median, dispersion):
    rng = np.random.default_rng(20261122)
    n = np.full(LEVELS.size, 400)
    fit = fit_lognormal(LEVELS, n, _sample(median, dispersion, n, rng))
    assert fit.status == "ok"
    assert fit.log_median_se < 0.02 and fit.dispersion_se < 0.02  # 400 records per stripe: a sharp estimate
    assert abs(math.log(fit.median / median)) < 4 * fit.log_median_se
    assert abs(fit.dispersion - dispersion) < 4 * fit.dispersion_se


def test_wald_interval_covers_the_truth_about_95_percent_of_the_time():
    """The observed-information standard errors are right if the 95 % interval covers θ in
    about 95 % of repeated experiments (30 records per stripe, as in the study)."""
    rng = np.random.default_rng(1)
    n = np.full(LEVELS.size, 30)
    covered_median, covered_beta, trials = 0, 0, 300
    for _ in range(trials):
        fit = fit_lognormal(LEVELS, n, _sample(4.0, 0.4, n, rng))
        lo, hi = fit.median_interval()
        covered_median += lo <= 4.0 <= hi
        covered_beta += abs(fit.dispersion - 0.4) <= 1.96 * fit.dispersion_se
    assert 0.90 <= covered_median / trials <= 0.99
    assert 0.88 <= covered_beta / trials <= 0.99


def test_gradient_of_the_likelihood():
    k = np.array([0, 1, 5, 12, 20, 29, 30])
    x = np.array([0.5, 1.0, 2.0, 3.0, 4.0, 6.0, 9.0])
    n = np.full(x.size, 30.0)
    for params in ([1.0, 0.5], [1.5, 0.2], [0.3, 1.3]):
        err = optimize.check_grad(lambda q: _nll_and_gradient(q, np.log(x), n, k)[0],
                                  lambda q: _nll_and_gradient(q, np.log(x), n, k)[1], params)
        assert err < 1e-4 * (1 + np.abs(_nll_and_gradient(params, np.log(x), n, k)[1]).max())


def test_degenerate_stripes_are_flagged_not_fitted():
    x, n = [1.0, 2.0, 4.0, 8.0], [10, 10, 10, 10]
    assert fit_lognormal(x, n, [0, 0, 0, 0]).status == "no overturning"
    assert fit_lognormal(x, n, [10, 10, 10, 10]).status == "all overturned"
    sep = fit_lognormal(x, n, [0, 0, 10, 10])
    assert sep.status == "separated" and sep.median == pytest.approx(math.sqrt(8.0)) and sep.dispersion == 0
    with pytest.raises(ValueError, match="between 0 and n_total"):
        fit_lognormal(x, n, [0, 0, 11, 10])
    with pytest.raises(ValueError, match="positive finite"):
        fit_lognormal([0.0, 1.0], [1, 1], [0, 1])


def test_threshold_fit_recovers_a_censored_lognormal():
    """400 thresholds drawn from a lognormal (θ = 0.6, β = 0.4), those above 0.9 censored: the MLE recovers
    θ and β within 4 standard errors; without censoring it is the sample's log mean and (biased) log std."""
    from rockstudy.analysis.fragility_fit import fit_lognormal_thresholds
    rng = np.random.default_rng(20261127)
    t = np.exp(np.log(0.6) + 0.4 * rng.standard_normal(400))
    top = np.full(t.size, 0.9)
    fit = fit_lognormal_thresholds(np.where(t <= 0.9, t, np.nan), top)
    assert fit.status == "ok" and np.isnan(t[t > 0.9]).sum() == 0 and (t > 0.9).sum() > 20
    assert abs(math.log(fit.median / 0.6)) < 4 * fit.log_median_se
    assert abs(fit.dispersion - 0.4) < 4 * fit.dispersion_se
    full = fit_lognormal_thresholds(t, top)
    assert full.median == pytest.approx(math.exp(np.mean(np.log(t))), rel=1e-6)
    assert full.dispersion == pytest.approx(np.std(np.log(t)), rel=1e-5)
    assert fit_lognormal_thresholds([np.nan, np.nan], [1.0, 1.0]).status == "no overturning"
