"""Tests for the readings study (rockstudy.studies.noise_readings) and the device calibration."""
import math

import numpy as np
import pytest
import xarray as xr

from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, spectrum_dataset
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import BLOCK_PRESETS
from rockstudy.model.control import Control
from rockstudy.model.noise import NoiseReading
from rockstudy.studies import claims
from rockstudy.studies import device_calibration as calibration
from rockstudy.studies import noise_readings as readings

BLC06 = BLOCK_PRESETS["BLC06"]
FREQS = np.array([0.5, 1.0, 2.0, 3.0])
LEVELS = {"R001": 0.01, "R005": 0.05, "R010": 0.10}


def fake(strategy, level, thresholds, anchorage=None):
    thr = np.atleast_2d(np.asarray(thresholds, float))
    sc = Scenario(BLC06, anchorage or Anchorage(), Control(strategy), noise_level=level)
    ones = np.ones_like(thr)
    return spectrum_dataset(sc, FREQS, list(range(thr.shape[0])), thr, thr - 0.01, ones.astype(int), ones, ones,
                            AmplitudeGrid())


def below(j_percent):
    """Thresholds 2*(1 + J/100) below a reference of 2.0 everywhere: J_OS = J exactly (Eq. 22, a* < a*_REF)."""
    return [2.0 * (1 + j_percent / 100)] * len(FREQS)


def test_jos_against_and_distance_hand_worked():
    ref = fake("FS", 0.0, [2.0] * 4)
    j, n = readings.jos_against(fake("FS", 0.05, below(-5.0)), ref, 1.0)
    assert j == pytest.approx(-5.0, abs=1e-12) and n == 4
    assert readings.distance([1.0, 2.0, 3.0], [1.0, 1.0, 1.0]) == pytest.approx((2.0, math.sqrt(5 / 3)))
    assert all(math.isnan(v) for v in readings.distance([1.0, np.nan], [1.0, 1.0]))


def test_readings_table_finds_the_reading_that_reproduces_the_paper():
    ref = fake("FS", 0.0, [2.0] * 4)
    paper = readings.PAPER_FS_ROW
    spectra = {}
    for level, value in LEVELS.items():
        spectra[("exact", level)] = fake("FS", value, below(paper[level]))
        spectra[("off_by_one", level)] = fake("FS", value, below(paper[level] + 1.0))
    table = readings.readings_table(spectra, ref, {"off_by_one": NoiseReading(step=0.02),
                                                   "exact": NoiseReading(rescale="none")}, LEVELS, 1.0)
    np.testing.assert_allclose(table["j_os"].sel(reading="exact"), [paper[lv] for lv in LEVELS], atol=1e-10)
    assert float(table["max_abs_difference"].sel(reading="exact")) == pytest.approx(0.0, abs=1e-10)
    assert float(table["rms_difference"].sel(reading="off_by_one")) == pytest.approx(1.0, abs=1e-10)
    assert table.attrs["closest_reading"] == readings.closest_reading(table) == "exact"
    assert table["step"].sel(reading="off_by_one").item() == 0.02
    assert table["rescale"].sel(reading="exact").item() == "none"
    md = readings.readings_markdown(table)
    assert md.index("| exact |") < md.index("| off_by_one |")  # closest first
    csv = readings.readings_csv(table).splitlines()
    assert len(csv) == 1 + 2 * 3 and csv[0].startswith("reading,label,step_s")


def table1_of(cs01_vs_fs, cs02_vs_fs, cs01_nn=(0, 0, 0), cs02_nn=(0, 0, 0)):
    refs, strategies, levels = ["no_noise", "fs_same_noise"], ["FS", "CS01", "CS02"], ["R001", "R005", "R010"]
    j = np.full((2, 3, 3), np.nan)
    j[0, 1], j[0, 2], j[1, 1], j[1, 2] = cs01_nn, cs02_nn, cs01_vs_fs, cs02_vs_fs
    return xr.Dataset({"j_os": (("reference", "strategy", "noise_level"), j)},
                      coords={"reference": refs, "strategy": strategies, "noise_level": levels})


def paper_device():
    paper = claims.PAPER_TABLE1
    return table1_of(paper[("fs_same_noise", "CS01")], paper[("fs_same_noise", "CS02")],
                     paper[("no_noise", "CS01")], paper[("no_noise", "CS02")])


