"""Bitwise fingerprint of the fast engine: run many random cases and save every field of each
:class:`~rockstudy.engine._kernel.layout.KernelResult`, or compare two saved fingerprints bit for bit.

A refactor or speed-up of ``rockstudy.engine._kernel`` that must not change results is checked by
running ``save`` on the code before and after (e.g. from a ``git worktree`` with ``PYTHONPATH``
pointed at its ``src``) and then ``compare``:

    NUMBA_NUM_THREADS=1 python benchmarks/kernel_fingerprint.py save before.npz
    NUMBA_NUM_THREADS=1 python benchmarks/kernel_fingerprint.py save after.npz
    python benchmarks/kernel_fingerprint.py compare before.npz after.npz

A change that is allowed to move results by round-off or by the integrator's tolerance (another
embedded pair, say) is checked with ``compare --tolerance``: every run must end in the same way
(status), and its times and largest rotation must agree to the relative tolerance given; it prints
how many runs are bitwise equal, equal within the tolerance, and which differ in what:

    python benchmarks/kernel_fingerprint.py compare before.npz after.npz --tolerance 1e-4

A change to the early stops (runs that may end sooner as safe, status ``ST_BOUND``) is checked with
``compare --early-stop``: every run bitwise equal, or ended as safe by the stop in B no later than in A,
where A did not overturn either; it prints which fields the earlier stops change:

    python benchmarks/kernel_fingerprint.py compare before.npz after.npz --early-stop

The cases cover every strategy, sampling time, delay, anchorage and overturn criterion, on noisy
records, the analytic excitations and (``--vertical``) vertical records, with histories and logs
switched on and off, and (``--sensor``) the controller's sensor. The same seed gives the same
cases, so two fingerprints of the same code are identical. Few of those runs reach the early stops
(which only outcome runs take); ``save --stops`` makes every run an outcome run as the threshold scans
make it (no history, no log, the stops on), at amplitudes where most runs are safe, and prints how the
runs ended: a change to the stops or to what they read is checked there.
"""
from __future__ import annotations

import argparse
import dataclasses
import math
import sys

import numpy as np

from rockstudy import BLOCK_PRESETS, Anchorage, Control
from rockstudy.engine import _kernel as kn
from rockstudy.engine.simulate import kernel_record, pack_parameters
from rockstudy.model.excitation import GroundMotion, modulated_duration
from rockstudy.model.noise import noisy_record, record_motion

BLC06 = BLOCK_PRESETS["BLC06"]


