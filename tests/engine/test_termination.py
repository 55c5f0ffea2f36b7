"""Every loop of the scans and of the engine ends, whatever it is given: the bisection below a float
spacing, absurd brackets, and the compiled scans (which Ctrl-C cannot stop) run in a subprocess with a
time limit, so that a loop that does not end fails the test instead of hanging the suite."""
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import rockstudy
from rockstudy.engine import _kernel as kn
from rockstudy.engine._kernel.scan import (
    MAX_HALVINGS,
    S_HALVINGS,
    SPACING_FLOOR,
    scan_amplitude,
    scan_start,
    scan_update,
)

GRID = np.round(np.arange(0.9, 2.01, 0.1), 10)
TIME_LIMIT = 240  # [s] a fresh interpreter loads (or compiles) the engine, then runs a few hundred runs


def scan(overturns, resolution, lower=0.0, grid=GRID, limit=100_000):
    """Drive the scan state machine; fails (instead of hanging) past ``limit`` updates."""
    state, done, n = scan_start(), False, 0
    while not done:
        n += 1
        assert n <= limit, "the scan does not end"
        done = scan_update(state, grid, resolution, lower, overturns(float(scan_amplitude(state, grid))))
    return state, n


@pytest.mark.parametrize("resolution", [1e-300, 5e-324, 0.0, -1.0])
def test_bisection_ends_at_the_float_spacing_of_its_bracket(resolution):
    """A resolution below one float spacing: the bisection stops at a few spacings of the threshold,
    the bracket still holds it, within 52 halvings of the grid step (the bits of a float's mantissa)."""
    critical = 1.234
    state, n = scan(lambda a: a >= critical, resolution)
    lo, hi = state[kn.S_LO], state[kn.S_HI]
    assert lo < critical <= hi
    assert hi - lo <= SPACING_FLOOR * np.spacing(hi)
    assert state[S_HALVINGS] <= 52 and n == list(GRID).index(1.3) + 1 + state[S_HALVINGS]


def test_bisection_of_an_absurd_bracket_stops_at_its_cap():
    """A bracket of 600 decades (0 to 1e300, the threshold at 1e-250) cannot close at the float
    spacing in fewer than about 1900 halvings: the cap ends it, with the threshold still inside."""
    state, _ = scan(lambda a: a >= 1e-250, 1e-300, grid=np.array([1e300]))
    assert state[S_HALVINGS] == MAX_HALVINGS
    assert state[kn.S_LO] < 1e-250 <= state[kn.S_HI]


@pytest.mark.parametrize("critical", [0.95, 1.234, 1.99])
@pytest.mark.parametrize("resolution", [0.01, 1e-6, 1e-12])
def test_bisection_at_an_ordinary_resolution_is_plain_bisection(critical, resolution):
    """Above a few float spacings the floor never acts: the bracket is, bit for bit, that of a plain
    bisection from the first overturning grid point down to ``resolution``."""
    state, _ = scan(lambda a: a >= critical, resolution, lower=0.9)
    j = int(np.argmax(GRID >= critical))
    lo, hi = (GRID[j - 1] if j > 0 else 0.9), GRID[j]
    while hi - lo > resolution:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if mid >= critical else (mid, hi)
    assert (state[kn.S_LO], state[kn.S_HI]) == (lo, hi)


class _Critical:
    """A stand-in for :class:`~rockstudy.analysis.record_scan.RecordRun`: overturns from ``critical`` on."""

    def __init__(self, critical):
        self.critical, self.calls = critical, 0

    def outcome(self, amplitude_ratio):
        from rockstudy.engine.outcome import OVERTURNED_AFTER_IMPACT, SAFE
        self.calls += 1
        assert self.calls < 10_000, "record_threshold does not end"
        return OVERTURNED_AFTER_IMPACT if amplitude_ratio >= self.critical else SAFE


def test_record_threshold_ends_below_the_float_spacing():
    from rockstudy.analysis.record_scan import record_threshold
    run = _Critical(1.7)
    res = record_threshold(run, GRID, 1e-300)
    assert res["last_safe_amplitude_ratio"] < 1.7 <= res["amplitude_ratio"]
    assert res["amplitude_ratio"] - res["last_safe_amplitude_ratio"] <= SPACING_FLOOR * np.spacing(1.7)