def test_calibration_grid_scores_ranks_and_shares():
    design = calibration.CalibrationDesign(kappa_max=(1.0, 2.0), damping_ratio=(0.05,))
    exact = paper_device()
    reversed_ranking = table1_of((10, 10, 10), (20, 20, -1))
    grid = calibration.grid_dataset(design, [reversed_ranking, exact], BLC06.alpha)
    assert float(grid["rms_residual"].sel(kappa_max=2.0).squeeze()) == pytest.approx(0.0, abs=1e-12)
    (best, rms), = calibration.best_devices(grid, 1)
    assert best["kappa_max"] == 2.0 and best["spring_ultimate_rotation"] is None and rms == pytest.approx(0.0)
    Anchorage(**best)  # a valid anchorage
    np.testing.assert_allclose(grid["ranking_share"].values, [0.5, 0.5, 0.5])
    assert calibration.conclusions_hold(calibration.rows_of(exact)).all()
    assert not calibration.conclusions_hold(calibration.rows_of(reversed_ranking)).any()
    assert calibration.score(calibration.rows_of(exact)) == (0.0, 0.0)


@pytest.mark.parametrize("where", [0, 5, 11, 13, 23])
def test_best_device_is_found_on_every_axis_of_the_grid(where):
    # 3 theta_u/alpha x 2 kappa_min/kappa_max x 2 kappa_max x 2 xi: only device `where` matches the paper;
    # the grid must hand back exactly that device (axes not mixed up between devices() and the grid)
    design = calibration.CalibrationDesign(kappa_max=(1.0, 4.0), damping_ratio=(0.05, 0.2),
                                           ultimate_rotation_ratio=(0.5, 1.0, 1.5), kappa_min_ratio=(0.0, 0.25))
    devices = design.devices(BLC06.alpha)
    tables = [paper_device() if i == where else table1_of((10, 10, 10), (5, 5, 5)) for i in range(len(devices))]
    grid = calibration.grid_dataset(design, tables, BLC06.alpha)
    assert grid["rms_residual"].shape == (3, 2, 2, 2)
    (best, rms), (second, _) = calibration.best_devices(grid, 2)
    assert best == devices[where] and rms == pytest.approx(0.0, abs=1e-12) and second != best
    assert int((grid["rms_residual"] < 1e-9).sum()) == 1
    md = calibration.calibration_markdown(grid)
    assert "positive at all three levels" in md and ": 1 of 24." in md  # only the paper's device has CS02 > 0
    np.testing.assert_allclose(float(calibration.row_distance(grid, "CS02", "no_noise").min()), 0.0, atol=1e-12)


def test_row_distance_hand_worked():
    design = calibration.CalibrationDesign(kappa_max=(1.0,), damping_ratio=(0.05,))
    paper = claims.PAPER_TABLE1[("no_noise", "CS02")]
    off = table1_of((0, 0, 0), (0, 0, 0), cs02_nn=[p + d for p, d in zip(paper, (1.0, -2.0, 2.0))])
    grid = calibration.grid_dataset(design, [off], BLC06.alpha)
    assert float(calibration.row_distance(grid, "CS02", "no_noise").squeeze()) == pytest.approx(math.sqrt(3.0))


def test_figure_calibration_draws_the_slice_of_the_best_device():
    import matplotlib
    matplotlib.use("Agg")
    from rockstudy import plotting
    design = calibration.CalibrationDesign(kappa_max=(1.0, 4.0), damping_ratio=(0.05, 0.2),
                                           ultimate_rotation_ratio=(1.0, 1.5), kappa_min_ratio=(0.0, 0.25))
    devices = design.devices(BLC06.alpha)
    tables = [table1_of((i, i, i), (i / 2, i / 2, i / 2)) for i in range(len(devices))]
    grid = calibration.grid_dataset(design, tables, BLC06.alpha)
    fig = plotting.figure_calibration(grid, devices[13])  # theta_u = 1.5 alpha, kappa_min = 0.25 kappa_max
    assert "1.5" in fig._suptitle.get_text() and "0.25" in fig._suptitle.get_text()
    mesh = fig.axes[0].collections[0]  # CS01 vs FS at R001: the values i of devices 12..15
    np.testing.assert_allclose(np.sort(np.asarray(mesh.get_array()).ravel()), [12, 13, 14, 15])
    matplotlib.pyplot.close(fig)


