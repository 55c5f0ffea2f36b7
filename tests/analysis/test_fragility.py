"""Lognormal fragility by maximum likelihood (Eqs. F1-F2) and the stripes over a record suite."""
import math

import numpy as np
import pytest
from scipy import optimize, stats

from rockstudy import Anchorage, Control
from rockstudy.analysis.fragility import (
    _nll_and_gradient,
    fit_lognormal,
    fragility_dataset,
    fragility_markdown,
    intensity,
    peak_ground_velocity,
    stripe_outcomes,
)
from rockstudy.engine.simulate import simulate
from rockstudy.model.records import Record
from rockstudy.model.synthetic import synthetic_suite

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


def test_peak_ground_velocity_of_a_sine_cycle():
    """a = A sin(ωt) over one period from rest: v = A/ω (1 − cos ωt), PGV = 2A/ω."""
    omega, amplitude, dt = 2 * math.pi, 3.0, 1e-4
    t = np.arange(0, 1.0 + dt / 2, dt)
    rec = Record("sine", dt, amplitude * np.sin(omega * t))
    assert peak_ground_velocity(rec) == pytest.approx(2 * amplitude / omega, rel=1e-6)


def test_stripes_scale_records_to_the_level_and_match_direct_runs(blc06):
    records = [r for r, _ in synthetic_suite(3, 5)]
    levels = [0.9, 2.0, 4.0]
    controls = [Control("FS"), Control("CS01")]
    over, rot, scale = stripe_outcomes(blc06, Anchorage(), controls, records, levels)
    for r, rec in enumerate(records):
        np.testing.assert_allclose(scale[r] * rec.pga / blc06.uplift_acceleration, levels)
        for c, control in enumerate(controls):
            direct = simulate(blc06, Anchorage(), control, rec.motion(float(scale[r, 2])))
            assert over[c, r, 2] == direct.overturned and rot[c, r, 2] == direct.max_rotation_ratio
    # below the uplift acceleration (PGA < g tan(alpha)) the block never leaves the ground
    assert not over[:, :, 0].any() and np.all(rot[:, :, 0] == 0)
    over_v, _, scale_v = stripe_outcomes(blc06, Anchorage(), controls[:1], records[:1], levels, measure="pgv_ratio")
    assert scale_v[0, 1] * intensity(records[0], blc06, "pgv_ratio") == pytest.approx(2.0)


def test_fragility_dataset_and_table(blc06):
    records = [r for r, _ in synthetic_suite(6, 3)]
    levels = np.arange(1.0, 9.01, 1.0)
    ds = fragility_dataset(blc06, Anchorage(), [Control("FS"), Control("CS01")], records, levels, n_boot=20, seed=2)
    np.testing.assert_allclose(ds.fraction.values, ds.overturned.mean("record").values)
    assert float(ds.median_ratio.sel(strategy="FS")) == 1.0
    assert float(ds.median_shift_percent.sel(strategy="FS")) == 0.0
    assert ds.intensity.attrs["long_name"].endswith("PGA/(g tan(alpha))")
    table = fragility_markdown(ds)
    assert sum(line.startswith("| ") for line in table.splitlines()) == 3 and "| CS01 |" in table
    with pytest.raises(ValueError, match="must include FS"):
        fragility_dataset(blc06, Anchorage(), [Control("CS01")], records, levels)


@pytest.mark.filterwarnings("error::RuntimeWarning")  # no finite bootstrap ratio: a NaN interval, no warning
def test_suite_fragility_names_every_record_and_its_threshold(blc06):
    """Three synthetic records of the suite by name: the dataset carries suite, id, event and station; each
    threshold lies at or below the first overturning stripe and above the last safe one below it; the
    median in g is the ratio times tan(alpha) g / g_n."""
    from rockstudy.analysis.fragility import suite_fragility_dataset
    from rockstudy.analysis.record_scan import is_overturned
    from rockstudy.model import record_suites
    from rockstudy.model.records import STANDARD_GRAVITY
    entries = [record_suites.load_record(f"synthetic:SYN00{i}") for i in range(3)]
    levels = np.arange(1.0, 5.01, 0.5)
    ds = suite_fragility_dataset(blc06, Anchorage(), [Control("FS"), Control("CS01")], entries, levels,
                                 suite="synthetic", resolution=0.05, n_boot=5, free_time=10.0)
    assert list(ds.record.values) == [f"synthetic:SYN00{i}" for i in range(3)]
    assert set(ds.record_station.values) == {"SYN000", "SYN001", "SYN002"}
    assert all(str(e).startswith("synthetic") for e in ds.record_event.values)
    over = is_overturned(ds.outcome.values)
    for c in range(2):
        for r in range(3):
            thr = float(ds.threshold_intensity.values[c, r])
            if not over[c, r].any():
                assert np.isnan(thr)
                continue
            first = int(np.argmax(over[c, r]))
            assert thr <= levels[first] and (first == 0 or thr > levels[first - 1])
            assert thr - float(ds.last_safe_intensity.values[c, r]) <= 0.05
    np.testing.assert_allclose(ds.fragility_median_physical.values, ds.fragility_median.values
                               * blc06.uplift_acceleration / STANDARD_GRAVITY)
    np.testing.assert_allclose(ds.threshold_pga.values, ds.threshold_scale.values * ds.record_pga.values[None, :])
