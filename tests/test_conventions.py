"""Every kind of netCDF file rockstudy writes is CF-1.11 conforming (IOOS compliance checker, no
high-priority finding at all), declares its conventions and provenance, and a history has one value
per time on a strictly increasing elapsed-time axis ``t`` that xarray leaves in seconds."""
import netCDF4
import numpy as np
import pytest
import xarray as xr

from builders import A_MAX0, BLC06, fake_spectrum
from compliance import high_priority_findings
from rockstudy import __version__, cli
from rockstudy.analysis.fragility import fragility_dataset, suite_fragility_dataset
from rockstudy.analysis.probability import probability_surface
from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, spectrum
from rockstudy.core import io
from rockstudy.core.constants import CF_CONVENTIONS, PAPER, rest_velocity
from rockstudy.model import record_suites, records
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.control import Control
from rockstudy.model.noise import NoiseReading
from rockstudy.model.synthetic import suite_dataset, suite_record, synthetic_suite
from rockstudy.studies import claims, datasets, design, tables
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
    grid = calibration.CalibrationDesign(kappa_max=(1.0, 2.0), damping_ratio=(0.05,))
    return calibration.grid_dataset(grid, [_table1(), _table1()], BLC06.alpha)


def _device_table():
    fs = [ds for ds in _spectra() if ds["strategy"].item() == "FS"]
    devices = [ds for ds in _spectra() if ds["strategy"].item() != "FS"]
    return calibration.device_table(fs, devices, LEVELS, 1.0)


def _candidates():
    device = {"kappa_max": 1.0, "kappa_min": 0.0, "damping_ratio": 0.05}
    return calibration.candidates_dataset(BLC06, [device], [_device_table()], [3.0], {"noise_reading": "default"})


def _p695(n=2):
    """The first ``n`` records of the FEMA P695 far-field set (the default study's record sets)."""
    return record_suites.load_suite("p695-far-field")[:n]


def _suite_fragility():
    return suite_fragility_dataset(BLC06, Anchorage(), [Control("FS"), Control("CS01")], _p695(),
                                   [1.0, 2.0, 4.0], suite="p695-far-field", n_boot=5, seed=2, resolution=0.1)


def _step(duration, dt=0.01):
    values = np.ones(int(round(duration / dt)) + 1)
    values[0] = values[-1] = 0.0
    return records.Record(f"step{duration:g}", dt, values)


def _block_point(R=0.5):
    return design.block_point(R, 0.2, Anchorage(), ["FS", "CS01"], [1.0, 2.0], amplitude_start=0.9,
                              amplitude_step=1.0, resolution=0.2, a_max0_g=1.0, records=[_step(1.0), _step(2.0)],
                              levels_g=design.pga_levels(0.1, 1.0, 4), suite="steps")


def _device_point(kappa_max=1.0):
    return design.device_point(BLC06, kappa_max, 0.05, ["FS", "CS01"], [_step(1.0), _step(2.0)],
                               design.pga_levels(0.1, 1.0, 4), suite="steps")


def _record_history(tmp_path):
    """``rockstudy simulate --record FILE --output``: a history under an earthquake record."""
    quake, _ = suite_record(0, seed=20190101)
    records.write_at2(quake, tmp_path / "quake.AT2")
    cli.main(["simulate", "--strategy", "CS01", "--record", str(tmp_path / "quake.AT2"), "--record-scale", "2",
              "--output", str(tmp_path / "record_history.nc")])
    return io.read_netcdf(tmp_path / "record_history.nc")


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
    "calibration device table": _device_table,
    "calibration candidates": _candidates,
    "record set": lambda: record_suites.suite_dataset(_p695(), title="Record set p695-far-field"),
    "fragility over a record set": _suite_fragility,
    "design block point": _block_point,
    "design device point": _device_point,
    "design blocks": lambda: design.gather_blocks([_block_point(0.5), _block_point(1.0)]),
    "design devices": lambda: design.gather_devices([_device_point(1.0), _device_point(2.0)]),
    "history under a record": _record_history,
}
"""One builder per kind of netCDF file: the workflow's (tiny and default study, calibration, readings,
records, design) and the CLI's; each is written through :func:`rockstudy.core.io.write_netcdf`."""


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_every_kind_of_file_passes_the_cf_checker(kind, tmp_path):
    build = KINDS[kind]
    ds = build(tmp_path) if kind == "history under a record" else build()
    path = io.write_netcdf(ds, tmp_path / "out.nc")
    assert high_priority_findings(path) == []
    with netCDF4.Dataset(path) as nc:
        attrs = nc.__dict__
        assert attrs["Conventions"] == CF_CONVENTIONS and PAPER in attrs["references"]
        assert __version__ in attrs["source"] and "rockstudy" in attrs["history"] and attrs["title"]
        for name, var in nc.variables.items():
            if name in nc.dimensions:  # a coordinate variable
                assert "_FillValue" not in var.ncattrs(), name
            if "flag_values" in var.ncattrs():  # CF 3.5: each flag value named, of the variable's own type
                values = np.atleast_1d(var.getncattr("flag_values"))
                assert len(var.getncattr("flag_meanings").split()) == values.size, name
                assert values.dtype == var.dtype, name
    assert units_problems(path) == []


def units_problems(path) -> list[str]:
    """Every ``units`` attribute of the netCDF file ``path`` that cf-units (UDUNITS-2) cannot parse, or reads
    as a mass: "g" is the gram there, not an acceleration."""
    import cf_units

    problems = []
    with netCDF4.Dataset(path) as nc:
        for name, var in nc.variables.items():
            if "units" not in var.ncattrs():
                continue
            units = var.getncattr("units")
            try:
                unit = cf_units.Unit(units)
            except ValueError as exc:
                problems.append(f"{name}: {units!r} does not parse ({exc})")
                continue
            if unit.is_convertible(cf_units.Unit("kg")):
                problems.append(f"{name}: {units!r} is a mass to UDUNITS")
    return problems


