"""Speed of the engines and of spectra (issues 2 and 3). Prints figures; asserts nothing.

    python benchmarks/bench_engines.py [--quick]

Single-core figures: numba is limited to one thread. Medians of repeats are reported;
the machine is shared, so compare ratios measured in the same run.
"""
from __future__ import annotations

import argparse
import statistics
import time

import numba

from rockstudy import BLOCK_PRESETS, Anchorage, Control
from rockstudy.simulate import simulate
from rockstudy.spectra import AmplitudeGrid, Scenario, frequency_grid, spectrum, threshold

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


def bench_engines(repeats_fast, repeats_ref):
    print("engine comparison (CPU time per simulation, median)")
    print(f"{'case':44s} {'fast [ms]':>10s} {'ref [ms]':>10s} {'ratio':>8s} {'sim s/CPU s':>12s}")
    ratios, rates = [], []
    for strategy, exc, fr, ar, noise, ts in CASES:
        sc = Scenario(BLOCK, Anchorage(), Control(strategy, sampling_time=ts), excitation=exc, noise_level=noise)
        motion, _ = sc.motion(fr, ar, 0)
        res = simulate(sc.block, sc.anchorage, sc.control, motion)
        tf = median_time(lambda: simulate(sc.block, sc.anchorage, sc.control, motion), repeats_fast)
        tr = median_time(lambda: simulate(sc.block, sc.anchorage, sc.control, motion, engine="reference"), repeats_ref)
        ratios.append(tr / tf)
        rates.append(res.end_time / tf)
        label = f"{strategy} {exc} w/p={fr} a={ar} r={noise} Ts={ts}"
        print(f"{label:44s} {tf*1e3:10.3f} {tr*1e3:10.1f} {tr/tf:8.0f} {res.end_time/tf:12.0f}")
    print(f"median speed-up fast/reference: {statistics.median(ratios):.0f}x (target >= 300x)")
    print(f"median simulated seconds per CPU second (fast): {statistics.median(rates):.0f} (target >= 10000)")


def bench_spectra(n_realisations):
    grid = AmplitudeGrid()
    freqs = frequency_grid()
    sc = Scenario(BLOCK, Anchorage(), Control("CS01"))
    spectrum(sc, freqs[:2], grid=grid)  # compile
    t0 = time.perf_counter()
    ds = spectrum(sc, freqs, grid=grid)
    t = time.perf_counter() - t0
    n = int(ds.n_simulations.sum())
    print(f"noise-free CS01 spectrum, {len(freqs)} frequencies: {t:.1f} s, {n} simulations, {t/n*1e3:.3f} ms/sim")
    sc = Scenario(BLOCK, Anchorage(), Control("CS01"), noise_level=0.05, seed=1)
    t0 = time.perf_counter()
    ds = spectrum(sc, freqs, realisations=range(n_realisations), grid=grid)
    t = time.perf_counter() - t0
    n = int(ds.n_simulations.sum())
    print(f"{n_realisations}-realisation CS01 spectrum at 5% noise: {t:.1f} s, {n} simulations, "
          f"{t/n*1e3:.3f} ms/sim in the batch (target: 40 realisations < 120 s)")
    # the same simulations one call at a time from Python (compiled first: not timed)
    k = 0
    threshold(sc, float(freqs[0]), realisation=k, grid=grid)
    t0 = time.perf_counter()
    for fr in freqs[::6]:
        threshold(sc, float(fr), realisation=k, grid=grid)
    t_single = time.perf_counter() - t0
    n_single = int(ds.n_simulations.sel(realisation=k).values[::6].sum())
    print(f"single threshold calls: {t_single/n_single*1e3:.3f} ms/sim "
          f"(batch/single = {(t/n)/(t_single/n_single):.2f})")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="fewer repeats and realisations")
    args = ap.parse_args()
    numba.set_num_threads(1)
    bench_engines(5 if args.quick else 20, 1 if args.quick else 3)
    bench_spectra(4 if args.quick else 40)


if __name__ == "__main__":
    main()
