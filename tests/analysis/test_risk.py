"""Risk at a site (Eqs. R1-R3): against Cornell et al.'s closed form for a power-law hazard, an independent
quadrature on a curved hazard, the inverse, the disaggregation, the tails and the scenario formula."""
import math
import warnings

import numpy as np
import pytest
import xarray as xr
from scipy import integrate, stats

from builders import two_fragilities
from rockstudy.analysis.hazard import HazardCurve
from rockstudy.analysis.risk import (
    HazardExtensionWarning,
    LognormalFragility,
    annual_rate,
    fragility_from_dataset,
    median_for_target,
    probability_in_years,
    rate_for_probability,
    scenario_probability,
)
from rockstudy.analysis.risk_devices import devices_meeting

K0, K = 1e-4, 2.5
"""Power-law hazard λ(x) = k0 x^-k: k0 the rate of exceeding 1 g. [1/yr]"""


def power_law(k0=K0, k=K, points=200, lo=0.001, hi=20.0):
    x = np.geomspace(lo, hi, points)
    return HazardCurve(x, k0 * x ** -k, source="power law")


def cornell(theta, beta, k0=K0, k=K):
    """λ = k0 θ^-k exp(k²β²/2), Cornell et al. (2002), Eq. 11."""
    return k0 * theta ** -k * math.exp(0.5 * (k * beta) ** 2)


@pytest.mark.parametrize("theta, beta, k", [(0.6, 0.4, 2.5), (0.3, 0.6, 3.0), (1.2, 0.2, 1.8), (0.5, 0.0, 2.5)])
def test_rate_equals_cornells_closed_form(theta, beta, k):
    result = annual_rate(LognormalFragility(theta, beta), power_law(k=k))
    assert result.annual_rate == pytest.approx(cornell(theta, beta, k=k), rel=0.01)
    assert result.band_rate.sum() == pytest.approx(result.annual_rate, rel=1e-12)
    assert result.tail_share < 0.01
    assert result.probability(50) == pytest.approx(1 - math.exp(-50 * result.annual_rate), rel=1e-12)


def test_rate_equals_a_quadrature_of_a_curved_hazard():
    """A hazard that is no power law, read log-log between its 25 points: Eq. R1 by scipy's quad on every
    segment (P(x) times -dλ/dx of the interpolated curve) gives the same rate."""
    x = np.geomspace(0.005, 3.0, 25)
    hazard = HazardCurve(x, 0.05 * np.exp(-3 * x ** 0.7) / (1 + x))
    fragility = LognormalFragility(0.4, 0.35)
    result = annual_rate(fragility, hazard, extension="none")
    total = 0.0
    for i in range(x.size - 1):
        def integrand(u, i=i):
            return fragility.probability(math.exp(u)) * hazard.slopes[i] * hazard.rate(math.exp(u))
        total += integrate.quad(integrand, math.log(x[i]), math.log(x[i + 1]), epsabs=0, epsrel=1e-10)[0]
    assert result.annual_rate == pytest.approx(total, rel=1e-8)


def test_tails_are_reported_and_warned_about():
    """A fragile object on a curve that stops at 0.3 g: most of λ comes from beyond the last point."""
    hazard = power_law(points=30, lo=0.01, hi=0.3)
    fragility = LognormalFragility(0.6, 0.4)
    with pytest.warns(HazardExtensionWarning, match="outside the hazard curve"):
        loglog = annual_rate(fragility, hazard)
    assert loglog.annual_rate == pytest.approx(cornell(0.6, 0.4), rel=0.01)  # the extension is the power law
    assert loglog.rate_above / loglog.annual_rate == pytest.approx(loglog.tail_share, rel=1e-9)
    with pytest.warns(HazardExtensionWarning, match="left out"):
        none = annual_rate(fragility, hazard, extension="none")
    assert none.annual_rate == pytest.approx(loglog.annual_rate - loglog.rate_below - loglog.rate_above, rel=1e-12)
    assert none.band_rate[0] == 0 and none.band_rate[-1] == 0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        annual_rate(fragility, hazard, warn=False)


