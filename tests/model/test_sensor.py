"""What the controller senses (rockstudy.model.sensor, Control.sensor_band): the filter against the analytic
Butterworth, the engines' controller reading the sensed record while the block feels the driving one,
the option off identical to rockstudy before it, and the two engines agreeing with the sensor on."""
import math

import numpy as np
import pytest
from scipy import signal

from rockstudy import Anchorage, Control
from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, spectrum, threshold
from rockstudy.engine import _kernel as kn
from rockstudy.engine.reference import ground as reference_ground
from rockstudy.engine.simulate import _result_from_kernel, kernel_record, pack_parameters, simulate
from rockstudy.model.excitation import GroundMotion
from rockstudy.model.noise import NoiseReading
from rockstudy.model.sensor import (
    SENSOR_STEP,
    butterworth_coefficients,
    butterworth_gain,
    check_band,
    sense,
    sensed_samples,
)

DT = 0.0025
NONE = NoiseReading(rescale="none")


# ---- the filter ----------------------------------------------------------------------------------
@pytest.mark.parametrize("band", [0.5, 5.0, 10.0, 20.0, 150.0])
def test_coefficients_are_scipys_butterworth(band):
    """The closed-form bilinear coefficients against scipy's independent design (pre-warped cut-off)."""
    b, a = butterworth_coefficients(band, DT)
    b_ref, a_ref = signal.butter(2, band, btype="low", fs=1.0 / DT)
    assert np.allclose(b, b_ref, rtol=1e-12, atol=1e-15)
    assert np.allclose(a, a_ref, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("band", [5.0, 10.0, 20.0])
def test_gain_is_one_at_dc_and_minus_3_db_at_the_band_edge(band):
    """Steady-state gain of the filtered samples: 1 for a constant, 1/√2 for a sine at f_c, and the
    analytic |H(f)| = 1/√(1 + (tan(πfΔt)/tan(πf_cΔt))⁴) at other frequencies."""
    n = 40000  # 100 s: the transient (time constant ~ 1/(2π f_c ζ)) is long gone in the last half
    t = np.arange(n) * DT
    assert sense(np.ones(n), DT, band)[-1] == pytest.approx(1.0, abs=1e-12)
    for f, expected in ((band, 1.0 / math.sqrt(2.0)), (0.5 * band, None), (2.0 * band, None)):
        y = sense(np.sin(2 * np.pi * f * t), DT, band)[n // 2:]
        tail = t[n // 2:]
        # amplitude of the steady state by least squares on sin and cos
        A = np.column_stack([np.sin(2 * np.pi * f * tail), np.cos(2 * np.pi * f * tail)])
        amp = float(np.hypot(*np.linalg.lstsq(A, y, rcond=None)[0]))
        analytic = 1.0 / math.sqrt(1.0 + (math.tan(math.pi * f * DT) / math.tan(math.pi * band * DT)) ** 4)
        assert amp == pytest.approx(analytic, rel=1e-6)
        assert float(butterworth_gain(f, band, DT)) == pytest.approx(analytic, rel=1e-12)
        if expected is not None:
            assert amp == pytest.approx(expected, rel=1e-6)
            assert 20 * math.log10(amp) == pytest.approx(-3.0103, abs=1e-3)


def test_filter_is_causal():
    """Changing sample j changes no reading before j: the controller cannot see the future."""
    rng = np.random.default_rng(3)
    x = rng.standard_normal(500)
    y = sense(x, DT, 10.0)
    x2 = x.copy()
    x2[300] += 5.0
    y2 = sense(x2, DT, 10.0)
    assert np.array_equal(y[:300], y2[:300])
    assert not np.allclose(y[300:], y2[300:])


def test_band_at_or_above_nyquist_is_refused():
    with pytest.raises(ValueError, match="Nyquist"):
        check_band(200.0, DT)
    with pytest.raises(ValueError, match="sensor_band"):
        Control("CS02", sensor_band=-1.0)
    with pytest.raises(ValueError, match="sensor_band"):
        Control("CS02", sensor_band=float("nan"))
    m = GroundMotion("record", 1.0, 1.0, 1.0, 0.01, np.ones(101))
    with pytest.raises(ValueError, match="Nyquist"):
        sensed_samples(m, 60.0)  # 0.01 s step: Nyquist 50 Hz


def test_analytic_excitation_is_sampled_for_the_sensor(blc06):
    """Eq. 23 is read at SENSOR_STEP from rest; the block still feels the analytic motion."""
    omega = 2.0 * blc06.p
    m = GroundMotion("modulated", 1.0, omega, 5 * 2 * math.pi / omega)
    values, step = sensed_samples(m, 10.0)
    assert step == SENSOR_STEP
    t = np.arange(len(values)) * step
    assert t[-1] >= m.duration > t[-2]
    assert np.allclose(values, sense(m.horizontal(t), step, 10.0), rtol=0, atol=1e-14)
    P = pack_parameters(blc06, Anchorage(), Control("CS02", sensor_band=10.0), m)
    assert P[kn.I_SENSE] == 1.0 and P[kn.I_SOFF] == 0 and P[kn.I_SDT] == SENSOR_STEP
    assert np.array_equal(kernel_record(Control("CS02", sensor_band=10.0), m), values)


# ---- option off: identical to rockstudy before the option -----------------------------------------
def test_option_off_is_the_record_itself(blc06):
    m = GroundMotion("record", 1.0, 1.0, 1.0, 0.01, np.ones(101))
    assert kernel_record(Control("CS02"), m) is m.record
    P = pack_parameters(blc06, Anchorage(), Control("CS02"), m)
    assert P[kn.I_SENSE] == 0.0


# thresholds computed with main at 213209f (before the sensor option), BLC06, default anchorage,
# seed 20190101, rescale "none" (scripts: the sensor branch's report)
MAIN_THRESHOLDS = [
    ("CS02", 2.0, 0.0, 0.0, 0.0, 0, 1.4875, 10),
    ("CS02", 1.2, 0.05, 0.0, 0.0, 3, 1.25, 9),
    ("CS02", 3.0, 0.10, 0.0, 0.0, 1, 2.5437499999999997, 22),
    ("CS01", 2.0, 0.05, 0.1, 0.0, 0, 1.775, 14),
    ("CS02", 2.0, 0.01, 0.05, 0.02, 2, 1.4875, 10),
    ("FS", 1.5, 0.10, 0.0, 0.0, 4, 1.2125, 9),
]


@pytest.mark.parametrize("strategy,frequency_ratio,level,ts,delay,k,expected,n_sim", MAIN_THRESHOLDS)
def test_option_off_gives_mains_thresholds(blc06, strategy, frequency_ratio, level, ts, delay, k, expected, n_sim):
    sc = Scenario(blc06, Anchorage(), Control(strategy, sampling_time=ts, delay=delay), noise_level=level,
                  seed=20190101, noise=NONE)
    r = threshold(sc, frequency_ratio, realisation=k)
    assert r["amplitude_ratio"] == expected  # exactly: the same arithmetic
    assert r["n_simulations"] == n_sim


# ---- the controller reads the sensed record, the block the driving one ------------------------------
def _hand_made(blc06):
    """A constant push (no zero of the driving Ẍg) and a sensed reading sin(2π·3 t) (zeros near k/6 s)."""
    dt = 0.01
    t = np.arange(101) * dt
    drive = np.ones(101)
    sensed = np.sin(2 * np.pi * 3.0 * t)
    motion = GroundMotion("record", 1.5 * blc06.uplift_acceleration, 1.0, 1.0, dt, drive)
    # zeros of the linear interpolation of the sensed samples (the oracle)
    i = np.nonzero(np.sign(sensed[1:-1]) != np.sign(sensed[2:]))[0] + 1
    zeros = t[i] - sensed[i] * dt / (sensed[i + 1] - sensed[i])
    return motion, sensed, zeros


def _switch_times(history, end=1.0):
    """Instants where κ changes, before the excitation's end (where CS02 becomes CS01). [s], [rad]"""
    k = history["kappa"]
    changed = np.nonzero(np.diff(k) != 0)[0] + 1
    changed = changed[history["t"][changed] < end - 1e-6]
    return history["t"][changed], history["theta"][changed]


def test_fast_engine_switches_at_the_sensed_zeros(blc06):
    motion, sensed, zeros = _hand_made(blc06)
    P = pack_parameters(blc06, Anchorage(), Control("CS02", sensor_band=10.0), motion)
    rec = np.concatenate([motion.record, sensed])  # hand-made sensed samples in place of the filter's
    res = _result_from_kernel(kn.simulate_kernel(P, rec, np.zeros(0), True, True), blc06)
    assert len(res.impact_times) == 0  # θ keeps its sign: every switch is the law's reading of Ẍg
    times, theta = _switch_times(res.history)
    before = zeros[zeros < res.end_time]
    assert len(before) >= 3
    assert np.allclose(times, before, rtol=0, atol=1e-9)
    assert np.all(theta < 0)
    # with the ideal sensor the driving Ẍg never changes sign: no switch at all
    ideal = simulate(blc06, Anchorage(), Control("CS02"), motion, record_history=True)
    assert len(_switch_times(ideal.history)[0]) == 0


def test_reference_engine_switches_at_the_sensed_zeros(blc06, monkeypatch):
    motion, sensed, zeros = _hand_made(blc06)
    monkeypatch.setattr(reference_ground, "sensed_samples", lambda m, band: (sensed, m.record_dt))
    res = simulate(blc06, Anchorage(), Control("CS02", sensor_band=10.0), motion, engine="reference",
                   record_history=True)
    assert len(res.impact_times) == 0
    times, _ = _switch_times(res.history)
    before = zeros[zeros < res.end_time]
    assert len(before) >= 3
    assert np.allclose(times, before, rtol=0, atol=1e-8)


def test_sensed_reading_changes_cs02_only(blc06):
    """FS, PASSIVE and CS01 never read Ẍg: the sensor leaves them bit-identical."""
    sc_args = dict(noise_level=0.05, seed=20190101, noise=NONE)
    for strategy in ("FS", "PASSIVE", "CS01"):
        a = threshold(Scenario(blc06, Anchorage(), Control(strategy), **sc_args), 1.5, realisation=2)
        b = threshold(Scenario(blc06, Anchorage(), Control(strategy, sensor_band=5.0), **sc_args), 1.5,
                      realisation=2)
        assert a["amplitude_ratio"] == b["amplitude_ratio"]


# ---- convergence and agreement ----------------------------------------------------------------------
def _peak_error(blc06, motion, bands):
    ideal = simulate(blc06, Anchorage(), Control("CS02"), motion).max_rotation_ratio
    return ideal, [abs(simulate(blc06, Anchorage(), Control("CS02", sensor_band=b), motion).max_rotation_ratio - ideal)
                   for b in bands]


def test_wide_band_converges_to_the_ideal_sensor_noise_free(blc06):
    """Eq. 23: the wider the band, the closer the peak rotation of CS02 to the ideal sensor's (the
    floor left at the widest band is the sensor's linear interpolation of the 2.5 ms samples)."""
    motion, _ = Scenario(blc06, Anchorage(), Control("CS02")).motion(2.0, 1.3)
    ideal, errors = _peak_error(blc06, motion, (5.0, 20.0, 50.0, 100.0, 199.9))
    assert all(a > b for a, b in zip(errors, errors[1:]))
    assert errors[-1] < 1e-5 * ideal


def test_wide_band_converges_to_the_ideal_sensor_noisy(blc06):
    """A noisy record: as f_c approaches the Nyquist frequency the bilinear filter tends to the
    identity (tan(πf_cΔt) → ∞), and the result to the ideal sensor's."""
    sc = Scenario(blc06, Anchorage(), Control("CS02"), noise_level=0.05, seed=20190101, noise=NONE)
    motion, _ = sc.motion(2.0, 1.3, 1)
    ideal, errors = _peak_error(blc06, motion, (199.9, 199.99, 199.999, 199.9999))
    assert all(a > b for a, b in zip(errors, errors[1:]))
    assert errors[-1] < 1e-6 * ideal


@pytest.mark.parametrize("level,band,frequency_ratio", [(0.0, 5.0, 2.0), (0.05, 10.0, 2.0), (0.10, 5.0, 1.2)])
def test_engines_agree_with_the_sensor_on(blc06, level, band, frequency_ratio):
    sc = Scenario(blc06, Anchorage(), Control("CS02", sensor_band=band), noise_level=level, seed=20190101,
                  noise=NONE)
    motion, _ = sc.motion(frequency_ratio, 1.3, 1)
    fast = simulate(blc06, sc.anchorage, sc.control, motion)
    ref = simulate(blc06, sc.anchorage, sc.control, motion, engine="reference")
    assert fast.max_rotation_ratio == pytest.approx(ref.max_rotation_ratio, rel=1e-6)
    assert len(fast.impact_times) == len(ref.impact_times)


def test_every_dataset_records_the_sensor(blc06):
    grid = AmplitudeGrid(0.9, 3.0, 0.3, 0.1)
    for band, attr in ((None, "none"), (10.0, 10.0)):
        sc = Scenario(blc06, Anchorage(), Control("CS02", sensor_band=band), noise_level=0.01, seed=1, noise=NONE)
        ds = spectrum(sc, [2.0], realisations=[0], grid=grid, progress_chunks=1)
        assert ds.attrs["control_sensor_band_hz"] == attr


# ---- command line ------------------------------------------------------------------------------------
def test_cli_sensor_band_reaches_the_controller(tmp_path, capsys, blc06):
    import json

    import xarray as xr

    from rockstudy.cli import main
    main(["threshold", "--strategy", "CS02", "--frequency-ratio", "2", "--noise-level", "0.05", "--realisation", "1",
          "--noise-rescale", "none", "--max-amplitude-ratio", "3", "--sensor-band", "5"])
    out = json.loads(capsys.readouterr().out)
    lib = threshold(Scenario(blc06, control=Control("CS02", sensor_band=5.0), noise_level=0.05, noise=NONE), 2.0,
                    realisation=1, grid=AmplitudeGrid(stop=3.0))
    assert out["sensor_band_hz"] == 5.0 and out["amplitude_ratio"] == lib["amplitude_ratio"]
    main(["spectrum", "--strategy", "CS02", "--frequency-start", "2", "--frequency-stop", "2",
          "--max-amplitude-ratio", "3", "--sensor-band", "10", "--output", str(tmp_path / "s.nc")])
    with xr.open_dataset(tmp_path / "s.nc") as ds:
        assert ds.attrs["control_sensor_band_hz"] == 10.0


@pytest.mark.parametrize("args", [["--sensor-band", "0"], ["--sensor-band", "-3"], ["--sensor-band", "200"],
                                  ["--noise-level", "0.05", "--noise-step", "0.01", "--sensor-band", "60"]])
def test_cli_bad_sensor_band_exits_2_naming_it(args, capsys):
    from rockstudy.cli import main
    with pytest.raises(SystemExit) as exc:
        main(["simulate", "--strategy", "CS02"] + args)
    assert exc.value.code == 2
    assert "--sensor-band" in capsys.readouterr().err


def test_config_control_sensor_band_is_checked():
    from pathlib import Path

    import yaml

    from rockstudy.studies import parameters, study
    cfg = yaml.safe_load((Path(__file__).parents[2] / "config.yaml").read_text())
    assert cfg["control"] == {"sensor_band": None}  # the default: the ideal sensor
    study.check_study({**cfg, "control": {"sensor_band": 10.0}})
    with pytest.raises(ValueError, match="control.sensor_band"):
        study.check_study({**cfg, "control": {"sensor_band": 200.0}})  # the Nyquist frequency of 2.5 ms
    spec = {"block": cfg["block"], "control": {"strategy": "CS02", "sensor_band": 5.0}}
    assert parameters.scenario_from_dict(spec).control.sensor_band == 5.0
