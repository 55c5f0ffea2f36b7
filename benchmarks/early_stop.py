"""The early stop during the excitation, measured and checked: one spectrum's threshold scans with the
stop and without it (the same scans, the stop's level set to 0 so that it never fires), on one core.

    python benchmarks/early_stop.py [--strategy CS01] [--noise-level 0.05] [--realisations 10]
                                    [--sampling-time 0] [--delay 0] [--rounds 3] [--config config.yaml]

Prints how many thresholds (and safe amplitudes below them) differ between the two scans, which must be
none, and the scans' CPU time, rounds interleaved, medians and their ratio. The machine is shared:
compare the ratio, not the times.
"""
from __future__ import annotations

import argparse
import dataclasses
import sys
import time
from pathlib import Path

import numpy as np
import yaml
from converged_thresholds import SCENARIO_KEYS
from numba import njit

from rockstudy.analysis.spectra import _cases
from rockstudy.engine._kernel.engine import driven_bound_data
from rockstudy.engine._kernel.layout import B_LEVEL
from rockstudy.engine._kernel.scan import (
    DONE,
    S_HI,
    S_LO,
    S_PHASE,
    case_outcome,
    is_overturned,
    scan_amplitude,
    scan_start,
    scan_update,
    uplift_floor,
)
from rockstudy.studies import parameters


@njit(cache=True)
def scan_case(P, rec, vert, grid, resolution, unit_peak, stop):
    """The threshold scan of ``rockstudy.engine._kernel.scan.threshold_kernel``, with the early stop
    during the excitation (``stop``) or without it; returns (threshold, highest safe amplitude)."""
    B = driven_bound_data(P, rec, vert)
    if not stop:
        B[B_LEVEL] = 0.0  # nothing is below 0: the stop never fires
    state = scan_start()
    lower = uplift_floor(vert, unit_peak)
    done = state[S_PHASE] == DONE
    while not done:
        o = case_outcome(P, rec, vert, B, scan_amplitude(state, grid), unit_peak)
        done = scan_update(state, grid, resolution, lower, is_overturned(o))
    return state[S_HI], state[S_LO]


def scan_all(Pm, recs, off, lens, vert, grid, resolution, peaks, stop):
    out = np.empty((len(Pm), 2))
    for i in range(len(Pm)):
        out[i] = scan_case(Pm[i], recs[off[i]:off[i] + lens[i]], vert, grid, resolution, peaks[i], stop)
    return out


def add_case_options(ap: argparse.ArgumentParser) -> None:
    """The options that choose one spectrum's cases (the study's config, a strategy, noise level, number of
    realisations, sampling time and delay)."""
    ap.add_argument("--config", type=Path, default=Path("config.yaml"))
    ap.add_argument("--strategy", default="CS01")
    ap.add_argument("--noise-level", type=float, default=0.05)
    ap.add_argument("--realisations", type=int, default=10)
    ap.add_argument("--sampling-time", type=float, default=0.0)
    ap.add_argument("--delay", type=float, default=0.0)


def spectrum_cases(args):
    """The cases of the spectrum :func:`add_case_options` chose, packed as the study's scans pack them:
    (parameters, records, offsets, lengths, unit peaks, amplitude grid values, resolution)."""
    config = yaml.safe_load(args.config.read_text(encoding="utf-8"))
    base = parameters.scenario_from_dict({k: config[k] for k in SCENARIO_KEYS if k in config})
    control = dataclasses.replace(base.control, strategy=args.strategy, sampling_time=args.sampling_time,
                                  delay=args.delay)
    scenario = dataclasses.replace(base, control=control, noise_level=args.noise_level)
    freqs = parameters.frequency_ratios(config["frequency_grid"])
    grid = parameters.amplitude_grid(config["amplitude_grid"])
    Pm, recs, off, lens, peaks, _, _ = _cases(scenario, freqs, range(args.realisations))
    return Pm, recs, off, lens, peaks, grid.values(), float(grid.resolution)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_case_options(ap)
    ap.add_argument("--rounds", type=int, default=3)
    args = ap.parse_args(argv)
    Pm, recs, off, lens, peaks, values, res = spectrum_cases(args)
    vert = np.zeros(0)
    print(f"{args.strategy}, T_s {args.sampling_time:g} s, delay {args.delay:g} s, noise level "
          f"{args.noise_level:g}: {len(Pm)} thresholds; {args.rounds} rounds, interleaved")
    for stop in (True, False):  # compile (or load from the cache) outside the timed rounds
        scan_all(Pm[:1], recs, off[:1], lens[:1], vert, values, res, peaks[:1], stop)
    times, results = {True: [], False: []}, {}
    for r in range(args.rounds):
        for stop in (True, False):
            start = time.process_time()
            results[stop] = scan_all(Pm, recs, off, lens, vert, values, res, peaks, stop)
            times[stop].append(time.process_time() - start)
        print(f"  round {r + 1}: with the stop {times[True][-1]:.2f} s, without {times[False][-1]:.2f} s", flush=True)
    differ = int((~((results[True] == results[False]) | (np.isnan(results[True]) & np.isnan(results[False]))))
                 .any(axis=1).sum())
    med = {k: float(np.median(v)) for k, v in times.items()}
    print(f"thresholds or safe amplitudes that differ: {differ} of {len(Pm)}; median CPU with the stop "
          f"{med[True]:.2f} s, without {med[False]:.2f} s ({med[True] / med[False]:.2f}x)")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
