"""Tests for rockstudy.studies.study: parameters from dicts, chunks, gathering, J_OS tables, noise and histories."""
import math

import numpy as np
import pytest

from builders import BLC06, FREQS, fake_spectrum
from rockstudy.analysis.jos import jos
from rockstudy.analysis.spectra import AmplitudeGrid, Scenario
from rockstudy.core import io
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.control import Control
from rockstudy.model.excitation import modulated_peak
from rockstudy.model.noise import noisy_record
from rockstudy.studies import datasets, parameters, study, tables


def base_config():
    from pathlib import Path

    import yaml
    return yaml.safe_load((Path(__file__).parents[2] / "config.yaml").read_text())


# --- parameters -------------------------------------------------------------------------------
def test_block_from_preset_and_dimensions():
    assert parameters.block_from_dict({"preset": "BLC06"}) is BLC06
    b = parameters.block_from_dict({"width": 0.4, "height": 1.6, "depth": 0.47})
    assert b.alpha == pytest.approx(math.atan(0.25), rel=1e-12)
    with pytest.raises(ValueError, match="preset"):
        parameters.block_from_dict({"preset": "NOPE"})
    with pytest.raises(ValueError, match="not both"):
        parameters.block_from_dict({"preset": "BLC06", "width": 1.0})


def test_scenario_from_dict():
    sc = parameters.scenario_from_dict({"block": {"preset": "BLC06"}, "anchorage": {"kappa_max": 2.0},
                                   "control": {"strategy": "CS02", "sampling_time": 0.1, "delay": 0.06},
                                   "noise_level": 0.05, "seed": 3})
    assert sc.anchorage.kappa_max == 2.0 and sc.control.delay == 0.06 and sc.noise_level == 0.05


@pytest.mark.parametrize("spec, message", [
    ({"anchorage": {"kappa_max": 1.0, "kappa_min": 2.0}},
     r"anchorage.kappa_min \(2.0\) must not exceed anchorage.kappa_max"),
    ({"control": {"strategy": "CS01", "delay": 0.06}}, "control.delay > 0 needs a control.sampling_time > 0"),
    ({"noise": {"step": 0.0025, "band": 300.0}},
     r"noise.band must be below the Nyquist frequency 1/\(2 noise.step\)"),
])
def test_scenario_errors_name_the_config_keys(spec, message):
    with pytest.raises(ValueError, match=message):
        parameters.scenario_from_dict({"block": {"preset": "BLC06"}, **spec})
    with pytest.raises(ValueError, match="block.height"):
        parameters.block_from_dict({"width": 0.4, "height": -1.0, "depth": 0.47})


def test_realisation_chunks_cover_each_realisation_once():
    chunks = parameters.realisation_chunks(40, 15)
    assert [len(c) for c in chunks] == [15, 15, 10]
    assert sum(chunks, []) == list(range(40))
    assert parameters.realisation_chunks(40, 15, noisy=False) == [[0]]
    with pytest.raises(ValueError):
        parameters.realisation_chunks(0, 10)


def test_a_max0_ratio_is_one_over_tan_alpha():
    ds = fake_spectrum("FS", 0.0, np.ones(4))
    assert parameters.a_max0_ratio(ds, 1.0) == pytest.approx(4.0, rel=1e-12)  # BLC06: H/B = 4
    assert parameters.a_max0_ratio(ds, 0.5) == pytest.approx(2.0, rel=1e-12)


def test_check_study_names_the_key():
    cfg = base_config()
    study.check_study(cfg)
    bad = {**cfg, "convergence": {"strategy": "FS", "noise_level": "R999"}}
    with pytest.raises(ValueError, match="convergence.noise_level"):
        study.check_study(bad)
    bad = {**cfg, "a_max0": 2.0}  # 8 as a ratio, above the scan's 6
    with pytest.raises(ValueError, match="a_max0"):
        study.check_study(bad)
    bad = {**cfg, "noise_levels": {"R001": 0.01}}
    with pytest.raises(ValueError, match="noise_levels"):
        study.check_study(bad)