def cases(n: int, seed: int, sensor: bool, vertical: bool, stepper: str | None = None, sampled: bool = False,
          stops: bool = False):
    """(P, record, vertical record, want_history, want_log) of ``n`` random runs; with ``sampled`` every run
    has sampled control (T_s from the record step up, a T_s that is no multiple of it, delays from none to
    several samples) and two in three runs a noisy record; with ``stops`` every run is an outcome run with
    the early stops on (no history, no log), at 1 to 2.5 times the uplift acceleration."""
    rng = np.random.default_rng(seed)
    records = [(noisy_record("modulated", fr * BLC06.p, 0.05, k, 7), fr * BLC06.p)
               for k, fr in enumerate((0.7, 1.5, 3.0, 4.5))]
    for i in range(n):
        strategy = ("FS", "PASSIVE", "CS01", "CS02")[i % 4]
        if sampled:
            sampling = (0.0025, 0.003, 0.01, 0.05, 0.1, 0.2)[(i // 4) % 6]
            delay = float(rng.choice([0, 0, 0.0025, 0.02, 0.06]))
        else:
            sampling = (0.0, 0.0, 0.01, 0.1)[(i // 4) % 4]
            delay = 0.0 if sampling == 0 else float(rng.choice([0, 0.02, 0.06]))
        band = float(rng.choice([5.0, 20.0, 60.0])) if sensor else None
        control = Control(strategy, sampling_time=sampling, delay=delay, sensor_band=band)
        kmax = float(rng.uniform(0.1, 4.0))
        anchorage = Anchorage(kappa_max=kmax, kappa_min=float(rng.choice([0.0, rng.uniform(0, kmax)])),
                              damping_ratio=float(rng.uniform(0, 0.1)),
                              spring_ultimate_rotation=float(rng.uniform(0.3, 1.2) * BLC06.alpha),
                              damper_ultimate_rotation=float(rng.uniform(0.3, 1.2) * BLC06.alpha))
        amplitude = float(rng.uniform(1.0, 2.5 if stops else 4.0)) * BLC06.uplift_acceleration
        if (i % 3 != 2) if sampled else (i % 3 == 0):
            rec, omega = records[int(rng.integers(len(records)))]
            motion = record_motion(rec, amplitude, omega)
        else:
            omega = float(rng.uniform(0.5, 5.0)) * BLC06.p
            kind = "modulated" if i % 3 == 1 else "one-sine"
            end = modulated_duration(omega) if kind == "modulated" else 2 * math.pi / omega
            motion = GroundMotion(kind, amplitude, omega, end)
        if vertical and i % 2 == 0:  # a vertical record at 5 ms over the first half of the excitation
            t = np.arange(int(0.5 * motion.duration / 0.005) + 2) * 0.005
            vert = 0.3 * BLC06.gravity * np.sin(float(rng.uniform(0.5, 5.0)) * omega * t)
            motion = dataclasses.replace(motion, vertical_dt=0.005, vertical=vert)
        th0 = float(rng.uniform(-0.5, 0.5) * BLC06.alpha) if i % 11 == 0 else 0.0
        P = pack_parameters(BLC06, anchorage, control, motion, overturn_criterion="alpha" if i % 5 == 0 else "flat",
                            free_time=10.0, energy_bound=stops or bool(i % 2), initial_rotation=th0,
                            **({} if stepper is None else {"stepper": stepper}))
        want_history, want_log = (False, False) if stops else (bool((i // 2) % 2), bool((i // 3) % 2))
        yield P, kn.writable(kernel_record(control, motion)), kn.writable(motion.vertical), want_history, want_log


STATUS_NAMES = {kn.ST_OVER: "overturned", kn.ST_BOUND: "ended as safe by an early stop", kn.ST_REST: "at rest",
                kn.ST_ELIMIT: "undetermined"}
"""How a run ended, by its ``status`` (the others: the run's end)."""


def save(path: str, n: int, seed: int, sensor: bool, vertical: bool, stepper: str | None = None,
         sampled: bool = False, stops: bool = False) -> None:
    fields, ended = {}, {}
    for i, (P, rec, vert, want_history, want_log) in enumerate(cases(n, seed, sensor, vertical, stepper, sampled,
                                                                     stops)):
        result = kn.simulate_kernel(P, rec, vert, want_history, want_log)
        for name, value in zip(kn.KernelResult._fields, result):
            fields[f"{i}/{name}"] = np.array(value, copy=True)
        how = STATUS_NAMES.get(int(result.status), "at the end of the run")
        ended[how] = ended.get(how, 0) + 1
    np.savez_compressed(path, **fields)
    counts = sorted(ended.items(), key=lambda kv: -kv[1])
    print(f"{n} runs saved to {path}: " + ", ".join(f"{v} {k}" for k, v in counts))


TOLERANCE_FIELDS = ("overturn_time", "end_time", "max_abs_theta", "fracture_times")
"""Fields compared to a relative tolerance in ``compare --tolerance``; ``status`` must be equal."""


def _within(u, v, rtol: float) -> bool:
    """Same shape and every entry equal within ``rtol`` (relative to the larger, NaN equal to NaN)."""
    if u.shape != v.shape:
        return False
    both_nan = np.isnan(u) & np.isnan(v)
    scale = np.maximum(np.abs(u), np.abs(v))
    return bool(np.all(both_nan | (np.abs(u - v) <= rtol * scale)))


def _early_stop_fields(x, y, r: str):
    """The fields of run ``r`` that differ between A (``x``) and B (``y``) when B ended it as safe by an
    early stop no later than A and A did not overturn it; None when the run differs otherwise."""
    sx, sy = int(x[f"{r}/status"]), int(y[f"{r}/status"])
    if sx == kn.ST_OVER or sy != kn.ST_BOUND or not float(y[f"{r}/end_time"]) <= float(x[f"{r}/end_time"]):
        return None
    if not (np.isnan(x[f"{r}/overturn_time"]) and np.isnan(y[f"{r}/overturn_time"])):
        return None
    return [f for f in kn.KernelResult._fields if not np.array_equal(x[f"{r}/{f}"], y[f"{r}/{f}"], equal_nan=True)]


def compare_early_stop(x, y, runs, bad) -> int:
    """``compare --early-stop``: every run that differs is one that B ended earlier as safe and A did not
    overturn. Returns 0 when that holds, 1 otherwise."""
    counts, wrong = {}, []
    for r in bad:
        fields = _early_stop_fields(x, y, r)
        if fields is None:
            wrong.append(r)
            continue
        for f in fields:
            counts[f] = counts.get(f, 0) + 1
    for r in wrong[:20]:
        print(f"run {r}: status {int(x[f'{r}/status'])} -> {int(y[f'{r}/status'])}, not an earlier safe stop")
    overturned = sum(int(x[f"{r}/status"]) == kn.ST_OVER for r in runs)
    print(f"{len(runs)} runs compared ({overturned} overturned in A): {len(runs) - len(bad)} bitwise equal, "
          f"{len(bad) - len(wrong)} ended earlier as safe by the stop in B, {len(wrong)} otherwise different"
          + (f"; fields changed by the earlier stops: {', '.join(f'{k} {v}' for k, v in counts.items())}"
             if counts else ""))
    return 1 if wrong else 0


def compare(a: str, b: str, tolerance: float | None = None, early_stop: bool = False) -> int:
    """Compare two fingerprints: bit for bit, or (``tolerance``) each run's ending and its
    :data:`TOLERANCE_FIELDS` to a relative tolerance. Returns 0 when they agree, 1 otherwise."""
    x, y = np.load(a), np.load(b)
    if sorted(x.files) != sorted(y.files):
        print("the fingerprints hold different runs or fields")
        return 1
    fields_of = {}
    for k in x.files:
        fields_of.setdefault(k.split("/")[0], []).append(k)
    runs = sorted(fields_of, key=int)
    bad = [r for r in runs if any(not np.array_equal(x[k], y[k], equal_nan=True) or x[k].dtype != y[k].dtype
                                  for k in fields_of[r])]
    if early_stop:
        return compare_early_stop(x, y, runs, bad)
    if tolerance is None:
        for r in bad[:20]:
            print(f"run {r} differs")
        print(f"{len(runs)} runs compared, {len(bad)} differ")
        return 1 if bad else 0
    failed, counts = [], {}
    for r in bad:
        wrong = [] if x[f"{r}/status"] == y[f"{r}/status"] else ["status"]
        wrong += [f for f in TOLERANCE_FIELDS if not _within(x[f"{r}/{f}"], y[f"{r}/{f}"], tolerance)]
        for f in wrong:
            counts[f] = counts.get(f, 0) + 1
        if wrong:
            failed.append((r, wrong))
    for r, wrong in failed[:20]:
        print(f"run {r}: {', '.join(wrong)} beyond the tolerance")
    print(f"{len(runs)} runs compared at relative tolerance {tolerance:g}: {len(runs) - len(bad)} bitwise equal, "
          f"{len(bad) - len(failed)} within the tolerance, {len(failed)} beyond it"
          + (f" ({', '.join(f'{k}: {v}' for k, v in counts.items())})" if counts else ""))
    return 1 if failed else 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="command", required=True)
    s = sub.add_parser("save", help="run the cases and save every result field")
    s.add_argument("path")
    s.add_argument("-n", type=int, default=1500, help="number of runs (default 1500)")
    s.add_argument("--seed", type=int, default=77)
    s.add_argument("--sensor", action="store_true", help="give the controller a sensor (random band)")
    s.add_argument("--vertical", action="store_true", help="add vertical records to every other run")
    s.add_argument("--sampled", action="store_true",
                   help="sampled control in every run (T_s 2.5 ms to 0.2 s, delays), mostly on noisy records")
    s.add_argument("--stops", action="store_true",
                   help="outcome runs only, the early stops on, mostly safe: the runs the stops end")
    s.add_argument("--stepper", choices=("taylor", "dopri"), default=None,
                   help="how the engine steps between record knots (default: the engine's default; code from "
                        "before the Taylor step has no such choice and always uses Dormand-Prince)")
    c = sub.add_parser("compare", help="compare two saved fingerprints bit for bit (or to a tolerance)")
    c.add_argument("a")
    c.add_argument("b")
    c.add_argument("--tolerance", type=float, default=None,
                   help="compare each run's ending and times to this relative tolerance instead of bit for bit")
    c.add_argument("--early-stop", action="store_true",
                   help="allow runs that B ends earlier as safe (ST_BOUND) where A did not overturn; else bit for bit")
    args = ap.parse_args(argv)
    if args.command == "save":
        save(args.path, args.n, args.seed, args.sensor, args.vertical, args.stepper, args.sampled, args.stops)
        return 0
    return compare(args.a, args.b, args.tolerance, args.early_stop)


if __name__ == "__main__":
    sys.exit(main())
