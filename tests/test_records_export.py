"""One record of a suite for other tools (`rockstudy records --export`), and the time accessor of a
record set."""
import json

import numpy as np
import pytest

from rockstudy.cli import main
from rockstudy.model import record_suites
from rockstudy.model.records import read_at2, unit_factor

RECORD = "synthetic:SYN001"  # made by rockstudy itself: no optional package needed


def test_one_column_holds_every_sample_and_the_summary_gives_dt(tmp_path, capsys):
    _, record = record_suites.load_record(RECORD)
    main(["records", "--export", RECORD, "--output", str(tmp_path / "a.txt")])
    out = json.loads(capsys.readouterr().out)
    values = np.loadtxt(tmp_path / "a.txt")
    assert values.ndim == 1 and values.size == record.acceleration.size == out["npts"]
    np.testing.assert_allclose(values, record.acceleration, rtol=1e-9, atol=1e-12)
    assert out["dt_s"] == record.dt and out["unit"] == record.unit
    assert out["to_m_per_s2"] == unit_factor(record.unit)
    assert out["duration_s"] == pytest.approx((record.acceleration.size - 1) * record.dt)
    assert f"-dt {record.dt:g} " in out["opensees"] and str(tmp_path / "a.txt") in out["opensees"]


def test_two_column_and_at2_carry_the_times(tmp_path, capsys):
    _, record = record_suites.load_record(RECORD)
    main(["records", "--export", RECORD, "--format", "two-column", "--output", str(tmp_path / "b.txt")])
    capsys.readouterr()
    t, a = np.loadtxt(tmp_path / "b.txt", unpack=True)
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