# --- gathering -----------------------------------------------------------------------------------
def test_gather_equals_one_job_over_all_realisations():
    thr = np.array([[1.2, 1.5, np.nan, 2.0], [1.1, 1.6, np.nan, np.nan], [1.3, 1.4, 5.0, 2.2]])
    whole = fake_spectrum("FS", 0.05, thr)
    parts = [fake_spectrum("FS", 0.05, thr[2:], [2]), fake_spectrum("FS", 0.05, thr[:2], [0, 1])]
    gathered = datasets.gather_spectra(parts)
    np.testing.assert_array_equal(gathered["realisation"], [0, 1, 2])
    np.testing.assert_allclose(gathered["threshold"], [1.1, 1.4, 5.0, 2.0])  # min over realisations
    np.testing.assert_allclose(gathered["threshold"], whole["threshold"])
    np.testing.assert_allclose(gathered["threshold_mean"], whole["threshold_mean"])
    np.testing.assert_allclose(gathered["threshold_std"], whole["threshold_std"])
    np.testing.assert_allclose(gathered["threshold_std"][0], np.std([1.2, 1.1, 1.3]), rtol=1e-12)
    with pytest.raises(ValueError, match="overlap"):
        datasets.gather_spectra([parts[1], parts[1]])


def test_gather_refuses_chunks_of_different_spectra():
    thr = np.array([[1.2, 1.5, np.nan, 2.0], [1.1, 1.6, np.nan, np.nan]])
    fs = fake_spectrum("FS", 0.05, thr[:1], [0])
    for other, attr in [(fake_spectrum("CS01", 0.05, thr[1:], [1]), "control_strategy"),
                        (fake_spectrum("FS", 0.05, thr[1:], [1], seed=3), "noise_seed"),
                        (fake_spectrum("FS", 0.05, thr[1:], [1], free_time=10.0), "free_time_s")]:
        with pytest.raises(io.DatasetMismatch, match=attr):
            datasets.gather_spectra([fs, other])


def test_expected_attrs_of_a_scenario_match_its_spectrum_and_noise_file():
    from rockstudy.model.noise import NoiseReading
    sc = Scenario(BLC06, Anchorage(), Control("CS02", 0.01), noise_level=0.05, seed=4, noise=NoiseReading(step=0.005))
    ds = fake_spectrum("CS02", 0.05, [[1.0, 1.0, 1.0, 1.0]], [3], 0.01, seed=4, noise=NoiseReading(step=0.005))
    io.check_dataset(ds, "s.nc", datasets.expected_attrs(sc, realisations=[3], frequency_ratios=FREQS,
                                                         amplitude_grid={"start": 0.9, "stop": 6.0, "step": 0.1,
                                                                         "resolution": 0.01}))
    with pytest.raises(io.DatasetMismatch, match="noise_(dt|step)_s is 0.005, expected 0.0025"):
        io.check_dataset(ds, "s.nc", datasets.expected_attrs(Scenario(BLC06, Anchorage(), Control("CS02", 0.01),
                                                                      noise_level=0.05, seed=4)))
    noise = datasets.expected_attrs(sc, "noise")
    assert "control_strategy" not in noise and noise["noise_seed"] == 4 and noise["noise_step_s"] == 0.005


def test_convergence_dataset_is_running_minimum():
    thr = np.array([[2.0, np.nan, 3.0, 1.0], [1.5, np.nan, 3.5, 1.0], [1.8, 2.5, 1.0, 1.0]])
    conv = datasets.convergence_dataset(fake_spectrum("FS", 0.05, thr))
    np.testing.assert_allclose(conv["threshold_convergence"].sel(n_realisations=1), thr[0])
    np.testing.assert_allclose(conv["threshold_convergence"].sel(n_realisations=3), [1.5, 2.5, 1.0, 1.0])


# --- J_OS tables ---------------------------------------------------------------------------------
LEVELS = {"R000": 0.0, "R005": 0.05}


