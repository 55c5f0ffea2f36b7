"""Where one spectrum's threshold scans spend their time: every run of the scans timed, by the scan's
phase (the upward scan of the amplitude grid or the bisection) and by how the run ended, on one core.

    python benchmarks/scan_cost.py [--strategy CS01] [--noise-level 0.05] [--realisations 10]
                                   [--sampling-time 0] [--delay 0] [--config config.yaml]

The scans are driven from Python, one compiled run per amplitude, with the decisions of
``rockstudy.engine._kernel.scan.threshold_kernel`` (its state machine and its runs); the thresholds and safe
amplitudes are compared with the compiled scan's, which must all be the same. For each (phase, ending):
runs, their share of the runs' CPU time, the time per run, and how far into the excitation the runs end
(the mean of end time / duration of the excitation). Endings: ``bound`` (an early stop proved the run
safe), ``over`` (overturned), ``rest`` (at rest after the excitation), ``time`` (end of the free time),
``cap`` (event cap or step budget). The machine is shared: compare the shares, not the times.
"""
from __future__ import annotations

import argparse
import sys
import time
from collections import defaultdict

import numpy as np
from early_stop import add_case_options, spectrum_cases
from numba import njit

from rockstudy.engine._kernel.engine import driven_bound_data, run_kernel
from rockstudy.engine._kernel.layout import I_ALPHA, I_AMP, I_DUR, I_G
from rockstudy.engine._kernel.scan import (
    _NO,
    S_HI,
    S_LO,
    SCANNING,
    scan_amplitude,
    scan_start,
    scan_update,
    threshold_kernel,
    uplift_floor,
)

ENDINGS = ("rest", "over", "time", "cap", "bound")
"""How a run ended, by its status code (``layout.ST_REST`` ... ``layout.ST_BOUND``)."""


@njit(cache=True)
def run_at(P, rec, vert, B, amplitude_ratio):
    """One run of the scans (``scan.case_outcome`` past its uplift test): (status, end time [s])."""
    Q = P.copy()
    Q[I_AMP] = amplitude_ratio * P[I_G] * np.tan(P[I_ALPHA])
    res = run_kernel(Q, rec, vert, B, _NO[0], _NO[1])
    return res.status, res.end_time


def scan_timed(P, rec, vert, grid, resolution, unit_peak, table):
    """The threshold scan of one case, each run timed into ``table[(phase, ending)]`` = [runs, CPU [s],
    sum of end time / duration]; returns (threshold, highest safe amplitude)."""
    B = driven_bound_data(P, rec, vert)
    state, lower, done = scan_start(), uplift_floor(vert, unit_peak), False
    while not done:
        phase = "up" if state[0] == SCANNING else "bisect"
        amplitude = scan_amplitude(state, grid)
        overturned = False
        if not (vert.shape[0] == 0 and amplitude * unit_peak <= 1.0):  # NO_UPLIFT: no run
            start = time.perf_counter()
            status, end = run_at(P, rec, vert, B, amplitude)
            row = table[(phase, ENDINGS[status])]
            row[0] += 1
            row[1] += time.perf_counter() - start
            row[2] += end / P[I_DUR]
            overturned = status == 1
        done = scan_update(state, grid, resolution, lower, overturned)
    return state[S_HI], state[S_LO]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_case_options(ap)
    args = ap.parse_args(argv)
    Pm, recs, off, lens, peaks, values, res = spectrum_cases(args)
    vert = np.zeros(0)
    cases = [(Pm[i], recs[off[i]:off[i] + lens[i]], peaks[i]) for i in range(len(Pm))]
    print(f"{args.strategy}, T_s {args.sampling_time:g} s, delay {args.delay:g} s, noise level "
          f"{args.noise_level:g}: {len(Pm)} thresholds", flush=True)
    compiled = np.array([threshold_kernel(P, rec, vert, values, res, peak)[:2] for P, rec, peak in cases])
    table = defaultdict(lambda: [0, 0.0, 0.0])
    scan_timed(*cases[0][:2], vert, values, res, cases[0][2], defaultdict(lambda: [0, 0.0, 0.0]))  # compile
    timed = np.array([scan_timed(P, rec, vert, values, res, peak, table) for P, rec, peak in cases])
    differ = int((~((timed == compiled) | (np.isnan(timed) & np.isnan(compiled)))).any(axis=1).sum())
    total = sum(row[1] for row in table.values())
    print(f"{'phase':7s} {'ending':6s} {'runs':>7s} {'CPU share':>10s} {'per run':>10s} {'ends at':>8s}")
    for (phase, ending), (n, cpu, ends) in sorted(table.items(), key=lambda kv: -kv[1][1]):
        print(f"{phase:7s} {ending:6s} {n:7d} {100 * cpu / total:9.1f} % {1e3 * cpu / n:7.3f} ms "
              f"{ends / n:7.2f} T")
    print(f"runs' CPU {total:.2f} s; thresholds or safe amplitudes that differ from the compiled scan's: "
          f"{differ} of {len(Pm)}")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
