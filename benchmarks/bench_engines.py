"""Speed of the engines and of spectra. Prints figures; asserts nothing.

    python benchmarks/bench_engines.py [--quick] [--skip-reference]

Single-core figures: numba is limited to one thread. Medians of repeats (CPU time) are reported;
the machine is shared, so compare ratios measured in the same run. Each shortcut of the fast engine is
measured switched off ("old") and on ("new") side by side:

* ``energy bound``: outcome runs (threshold scans, maps) end once the block provably cannot
  overturn any more (docs/model.md). Histories and ``simulate()`` never use it.
  Under sampled control (T_s > 0) the bound is the weaker half-cycle bound (docs/model.md, "Early
  stop under sampled control"); "old" there means no early stop at all, as before it existed.
  (An opt-in ``step_across_knots`` was measured here at 6-12x slower and removed.)

The selective inlining of the hot calls (docs/model.md, "What a step costs") is compiled in and
has no switch: measure it as code before/after, e.g. this script run from a ``git worktree`` of
the older commit (``PYTHONPATH=<worktree>/src``) and from main, one after the other.

"simulated seconds" are those of the full run (to rest or the time limit), so that the rate of an
outcome run that stops early counts the motion it no longer needs to integrate.
"""
from __future__ import annotations

import argparse
import statistics
import time

import numba
import numpy as np

from rockstudy import BLOCK_PRESETS, Anchorage, Control
from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, frequency_grid, spectrum, threshold
from rockstudy.engine import _kernel as kn
from rockstudy.engine.simulate import pack_parameters, simulate

BLOCK = BLOCK_PRESETS["BLC06"]
CASES = [  # strategy, excitation, frequency ratio, amplitude ratio, noise, T_s
    ("FS", "modulated", 2.0, 1.2, 0.0, 0.0),
    ("CS01", "modulated", 2.0, 1.5, 0.0, 0.0),
    ("CS02", "modulated", 2.0, 1.4, 0.0, 0.0),
    ("CS01", "modulated", 2.0, 1.5, 0.05, 0.1),
    ("CS02", "one-sine", 3.0, 2.0, 0.0, 0.0),
    ("PASSIVE", "modulated", 1.0, 1.3, 0.05, 0.0),
]


