"""benchmarks/threshold_steppers.py: its scan handed over from Taylor-step runs to Dormand–Prince runs
near the threshold is decided by Dormand–Prince, and counts every run."""
import sys
from pathlib import Path

import pytest

from rockstudy.engine import _kernel as kn

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import threshold_steppers  # noqa: E402  (a script beside its sibling converged_thresholds)


def run_scan(overturns, lower, grid, resolution=0.01):
    """The scan state machine driven by ``overturns(a)``: (threshold, last safe, amplitudes tried)."""
    state, tried, done = kn.scan_start(), [], False
    while not done:
        a = float(kn.scan_amplitude(state, grid))
        tried.append(a)
        done = kn.scan_update(state, grid, resolution, lower, overturns(a))
    return state[kn.S_HI], state[kn.S_LO], tried


def test_a_taylor_scan_handed_over_to_dormand_prince_is_decided_by_dormand_prince(blc06):
    """A run of the default study that grazes overturning (FS, 10 % noise, realisation 24,
    ω_p/p = 3.55): the Taylor step overturns the block at 5.1 where Dormand–Prince does not.
    Handed over at the first grid point the Taylor step overturns at, the threshold, its bracket and
    every outcome from there on are Dormand–Prince's, and every run is counted; without the
    hand-over (the study's scan) the threshold is the Taylor step's own."""
    from rockstudy.analysis.scenario import Scenario
    from rockstudy.analysis.spectra import AmplitudeGrid
    from rockstudy.engine._kernel.engine import takes_taylor_steps
    from rockstudy.engine._kernel.scan import is_overturned, outcome_kernel, threshold_kernel
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

    handed = threshold_steppers.handover_scan(taylor, rec, vert, grid, 0.01, peak, 0)
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