def test_figure_calibration_with_one_xi_draws_curves_and_only_the_panels_with_data():
    """One ξ leaves a map no area (it used to draw blank panels): each panel is then J_OS against
    κ_max with the values of the grid; a strategy or level without any J_OS gets no panel."""
    import matplotlib
    matplotlib.use("Agg")
    from rockstudy import plotting
    design = calibration.CalibrationDesign(kappa_max=(1.0, 2.0, 4.0), damping_ratio=(0.05,))
    devices = design.devices(BLC06.alpha)
    cs01 = [(10 + i, 20 + i, 30 + i) for i in range(len(devices))]
    tables = [table1_of(c, (math.nan,) * 3) for c in cs01]  # CS02: J_OS undefined everywhere
    grid = calibration.grid_dataset(design, tables, BLC06.alpha)
    fig = plotting.figure_calibration(grid, devices[1])
    panels = [ax for ax in fig.axes if "vs FS" in ax.get_title()]
    assert [ax.get_title().split(" (")[0] for ax in panels] == ["CS01 vs FS, R001", "CS01 vs FS, R005",
                                                                "CS01 vs FS, R010"]
    assert len(fig.axes) == 3  # no empty CS02 row, no colour bar of an empty map
    for j, ax in enumerate(panels):
        curve = next(line for line in ax.get_lines() if line.get_label().startswith(r"$\xi$"))
        np.testing.assert_array_equal(curve.get_xdata(), [1.0, 2.0, 4.0])
        np.testing.assert_array_equal(curve.get_ydata(), [c[j] for c in cs01])
    matplotlib.pyplot.close(fig)


def test_figure_readings_names_coinciding_readings_together():
    import matplotlib
    matplotlib.use("Agg")
    from rockstudy import plotting
    ref = fake("FS", 0.0, [2.0] * len(FREQS))
    value = {"a": -5.0, "b": -5.0, "c": -20.0}  # a and b give the same J_OS at every level
    spectra = {(name, lv): fake("FS", v, below(value[name])) for name in value for lv, v in LEVELS.items()}
    table = readings.readings_table(spectra, ref, {"a": NoiseReading(), "b": NoiseReading(rescale="none"),
                                                   "c": NoiseReading(step=0.01)}, LEVELS, 1.0)
    fig = plotting.figure_readings(table)
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert len(labels) == 3 and labels[0].startswith("a: ") and " = b: " in labels[0]
    assert labels[1].startswith("c: ") and labels[2] == "paper, Table 1"
    drawn = [line for line in ax.get_lines() if line.get_label() in labels[:2]]
    np.testing.assert_allclose(drawn[0].get_ydata(), -5.0)
    np.testing.assert_allclose(drawn[1].get_ydata(), -20.0)
    matplotlib.pyplot.close(fig)


def test_physical_device_for_blc06():
    an = Anchorage(kappa_max=1.0, damping_ratio=0.05)
    phys = calibration.physical(BLC06, an)
    # K = kappa m g R / (4 b^2); D from 3 D b^2 / (m R^2) = 2 xi p
    assert phys["K_max_N_per_m"] == pytest.approx(BLC06.mass * BLC06.gravity * BLC06.R / (4 * BLC06.b ** 2))
    assert phys["D_N_s_per_m"] == pytest.approx(2 * 0.05 * BLC06.p * BLC06.mass * BLC06.R ** 2 / (3 * BLC06.b ** 2))
    assert phys["K_max_N_per_m"] == pytest.approx(41.1e3, rel=2e-3)  # the README's figure for BLC06
    assert phys["theta_K_u_rad"] == pytest.approx(BLC06.alpha)


@pytest.mark.parametrize("kwargs, name", [
    (dict(kappa_max=(), damping_ratio=(0.05,)), "kappa_max"),
    (dict(kappa_max=(1.0, 1.0), damping_ratio=(0.05,)), "kappa_max"),
    (dict(kappa_max=(1.0,), damping_ratio=(-0.1,)), "damping_ratio"),
    (dict(kappa_max=(1.0,), damping_ratio=(0.05,), ultimate_rotation_ratio=(0.0,)), "ultimate_rotation_ratio"),
    (dict(kappa_max=(1.0,), damping_ratio=(0.05,), ultimate_rotation_ratio=(None,)), "ultimate_rotation_ratio"),
    (dict(kappa_max=(1.0,), damping_ratio=(0.05,), kappa_min_ratio=(1.5,)), "kappa_min_ratio"),
    (dict(kappa_max=(1.0,), damping_ratio=(0.05,), kappa_min_ratio=(-0.1,)), "kappa_min_ratio")])
