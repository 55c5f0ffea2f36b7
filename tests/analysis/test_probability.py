"""Probability of overturning over noise realisations (Eq. P1)."""
import numpy as np
import pytest
import xarray as xr

from rockstudy import Control
from rockstudy.analysis.probability import lowest_positive_amplitude, probability_from_outcomes, probability_surface
from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, spectrum


def _fake_spectrum(outcome):
    outcome = np.asarray(outcome, dtype=np.int8)
    n_k, n_f, n_a = outcome.shape
    return xr.Dataset({"outcome": (("realisation", "frequency_ratio", "amplitude_ratio"), outcome),
                       "threshold": ("frequency_ratio", np.full(n_f, np.nan)),
                       "threshold_mean": ("frequency_ratio", np.full(n_f, np.nan))},
                      coords={"realisation": np.arange(n_k), "frequency_ratio": np.arange(1.0, n_f + 1),
                              "amplitude_ratio": 1.0 + 0.5 * np.arange(n_a)})


def test_hand_worked_counts():
    # 4 realisations, 1 frequency, 3 amplitudes; codes: 0 no uplift, 1 safe, 2/3 overturned, 4 undetermined
    ds = _fake_spectrum([[[0, 1, 2]], [[1, 3, 2]], [[1, 4, 1]], [[1, 1, 3]]])
    out = probability_from_outcomes(ds)
    np.testing.assert_array_equal(out.probability.values, [[0.0, 0.25, 0.75]])
    np.testing.assert_array_equal(out.n_undetermined.values, [[0, 1, 0]])
    np.testing.assert_allclose(out.probability_se.values, [[0.0, np.sqrt(0.25 * 0.75 / 4), np.sqrt(0.75 * 0.25 / 4)]])
    assert int(out.n_realisations) == 4
    assert lowest_positive_amplitude(out.probability).values.tolist() == [1.5]


def test_refuses_a_spectrum_without_outcomes():
    ds = _fake_spectrum(np.ones((1, 1, 2))).drop_vars("outcome")
    with pytest.raises(ValueError, match="with_map=True"):
        probability_from_outcomes(ds)


def test_noisy_surface_agrees_with_the_threshold_scan(blc06):
    """The threshold scan (its own kernel) and the map must agree: the lower envelope lies in
    (a_{J-1}, a_J], a_J the lowest grid amplitude with P > 0, and each realisation's threshold in
    (a_{j-1}, a_j] with a_j its own first overturning grid point."""
    scenario = Scenario(blc06, control=Control("FS"), noise_level=0.05, seed=7)
    grid = AmplitudeGrid(start=0.9, stop=3.0, step=0.15, resolution=0.02)
    freqs = [1.5, 2.5, 3.5]
    out = probability_surface(scenario, freqs, realisations=range(6), grid=grid)
    p = out.probability.values
    assert np.all((p >= 0) & (p <= 1)) and np.allclose(p * 6, np.round(p * 6))
    first = lowest_positive_amplitude(out.probability).values
    step = grid.step
    for f, a_first, thr in zip(freqs, first, out.threshold.values):
        if np.isnan(a_first):
            assert np.isnan(thr)
        else:
            assert a_first - step - 1e-9 < thr <= a_first + 1e-9, (f, a_first, thr)
    assert out.attrs["compute_time_s"] > 0 and int(out.n_undetermined.sum()) == 0
    # the same realisations' spectrum, realisation by realisation
    ds = spectrum(scenario, freqs, realisations=range(6), grid=grid, with_map=True)
    amps = ds.amplitude_ratio.values
    for k in range(6):
        for i in range(len(freqs)):
            over = np.isin(ds.outcome.values[k, i], (2, 3))
            thr = ds.threshold_realisation.values[k, i]
            if over.any():
                a_j = amps[np.argmax(over)]
                assert a_j - step - 1e-9 < thr <= a_j + 1e-9
            else:
                assert np.isnan(thr)


def test_noise_free_surface_is_the_overturning_map(blc06):
    scenario = Scenario(blc06, control=Control("CS01"))
    grid = AmplitudeGrid(start=0.9, stop=3.0, step=0.3, resolution=0.05)
    out = probability_surface(scenario, [1.0, 2.0], realisations=range(3), grid=grid)
    ds = spectrum(scenario, [1.0, 2.0], grid=grid, with_map=True)
    np.testing.assert_array_equal(out.probability.values, np.isin(ds.outcome.values[0], (2, 3)).astype(float))
    assert int(out.n_realisations) == 1  # without noise every realisation is the same record
