"""``rockstudy fragility`` and ``rockstudy risk``: the same numbers as the workflow and the library, the
closed forms through the command line, and bad input refused with exit status 2 and a message."""
import json
import math

import numpy as np
import pytest
import yaml

from rockstudy.analysis.fragility import SUITE_DEFAULTS, suite_fragility_dataset, suite_summary
from rockstudy.cli import main
from rockstudy.core import io
from rockstudy.model import record_suites
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import BLOCK_PRESETS
from rockstudy.model.control import Control
from rockstudy.studies import parameters
from test_docs import ROOT

K0, K = 1e-4, 2.5


def run(args, capsys):
    assert main(args) == 0
    return json.loads(capsys.readouterr().out)


def refused(args, capsys, *words):
    with pytest.raises(SystemExit) as exit_:
        main(args)
    err = capsys.readouterr().err
    assert exit_.value.code == 2 and all(w in err for w in words), err


@pytest.fixture
def hazard_file(tmp_path):
    """A power-law hazard λ = k0 x^-k at 200 points from 0.001 to 20 g."""
    x = np.geomspace(0.001, 20.0, 200)
    path = tmp_path / "site.txt"
    path.write_text("# PGA [g], annual rate of exceedance [1/yr]\n"
                    + "".join(f"{float(a)!r}, {float(K0 * a ** -K)!r}\n" for a in x))
    return str(path)


def test_fragility_defaults_are_the_studys():
    frag = yaml.safe_load((ROOT / "config.yaml").read_text())["beyond"]["fragility"]
    for key, value in SUITE_DEFAULTS.items():
        assert frag[key] == value, key


def test_fragility_equals_the_workflows_summary(tmp_path, capsys):
    """Two far-field records on coarse stripes: the command line's median and dispersion of CS01 are the
    workflow's (the record set written and read back as its rules do, every strategy run together)."""
    levels = {"start": 1.0, "stop": 4.0, "step": 1.0}
    out = run(["fragility", "--strategy", "CS01", "--suite", "p695-far-field", "--max-records", "2",
               "--levels-start", "1", "--levels-stop", "4", "--levels-step", "1", "--threshold-resolution", "0.1",
               "--bootstrap", "5", "--output", str(tmp_path / "f.nc")], capsys)
    io.write_netcdf(record_suites.suite_dataset(record_suites.load_suite("p695-far-field")[:2]), tmp_path / "r.nc")
    entries = record_suites.entries_from_dataset(io.read_netcdf(tmp_path / "r.nc"))
    scenario = parameters.scenario_from_dict({"block": {"preset": "BLC06"}, "anchorage": {}, "control": {}})
    ds = suite_fragility_dataset(scenario.block, scenario.anchorage, [Control(s) for s in ("FS", "CS01", "CS02")],
                                 entries, parameters.intensity_levels(levels), suite="p695-far-field",
                                 resolution=0.1, n_boot=5, seed=SUITE_DEFAULTS["seed"])
    (row,) = [r for r in suite_summary([ds]) if r["strategy"] == "CS01"]
    assert out["median_g"] == row["median_physical"] and out["dispersion"] == row["dispersion"]
    assert out["n_records"] == 2 and out["fit"] == row["fit"]
    assert math.isfinite(out["median_g"])
    written = io.read_netcdf(tmp_path / "f.nc")
    assert list(written.strategy.values) == ["FS", "CS01"]


def test_risk_from_a_hazard_curve_is_cornells(hazard_file, capsys):
    out = run(["risk", "--median", "0.6", "--dispersion", "0.4", "--hazard", hazard_file, "--years", "50"], capsys)
    expected = K0 * 0.6 ** -K * math.exp(0.5 * (K * 0.4) ** 2)
    assert out["annual_rate"] == pytest.approx(expected, rel=0.01)
    assert out["probability"] == pytest.approx(1 - math.exp(-50 * out["annual_rate"]), rel=1e-12)
    assert out["tail_share"] < 0.01 and out["extension"] == "loglog"
    out = run(["risk", "--median", "0.6", "--dispersion", "0.4", "--hazard", hazard_file, "--bands", "0.3,0.6,1.2"],
              capsys)
    assert len(out["disaggregation"]) == 4 and sum(b["share"] for b in out["disaggregation"]) == pytest.approx(1)


