"""Empty data is refused at every entry, never turned into a number: generated over every sequence argument of
the entries that fit, sweep, gather or summarise many runs, and over the forms an empty sequence takes (a list,
a tuple, a numpy array of no items). Each case replaces one argument of a valid call by an empty one; the
call must refuse it (a ``ValueError``: :class:`InputError` or the entry's own) in at most three lines naming
that argument, before any simulation.
"""
from __future__ import annotations

import time

import numpy as np
import pytest

from rockstudy.analysis import fragility, fragility_fit, record_scan, utility_index
from rockstudy.analysis.scenario import Scenario
from rockstudy.analysis.spectra import spectrum
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import BLOCK_PRESETS
from rockstudy.model.control import Control
from rockstudy.model.record_suites import load_record
from rockstudy.model.records import Record
from rockstudy.studies import design

BLOCK = BLOCK_PRESETS["BLC06"]
CONTROLS = [Control(strategy="FS"), Control(strategy="PASSIVE")]
RECORD = Record(name="pulse", dt=0.01, acceleration=np.sin(np.linspace(0.0, np.pi, 51)))


def _entries():
    return [load_record("synthetic:SYN000")]


ENTRIES = {
    # name: (callable, valid keyword arguments, the sequence arguments)
    "fit_lognormal": (fragility_fit.fit_lognormal,
                      {"im": [0.5, 1.0, 2.0], "n_total": [10, 10, 10], "n_overturned": [1, 5, 9]},
                      ("im", "n_total", "n_overturned")),
    "fit_lognormal_points": (fragility_fit.fit_lognormal_points,
                             {"im": [0.5, 1.0, 2.0, 3.0], "overturned": [False, True, False, True]},
                             ("im", "overturned")),
    "fit_lognormal_thresholds": (fragility_fit.fit_lognormal_thresholds,
                                 {"thresholds": [0.5, 1.0, 1.5], "censored_above": [3.0, 3.0, 3.0]},
                                 ("thresholds", "censored_above")),
    "utility_index": (utility_index.utility_index, {"a_sys": [1.0, 2.0], "a_ref": [1.0, 1.5], "a_max0": 3.0},
                      ("a_sys", "a_ref")),
    "stripe_outcomes": (fragility.stripe_outcomes,
                        {"block": BLOCK, "anchorage": Anchorage(), "controls": CONTROLS, "records": [RECORD],
                         "levels": [0.5]}, ("controls", "records", "levels")),
    "fragility_dataset": (fragility.fragility_dataset,
                          {"block": BLOCK, "anchorage": Anchorage(), "controls": CONTROLS, "records": [RECORD],
                           "levels": [0.5, 1.0], "n_boot": 2}, ("controls", "records", "levels")),
    "fragility_from_stripes": (fragility.fragility_from_stripes,
                               {"block": BLOCK, "anchorage": Anchorage(), "controls": CONTROLS,
                                "records": [RECORD], "levels": [0.5, 1.0],
                                "overturned": np.zeros((2, 1, 2), bool), "scale": np.ones((1, 2)), "n_boot": 2},
                               ("controls", "records", "levels")),
    "suite_fragility_dataset": (fragility.suite_fragility_dataset,
                                {"block": BLOCK, "anchorage": Anchorage(), "controls": CONTROLS,
                                 "entries": "entries", "levels": [0.5, 1.0], "suite": "x", "n_boot": 2},
                                ("controls", "entries", "levels")),
    "suite_summary": (fragility.suite_summary, {"datasets": "never called with data"}, ("datasets",)),
    "stripes_and_thresholds": (record_scan.stripes_and_thresholds,
                               {"block": BLOCK, "anchorage": Anchorage(), "controls": CONTROLS, "records": [RECORD],
                                "levels": [0.5, 1.0], "intensities": [1.0], "resolution": 0.1},
                               ("controls", "records", "levels")),
    "spectrum": (spectrum, {"scenario": Scenario(block=BLOCK), "frequency_ratios": [2.0], "realisations": [0]},
                 ("frequency_ratios", "realisations")),
    "fragility_medians_g": (design.fragility_medians_g,
                            {"block": BLOCK, "anchorage": Anchorage(), "controls": CONTROLS, "records": [RECORD],
                             "levels_g": [0.1, 0.2]}, ("controls", "records", "levels_g")),
    "device_point": (design.device_point,
                     {"block": BLOCK, "kappa_max": 1.0, "damping_ratio": 0.05, "strategies": ["FS", "PASSIVE"],
                      "records": [RECORD], "levels_g": [0.1, 0.2], "suite": "x"},
                     ("strategies", "records", "levels_g")),
    "gather_devices": (design.gather_devices, {"points": "never called with data"}, ("points",)),
    "gather_blocks": (design.gather_blocks, {"points": "never called with data"}, ("points",)),
}
EMPTY = {"list": lambda: [], "tuple": lambda: (), "array": lambda: np.empty(0)}

CASES = [pytest.param(entry, arg, form, id=f"{entry}-{arg}-{form}")
         for entry, (_, _, args) in ENTRIES.items() for arg in args for form in EMPTY]


def test_the_generation_covers_every_entry():
    assert len(CASES) == 3 * sum(len(args) for _, _, args in ENTRIES.values())
    assert len(ENTRIES) >= 15


@pytest.mark.parametrize(("entry", "arg", "form"), CASES)
def test_an_empty_sequence_is_refused_naming_it(entry, arg, form):
    call, valid, _ = ENTRIES[entry]
    kwargs = {k: (_entries() if isinstance(v, str) and v == "entries" else v) for k, v in valid.items()}
    kwargs[arg] = EMPTY[form]()
    t0 = time.perf_counter()
    with pytest.raises(ValueError) as refused:
        call(**kwargs)
    assert time.perf_counter() - t0 < 5.0, "refused only after work"
    assert arg in str(refused.value), str(refused.value)
    assert len(str(refused.value).splitlines()) <= 3
