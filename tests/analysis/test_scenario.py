"""A scenario's one way in: a run at an amplitude and realisation, a run under any motion, and the case the
fast engine's scans read, each the engine's own call with the scenario's settings; its defaults are the
study's."""
import numpy as np
import pytest

from rockstudy.analysis.scenario import Scenario
from rockstudy.engine.simulate import kernel_record, pack_parameters, simulate
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.control import Control
from rockstudy.model.noise import DEFAULT_READING, DEFAULT_SEED


def test_defaults_are_the_study_settings(blc06):
    sc = Scenario(blc06)
    assert sc.seed == DEFAULT_SEED == 20190101
    assert sc.noise == DEFAULT_READING and sc.noise.rescale == "energy" and sc.noise.step == 0.0025
    assert (sc.excitation, sc.overturn_criterion, sc.free_time) == ("modulated", "flat", 30.0)


@pytest.mark.parametrize("noise_level", [0.0, 0.05])
def test_simulate_is_the_engine_run_with_the_scenario_settings(blc06, noise_level):
    sc = Scenario(blc06, Anchorage(kappa_max=2.0), Control("CS02", sampling_time=0.01), noise_level=noise_level,
                  overturn_criterion="alpha", free_time=5.0)
    run = sc.simulate(2.0, 1.3, 1, record_history=True)
    motion, rec = sc.motion(2.0, 1.3, 1)
    direct = simulate(blc06, sc.anchorage, sc.control, motion, overturn_criterion="alpha", free_time=5.0,
                      record_history=True)
    assert np.array_equal(run.result.history["theta"], direct.history["theta"])
    assert run.result.status == direct.status
    assert (run.record is None) == (noise_level == 0)
    if rec is not None:
        assert np.array_equal(run.record.values, rec.values)


def test_kernel_case_is_what_the_scans_pack(blc06):
    sc = Scenario(blc06, control=Control("CS01"), noise_level=0.05, free_time=5.0)
    case = sc.kernel_case(2.0, 3, energy_bound=True)
    motion, rec = sc.motion(2.0, 1.0, 3)
    expected = pack_parameters(blc06, sc.anchorage, sc.control, motion, free_time=5.0, energy_bound=True)
    assert np.array_equal(case.parameters, expected)
    assert np.array_equal(case.samples, kernel_record(sc.control, motion))
    assert case.peak == float(np.max(np.abs(rec.values))) == sc.unit_peak(2.0, 3)
    assert (case.energy_ratio, case.pga_ratio) == (rec.energy_ratio, rec.pga_ratio)
    free = Scenario(blc06).kernel_case(2.0)
    assert (free.energy_ratio, free.pga_ratio) == (1.0, 1.0)