def test_design_errors_name_the_field(kwargs, name):
    with pytest.raises(ValueError, match=name):
        calibration.CalibrationDesign(**kwargs)


def test_design_devices_hand_worked():
    d = calibration.CalibrationDesign(kappa_max=(1.0, 2.0), damping_ratio=(0.0, 0.1),
                                      ultimate_rotation_ratio=(1.0, 2.0), kappa_min_ratio=(0.0, 0.25))
    devices = d.devices(0.3)
    assert d.shape == (2, 2, 2, 2) and len(devices) == 16
    assert devices[0] == {"kappa_max": 1.0, "kappa_min": 0.0, "damping_ratio": 0.0, "spring_ultimate_rotation": None,
                          "damper_ultimate_rotation": None}  # theta_u = alpha: the library default
    theta = pytest.approx(0.6)  # 2 alpha
    assert devices[-1] == {"kappa_max": 2.0, "kappa_min": 0.5, "damping_ratio": 0.1,
                           "spring_ultimate_rotation": theta, "damper_ultimate_rotation": theta}
    assert devices[5] == {"kappa_max": 1.0, "kappa_min": 0.25, "damping_ratio": 0.1, "spring_ultimate_rotation": None,
                          "damper_ultimate_rotation": None}  # C order: (theta 0, kappa_min 1, kappa_max 0, xi 1)
    for dev in devices:
        Anchorage(**dev)
    with pytest.raises(ValueError, match="theta_u"):  # 2 x 0.9 rad > pi/2
        d.devices(0.9)


def test_check_study_names_bad_readings_and_designs():
    import copy
    from pathlib import Path

    import yaml

    from rockstudy.studies import study
    config = yaml.safe_load((Path(__file__).parents[2] / "config.yaml").read_text())
    study.check_study(config)
    bad = copy.deepcopy(config)
    bad["reproduction"]["readings"]["wide"] = {"step": 0.02, "band": 30.0}  # above the 25 Hz Nyquist
    with pytest.raises(ValueError, match="reproduction.readings.wide.*Nyquist"):
        study.check_study(bad)
    bad = copy.deepcopy(config)
    bad["calibration"]["kappa_min_ratio"] = [0.0, 2.0]
    with pytest.raises(ValueError, match=r"calibration.kappa_min_ratio\[1\] = 2(\.0)? is not allowed"):
        study.check_study(bad)
    bad = copy.deepcopy(config)
    bad["calibration"]["ultimate_rotation_ratio"] = [1.0, 7.0]  # 7 alpha > pi/2 for BLC06
    with pytest.raises(ValueError, match=r"calibration.ultimate_rotation_ratio\[1\] = 7 .*theta_u"):
        study.check_study(bad)
    bad = copy.deepcopy(config)
    bad["noise"]["band"] = 300.0
    with pytest.raises(ValueError, match=r"noise.band must be below the Nyquist frequency 1/\(2 noise.step\)"):
        study.check_study(bad)


def test_device_spectra_apply_the_configs_control_options_to_every_strategy():
    """The calibration's spectra use the study's ``control:`` keys (the sensor) for CS01 and CS02."""
    spec = {"block": {"preset": "BLC06"}, "excitation": "modulated", "seed": 1, "overturn_criterion": "flat",
            "free_time": 5.0, "control_options": {"sensor_band": 5.0}}
    grid = AmplitudeGrid(start=0.9, stop=1.5, step=0.3, resolution=0.3)
    out = calibration.device_spectra(spec, {"kappa_max": 1.0}, ["CS01", "CS02"], {"R000": 0.0}, [2.0], 1, grid)
    assert [ds.attrs["control_sensor_band_hz"] for ds in out] == [5.0, 5.0]
    assert [ds.attrs["control_strategy"] for ds in out] == ["CS01", "CS02"]