def test_table1_hand_worked():
    fs0 = fake_spectrum("FS", 0.0, [2.0, 2.0, 2.0, np.nan])
    fs5 = fake_spectrum("FS", 0.05, [1.0, 2.0, 2.0, np.nan])  # halves a* at one of 3 counted frequencies
    cs0 = fake_spectrum("CS01", 0.0, [2.0, 2.0, 2.0, np.nan])
    cs5 = fake_spectrum("CS01", 0.05, [np.nan, np.nan, np.nan, np.nan])  # never overturns: +100 % vs anything
    table = tables.table1([fs0, fs5, cs0, cs5], ["FS", "CS01"], LEVELS, 1.0)
    j = table["j_os"]
    # FS, ref. no noise: terms (1-2)/2 = -0.5, 0, 0 over N* = 3 -> -16.67 %
    assert float(j.sel(reference="no_noise", strategy="FS", noise_level="R005")) == pytest.approx(-50 / 3, rel=1e-12)
    assert int(table["n_star"].sel(reference="no_noise", strategy="FS", noise_level="R005")) == 3
    # FS against itself: every term is 0 over the 3 frequencies below a_max,0 -- as `rockstudy jos` gives
    assert float(j.sel(reference="fs_same_noise", strategy="FS", noise_level="R005")) == 0.0
    assert int(table["n_star"].sel(reference="fs_same_noise", strategy="FS", noise_level="R005")) == 3
    assert (jos(fs5, fs5, 1.0).j_os, jos(fs5, fs5, 1.0).n_star) == (0.0, 3)
    assert float(j.sel(reference="no_noise", strategy="CS01", noise_level="R005")) == pytest.approx(100.0)
    assert float(j.sel(reference="fs_same_noise", strategy="CS01", noise_level="R005")) == pytest.approx(100.0)
    md = tables.table_markdown(table)
    assert "| FS | -16.67% | +0.00% |" in md and "+100.00%" in md
    # provenance and the meaning of NaN travel with the table
    for key in ("noise_seed", "block_width", "block_alpha", "anchorage_kappa_max", "n_realisations"):
        assert key in table.attrs, key
    assert "N* = 0" in table["j_os"].attrs["missing_value_meaning"]
    assert "j_os" in tables.table_csv(table).splitlines()[0]


def test_jos_undefined_is_nan_with_n_star_zero_and_a_max0_above_the_scan_is_refused():
    never = fake_spectrum("CS01", 0.05, [np.nan, np.nan, np.nan, np.nan])
    j, n = jos(never, never, 1.0).j_os, jos(never, never, 1.0).n_star
    assert np.isnan(j) and n == 0
    top_g = never.attrs["grid_amplitude_stop"] * math.tan(never.attrs["block_alpha"])
    with pytest.raises(ValueError, match=r"a_max0_g = .* g is not allowed.*scan"):
        jos(never, never, 1.01 * top_g)


def test_timing_table_references():
    cont = fake_spectrum("CS01", 0.05, [2.0, 2.0, 2.0, 2.0])
    fs = fake_spectrum("FS", 0.05, [1.0, 1.0, 1.0, 1.0])
    sampled = [fake_spectrum("CS01", 0.05, [2.0, 2.0, 2.0, 2.0], sampling_time=0.01),
               fake_spectrum("CS01", 0.05, [1.0, 1.0, 1.0, 1.0], sampling_time=0.2)]
    table = tables.timing_table(sampled, [cont], [fs], "sampling_time", 1.0)
    j = table["j_os"].sel(strategy="CS01")
    assert float(j.sel(reference="continuous_same_noise", sampling_time=0.01)) == pytest.approx(0.0)
    assert float(j.sel(reference="continuous_same_noise", sampling_time=0.2)) == pytest.approx(-50.0)
    # vs FS: (2-1)/(4-1) at every frequency
    assert float(j.sel(reference="fs_same_noise", sampling_time=0.01)) == pytest.approx(100 / 3)


