"""SimulationResult and the Outcome codes shared by the engine, the scan and the datasets."""
import math

import numpy as np
import pytest

from rockstudy import BLOCK_PRESETS, Anchorage, Control
from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, spectrum
from rockstudy.engine import _kernel as kn
from rockstudy.engine.outcome import OUTCOME_MEANINGS, Outcome
from rockstudy.engine.simulate import pack_parameters
from rockstudy.engine.simulation_result import SimulationResult
from rockstudy.model.excitation import modulated_peak

BLC06 = BLOCK_PRESETS["BLC06"]


def test_result_summary_and_impact_mode():
    r = SimulationResult("overturned", True, 1.5, 1.5, 2.0, impact_times=np.array([0.3, 0.9]), engine="fast")
    assert r.n_impacts == 2 and r.overturned_with_impact
    s = r.summary()
    assert s["overturn_time_s"] == 1.5 and s["impact_times_s"] == [0.3, 0.9] and s["n_impacts"] == 2
    quiet = SimulationResult("rest", False, math.nan, 0.0, 0.0)
    assert quiet.summary()["overturn_time_s"] is None and not quiet.overturned_with_impact


def test_outcome_codes_and_meanings_are_one_list():
    assert [int(o) for o in Outcome] == list(range(5))
    assert OUTCOME_MEANINGS == ("no_uplift", "safe", "overturned_without_impact", "overturned_after_impact",
                                "undetermined")
    assert [o.overturned for o in Outcome] == [False, False, True, True, False]


def test_kernel_dataset_and_enum_agree_on_every_outcome():
    """The kernel's ints, the dataset's flag_values/flag_meanings and the enum name the same outcomes."""
    sc = Scenario(BLC06, Anchorage(), Control("FS"))
    grid = AmplitudeGrid(0.5, 6.0, 0.5, 0.5)
    ds = spectrum(sc, [2.0], grid=grid, with_map=True)
    out = ds["outcome"]
    assert out.attrs["flag_values"].tolist() == [int(o) for o in Outcome]
    assert out.attrs["flag_meanings"].split() == [o.meaning for o in Outcome]
    codes = out.values[0, 0]
    amplitudes = ds["amplitude_ratio"].values
    peak = modulated_peak()  # noise-free Eq. 23 with a_p = 1
    # below the uplift acceleration the scan does not simulate: NO_UPLIFT
    assert (codes[amplitudes * peak <= 1.0] == Outcome.NO_UPLIFT).all()
    assert (codes[amplitudes * peak > 1.0] != Outcome.NO_UPLIFT).all()
    # the scan's threshold is the first overturning grid point's bracket, and the map agrees
    first = amplitudes[np.isin(codes, [Outcome.OVERTURNED_WITHOUT_IMPACT, Outcome.OVERTURNED_AFTER_IMPACT])][0]
    assert float(ds.threshold.values[0]) <= first
    # the kernel returns exactly these codes for one run each
    motion, _ = sc.motion(2.0, 1.0)
    P = pack_parameters(BLC06, Anchorage(), Control("FS"), motion)
    for a, code in zip(amplitudes, codes):
        assert kn.outcome_kernel(P, motion.record, motion.vertical, a, peak) == code


@pytest.mark.parametrize("amplitude_ratio,outcome", [(0.9, Outcome.NO_UPLIFT), (1.05, Outcome.SAFE)])
def test_kernel_outcome_codes_below_the_threshold(amplitude_ratio, outcome):
    sc = Scenario(BLC06, Anchorage(), Control("CS01"))
    motion, _ = sc.motion(2.0, 1.0)
    P = pack_parameters(BLC06, Anchorage(), Control("CS01"), motion)
    assert kn.outcome_kernel(P, motion.record, motion.vertical, amplitude_ratio, 1.0011) == outcome


def test_public_api_at_the_top():
    import rockstudy
    assert callable(rockstudy.simulate) and callable(rockstudy.threshold) and callable(rockstudy.spectrum)
    assert rockstudy.Scenario is Scenario and rockstudy.Outcome is Outcome