def test_disaggregation_by_band():
    """Bands [0, θ] and [θ, inf) on a power law: the part above θ is ∫_θ^inf Φ(ln(x/θ)/β) |dλ|, by quad."""
    theta, beta = 0.6, 0.4
    result = annual_rate(LognormalFragility(theta, beta), power_law(), band_edges_g=[theta])
    np.testing.assert_array_equal(result.band_edges_g, [0.0, theta, np.inf])
    above = integrate.quad(lambda u: stats.norm.cdf((u - math.log(theta)) / beta) * K * K0 * math.exp(-K * u),
                           math.log(theta), math.log(theta) + 40 * beta, epsabs=0, epsrel=1e-10)[0]
    assert result.band_rate[1] == pytest.approx(above, rel=1e-6)
    assert result.band_share.sum() == pytest.approx(1.0, rel=1e-12)


@pytest.mark.parametrize("beta, target", [(0.4, 1e-3), (0.6, 2e-4), (0.0, 1e-3)])
def test_inverse_equals_the_closed_form(beta, target):
    theta = median_for_target(power_law(), beta, target_rate=target)
    assert theta == pytest.approx((K0 * math.exp(0.5 * (K * beta) ** 2) / target) ** (1 / K), rel=0.01)


def test_inverse_from_a_probability_in_years():
    """1 % in 50 years is the rate -ln(0.99)/50; the median meeting it gives back 1 % in 50 years."""
    assert rate_for_probability(0.01, 50) == pytest.approx(-math.log(0.99) / 50, rel=1e-12)
    hazard = power_law()
    theta = median_for_target(hazard, 0.5, target_probability=0.01, years=50)
    rate = annual_rate(LognormalFragility(theta, 0.5), hazard).annual_rate
    assert probability_in_years(rate, 50) == pytest.approx(0.01, rel=1e-6)
    with pytest.raises(ValueError, match="one target"):
        median_for_target(hazard, 0.5)


def test_devices_meeting_a_median():
    devices = xr.Dataset({"fragility_median": (("strategy", "kappa_max", "damping_ratio"),
                                               [[[0.5], [0.6]], [[0.7], [np.nan]]], {"units": "g"})},
                         coords={"strategy": ["FS", "CS01"], "kappa_max": [1.0, 2.0], "damping_ratio": [0.05]})
    rows = devices_meeting(devices, 0.6)
    assert [(r["strategy"], r["kappa_max"]) for r in rows if r["meets"]] == [("FS", 2.0), ("CS01", 1.0)]


def test_scenario_probability_formula():
    fragility = LognormalFragility(0.5, 0.4)
    assert scenario_probability(fragility, 0.5, 0.6) == pytest.approx(0.5, abs=1e-15)
    expected = stats.norm.cdf((math.log(0.3) - math.log(0.5)) / math.sqrt(0.4 ** 2 + 0.6 ** 2))
    assert scenario_probability(fragility, 0.3, 0.6) == pytest.approx(expected, rel=1e-12)


def test_fragility_from_a_dataset():
    ds = xr.Dataset({"fragility_median_physical": ("strategy", [0.62, np.nan], {"units": "g"}),
                     "fragility_median": ("strategy", [2.48, np.nan], {"units": "1"}),
                     "fragility_dispersion": ("strategy", [0.47, np.nan]),
                     "fit_status": ("strategy", ["ok", "no overturning"])},
                    coords={"strategy": ["FS", "CS01"]}, attrs={"record_suite": "p695-far-field"})
    f = fragility_from_dataset(ds, "FS")
    assert (f.median_g, f.dispersion) == (0.62, 0.47) and "p695-far-field" in f.label
    with pytest.raises(ValueError, match="no overturning"):
        fragility_from_dataset(ds, "CS01")
    with pytest.raises(ValueError, match="not in the fragility dataset"):
        fragility_from_dataset(ds, "CS02")
    with pytest.raises(ValueError, match="not a PGA"):
        fragility_from_dataset(ds.drop_vars("fragility_median_physical"), "FS")