def _in_subprocess(code: str) -> str:
    """``code`` in a fresh interpreter stopped after TIME_LIMIT seconds (compiled loops ignore Ctrl-C)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([os.path.dirname(os.path.dirname(rockstudy.__file__)),
                                                       os.environ.get("PYTHONPATH", "")]))
    try:
        res = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                             timeout=TIME_LIMIT, env=env)
    except subprocess.TimeoutExpired:
        pytest.fail(f"did not end within {TIME_LIMIT} s")
    assert res.returncode == 0, res.stderr
    return res.stdout


def test_compiled_scans_and_the_suite_fragility_end_below_the_float_spacing():
    """The compiled threshold scan and ``suite_fragility_dataset`` at resolution 1e-300: both return,
    with thresholds bracketed to a few float spacings."""
    out = _in_subprocess("""
        import numpy as np
        from rockstudy import BLOCK_PRESETS, Anchorage, Control, Scenario
        from rockstudy.analysis.spectra import AmplitudeGrid
        from rockstudy.engine import _kernel as kn
        from rockstudy.engine._kernel.scan import SPACING_FLOOR
        blc06 = BLOCK_PRESETS["BLC06"]
        case = Scenario(blc06, control=Control("FS"), noise_level=0.05).kernel_case(2.0, 0)
        thr, low, nsim, _ = kn.threshold_kernel(case.parameters, kn.writable(case.samples),
                                                kn.writable(case.vertical), AmplitudeGrid().values(), 1e-300,
                                                float(case.peak))
        assert np.isfinite(thr) and low < thr and thr - low <= SPACING_FLOOR * np.spacing(thr), (thr, low)
        from rockstudy.analysis.fragility import suite_fragility_dataset
        from rockstudy.model import record_suites
        entries = [record_suites.load_record("synthetic:SYN000")]
        ds = suite_fragility_dataset(blc06, Anchorage(), [Control("FS")], entries, np.arange(1.0, 5.01, 1.0),
                                     suite="synthetic", resolution=1e-300, n_boot=2, free_time=5.0)
        print(int(nsim), float(ds.threshold_intensity.values[0, 0]))
    """)
    assert len(out.split()) == 2


def test_a_run_of_a_billion_controller_samples_ends_within_the_step_budget():
    """A controller sampled every nanosecond over 31 s of motion (3·10^10 passes of the driver's loop,
    half an hour of compiled code that Ctrl-C cannot stop) ends as undetermined once it has spent
    ``MAX_STEPS``: at the time the budget's samples reach, within seconds."""
    out = _in_subprocess("""
        import math
        import numpy as np
        from rockstudy import BLOCK_PRESETS, Anchorage, Control
        from rockstudy.engine import _kernel as kn
        from rockstudy.engine.simulate import pack_parameters
        from rockstudy.model.excitation import GroundMotion
        b = BLOCK_PRESETS["BLC06"]
        motion = GroundMotion("one-sine", 0.5 * b.uplift_acceleration, 2 * b.p, math.pi / b.p)
        P = pack_parameters(b, Anchorage(), Control("CS01", sampling_time=1e-9), motion)
        r = kn.simulate_kernel(P, np.zeros(0), np.zeros(0), False, False)
        print(r.status, r.end_time)
    """)
    status, end_time = out.split()
    assert int(status) == kn.ST_ELIMIT
    assert float(end_time) == pytest.approx(kn.MAX_STEPS * 1e-9, rel=1e-3)


def test_a_run_whose_work_exceeds_the_limits_is_refused_before_it_starts():
    """A sampled controller or a step count past the limits of rockstudy.core.validation is refused by
    simulate() at once (before, T_s = 1e-9 s ran ~30 s to the engine's event cap and ended undetermined),
    and a run just within them is not."""
    import time

    from rockstudy.core import validation
    block = rockstudy.BLOCK_PRESETS["BLC06"]
    motion = rockstudy.GroundMotion(kind="modulated", amplitude=0.1, omega=10.0, duration=2.0)
    span = motion.end_time + 30.0  # the default free time
    t0 = time.perf_counter()
    with pytest.raises(validation.InputError, match=r"control.sampling_time = 1e-09 s .* controller samples"):
        rockstudy.simulate(block, rockstudy.Anchorage(), rockstudy.Control("CS01", sampling_time=1e-9), motion)
    fast = rockstudy.GroundMotion(kind="modulated", amplitude=0.1, omega=1e6, duration=2.0)
    with pytest.raises(validation.InputError, match=r"motion.omega = 1e\+06 .* steps"):
        rockstudy.simulate(block, rockstudy.Anchorage(), rockstudy.Control("FS"), fast)
    assert time.perf_counter() - t0 < 2.0
    within = 1.001 * span / validation.MAX_CONTROLLER_SAMPLES
    result = rockstudy.simulate(block, rockstudy.Anchorage(), rockstudy.Control("CS01", sampling_time=within), motion)
    assert result.status == "rest"  # 0.1 m/s^2 does not lift BLC06 (a g tan(alpha) of about 2.4 m/s^2)
