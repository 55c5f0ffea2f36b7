"""Scenario PGA from the NGA-West2 models: the same numbers as pygmm for the same scenario, every value
used echoed, and P(overturn | scenario) by Eq. R3."""
import math

import pytest
from scipy import stats

from rockstudy.analysis import ground_motion
from rockstudy.analysis.risk import LognormalFragility, scenario_risk
from rockstudy.core.risk_inputs import GMMS

pygmm = pytest.importorskip("pygmm")


@pytest.mark.parametrize("gmm", sorted(GMMS))
def test_median_and_sigma_equal_pygmms(gmm):
    scenario = {"mag": 6.5, "dist_rup": 20.0, "v_s30": 360.0}
    median, sigma, used = ground_motion.pga(scenario, gmm)
    # pygmm called directly with the same scenario (a vertical strike-slip rupture, the site off its end)
    model = getattr(pygmm, GMMS[gmm])(pygmm.Scenario(mag=6.5, dist_rup=20.0, dist_jb=20.0, dist_x=20.0, v_s30=360.0,
                                                     mechanism="SS", dip=90.0, depth_tor=0.0))
    assert median == model.pga and sigma == model.ln_std_pga
    assert used["mag"] == 6.5 and used["v_s30"] == 360.0 and used["mechanism"] == "SS"
    assert "region" in used  # pygmm's own default, echoed


def test_scenario_risk_echoes_defaults_and_applies_eq_r3():
    fragility = LognormalFragility(0.5, 0.4)
    risk = scenario_risk(fragility, {"mag": 7, "dist_rup": 10, "v_s30": 400})
    assert risk.gmm == "ASK14"
    for key, value in {"mag": 7.0, "dist_rup": 10.0, "dist_jb": 10.0, "dist_x": 10.0, "v_s30": 400.0, "dip": 90.0,
                       "mechanism": "SS", "region": "global"}.items():
        assert risk.scenario[key] == value, key
    expected = stats.norm.cdf(math.log(risk.median_pga_g / 0.5) / math.hypot(0.4, risk.ln_std))
    assert risk.probability == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("scenario, words", [
    ({"mag": 7, "dist_rup": 10}, ["missing v_s30"]),
    ({"mag": 7, "dist_rup": 10, "v_s30": 400, "depth": 3}, ["unknown key", "depth"]),
    ({"mag": 9.5, "dist_rup": 10, "v_s30": 400}, ["scenario.mag"]),
    ({"mag": 7, "dist_rup": 10, "v_s30": 400, "mechanism": "XX"}, ["mechanism"]),
])
def test_bad_scenarios_are_refused(scenario, words):
    with pytest.raises(ValueError) as err:
        ground_motion.pga(scenario)
    assert all(w in str(err.value) for w in words)
    with pytest.raises(ValueError, match="gmm"):
        ground_motion.pga({"mag": 7, "dist_rup": 10, "v_s30": 400}, "XYZ14")


@pytest.mark.parametrize("gmm, scenario, words", [
    ("CY14", {"mag": 3.0, "dist_rup": 10, "v_s30": 400}, ["mag = 3", "CY14's range 3.5 to 8.5"]),
    ("ASK14", {"mag": 7.0, "dist_rup": 10, "v_s30": 150}, ["v_s30 = 150", "ASK14's range 180 to 1000"]),
    ("CB14", {"mag": 8.2, "dist_rup": 10, "v_s30": 400, "mechanism": "NS"}, ["exceeds CB14's 7.5"]),
])
def test_a_scenario_outside_its_models_range_is_refused_or_warned(gmm, scenario, words):
    with pytest.raises(ValueError) as err:
        ground_motion.pga(scenario, gmm)
    assert all(w in str(err.value) for w in words), str(err.value)
    with pytest.warns(ground_motion.GmmRangeWarning):
        risk = scenario_risk(LognormalFragility(0.5, 0.4), scenario, gmm, outside_range=True)
    assert risk.warnings and all(w in " ".join(risk.warnings) for w in words)
    assert 0.0 <= risk.probability <= 1.0


@pytest.mark.parametrize("scenario, words", [
    ({"mag": 7, "dist_rup": 10, "dist_jb": 12, "v_s30": 400}, ["dist_jb = 12", "exceeds dist_rup"]),
    ({"mag": 7, "dist_rup": 2, "v_s30": 400, "depth_tor": 5, "dist_jb": 0}, ["depth_tor = 5"]),
    ({"mag": 7, "dist_rup": 10, "v_s30": 400, "dist_x": -20}, ["|dist_x| = 20"]),
])
def test_inconsistent_scenarios_are_refused(scenario, words):
    with pytest.raises(ValueError) as err:
        ground_motion.check_scenario(scenario)
    assert all(w in str(err.value) for w in words), str(err.value)
