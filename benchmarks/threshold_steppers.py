"""Which stepper decides a threshold, and what each choice costs: one noisy spectrum scanned four ways
on one core, each threshold compared with the scan of Dormand–Prince runs throughout.

    python benchmarks/threshold_steppers.py [--strategy CS01] [--noise-level 0.05] [--realisations 40]
                                            [--rounds 3] [--config config.yaml]

The four scans (:func:`handover_scan`, built from ``rockstudy.engine._kernel.scan.run_scan``):

- ``taylor``: Taylor steps between the record's knots in every run (the study's scan);
- ``handover 0``: Taylor steps up to the first grid point they overturn the block at, then
  Dormand–Prince runs from that point on (that point again, any above it, the bisection);
- ``handover 3``: the same, Dormand–Prince from three grid points below that point;
- ``dopri``: Dormand–Prince runs throughout (the engine before the Taylor step, bit for bit).

Prints, per scan, how many of the spectrum's thresholds differ from ``dopri``'s and by more than one
amplitude step, and the scans' CPU time (one compiled scan per threshold, case building excluded), the
rounds interleaved, medians and their ratios to ``taylor`` and ``dopri``. The machine is shared:
compare the ratios, not the times.
"""
from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import time
from pathlib import Path

import numpy as np
import yaml
from converged_thresholds import SCENARIO_KEYS
from numba import njit

from rockstudy.analysis.spectra import _cases
from rockstudy.engine import _kernel as kernel
from rockstudy.engine._kernel.engine import takes_taylor_steps
from rockstudy.engine._kernel.scan import S_J, run_scan, scan_start, threshold_kernel, uplift_floor
from rockstudy.studies import parameters

SCANS = {"taylor": (1.0, -1), "handover 0": (1.0, 0), "handover 3": (1.0, 3), "dopri": (0.0, -1)}


@njit(cache=True)
def handover_scan(P, rec, vert, grid, resolution, unit_peak, handover):
    """The threshold scan of ``rockstudy.engine._kernel.scan.threshold_kernel``, handed over to
    Dormand–Prince runs near the threshold; the same returns.

    ``handover`` < 0: every run takes the stepper of ``P`` (the study's scan). ``handover`` = k >= 0,
    when the runs of ``P`` take Taylor steps: they scan upward only to the first grid point they
    overturn at (the last grid point if none); from k grid points below it Dormand–Prince runs scan
    on, so that point, any above it and every bisection point are Dormand–Prince outcomes. Every run
    is counted, the Taylor runs the hand-over repeats included.
    """
    if handover < 0 or not takes_taylor_steps(P, vert.shape[0]):
        return threshold_kernel(P, rec, vert, grid, resolution, unit_peak)
    counts = np.zeros(2, dtype=np.int64)
    lower = uplift_floor(vert, unit_peak)
    state = scan_start()
    run_scan(P, rec, vert, grid, math.inf, unit_peak, lower, state, counts)  # upward only: no bisection
    j = max(int(state[S_J]) - handover, 0)
    state = scan_start()
    state[S_J] = j
    dopri = P.copy()
    dopri[kernel.I_TAYLOR] = 0.0
    run_scan(dopri, rec, vert, grid, resolution, unit_peak, lower, state, counts)
    return state[kernel.S_HI], state[kernel.S_LO], counts[0], counts[1]


def scan_all(Pm, recs, rec_off, rec_len, vert, grid, resolution, peaks, handover):
    """handover_scan over every case (rows of Pm), one after the other; thresholds and simulations."""
    out, nsim = np.empty(len(Pm)), np.zeros(len(Pm), dtype=np.int64)
    for i in range(len(Pm)):
        rec = recs[rec_off[i]:rec_off[i] + rec_len[i]]
        out[i], _, nsim[i], _ = handover_scan(Pm[i], rec, vert, grid, resolution, peaks[i], handover)
    return out, nsim


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--config", type=Path, default=Path("config.yaml"))
    ap.add_argument("--strategy", default="CS01")
    ap.add_argument("--noise-level", type=float, default=0.05)
    ap.add_argument("--realisations", type=int, default=40)
    ap.add_argument("--rounds", type=int, default=3)
    args = ap.parse_args(argv)
    config = yaml.safe_load(args.config.read_text(encoding="utf-8"))
    base = parameters.scenario_from_dict({k: config[k] for k in SCENARIO_KEYS if k in config})
    scenario = dataclasses.replace(base, control=dataclasses.replace(base.control, strategy=args.strategy),
                                   noise_level=args.noise_level)
    freqs = parameters.frequency_ratios(config["frequency_grid"])
    grid = parameters.amplitude_grid(config["amplitude_grid"])
    Pm, recs, off, lens, peaks, _, _ = _cases(scenario, freqs, range(args.realisations))
    values, vert = grid.values(), np.zeros(0)
    print(f"{args.strategy} at noise level {args.noise_level:g}: {args.realisations} realisations x "
          f"{len(freqs)} frequencies = {len(Pm)} thresholds; {args.rounds} rounds, interleaved")

    def run(name, cases=slice(None)):
        P = Pm[cases].copy()
        P[:, kernel.I_TAYLOR] = SCANS[name][0]
        start = time.process_time()
        thr, nsim = scan_all(P, recs, off[cases], lens[cases], vert, values, float(grid.resolution), peaks[cases],
                             SCANS[name][1])
        return time.process_time() - start, thr, int(nsim.sum())

    for name in SCANS:  # compile (or load from the cache) outside the timed rounds
        run(name, slice(0, 1))
    times = {name: [] for name in SCANS}
    results = {}
    for r in range(args.rounds):
        for name in SCANS:
            seconds, thr, nsim = run(name)
            times[name].append(seconds)
            results[name] = (thr, nsim)
        print(f"  round {r + 1}: " + ", ".join(f"{n} {times[n][-1]:.2f} s" for n in SCANS), flush=True)
    ref = np.nan_to_num(results["dopri"][0], nan=1e9)
    med = {name: float(np.median(times[name])) for name in SCANS}
    step = float(grid.resolution)
    for name in SCANS:
        d = np.abs(np.nan_to_num(results[name][0], nan=1e9) - ref)
        print(f"{name:>11}: {int((d > 0).sum())} of {len(d)} thresholds differ from dopri's, "
              f"{int((d > step * (1 + 1e-9)).sum())} by more than one step; {results[name][1]} simulations; "
              f"median {med[name]:.2f} s CPU = {med[name] / med['taylor']:.2f}x taylor, "
              f"{med[name] / med['dopri']:.2f}x dopri")
    return 0


if __name__ == "__main__":
    sys.exit(main())
