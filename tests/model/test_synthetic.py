"""Synthetic records: Kanai-Tajimi-Clough-Penzien filtered noise with the Saragoni-Hart envelope."""
import math

import numpy as np
import pytest
from scipy import signal

from rockstudy.model.synthetic import (
    GroundMotionModel,
    SuiteRanges,
    envelope,
    filtered_noise,
    record_generator,
    spectral_density_shape,
    suite_record,
    synthetic_suite,
)


def test_envelope_is_saragoni_hart_with_peak_one_at_peak_time():
    t = np.linspace(0, 20, 2001)
    b, tm = 2.0, 4.0
    # a t^b exp(-c t) with c = b/t_m and a = (e/t_m)^b ... normalised to 1 at t_m
    a, c = (math.e / tm) ** b, b / tm
    np.testing.assert_allclose(envelope(t, tm, b), a * t**b * np.exp(-c * t), rtol=1e-12)
    assert envelope(tm, tm, b) == pytest.approx(1.0) and t[np.argmax(envelope(t, tm, b))] == pytest.approx(tm)
    assert envelope(-1.0, tm, b) == 0.0


def test_stationary_noise_has_the_model_spectrum():
    """Welch estimate of the filtered noise against S(w)/S0, both normalised over 0.3-20 Hz."""
    model = GroundMotionModel(ground_frequency=2 * math.pi * 2.5, ground_damping=0.5,
                              filter_frequency=2 * math.pi * 0.25, filter_damping=0.5, dt=0.01)
    x = filtered_noise(2**18, model.dt, model, np.random.default_rng(3))
    f, pxx = signal.welch(x, fs=1 / model.dt, nperseg=1024)
    band = (f >= 0.3) & (f <= 20)
    target = spectral_density_shape(2 * math.pi * f, model)
    ratio = (pxx[band] / pxx[band].sum()) / (target[band] / target[band].sum())
    assert np.all(np.abs(ratio - 1) < 0.25)  # each Welch bin (about 500 averages): a few % scatter
    assert abs(np.median(ratio) - 1) < 0.03
    peak = f[band][np.argmax(pxx[band])]
    assert abs(peak - f[band][np.argmax(target[band])]) < 0.3


def test_spectral_shape_limits():
    """Kanai-Tajimi: 1 at w = 0 and (1 + 4 zeta^2)/(4 zeta^2) at w_g; Clough-Penzien: ~ w^4 at low w."""
    m = GroundMotionModel(ground_frequency=10.0, ground_damping=0.5, filter_frequency=1.0, filter_damping=0.5)
    kt_at_wg = (1 + 4 * 0.25) / (4 * 0.25)
    cp_at_wg = 1e4 / ((1 - 100) ** 2 + 4 * 0.25 * 100)
    assert spectral_density_shape(10.0, m) == pytest.approx(kt_at_wg * cp_at_wg)
    low = spectral_density_shape(np.array([1e-3, 2e-3]), m)
    assert low[1] / low[0] == pytest.approx(16, rel=1e-3)


def test_records_are_keyed_by_index_and_seed():
    suite = synthetic_suite(4, 11)
    alone, model = suite_record(2, 11)
    np.testing.assert_array_equal(alone.acceleration, suite[2][0].acceleration)
    assert model == suite[2][1] and alone.name == "SYN002"
    other, _ = suite_record(2, 12)
    assert not np.allclose(other.acceleration, alone.acceleration)
    assert not np.allclose(suite[1][0].acceleration[:100], suite[2][0].acceleration[:100])
    with pytest.raises(ValueError, match="index must be an integer"):
        record_generator(1, -1)


def test_suite_records_have_the_stated_pga_length_and_parameter_ranges():
    ranges = SuiteRanges(ground_frequency_hz=(2.0, 3.0), ground_damping=(0.4, 0.5), peak_time=(3.0, 4.0),
                         duration=15.0, dt=0.005, pga=2.0)
    for rec, model in synthetic_suite(5, 1, ranges):
        assert rec.pga == pytest.approx(2.0) and rec.dt == 0.005 and rec.acceleration.size == 3001
        assert rec.acceleration[0] == 0.0  # the envelope starts at zero
        assert 2.0 <= model.ground_frequency / (2 * math.pi) <= 3.0 and 0.4 <= model.ground_damping <= 0.5
        assert model.filter_frequency == pytest.approx(0.1 * model.ground_frequency)
        assert 3.0 <= model.peak_time <= 4.0


@pytest.mark.parametrize("kwargs, words", [
    ({"ground_damping": -0.1}, "ground_damping"),
    ({"filter_frequency": 20.0, "ground_frequency": 10.0}, "filter_frequency"),
    ({"peak_time": 30.0}, "peak_time"),
    ({"dt": 0.2}, "dt"),
])
def test_model_validation_names_the_field(kwargs, words):
    with pytest.raises(ValueError, match=words):
        GroundMotionModel(**kwargs)
    with pytest.raises(ValueError, match="ground_frequency_hz"):
        SuiteRanges(ground_frequency_hz=(3.0, 2.0))
