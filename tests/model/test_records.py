"""Record files (PEER NGA .AT2, two-column text/CSV) and simulations driven by them."""
import json
import math

import numpy as np
import pytest

from rockstudy import Anchorage, Control
from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, threshold
from rockstudy.cli import main
from rockstudy.engine.simulate import simulate
from rockstudy.model.excitation import GroundMotion, excitation_duration, modulated, one_sine
from rockstudy.model.records import (
    STANDARD_GRAVITY,
    Record,
    RecordFormatError,
    read_at2,
    read_record,
    read_two_column,
    write_at2,
)

AT2_HEADER = ("PEER NGA STRONG MOTION DATABASE RECORD\nIMPERIAL VALLEY 10/15/79, TEST STATION, 230\n"
              "ACCELERATION TIME SERIES IN UNITS OF G\n")


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


# --- reading, by hand-worked files -------------------------------------------------------------
def test_at2_values_are_converted_from_g_with_standard_gravity(tmp_path):
    path = write(tmp_path, "a.AT2", AT2_HEADER + "NPTS=     5, DT=   .0100 SEC\n  .1000E+00 -.2000E+00\n"
                 "  .3000E+00\n\n  0.0  -1.5E-1\n")
    rec = read_at2(path)
    assert rec.dt == 0.01 and rec.unit == "g" and rec.name.startswith("IMPERIAL VALLEY")
    np.testing.assert_allclose(rec.acceleration, np.array([0.1, -0.2, 0.3, 0.0, -0.15]) * 9.80665, rtol=1e-15)
    assert rec.duration == pytest.approx(0.04) and rec.pga == pytest.approx(0.3 * 9.80665)


def test_at2_old_npts_dt_line_and_fortran_exponents(tmp_path):
    path = write(tmp_path, "b.at2", AT2_HEADER + "    3    0.005   NPTS, DT\n 1.0D-01 2.0D-01 -3.0E-01\n")
    rec = read_record(path)
    assert rec.dt == 0.005
    np.testing.assert_allclose(rec.acceleration / STANDARD_GRAVITY, [0.1, 0.2, -0.3])


def test_two_column_csv_with_unit_in_header_and_shifted_origin(tmp_path):
    path = write(tmp_path, "c.csv", "# a comment\ntime [s], acceleration [cm/s^2]\n2.00,10\n2.01,-20\n\n2.02,5\n")
    rec = read_two_column(path)
    assert rec.unit == "cm/s^2" and rec.dt == pytest.approx(0.01) and rec.duration == pytest.approx(0.02)
    np.testing.assert_allclose(rec.acceleration, [0.1, -0.2, 0.05])
    rec = read_record(write(tmp_path, "d.txt", "0 1\n0.02 2\n0.04 3\n"), unit="g")
    np.testing.assert_allclose(rec.acceleration, np.array([1, 2, 3]) * 9.80665)


def test_rounded_printed_times_give_the_true_step(tmp_path):
    dt = 1.0 / 300.0
    text = "t [s] a [m/s^2]\n" + "".join(f"{i * dt:.5f} {i % 7}\n" for i in range(3000))
    rec = read_record(write(tmp_path, "r.txt", text))
    assert rec.dt == pytest.approx(dt, rel=1e-6) and rec.unit == "m/s^2"


def test_at2_written_and_read_back(tmp_path):
    acc = np.sin(np.arange(1234) * 0.01) * 3.3
    rec = read_at2(write_at2(Record("roundtrip", 0.01, acc), tmp_path / "r.AT2"))
    assert rec.name == "roundtrip" and rec.acceleration.size == 1234
    np.testing.assert_allclose(rec.acceleration, acc, rtol=1e-7, atol=1e-7 * 3.3)


# --- malformed files are refused with the line ------------------------------------------------
@pytest.mark.parametrize("name, text, line, words", [
    ("a.AT2", AT2_HEADER, 4, "4 header lines"),
    ("a.AT2", AT2_HEADER.replace("UNITS OF G", "UNITS OF CM/S/S") + "NPTS= 2, DT= 0.01 SEC\n0.1 0.2\n", 3,
     "UNITS OF G"),
    ("a.AT2", AT2_HEADER + "DT= 0.01\n0.1 0.2\n", 4, "NPTS"),
    ("a.AT2", AT2_HEADER + "NPTS= 2, DT= 0.0 SEC\n0.1 0.2\n", 4, "DT > 0"),
    ("a.AT2", AT2_HEADER + "NPTS= 4, DT= 0.01 SEC\n0.1 0.2\n0.3 abc\n", 6, "accelerations in g"),
    ("a.AT2", AT2_HEADER + "NPTS= 4, DT= 0.01 SEC\n0.1 0.2\n0.3\n", 7, "NPTS = 4 values"),
    ("a.AT2", AT2_HEADER + "NPTS= 3, DT= 0.01 SEC\n0.1 0.2\n0.3 0.4\n", 6, "NPTS = 3 values"),
    ("a.csv", "time [s], acc [g]\n0, 1\n0.01, 2\n0.02, 3, 4\n", 4, "two numbers"),
    ("a.csv", "time [s], acc [g]\n0, 1\n0.01, 2\n0.02, 3\n0.04, 3\n0.05, 3\n", 5, "uniform step"),
    ("a.csv", "time [s], acc [g]\n0, 1\n0.01, 2\n0.02, 3\n0.01, 3\n", 5, "greater than the previous"),
    ("a.csv", "time [s], acc [g]\n0, 1\n0.01, nan\n", 3, "finite"),
    ("a.csv", "time [s], acc [g]\n0, 1\n0.01, 2\nend of data\n", 4, "two numbers"),
    ("a.csv", "time [s], acc [g]\n0, 1\n0, 2\n", 3, "greater than the previous"),
    ("a.csv", "time [s], acc [g]\n0, 1\n", 3, "at least 2 rows"),
])
def test_malformed_files_are_refused_with_the_line(tmp_path, name, text, line, words):
    with pytest.raises(RecordFormatError) as err:
        read_record(write(tmp_path, name, text))
    assert err.value.line == line and words in str(err.value)
    assert f"line {line}:" in str(err.value) and name in str(err.value)