def test_risk_dataset_and_table(tmp_path):
    """Two strategies' fragilities on a power-law site and a scenario (needs pygmm): Cornell's rate, the
    reduction over FS, the range from the median's interval, and one table row per strategy."""
    pytest.importorskip("pygmm")
    from rockstudy.analysis.risk_sites import risk_dataset
    from rockstudy.report import risk_markdown
    fragility = two_fragilities()
    ds = risk_dataset(fragility, scenarios={"M7": {"mag": 7, "dist_rup": 10, "v_s30": 400}},
                      hazard_curves={"site": power_law()}, years=50)
    rate = ds.annual_rate.sel(hazard="site").values
    np.testing.assert_allclose(rate, [cornell(0.5, 0.4), cornell(0.8, 0.4)], rtol=0.01)
    assert float(ds.reduction_percent.sel(strategy="CS01", hazard="site")) == pytest.approx(
        100 * (1 - (0.8 / 0.5) ** -K), rel=1e-9)  # same β: the rates' ratio is (θ/θ_FS)^-k
    p = ds.scenario_probability.values[:, 0]
    assert ds.scenario_probability_low.values[0, 0] < p[0] < ds.scenario_probability_high.values[0, 0]
    assert ds.disaggregation.sel(hazard="site").sum("pga_band").values == pytest.approx([1.0, 1.0])
    table = risk_markdown(ds)
    assert sum(line.startswith(("| FS |", "| CS01 |")) for line in table.splitlines()) == 2
    assert "stripes' lognormal fit" in table
    pytest.importorskip("compliance_checker")
    from compliance import high_priority_findings
    from rockstudy.core import io
    io.write_netcdf(ds, tmp_path / "risk.nc")
    assert high_priority_findings(tmp_path / "risk.nc") == []


def test_a_target_beyond_the_curve_is_refused_or_answered_with_how_far():
    """A curve that stops at 0.005 g and a target of 1e-6/yr: the median lies decades beyond the curve."""
    from rockstudy.analysis.risk import HazardExtrapolationWarning, target_median
    short = HazardCurve([0.001, 0.002, 0.005], [1e-2, 3e-3, 5e-4])
    with pytest.raises(ValueError, match="decades beyond the curve's last point, 0.005 g"):
        median_for_target(short, 0.4, target_rate=1e-6)
    with pytest.warns(HazardExtrapolationWarning, match="decades beyond"):
        found = target_median(short, 0.4, target_rate=1e-6, allow_extrapolation=True)
    assert found.extrapolated and found.decades_outside == pytest.approx(math.log10(found.median_g / 0.005))
    inside = target_median(power_law(), 0.4, target_rate=1e-3)
    assert not inside.extrapolated and inside.decades_outside == 0.0


def test_devices_that_never_or_always_overturn_meet_every_or_no_target():
    devices = xr.Dataset({"fragility_median": (("strategy", "kappa_max", "damping_ratio"),
                                               [[[0.5], [np.nan], [np.nan]]], {"units": "g"}),
                          "fit_status": (("strategy", "kappa_max", "damping_ratio"),
                                         [[["ok"], ["all overturned"], ["no overturning"]]])},
                         coords={"strategy": ["CS01"], "kappa_max": [1.0, 2.0, 4.0], "damping_ratio": [0.05]})
    rows = devices_meeting(devices, 5.0)
    assert [(r["kappa_max"], r["meets"], r["fit_status"]) for r in rows] == [
        (1.0, False, "ok"), (2.0, False, "all overturned"), (4.0, True, "no overturning")]
    assert rows[2]["median_g"] is None  # no NaN leaves: strict JSON
