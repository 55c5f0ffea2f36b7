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


# ---- the two steppers in one scan ------------------------------------------------------------
def test_a_taylor_scan_handed_over_to_dormand_prince_is_decided_by_dormand_prince(blc06):
    """A run of the default study that grazes overturning (FS, 10 % noise, realisation 24,
    ω_p/p = 3.55): the Taylor step overturns the block at 5.1 where Dormand–Prince does not.
    Handed over at the first grid point the Taylor step overturns at, the threshold, its bracket and
    every outcome from there on are Dormand–Prince's, and every run is counted; without the
    hand-over (the study's scan) the threshold is the Taylor step's own."""
    from rockstudy.analysis.scenario import Scenario
    from rockstudy.analysis.spectra import AmplitudeGrid
    from rockstudy.engine._kernel.scan import (
        is_overturned,
        outcome_kernel,
        takes_taylor_steps,
        threshold_kernel,
        threshold_scan,
    )
    from rockstudy.engine.outcome import NO_UPLIFT
    from rockstudy.model.control import Control

    case = Scenario(blc06, control=Control("FS"), noise_level=0.10).kernel_case(3.55, 24)
    rec, vert, peak = kn.writable(case.samples), kn.writable(case.vertical), float(case.peak)
    taylor = case.parameters
    dopri = taylor.copy()
    dopri[kn.I_TAYLOR] = 0.0
    assert takes_taylor_steps(taylor, len(vert)) and not takes_taylor_steps(dopri, len(vert))
    grid = AmplitudeGrid().values()
    lower = float(kn.uplift_floor(vert, peak))

    def outcomes(P):
        return lambda a: is_overturned(outcome_kernel(P, rec, vert, a, peak))

    handed = threshold_scan(taylor, rec, vert, grid, 0.01, peak, 0)
    throughout = threshold_kernel(dopri, rec, vert, grid, 0.01, peak)
    taylor_alone = run_scan(outcomes(taylor), lower=lower, grid=grid)
    dopri_alone = run_scan(outcomes(dopri), lower=lower, grid=grid)
    assert handed[:2] == throughout[:2] == pytest.approx(dopri_alone[:2], abs=0)
    assert threshold_kernel(taylor, rec, vert, grid, 0.01, peak)[:2] == pytest.approx(taylor_alone[:2], abs=0)
    assert abs(taylor_alone[0] - handed[0]) > 0.1          # the case does test the hand-over
    assert outcomes(dopri)(handed[0]) and not outcomes(dopri)(handed[1])

    # runs: the Taylor step's upward scan to its first overturning grid point, then Dormand–Prince's
    # scan from that grid point; points the record cannot uplift the block at are not simulated
    def simulated(tried):
        return sum(outcome_kernel(dopri, rec, vert, a, peak) != NO_UPLIFT for a in tried)

    first = next(a for a in grid if outcomes(taylor)(a))
    upward = [a for a in grid if a <= first]
    from_first = [a for a in dopri_alone[2] if a >= first or a not in grid]
    assert handed[2] == simulated(upward + from_first) and throughout[2] == simulated(dopri_alone[2])
