"""The one threshold scan (rockstudy.engine._kernel.scan), against hand-worked outcome sequences.

Both engines drive this state machine, so agreement between engines cannot guard it: these
oracles do (an upward grid scan, then a bisection to the resolution; safe islands above the
first overturning amplitude are not looked at).
"""
import numpy as np
import pytest

from rockstudy.engine import _kernel as kn
from rockstudy.engine._kernel.scan import scan_amplitude, scan_start, scan_update

GRID = np.round(np.arange(0.9, 2.01, 0.1), 10)


def run_scan(overturns, resolution=0.01, lower=0.0, grid=GRID):
    """Drive the scan with ``overturns(a)``; returns (threshold, last safe, amplitudes tried)."""
    state, tried, done = scan_start(), [], False
    while not done:
        a = float(scan_amplitude(state, grid))
        tried.append(a)
        done = scan_update(state, grid, resolution, lower, overturns(a))
    return state[kn.S_HI], state[kn.S_LO], tried


@pytest.mark.parametrize("critical", [1.234, 1.0501, 1.9999, 0.95])
def test_monotone_case_brackets_the_critical_amplitude(critical):
    thr, lo, tried = run_scan(lambda a: a >= critical)
    assert lo < critical <= thr and thr - lo <= 0.01
    first = GRID[GRID >= critical][0]
    assert tried[: list(GRID).index(first) + 1] == list(GRID[GRID <= first])  # every grid point up to it
    assert thr <= first


def test_bisection_halves_the_bracket_to_the_resolution():
    thr, lo, tried = run_scan(lambda a: a >= 1.234)
    # grid: ... 1.2 safe, 1.3 overturns; then 1.25 (o), 1.225 (s), 1.2375 (o), 1.23125 (s)
    assert tried[-4:] == pytest.approx([1.25, 1.225, 1.2375, 1.23125])
    assert (lo, thr) == pytest.approx((1.23125, 1.2375))


def test_safe_island_above_the_first_overturning_point_is_not_the_threshold():
    # unsafe in [1.3, 1.5), safe again above: the lowest threshold is the answer
    thr, lo, _ = run_scan(lambda a: 1.3 <= a < 1.5)
    assert lo < 1.3 <= thr <= 1.3 + 0.01


def test_nothing_overturns_on_the_grid():
    thr, lo, tried = run_scan(lambda a: False)
    assert np.isnan(thr) and lo == GRID[-1] and tried == list(GRID)


def test_overturning_at_the_first_grid_point_uses_the_uplift_floor():
    thr, lo, _ = run_scan(lambda a: a >= 0.85, lower=0.8)
    assert 0.8 <= lo < 0.85 <= thr and thr - lo <= 0.01