def test_risk_from_a_fragility_file(tmp_path, hazard_file, capsys):
    ds = suite_fragility_dataset(BLOCK_PRESETS["BLC06"], Anchorage(), [Control("FS"), Control("CS01")],
                                 record_suites.load_suite("p695-far-field")[:3], np.arange(1.0, 5.01, 0.5),
                                 suite="p695-far-field", resolution=0.1, n_boot=0)
    io.write_netcdf(ds, tmp_path / "f.nc")
    from_file = run(["risk", "--fragility", str(tmp_path / "f.nc"), "--strategy", "FS", "--hazard", hazard_file],
                    capsys)
    median, beta = float(ds.fragility_median_physical.sel(strategy="FS")), float(ds.fragility_dispersion.sel(
        strategy="FS"))
    by_hand = run(["risk", "--median", repr(median), "--dispersion", repr(beta), "--hazard", hazard_file], capsys)
    assert from_file["annual_rate"] == by_hand["annual_rate"] and from_file["strategy"] == "FS"


def test_risk_for_a_scenario(capsys):
    pygmm = pytest.importorskip("pygmm")
    out = run(["risk", "--median", "0.5", "--dispersion", "0.4", "--scenario", "mag=7,dist_rup=10,v_s30=400"], capsys)
    model = pygmm.AbrahamsonSilvaKamai2014(pygmm.Scenario(mag=7, dist_rup=10, dist_jb=10, dist_x=10, v_s30=400,
                                                          mechanism="SS", dip=90, depth_tor=0))
    assert out["gmm"] == "ASK14" and out["median_pga_g"] == model.pga and out["ln_std"] == model.ln_std_pga
    assert out["scenario"]["dip"] == 90 and out["scenario"]["mechanism"] == "SS"
    p = 0.5 * math.erfc(-math.log(model.pga / 0.5) / math.hypot(0.4, model.ln_std_pga) / math.sqrt(2))
    assert out["probability"] == pytest.approx(p, rel=1e-12)


def test_target_median_is_the_closed_form(tmp_path, hazard_file, capsys):
    out = run(["risk", "--dispersion", "0.4", "--hazard", hazard_file, "--target-probability", "0.01", "--years",
               "50"], capsys)
    rate = -math.log(0.99) / 50
    assert out["target_rate"] == pytest.approx(rate, rel=1e-12)
    assert out["median_g"] == pytest.approx((K0 * math.exp(0.5 * (K * 0.4) ** 2) / rate) ** (1 / K), rel=0.01)
    import xarray as xr
    devices = xr.Dataset({"fragility_median": (("strategy", "kappa_max", "damping_ratio"), [[[0.1], [9.0]]],
                                               {"units": "g"})},
                         coords={"strategy": ["CS01"], "kappa_max": [1.0, 2.0], "damping_ratio": [0.05]})
    io.write_netcdf(devices, tmp_path / "devices.nc")
    out = run(["risk", "--dispersion", "0.4", "--hazard", hazard_file, "--target-rate", "1e-3", "--devices",
               str(tmp_path / "devices.nc")], capsys)
    assert [d["meets"] for d in out["devices"]] == [False, True]


def test_bad_risk_input_is_refused(tmp_path, hazard_file, capsys):
    bad = tmp_path / "bad.txt"
    bad.write_text("0.1, 1e-2\n0.2, 2e-2\n")
    refused(["risk", "--median", "0.5", "--dispersion", "0.4", "--hazard", str(bad)], capsys, "line 2", "rises above")
    refused(["risk", "--median", "0.5", "--hazard", hazard_file], capsys, "--dispersion")
    refused(["risk", "--median", "0.5", "--dispersion", "0.4"], capsys, "--hazard")
    refused(["risk", "--median", "0.5", "--dispersion", "0.4", "--scenario", "mag=7,dist_rup"], capsys, "KEY=VALUE")
    refused(["risk", "--median", "0.5", "--dispersion", "9", "--hazard", hazard_file], capsys, "--dispersion")
    refused(["risk", "--dispersion", "0.4", "--hazard", hazard_file, "--target-probability", "1.5"], capsys,
            "--target-probability")