def test_two_column_without_a_stated_unit_is_refused(tmp_path):
    path = write(tmp_path, "u.csv", "0, 1\n0.01, 2\n")
    with pytest.raises(RecordFormatError, match="stated acceleration unit"):
        read_record(path)
    with pytest.raises(ValueError, match="record unit must be one of"):
        read_record(path, unit="furlong/fortnight^2")
    with pytest.raises(ValueError, match="in g by its format"):
        read_record(write(tmp_path, "x.AT2", AT2_HEADER + "NPTS= 2, DT= 0.01 SEC\n0.1 0.2\n"), unit="m/s^2")


# --- a record is the same excitation as the analytic function it samples ------------------------
def _sampled(fun, amplitude, omega, duration, dt):
    t = np.arange(int(round(duration / dt)) + 1) * dt
    return Record("sampled", dt, fun(t, amplitude, omega))


@pytest.mark.parametrize("amplitude_ratio", [1.2, 1.5, 2.0])
def test_at2_record_and_analytic_eq23_agree_within_interpolation_error(tmp_path, blc06, amplitude_ratio):
    """Same outcome; max rotation differs by the linear-interpolation error, which is O(dt^2):
    halving dt divides it by about 4 (the AT2 file's 7 digits are far below it)."""
    omega = 2.0 * blc06.p
    amplitude = amplitude_ratio * blc06.uplift_acceleration
    analytic = GroundMotion("modulated", amplitude, omega, excitation_duration("modulated", omega))
    exact = simulate(blc06, Anchorage(), Control("CS01"), analytic)
    errors = []
    for dt in (0.005, 0.0025):
        path = write_at2(_sampled(modulated, amplitude, omega, analytic.duration, dt), tmp_path / f"eq23_{dt}.AT2")
        res = simulate(blc06, Anchorage(), Control("CS01"), read_record(path).motion())
        assert res.overturned == exact.overturned
        errors.append(abs(res.max_rotation_ratio - exact.max_rotation_ratio))
    if exact.overturned:
        assert errors[1] < 1e-9
    else:
        assert errors[1] < 1e-3  # 0.1 % of alpha at dt = 2.5 ms
        assert 3.0 < errors[0] / errors[1] < 5.0


def _record_threshold(blc06, strategy, record, grid):
    """Upward scan and bisection (as spectra.threshold) with simulate on a record scaled by a ratio."""
    def overturns(ratio):
        motion = record.motion(ratio * blc06.uplift_acceleration)
        return simulate(blc06, Anchorage(), Control(strategy), motion).overturned
    values = grid.values()
    for j, a in enumerate(values):
        if overturns(a):
            lo, hi = (values[j - 1] if j else 1.0), a
            while hi - lo > grid.resolution:
                mid = 0.5 * (lo + hi)
                lo, hi = (lo, mid) if overturns(mid) else (mid, hi)
            return hi
    return math.nan


@pytest.mark.parametrize("strategy, frequency_ratio", [("FS", 2.0), ("CS01", 1.0)])
def test_one_sine_pulse_written_as_a_record_reproduces_the_one_sine_threshold(tmp_path, blc06, strategy,
                                                                               frequency_ratio):
    omega = frequency_ratio * blc06.p
    grid = AmplitudeGrid(resolution=0.001)
    analytic = threshold(Scenario(blc06, control=Control(strategy), excitation="one-sine"), frequency_ratio,
                         grid=grid)["amplitude_ratio"]
    unit = _sampled(one_sine, 1.0, omega, 2 * math.pi / omega, 0.0025)  # unit pulse, 1 m/s^2
    path = tmp_path / "pulse.csv"
    path.write_text("time [s], acceleration [m/s^2]\n"
                    + "".join(f"{t:.4f}, {a:.12e}\n" for t, a in zip(unit.times, unit.acceleration)))
    from_record = _record_threshold(blc06, strategy, read_record(path), grid)
    assert analytic is not None and from_record == pytest.approx(analytic, abs=2 * grid.resolution + 1e-3)


