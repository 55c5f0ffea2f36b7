"""The optional `risk:` section of the workflow: checked on load, its targets in the DAG, and a small run whose
risk datasets hold what the library computes from the run's own fragility files."""
import math
import shutil

import numpy as np
import pytest
import yaml

from rockstudy.analysis.hazard import read_hazard_curve
from rockstudy.analysis.risk import LognormalFragility, annual_rate, fragility_from_dataset
from rockstudy.core import io
from rockstudy.core.risk_inputs import RISK_INPUTS, SCENARIO_INPUTS
from rockstudy.model.records import STANDARD_GRAVITY_UNITS
from workflow_runs import ROOT, TEST_CONFIG, dry_run, snakemake

needs_snakemake = pytest.mark.skipif(shutil.which("snakemake") is None, reason="snakemake is not installed")


def tiny_with_risk(tmp_path, hazard=True):
    config = yaml.safe_load(TEST_CONFIG.read_text())
    default = yaml.safe_load((ROOT / "config.yaml").read_text())
    config["beyond"] = default["beyond"]
    config["risk"] = default["risk"]
    if hazard:
        x = np.geomspace(0.001, 20.0, 200)
        path = tmp_path / "site.txt"
        path.write_text("# PGA [g], annual rate of exceedance [1/yr]\n"
                        + "".join(f"{float(a)!r} {float(1e-4 * a ** -2.5)!r}\n" for a in x))
        config["risk"]["hazard_curves"] = {"site": str(path), "bay": str(ROOT / "tests" / "data" / "hazard" /
                                                                          "openquake-hazard_curve-mean_PGA.csv")}
    return config


def test_the_schemas_risk_section_takes_the_librarys_bounds():
    schema = yaml.safe_load((ROOT / "workflow" / "schemas" / "config.schema.yaml").read_text())
    defs = schema["$defs"]
    assert defs["Risk"]["properties"]["years"]["maximum"] == RISK_INPUTS["years"].high
    for key, bound in SCENARIO_INPUTS.items():
        declared = defs["Scenario"]["properties"][key]
        declared = declared.get("anyOf", [declared])[0]
        assert declared["minimum"] == bound.low and declared["maximum"] == bound.high, key


@needs_snakemake
def test_risk_targets_are_in_the_dag(tmp_path):
    res = dry_run(tiny_with_risk(tmp_path), tmp_path, "risk")
    assert res.returncode == 0, res.stderr + res.stdout
    for name in ("p695-far-field", "p695-near-field-pulse"):
        for path in (f"risk/{name}.nc", f"tables/risk_{name}.md", f"figures/risk_{name}.png",
                     f"figures/risk_sites_{name}.png"):
            assert path in res.stdout
    res = dry_run(tiny_with_risk(tmp_path), tmp_path)  # `all`: the report's pages of the risk tables too
    assert res.returncode == 0, res.stderr + res.stdout
    for name in ("p695-far-field", "p695-near-field-pulse"):
        assert f"tables/risk_{name}.html" in res.stdout


@needs_snakemake
@pytest.mark.parametrize("change, words", [
    (lambda r: r["scenarios"]["M7_R10"].update(mag=9.5), ["mag"]),
    (lambda r: r["scenarios"]["M7_R10"].pop("v_s30"), ["v_s30"]),
    (lambda r: r["hazard_curves"].update(site="nowhere.txt"), ["risk.hazard_curves.site", "does not exist"]),
    (lambda r: r["scenarios"]["M7_R10"].update(v_s30=150.0), ["M7_R10", "v_s30 = 150", "ASK14"]),
    (lambda r: r.update(hazard_units={"other": "g"}), ["risk.hazard_units", "other"]),
])
def test_a_bad_risk_section_is_refused_on_load(tmp_path, change, words):
    config = tiny_with_risk(tmp_path)
    change(config["risk"])
    res = dry_run(config, tmp_path, "risk")
    assert res.returncode != 0 and all(w in res.stderr + res.stdout for w in words), res.stderr


@needs_snakemake
def test_a_small_risk_study(tmp_path):
    """Two far-field records on coarse stripes: the risk dataset's rates are the library's from the run's own
    fragility file, and its scenario echo holds the defaults."""
    config = tiny_with_risk(tmp_path)
    frag = config["beyond"]["fragility"]
    frag.update(records=["p695-far-field:1a", "p695-far-field:2a"], strategies=["FS", "CS01"], bootstrap=5,
                intensity_levels={"start": 0.5, "stop": 6.0, "step": 0.5}, threshold_resolution=0.1)
    path = tmp_path / "config.yaml"
    path.write_text(yaml.safe_dump(config))
    res = snakemake("-j1", "--configfile", str(path), "--replace-workflow-config", "risk", workdir=tmp_path)
    assert res.returncode == 0, res.stderr[-3000:]
    out = tmp_path / "results"
    risk = io.read_netcdf(out / "risk" / "selection.nc")
    fragility = io.read_netcdf(out / "fragility" / "selection.nc")
    curve = read_hazard_curve(config["risk"]["hazard_curves"]["site"])
    for s in ("FS", "CS01"):
        f = fragility_from_dataset(fragility, s)
        expected = annual_rate(LognormalFragility(f.median_g, f.dispersion), curve, warn=False).annual_rate
        # the same integral, its pieces also cut at the disaggregation's band edges: equal to rounding
        assert float(risk.annual_rate.sel(strategy=s, hazard="site")) == pytest.approx(expected, rel=1e-12)
        p = float(risk.probability.sel(strategy=s, hazard="site"))
        assert p == pytest.approx(-math.expm1(-50 * expected), rel=1e-12)
    assert float(risk.reduction_percent.sel(strategy="FS", hazard="site")) == 0.0
    # every site of the OpenQuake file, with its coordinates, and the map of them
    bay = [h for h in risk.hazard.values if str(h).startswith("bay/")]
    assert len(bay) == 4 and float(risk.lon.sel(hazard=bay[0])) == -122.34
    assert np.all((risk.probability.sel(hazard=bay).values >= 0) & (risk.probability.sel(hazard=bay).values <= 1))
    assert (out / "figures" / "risk_sites_selection.png").stat().st_size > 0
    assert '"dip": 90.0' in str(risk.scenario_values.values[0])
    assert risk.median_pga.attrs["units"] == STANDARD_GRAVITY_UNITS
    for name in ("tables/risk_selection.md", "figures/risk_selection.png"):  # its HTML page: report_pages
        assert (out / name).stat().st_size > 0
    assert "stripes' lognormal fit" in (out / "tables" / "risk_selection.md").read_text()
