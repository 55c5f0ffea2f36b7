"""The risk of one object at every site of a hazard file (risk_at_sites), the study's dataset over sites,
and every number checked before it leaves."""
import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from rockstudy.analysis.hazard import HazardCurve, read_hazard_sites
from rockstudy.analysis.risk import LognormalFragility, RiskRangeError, annual_rate
from rockstudy.analysis.risk_sites import risk_at_sites, risk_warnings_markdown

DATA = Path(__file__).resolve().parents[1] / "data" / "hazard"


def test_every_site_of_a_real_file_with_its_coordinates():
    sites = read_hazard_sites(DATA / "nshmp-haz" / "PGA" / "total.csv")
    named = {s.label: s for s in sites}
    fragility = LognormalFragility(0.2, 0.4)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = risk_at_sites({"object": fragility}, named, years=50)
    assert ds.sizes["site"] == 7 and list(ds.site.values)[1] == "Oakland CA"
    assert float(ds.lon.sel(site="Oakland CA")) == -122.25 and float(ds.lat.sel(site="Oakland CA")) == 37.8
    for s in sites:
        expected = annual_rate(fragility, s.curve, band_edges_g=(0.05, 0.1, 0.2, 0.4, 0.8, 1.6), warn=False)
        assert float(ds.annual_rate.sel(strategy="object", site=s.label)) == expected.annual_rate
    p = ds.probability.values
    np.testing.assert_allclose(p, -np.expm1(-50 * ds.annual_rate.values), rtol=1e-12)


def test_a_step_fragility_at_a_level_gives_that_levels_rate():
    """Analytic oracle: β = 0 at θ on a point of the curve: λ = λ_IM(θ), the rate written in the file."""
    (oakland,) = [s for s in read_hazard_sites(DATA / "nshmp-haz" / "PGA" / "total.csv") if s.name == "Oakland CA"]
    ds = risk_at_sites({"step": LognormalFragility(0.103, 0.0)}, {"oakland": oakland}, warn=False)
    assert float(ds.annual_rate.squeeze()) == pytest.approx(1.28698458e-03, rel=1e-12)
    # a dispersion of 1e-300 is that step, not NaN
    tiny = risk_at_sites({"step": LognormalFragility(0.103, 1e-300)}, {"oakland": oakland}, warn=False)
    assert float(tiny.annual_rate.squeeze()) == pytest.approx(1.28698458e-03, rel=1e-9)


def test_a_rate_that_cannot_be_is_refused_naming_the_fragility():
    curve = HazardCurve([0.01, 0.1, 1.0], [1e-2, 1e-4, 1e-6], source="steep.txt")
    with pytest.raises(RiskRangeError) as err:
        annual_rate(LognormalFragility(1e-300, 0.4), curve)
    assert "median 1e-300 g" in str(err.value) and "steep.txt" in str(err.value)
    with pytest.raises(RiskRangeError):
        risk_at_sites({"FS": LognormalFragility(1e-300, 0.4)}, {"s": curve})


def fragility_dataset():
    """Two strategies' fragilities in PGA, as a record set's fragility dataset holds them."""
    import xarray as xr
    return xr.Dataset({"fragility_median_physical": ("strategy", [0.3, 0.5], {"units": "g"}),
                       "fragility_median": ("strategy", [1.2, 2.0], {"units": "1"}),
                       "fragility_dispersion": ("strategy", [0.4, 0.4])},
                      coords={"strategy": ["FS", "CS01"]}, attrs={"record_suite": "test"})


def test_the_study_dataset_over_every_site_of_a_file():
    from rockstudy.analysis.risk_sites import risk_dataset
    sites = read_hazard_sites(DATA / "openquake-hazard_curve-mean_PGA.csv")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = risk_dataset(fragility_dataset(), hazard_curves={"bay": sites})
    assert list(ds.hazard.values) == ["bay/-122.34,37.72", "bay/-122.15,37.56", "bay/-119.33,35.06",
                                      "bay/-118.25,34.05"]
    assert ds.lon.values.tolist() == [-122.34, -122.15, -119.33, -118.25]
    assert np.all((ds.probability.values >= 0) & (ds.probability.values <= 1))
    assert "converted to annual rates" in risk_warnings_markdown(ds)
    assert math.isfinite(float(ds.annual_rate.sel(strategy="FS", hazard="bay/-118.25,34.05")))