def test_units_problems_sees_a_gram_and_a_made_up_unit(tmp_path):
    """What the files wrote before: ``units = "g"`` for a PGA (a gram to UDUNITS); and a unit nobody reads."""
    ds = xr.Dataset({"pga": ("record", [0.3], {"units": "g"}), "x": ("record", [1.0], {"units": "metres per fish"})})
    found = units_problems(io.write_netcdf(ds, tmp_path / "old.nc"))
    assert len(found) == 2 and "'g' is a mass" in found[0] and "does not parse" in found[1]


def test_a_pga_in_standard_gravity_converts_to_metres_per_second_squared():
    import cf_units

    from rockstudy.model.records import STANDARD_GRAVITY, STANDARD_GRAVITY_UNITS, unit_label

    assert cf_units.Unit(STANDARD_GRAVITY_UNITS).convert(0.5, cf_units.Unit("m s-2")) == pytest.approx(
        0.5 * STANDARD_GRAVITY, rel=1e-15)
    assert unit_label(STANDARD_GRAVITY_UNITS) == "g" and unit_label("m/s") == "m/s"


def test_the_checker_sees_what_main_used_to_write(tmp_path):
    """The checker catches a NaN _FillValue on a coordinate, a repeated time and an elapsed-time axis
    named ``time`` in plain seconds (what the files had before), so the test above can fail."""
    ds = xr.Dataset({"theta": ("time", [0.0, 1.0, 2.0])},
                    coords={"time": ("time", [0.0, 1.0, 1.0], {"units": "s", "long_name": "time"})})
    ds.to_netcdf(tmp_path / "old.nc")
    found = "\n".join(high_priority_findings(tmp_path / "old.nc"))
    assert "strictly monotonic" in found and "_FillValue" in found
    assert "Coordinate variable 'time' should have standard_name='time'" in found
    with pytest.raises(ValueError, match="'time' is not strictly monotonic"):
        io.write_netcdf(ds, tmp_path / "new.nc")
    assert not (tmp_path / "new.nc").exists()
    # the same axis in plain seconds named t passes; named time, it does not (CF keeps that name for
    # calendar time, "seconds since <epoch>")
    for name, expected in (("t", []), ("time", ["standard_name='time'"])):
        axis = xr.Dataset({"theta": (name, [0.0, 1.0, 2.0], {"units": "rad", "long_name": "rotation"})},
                          coords={name: (name, [0.0, 1.0, 2.0], {"units": "s", "long_name": "elapsed time"})})
        found = high_priority_findings(io.write_netcdf(axis, tmp_path / f"{name}.nc"))
        assert len(found) == len(expected) and all(e in f for e, f in zip(expected, found)), found


def test_history_keeps_each_time_once_and_the_impacts_on_their_own_dimension(tmp_path):
    ds = KINDS["history"]()
    t = ds["t"].values
    assert np.all(np.diff(t) > 0) and ds.sizes["impact"] == ds.attrs["n_impacts"] > 10
    assert np.all(np.diff(ds["t_ground"].values) > 0) and "time" not in ds.dims and "ground_time" not in ds.dims
    # Eq. (15): an impact multiplies theta_dot by the restitution e, unless the rebound e|theta_dot-| is below
    # the rest velocity: then the block comes to rest (theta_dot+ = 0), as it does at the last impact
    before, after = ds["theta_dot_before_impact"].values, ds["theta_dot_after_impact"].values
    rests = BLC06.e * np.abs(before) < rest_velocity(BLC06.p, BLC06.alpha)
    np.testing.assert_allclose(after[~rests] / before[~rests], BLC06.e, rtol=1e-12)
    assert np.all(after[rests] == 0) and rests[-1] and ds.attrs["status"] == "rest"
    # the value on `t` at an impact is the one just after it
    at = np.searchsorted(t, ds["impact_time"].values)
    np.testing.assert_array_equal(ds["theta_dot"].values[at], ds["theta_dot_after_impact"].values)
    io.write_netcdf(ds, tmp_path / "h.nc")
    with xr.open_dataset(tmp_path / "h.nc") as back:  # xarray leaves t in seconds (no dates)
        near = back["theta"].sel(t=2.0, method="nearest")
        assert near.size == 1 and abs(float(near["t"]) - 2.0) <= np.max(np.diff(t))
        assert float(near) == ds["theta"].values[np.argmin(np.abs(t - 2.0))]
        for name in ("t", "t_ground"):
            assert back[name].dtype == np.float64 and back[name].attrs["units"] == "s"
            assert np.all(np.diff(back[name].values) > 0), name


@pytest.mark.parametrize("kind", ["noise", "synthetic suite", "history under a record"])
def test_other_files_with_a_time_axis_keep_it_in_seconds_on_t(kind, tmp_path):
    build = KINDS[kind]
    path = io.write_netcdf(build(tmp_path) if kind == "history under a record" else build(), tmp_path / "o.nc")
    with xr.open_dataset(path) as ds:
        assert "time" not in ds.dims and ds["t"].dtype == np.float64 and ds["t"].attrs["units"] == "s"
        assert np.all(np.diff(ds["t"].values) > 0)


def test_cf_attributes_keep_a_title_and_extend_a_history():
    attrs = io.cf_attributes({"title": "T", "history": "made by hand"})
    assert attrs["title"] == "T" and attrs["history"].splitlines()[0] == "made by hand"
    assert io.cf_attributes(attrs)["history"] == attrs["history"]  # rewriting a file adds no line
    assert io.cf_attributes({})["title"] and A_MAX0 > 0
