"""Every entry of a ground motion is bounded by the declared amplitude range: generated over every way a ground
motion is made (the analytic pulses, a record's factor, its samples, the vertical samples, a record scaled, a
record read from a file, a scenario's run) and over strengths no declaration allows (just past the bound,
far past it, at the edge of float range, either sign). Each is refused where the ground motion is made, naming
the input, within 2 s -- never run as a block that "never moved". A strength inside the bound is accepted.
"""
from __future__ import annotations

import math
import time

import numpy as np
import pytest

from rockstudy.analysis.scenario import Scenario
from rockstudy.core.limits import MAX_GROUND_ACCELERATION
from rockstudy.model.block import BLOCK_PRESETS
from rockstudy.model.excitation import GroundMotion
from rockstudy.model.records import Record, read_one_column

BLOCK = BLOCK_PRESETS["BLC06"]


def _read(peak, tmp):
    path = tmp / "record.txt"
    path.write_text(f"0.0\n{peak!r}\n0.0\n0.0\n")
    return read_one_column(path, dt=0.01, unit="m/s^2").motion()


ENTRIES = {
    "one-sine": lambda a, tmp: GroundMotion("one-sine", a, 10.0, 0.6),
    "modulated": lambda a, tmp: GroundMotion("modulated", a, 10.0, 3.0),
    "rectangular": lambda a, tmp: GroundMotion("rectangular", a, 0.0, 0.5),
    "record-factor": lambda a, tmp: GroundMotion("record", a, 1.0, 0.02, 0.01, np.array([0.0, 1.0, 0.0])),
    "record-samples": lambda a, tmp: GroundMotion("record", 1.0, 1.0, 0.02, 0.01, np.array([0.0, a, 0.0])),
    "vertical": lambda a, tmp: GroundMotion("one-sine", 1.0, 10.0, 0.6, vertical_dt=0.01,
                                            vertical=np.array([0.0, a, 0.0])),
    "Record.motion-scale": lambda a, tmp: Record("r", 0.01, np.array([0.0, 1.0, 0.0])).motion(scale=a),
    "Record-samples": lambda a, tmp: Record("r", 0.01, np.array([0.0, a, 0.0])).motion(),
    "read_one_column": _read,
    "Scenario.motion": lambda a, tmp: Scenario(block=BLOCK).motion(2.0, a / BLOCK.uplift_acceleration)[0],
}
TOO_STRONG = {"just-past": MAX_GROUND_ACCELERATION * (1 + 1e-6), "far-past": 1e10, "float-edge": 1e300,
              "negative": -1e300}


@pytest.mark.parametrize(("entry", "strength"), [pytest.param(e, s, id=f"{e}-{s}") for e in ENTRIES
                                                 for s in TOO_STRONG])
def test_a_strength_no_declaration_allows_is_refused_where_the_motion_is_made(entry, strength, tmp_path):
    amplitude = TOO_STRONG[strength]
    if entry == "Scenario.motion" and amplitude < 0:
        amplitude = -MAX_GROUND_ACCELERATION  # an amplitude ratio below 0
    t0 = time.perf_counter()
    with pytest.raises(ValueError) as refused:
        ENTRIES[entry](amplitude, tmp_path)
    assert time.perf_counter() - t0 < 2.0
    text = str(refused.value)
    assert len(text.splitlines()) <= 3 and " is not allowed" in text, text


@pytest.mark.parametrize("entry", ENTRIES)
def test_a_strength_inside_the_bound_is_accepted(entry, tmp_path):
    amplitude = 100 * 9.80665  # 100 g: an amplitude ratio of about 400 for BLC06
    motion = ENTRIES[entry](amplitude, tmp_path)
    peak = max(abs(motion.amplitude) * (np.max(np.abs(motion.record)) if motion.kind == "record" else 1.0),
               float(np.max(np.abs(motion.vertical))) if motion.vertical.size else 0.0)
    assert math.isclose(peak, amplitude, rel_tol=1e-9)
