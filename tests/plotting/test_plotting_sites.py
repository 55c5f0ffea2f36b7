"""The map of the risk at many sites (rockstudy.plotting.sites): one panel per strategy, one colour scale."""
import warnings
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from rockstudy.analysis.hazard import read_hazard_sites
from rockstudy.analysis.risk_sites import risk_dataset
from rockstudy.plotting.sites import figure_risk_sites, mapped_sites

DATA = Path(__file__).resolve().parents[1] / "data" / "hazard"


def risk_of_the_bay():
    fragility = xr.Dataset({"fragility_median_physical": ("strategy", [0.15, 0.3], {"units": "g"}),
                            "fragility_median": ("strategy", [0.6, 1.2], {"units": "1"}),
                            "fragility_dispersion": ("strategy", [0.4, 0.4])},
                           coords={"strategy": ["FS", "CS01"]}, attrs={"record_suite": "test"})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return risk_dataset(fragility, hazard_curves={
            "bay": read_hazard_sites(DATA / "nshmp-haz" / "PGA" / "total.csv"),
            "flat": read_hazard_sites(DATA / "openquake-hazard_curve-mean.csv")})


def test_every_site_with_coordinates_is_drawn_on_one_scale(tmp_path):
    risk = risk_of_the_bay()
    assert mapped_sites(risk).size == 8  # 7 named sites and one at (0, 0)
    fig = figure_risk_sites(risk)
    maps = [ax for ax in fig.axes if ax.get_title() in ("FS", "CS01")]
    assert len(maps) == 2
    scales = {(c.norm.vmin, c.norm.vmax) for ax in maps for c in ax.collections if c.get_array() is not None}
    assert len(scales) == 1  # one colour scale for both strategies
    coloured = maps[0].collections[0].get_array()
    p = risk.probability.sel(strategy="FS").values
    np.testing.assert_allclose(np.sort(coloured), np.sort(p[p > 0]), rtol=1e-12)
    fig.savefig(tmp_path / "map.png")
    assert (tmp_path / "map.png").stat().st_size > 0


def test_a_dataset_without_coordinates_is_refused():
    risk = risk_of_the_bay().drop_vars(["lon", "lat"])
    with pytest.raises(ValueError, match="no site with coordinates"):
        figure_risk_sites(risk)