def median_time(fn, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.process_time()
        fn()
        times.append(time.process_time() - t0)
    return statistics.median(times)


def bench_engines(repeats_fast, repeats_ref, reference=True):
    print("engine comparison (CPU time per simulation, median); outcome runs with the energy bound off / on")
    print(f"{'case':44s} {'fast [ms]':>10s} {'ref [ms]':>10s} {'ratio':>7s} {'sim s/CPU s':>12s} "
          f"{'outcome old/new [ms]':>21s} {'sim s/CPU s old/new':>20s}")
    ratios, rates, rates_old, rates_new = [], [], [], []
    for strategy, exc, fr, ar, noise, ts in CASES:
        sc = Scenario(BLOCK, Anchorage(), Control(strategy, sampling_time=ts), excitation=exc, noise_level=noise)
        motion, _ = sc.motion(fr, ar, 0)
        res = simulate(sc.block, sc.anchorage, sc.control, motion)
        tf = median_time(lambda sc=sc, motion=motion: simulate(sc.block, sc.anchorage, sc.control, motion),
                         repeats_fast)
        tr = float("nan")
        if reference:
            tr = median_time(lambda sc=sc, motion=motion: simulate(sc.block, sc.anchorage, sc.control, motion,
                                                                   engine="reference"), repeats_ref)
            ratios.append(tr / tf)
        rates.append(res.end_time / tf)
        outcome = {}
        for key, bound in (("old", False), ("new", True)):
            P = pack_parameters(sc.block, sc.anchorage, sc.control, motion, energy_bound=bound)
            kn.simulate_kernel(P, motion.record, motion.vertical, False, False)
            outcome[key] = median_time(
                lambda P=P, motion=motion: kn.simulate_kernel(P, motion.record, motion.vertical, False, False),
                repeats_fast)
        rates_old.append(res.end_time / outcome["old"])
        rates_new.append(res.end_time / outcome["new"])
        label = f"{strategy} {exc} w/p={fr} a={ar} r={noise} Ts={ts}"
        print(f"{label:44s} {tf*1e3:10.3f} {tr*1e3:10.1f} {tr/tf:7.0f} {res.end_time/tf:12.0f} "
              f"{outcome['old']*1e3:10.3f}/{outcome['new']*1e3:<10.3f} {rates_old[-1]:9.0f}/{rates_new[-1]:<10.0f}")
    if ratios:
        print(f"median speed-up fast/reference: {statistics.median(ratios):.0f}x (target >= 300x)")
    print(f"median simulated seconds per CPU second (fast, simulate()): {statistics.median(rates):.0f}")
    print("median simulated seconds per CPU second (outcome runs): energy bound off "
          f"{statistics.median(rates_old):.0f}, on {statistics.median(rates_new):.0f} (target >= 20000)")


def bench_spectra(n_realisations):
    grid = AmplitudeGrid()
    freqs = frequency_grid()
    sc = Scenario(BLOCK, Anchorage(), Control("CS01"))
    for bound in (False, True):
        spectrum(sc, freqs[:2], grid=grid, energy_bound=bound)  # compile
    for bound in (False, True):
        t0 = time.perf_counter()
        ds = spectrum(sc, freqs, grid=grid, energy_bound=bound)
        t = time.perf_counter() - t0
        n = int(ds.n_simulations.sum())
        print(f"noise-free CS01 spectrum, {len(freqs)} frequencies, energy bound {'on ' if bound else 'off'}: "
              f"{t:.1f} s, {n} simulations, {t/n*1e3:.3f} ms/sim")
    for ts, target in ((0.0, " (target: 40 realisations <= 40 s)"), (0.1, "")):
        sc = Scenario(BLOCK, Anchorage(), Control("CS01", sampling_time=ts), noise_level=0.05, seed=1)
        results, times = {}, {}
        for bound in (False, True):
            t0 = time.process_time()
            ds = spectrum(sc, freqs, realisations=range(n_realisations), grid=grid, energy_bound=bound)
            times[bound] = t = time.process_time() - t0
            n = int(ds.n_simulations.sum())
            results[bound] = ds
            print(f"{n_realisations}-realisation CS01 T_s={ts:g} s spectrum at 5% noise, energy bound "
                  f"{'on ' if bound else 'off'}: {t:.1f} s CPU, {n} simulations, {t/n*1e3:.3f} ms/sim{target}")
        same = all(np.array_equal(results[False][v].values, results[True][v].values, equal_nan=True)
                   for v in ("threshold_realisation", "last_safe", "n_simulations", "n_undetermined"))
        print(f"  bound on/off: {times[False] / times[True]:.2f}x less CPU; thresholds identical: {same}")
    # the same simulations one call at a time from Python (compiled first: not timed)
    k = 0
    threshold(sc, float(freqs[0]), realisation=k, grid=grid)
    t0 = time.perf_counter()
    for fr in freqs[::6]:
        threshold(sc, float(fr), realisation=k, grid=grid)
    t_single = time.perf_counter() - t0
    ds = results[True]
    n_single = int(ds.n_simulations.sel(realisation=k).values[::6].sum())
    print(f"single threshold calls: {t_single/n_single*1e3:.3f} ms/sim")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="fewer repeats and realisations")
    ap.add_argument("--skip-reference", action="store_true", help="do not time the (slow) reference engine")
    ap.add_argument("--engines-only", action="store_true", help="only the per-simulation figures")
    ap.add_argument("--realisations", type=int, default=None, help="realisations of the noisy spectrum")
    args = ap.parse_args()
    numba.set_num_threads(1)
    bench_engines(5 if args.quick else 20, 1 if args.quick else 3, reference=not args.skip_reference)
    if not args.engines_only:
        bench_spectra(args.realisations or (4 if args.quick else 40))


if __name__ == "__main__":
    main()
