"""Every kind of netCDF file rockstudy writes is CF-1.11 conforming (IOOS compliance checker, no
high-priority finding), declares its conventions and provenance, and a history has one value
per time."""
import netCDF4
import numpy as np
import pytest
import xarray as xr

from builders import A_MAX0, BLC06, fake_spectrum
from compliance import high_priority_findings
from rockstudy import __version__
from rockstudy.analysis.fragility import fragility_dataset
from rockstudy.analysis.probability import probability_surface
from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, spectrum
from rockstudy.core import io
from rockstudy.core.constants import CF_CONVENTIONS, PAPER, rest_velocity
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.control import Control
from rockstudy.model.noise import NoiseReading
from rockstudy.model.synthetic import suite_dataset, synthetic_suite
from rockstudy.studies import claims, datasets, tables
from rockstudy.studies import device_calibration as calibration
from rockstudy.studies import noise_readings as readings

LEVELS = {"R000": 0.0, "R001": 0.01, "R005": 0.05, "R010": 0.1}
GRID = AmplitudeGrid(start=0.9, stop=2.7, step=0.6, resolution=0.1)


def _spectra():
    return [fake_spectrum(s, v, np.full((2, 4), 1.5 + v + 0.1 * i)) for i, s in enumerate(("FS", "CS01", "CS02"))
            for v in LEVELS.values()]


def _table1():
    return tables.table1(_spectra(), ["FS", "CS01", "CS02"], LEVELS, 1.0)


def _timing():
    sweep = [fake_spectrum(s, 0.05, np.full(4, 1.7), sampling_time=t) for s in ("CS01", "CS02") for t in (0.01, 0.1)]
    same = [fake_spectrum(s, 0.05, np.full(4, 1.6)) for s in ("CS01", "CS02")]
    return tables.timing_table(sweep, same, [fake_spectrum("FS", 0.05, np.full(4, 1.5))], "sampling_time", 1.0)


def _readings():
    ref = fake_spectrum("FS", 0.0, np.full(4, 2.0))
    noisy = {(name, level): fake_spectrum("FS", value, np.full(4, 1.9)) for name in ("a", "b")
             for level, value in LEVELS.items() if value > 0}
    return readings.readings_table(noisy, ref, {"a": NoiseReading(), "b": NoiseReading(step=0.02)},
                                   {k: v for k, v in LEVELS.items() if v > 0}, 1.0)


def _calibration():
    design = calibration.CalibrationDesign(kappa_max=(1.0, 2.0), damping_ratio=(0.05,))
    return calibration.grid_dataset(design, [_table1(), _table1()], BLC06.alpha)


def _fragility():
    records = [r for r, _ in synthetic_suite(3, 3)]
    return fragility_dataset(BLC06, Anchorage(), [Control("FS"), Control("CS01")], records, [1.0, 3.0, 6.0],
                             n_boot=5, seed=2)


KINDS = {
    "spectrum": lambda: _spectra()[1],
    "gathered spectrum": lambda: datasets.gather_spectra([fake_spectrum("FS", 0.05, [np.full(4, 1.5)], [k])
                                                          for k in (0, 1)]),
    "convergence": lambda: datasets.convergence_dataset(_spectra()[1]),
    "noise": lambda: datasets.noise_dataset(Scenario(BLC06, noise_level=0.05), [1.0, 2.0], [0, 1], 1.0, 1),
    "history": lambda: datasets.time_history(Scenario(BLC06, control=Control("CS01")), 2.0, 1.3),
    "map": lambda: spectrum(Scenario(BLC06, control=Control("FS")), [1.0, 2.0], grid=GRID, with_map=True),
    "table 1": _table1,
    "timing table": _timing,
    "claims": lambda: claims.claims_dataset(claims.evaluate_claims(_table1())),
    "table 1 vs paper": lambda: claims.table1_comparison(_table1()),
    "readings table": _readings,
    "calibration grid": _calibration,
    "probability": lambda: probability_surface(Scenario(BLC06, control=Control("FS"), noise_level=0.05),
                                               [1.0, 2.0], realisations=range(2), grid=GRID),
    "fragility": _fragility,
    "synthetic suite": lambda: suite_dataset(synthetic_suite(2, 4), 4),
}


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_every_kind_of_file_passes_the_cf_checker(kind, tmp_path):
    path = io.write_netcdf(KINDS[kind](), tmp_path / "out.nc")
    assert high_priority_findings(path) == []
    with netCDF4.Dataset(path) as nc:
        attrs = nc.__dict__
        assert attrs["Conventions"] == CF_CONVENTIONS and PAPER in attrs["references"]
        assert __version__ in attrs["source"] and "rockstudy" in attrs["history"] and attrs["title"]
        for name, var in nc.variables.items():
            if name in nc.dimensions:  # a coordinate variable
                assert "_FillValue" not in var.ncattrs(), name


def test_the_checker_sees_what_main_used_to_write(tmp_path):
    """The checker catches a NaN _FillValue on a coordinate and a repeated time (what the files
    had before), so the test above can fail."""
    ds = xr.Dataset({"theta": ("time", [0.0, 1.0, 2.0])},
                    coords={"time": ("time", [0.0, 1.0, 1.0], {"units": "s", "long_name": "time"})})
    ds.to_netcdf(tmp_path / "old.nc")
    found = "\n".join(high_priority_findings(tmp_path / "old.nc"))
    assert "strictly monotonic" in found and "_FillValue" in found
    with pytest.raises(ValueError, match="'time' is not strictly monotonic"):
        io.write_netcdf(ds, tmp_path / "new.nc")
    assert not (tmp_path / "new.nc").exists()


def test_history_keeps_each_time_once_and_the_impacts_on_their_own_dimension(tmp_path):
    ds = KINDS["history"]()
    t = ds["time"].values
    assert np.all(np.diff(t) > 0) and ds.sizes["impact"] == ds.attrs["n_impacts"] > 10
    # Eq. (15): an impact multiplies theta_dot by the restitution e, unless the rebound e|theta_dot-| is below
    # the rest velocity: then the block comes to rest (theta_dot+ = 0), as it does at the last impact
    before, after = ds["theta_dot_before_impact"].values, ds["theta_dot_after_impact"].values
    rests = BLC06.e * np.abs(before) < rest_velocity(BLC06.p, BLC06.alpha)
    np.testing.assert_allclose(after[~rests] / before[~rests], BLC06.e, rtol=1e-12)
    assert np.all(after[rests] == 0) and rests[-1] and ds.attrs["status"] == "rest"
    # the value on `time` at an impact is the one just after it
    at = np.searchsorted(t, ds["impact_time"].values)
    np.testing.assert_array_equal(ds["theta_dot"].values[at], ds["theta_dot_after_impact"].values)
    io.write_netcdf(ds, tmp_path / "h.nc")
    with xr.open_dataset(tmp_path / "h.nc") as back:
        assert back["theta"].sel(time=2.0, method="nearest").size == 1
        assert back["time"].dtype == np.float64 and back["time"].attrs["units"] == "s"


def test_cf_attributes_keep_a_title_and_extend_a_history():
    attrs = io.cf_attributes({"title": "T", "history": "made by hand"})
    assert attrs["title"] == "T" and attrs["history"].splitlines()[0] == "made by hand"
    assert io.cf_attributes(attrs)["history"] == attrs["history"]  # rewriting a file adds no line
    assert io.cf_attributes({})["title"] and A_MAX0 > 0