DATA = ROOT / "tests" / "data" / "hazard"


def test_risk_at_every_site_of_a_real_file(capsys):
    """An nshmp-haz curves file of 7 sites: one entry each, with name, lon and lat; a step fragility at a level
    of the curve gives that level's rate (Oakland: 1.28698458e-03 /yr at 0.103 g)."""
    out = run(["risk", "--median", "0.103", "--dispersion", "0", "--hazard", str(DATA / "nshmp-haz" / "PGA" /
                                                                                 "total.csv")], capsys)
    assert len(out["sites"]) == 7 and out["median_g"] == 0.103
    (oakland,) = [s for s in out["sites"] if s["name"] == "Oakland CA"]
    assert (oakland["lon"], oakland["lat"]) == (-122.25, 37.8)
    assert oakland["annual_rate"] == pytest.approx(1.28698458e-03, rel=1e-12)
    one = run(["risk", "--median", "0.3", "--dispersion", "0.4", "--hazard", str(DATA / "usgs-hazard-tool-curve.json")],
              capsys)
    assert "sites" not in one and (one["lon"], one["lat"]) == (-118.0, 34.0) and 0 <= one["probability"] <= 1


def test_a_curve_in_m_per_s2_is_refused_unless_its_unit_is_stated(tmp_path, capsys):
    levels = np.array([0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 3.0])
    rates = np.array([1.2e-1, 4e-2, 1.5e-2, 4e-3, 4.5e-4, 5e-5, 4e-6, 6e-7])
    path = tmp_path / "ms2.txt"
    path.write_text("".join(f"{float(x * 9.80665)!r} {float(r)!r}\n" for x, r in zip(levels, rates)))
    refused(["risk", "--median", "0.5", "--dispersion", "0.4", "--hazard", str(path)], capsys, "--hazard",
            "state it")
    stated = run(["risk", "--median", "0.5", "--dispersion", "0.4", "--hazard", str(path), "--hazard-unit", "m/s2"],
                 capsys)
    path.write_text("".join(f"{float(x)!r} {float(r)!r}\n" for x, r in zip(levels, rates)))
    in_g = run(["risk", "--median", "0.5", "--dispersion", "0.4", "--hazard", str(path)], capsys)
    assert stated["annual_rate"] == pytest.approx(in_g["annual_rate"], rel=1e-12)


def test_a_target_beyond_the_curve_is_refused_or_flagged(tmp_path, capsys):
    path = tmp_path / "short.txt"
    path.write_text("# PGA [g], annual rate [1/yr]\n0.001 1e-2\n0.002 3e-3\n0.005 5e-4\n")
    refused(["risk", "--dispersion", "0.4", "--hazard", str(path), "--target-rate", "1e-6"], capsys,
            "decades beyond")
    out = run(["risk", "--dispersion", "0.4", "--hazard", str(path), "--target-rate", "1e-6",
               "--allow-extrapolation"], capsys)
    assert out["extrapolated"] is True and out["decades_outside_curve"] > 1


def test_no_nan_or_infinity_leaves(hazard_file, capsys):
    refused(["risk", "--median", "1e-300", "--dispersion", "0.4", "--hazard", hazard_file], capsys, "median 1e-300")
    out = run(["risk", "--median", "0.6", "--dispersion", "1e-300", "--hazard", hazard_file], capsys)
    assert out["annual_rate"] == pytest.approx(K0 * 0.6 ** -K, rel=1e-6)  # the step's λ_IM(θ)


def test_a_scenario_outside_the_models_range(capsys):
    pytest.importorskip("pygmm")
    refused(["risk", "--median", "0.5", "--dispersion", "0.4", "--scenario", "mag=3,dist_rup=10,v_s30=400", "--gmm",
             "CY14"], capsys, "mag = 3", "CY14")
    out = run(["risk", "--median", "0.5", "--dispersion", "0.4", "--scenario", "mag=3,dist_rup=10,v_s30=400", "--gmm",
               "CY14", "--outside-gmm-range"], capsys)
    assert any("CY14's range" in w for w in out["warnings"])