# --- noise and histories -------------------------------------------------------------------------
def test_noise_dataset_regenerates_records_exactly():
    sc = Scenario(BLC06, noise_level=0.05, seed=7)
    ds = datasets.noise_dataset(sc, [1.0, 2.0], [0, 1, 2], 1.0, 2)
    np.testing.assert_allclose(ds["energy_ratio"], 1.0, rtol=1e-12)  # energy match
    rec = noisy_record("modulated", BLC06.p, 0.05, 1, 7)
    np.testing.assert_array_equal(ds["record"].sel(record_realisation=1).values, rec.values)
    assert ds.sizes["record_realisation"] == 2
    np.testing.assert_array_equal(ds["spawn_key"].values[:, 1], [0, 1, 2])
    assert ds.attrs["noise_seed"] == 7 and ds["t"].attrs["units"] == "s"
    datasets.check_noise(ds, sc)
    with pytest.raises(ValueError, match="noise_seed"):
        datasets.check_noise(ds, Scenario(BLC06, noise_level=0.05, seed=8))


def test_noise_free_dataset_is_the_baseline():
    ds = datasets.noise_dataset(Scenario(BLC06), [1.0], [0], 1.0, 1)
    np.testing.assert_array_equal(ds["record"].isel(record_realisation=0), ds["baseline"])
    assert float(ds["pga_ratio"].squeeze()) == 1.0


def test_history_below_uplift_stays_at_rest():
    # a_p·max|envelope·sin| < g·tanα: no uplift (docs/model.md §4), θ stays 0
    ds = datasets.time_history(Scenario(BLC06, control=Control("CS01")), 2.0, 0.9)
    assert ds.attrs["status"] != "overturned"
    np.testing.assert_array_equal(ds["theta"], 0.0)
    assert float(abs(ds["ground_ratio"]).max()) == pytest.approx(0.9 * modulated_peak(), rel=1e-3)
    assert ds["rotation_ratio"].attrs["long_name"] == "theta/alpha"


def test_history_overturning_reaches_flat():
    ds = datasets.time_history(Scenario(BLC06, control=Control("FS")), 1.0, 5.0)
    assert ds.attrs["overturned"] == 1
    assert float(abs(ds["theta"]).max()) >= math.pi / 2 - 1e-6
    assert set(np.unique(ds["stiffness_ratio"])) <= {0.0}  # FS: no anchorage


def test_chunked_spectrum_equals_one_job():
    """Results do not depend on how realisations are split into jobs (-j1 vs -j2, chunk size)."""
    from rockstudy.analysis.spectra import spectrum
    sc = Scenario(BLC06, control=Control("CS01"), noise_level=0.05, seed=11)
    grid = AmplitudeGrid(0.9, 3.0, 0.3, 0.05)
    freqs = [1.0, 2.5]
    whole = spectrum(sc, freqs, realisations=[0, 1, 2], grid=grid)
    parts = [spectrum(sc, freqs, realisations=[2], grid=grid), spectrum(sc, freqs, realisations=[0, 1], grid=grid)]
    gathered = datasets.gather_spectra(parts)
    for name in ("threshold", "threshold_realisation", "energy_ratio", "n_simulations"):
        np.testing.assert_array_equal(gathered[name].values, whole[name].values)


def test_a_whole_spectrum_written_by_its_job_is_its_one_chunk_gathered(tmp_path):
    """A spectrum of one chunk is written by its simulation job (workflow rule spectrum), aggregated in
    memory: the file is byte for byte the one writing the chunk, reading it and gathering it wrote."""
    from rockstudy.analysis.spectra import spectrum
    sc = Scenario(BLC06, control=Control("CS01"), noise_level=0.05, seed=11)
    ds = spectrum(sc, [1.0, 2.5], realisations=[0, 1], grid=AmplitudeGrid(0.9, 3.0, 0.3, 0.05))
    datasets.document_missing(ds)
    io.write_netcdf(ds, tmp_path / "chunk.nc")
    io.write_netcdf(datasets.gather_spectra([io.read_netcdf(tmp_path / "chunk.nc")]), tmp_path / "gathered.nc")
    io.write_netcdf(datasets.gather_spectra([ds]), tmp_path / "whole.nc")
    assert (tmp_path / "whole.nc").read_bytes() == (tmp_path / "gathered.nc").read_bytes()