# --- the command line -------------------------------------------------------------------------------
def test_cli_simulate_record_matches_the_library_and_writes_history(tmp_path, capsys, blc06):
    omega = 2.0 * blc06.p
    rec = _sampled(modulated, 1.0, omega, excitation_duration("modulated", omega), 0.0025)
    path = write_at2(rec, tmp_path / "m.AT2")
    scale = 1.5 * blc06.uplift_acceleration
    main(["simulate", "--strategy", "CS01", "--record", str(path), "--record-scale", str(scale),
          "--output", str(tmp_path / "h.nc")])
    out = json.loads(capsys.readouterr().out)
    lib = simulate(blc06, Anchorage(), Control("CS01"), read_record(path).motion(scale))
    assert out["overturned"] is lib.overturned and out["max_rotation_ratio"] == lib.max_rotation_ratio
    assert out["excitation"] == "record" and out["record_npts"] == rec.acceleration.size
    assert out["pga_uplift_ratio"] == pytest.approx(scale * rec.pga / blc06.uplift_acceleration, rel=1e-6)
    import xarray as xr
    with xr.open_dataset(tmp_path / "h.nc") as ds:
        assert ds.attrs["excitation"] == "record" and ds.attrs["record_scale"] == scale


def test_cli_refuses_a_malformed_record_with_the_line(tmp_path, capsys):
    path = write(tmp_path, "bad.AT2", AT2_HEADER + "NPTS= 3, DT= 0.01 SEC\n0.1 0.2 zz\n")
    with pytest.raises(SystemExit) as exit_:
        main(["simulate", "--record", str(path)])
    assert exit_.value.code == 2
    err = capsys.readouterr().err
    assert "--record" in err and "line 5" in err
    with pytest.raises(SystemExit):
        main(["simulate", "--record", str(path), "--noise-level", "0.05"])
    assert "--noise-level" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["simulate", "--record-scale", "2"])
    assert "--record" in capsys.readouterr().err


# --- one column with a given step (OpenSees timeSeries Path -dt) ----------------------------------------
def _one_and_two_columns(tmp_path, blc06):
    omega = 2.0 * blc06.p
    rec = _sampled(modulated, 1.5 * blc06.uplift_acceleration / 9.80665, omega,
                   excitation_duration("modulated", omega), 0.005)
    one, two = tmp_path / "quake.txt", tmp_path / "quake.csv"
    values = [f"{a:.12e}" for a in rec.acceleration]
    one.write_text("# one value per line, OpenSees style\n" + "\n".join(values) + "\n")
    two.write_text("time [s], acceleration [g]\n"
                   + "".join(f"{i * 0.005:.4f}, {a}\n" for i, a in enumerate(values)))
    return one, two


def test_one_column_record_and_the_same_as_two_columns_give_the_same_outcome(tmp_path, blc06):
    one, two = _one_and_two_columns(tmp_path, blc06)
    a, b = read_record(one, "g", dt=0.005), read_record(two)
    np.testing.assert_array_equal(a.acceleration, b.acceleration)
    assert a.dt == pytest.approx(b.dt, rel=1e-12) and a.unit == b.unit == "g"
    ra = simulate(blc06, Anchorage(), Control("CS01"), a.motion())
    rb = simulate(blc06, Anchorage(), Control("CS01"), b.motion())
    sa, sb = ra.compact_summary(), rb.compact_summary()
    assert sa["status"] == sb["status"] and sa["n_impacts"] == sb["n_impacts"] and sa["n_uplifts"] == sb["n_uplifts"]
    for key in ("max_rotation_ratio", "end_time_s", "first_impact_s", "last_impact_s"):
        assert sa[key] == pytest.approx(sb[key], rel=1e-9), key
    assert ra.n_impacts > 0  # the record rocks the block
    # several values per line read in order
    many = tmp_path / "many.txt"
    many.write_text("accel [g]\n" + "\n".join(" ".join(f"{x:.12e}" for x in a.acceleration[i:i + 5] / 9.80665)
                                              for i in range(0, a.acceleration.size, 5)) + "\n")
    np.testing.assert_allclose(read_record(many, dt=0.005).acceleration, a.acceleration, rtol=1e-12)


def test_one_column_refuses_a_time_column_a_bad_step_and_an_at2_step(tmp_path, blc06):
    one, two = _one_and_two_columns(tmp_path, blc06)
    with pytest.raises(RecordFormatError, match="time column"):
        read_record(two, dt=0.005)
    with pytest.raises(ValueError, match=r"dt = 0 s is not allowed: allowed is 0 < dt"):
        read_record(one, "g", dt=0.0)
    with pytest.raises(RecordFormatError, match="unit"):
        read_record(one, dt=0.005)
    at2 = write_at2(read_record(two), tmp_path / "q.AT2")
    with pytest.raises(ValueError, match="states its own time step"):
        read_record(at2, dt=0.005)
