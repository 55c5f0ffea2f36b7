"""The fast engine against the scipy reference engine (they agree within 0.5 %)."""
import pytest

from rockstudy import Anchorage, Control
from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, threshold

# strategy, excitation, omega_p/p, noise level, T_s: a spread over the model's branches
CASES = [
    ("FS", "modulated", 2.0, 0.0, 0.0),
    ("PASSIVE", "modulated", 1.5, 0.0, 0.0),
    ("PASSIVE", "one-sine", 3.0, 0.0, 0.0),  # grazing: the apex just passes theta_u = alpha
    ("CS01", "modulated", 2.0, 0.0, 0.0),
    ("CS02", "modulated", 2.0, 0.0, 0.0),
    ("CS01", "modulated", 2.0, 0.05, 0.1),
    ("CS02", "one-sine", 2.5, 0.01, 0.0),
]
# the same with the controller reading Ẍg through a sensor (rockstudy.model.sensor): band [Hz] last
SENSOR_CASES = [
    ("CS02", "modulated", 2.0, 0.0, 0.0, 5.0),
    ("CS02", "modulated", 2.0, 0.05, 0.0, 10.0),
    ("CS02", "modulated", 1.2, 0.10, 0.1, 5.0),
]


@pytest.mark.slow
@pytest.mark.parametrize("strategy,excitation,frequency_ratio,noise,ts,band",
                         [case + (None,) for case in CASES] + SENSOR_CASES)
def test_minimum_overturning_amplitude_agrees(blc06, strategy, excitation, frequency_ratio, noise, ts, band):
    sc = Scenario(blc06, Anchorage(), Control(strategy, sampling_time=ts, sensor_band=band), excitation=excitation,
                  noise_level=noise, seed=5)
    fast = threshold(sc, frequency_ratio, grid=AmplitudeGrid(0.9, 6.0, 0.1, 0.005))
    assert fast["amplitude_ratio"] is not None
    a = fast["amplitude_ratio"]
    # the reference scans a narrow window around it (it is ~500x slower); the window's lower edge
    # must be safe for the reference too, or the two disagree
    grid = AmplitudeGrid(round(a - 0.05, 4), round(a + 0.2, 4), 0.025, 0.005)
    ref = threshold(sc, frequency_ratio, grid=grid, engine="reference")
    assert ref["amplitude_ratio"] is not None
    assert ref["amplitude_ratio"] == pytest.approx(a, rel=0.005)
