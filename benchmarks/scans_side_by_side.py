"""Two versions' threshold scans timed taking turns: one worker process per version, each with its own
empty numba cache, run the same cases one after the other, case by case and round by round, so that the
machine's load falls on both alike. Prints, per case, each version's fastest and median CPU time, the
ratios, and whether their thresholds are the same.

    python benchmarks/scans_side_by_side.py [--before 26765bf] [--after HEAD] [--rounds 12]
                                            [--realisations 3] [--cases cs01,cs02,fs,free,ts]

``--before`` and ``--after`` are commits of this repository (their ``src`` is taken with ``git archive``)
or folders holding a ``rockstudy`` package. The cases are the default study's spectra (``config.yaml``):
``cs01``, ``cs02``, ``fs`` at 5 % noise, ``free`` (CS01 without noise, Dormand–Prince steps) and ``ts``
(CS01 at 5 % noise sampled at T_s = 2.5 ms), each for ``--realisations`` noise realisations on the study's
frequency grid, packed once by this checkout (``early_stop.spectrum_cases``) and handed to both versions'
``threshold_kernel``: the two must share the kernel's parameter layout, or their thresholds differ and the
line says so. A worker compiles its version in its first round, outside the timing. One numba thread.
Prints the figures and asserts nothing; a change that must not slow the scans shows ratios near 1 in the
fastest times (the medians move more with the load).
"""
from __future__ import annotations

import argparse
import hashlib
import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CASES = {"cs01": ["--strategy", "CS01"], "cs02": ["--strategy", "CS02"], "fs": ["--strategy", "FS"],
         "free": ["--strategy", "CS01", "--noise-level", "0"],
         "ts": ["--strategy", "CS01", "--sampling-time", "0.0025"]}
"""The cases by name, as ``early_stop.py``'s options."""


def parse(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--before", default="26765bf", help="commit or folder with a rockstudy package (default 26765bf)")
    ap.add_argument("--after", default="HEAD", help="commit or folder with a rockstudy package (default HEAD)")
    ap.add_argument("--rounds", type=int, default=12)
    ap.add_argument("--realisations", type=int, default=3)
    ap.add_argument("--cases", default=",".join(CASES), help=f"comma-separated, of {', '.join(CASES)}")
    ap.add_argument("--worker", help=argparse.SUPPRESS)  # the packed cases' file: run as a worker
    args = ap.parse_args(argv)
    unknown = sorted(set(args.cases.split(",")) - set(CASES))
    if unknown:
        ap.error(f"--cases: unknown {unknown}; allowed: {', '.join(CASES)}")
    if args.rounds < 1 or args.realisations < 1:
        ap.error("--rounds and --realisations must be at least 1")
    return args


def source(version: str, where: Path) -> Path:
    """The folder holding the ``rockstudy`` package of ``version`` (a folder, or a commit extracted to ``where``)."""
    if (Path(version) / "rockstudy").is_dir():
        return Path(version).resolve()
    archive = where / f"{version.replace('/', '_')}.tar"
    subprocess.run(["git", "-C", str(ROOT), "archive", "-o", str(archive), version, "src"], check=True)
    with tarfile.open(archive) as tar:
        tar.extractall(where / version.replace("/", "_"), filter="data")
    return where / version.replace("/", "_") / "src"


def pack(names, realisations: int, path: Path) -> None:
    """Pack the cases ``names`` into ``path`` (.npz) with this checkout's rockstudy."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import early_stop
    arrays = {}
    for name in names:
        ap = argparse.ArgumentParser()
        early_stop.add_case_options(ap)
        args = ap.parse_args(CASES[name] + ["--realisations", str(realisations), "--config", str(ROOT / "config.yaml")])
        Pm, recs, off, lens, peaks, values, res = early_stop.spectrum_cases(args)
        for key, value in dict(P=Pm, recs=recs, off=off, lens=lens, peaks=peaks, values=values, res=res).items():
            arrays[f"{name}.{key}"] = np.asarray(value)
    np.savez(path, **arrays)


def worker(path: str) -> None:
    """Serve the packed cases: read a case's name per line, scan it, answer "CPU seconds, thresholds' hash"."""
    from rockstudy.engine import _kernel as kernel
    data = np.load(path)
    vert = np.zeros(0)

    def scan(name):
        P, recs, off, lens = (data[f"{name}.{k}"] for k in ("P", "recs", "off", "lens"))
        peaks, values, res = data[f"{name}.peaks"], data[f"{name}.values"], float(data[f"{name}.res"])
        return [kernel.threshold_kernel(P[i], recs[off[i]:off[i] + lens[i]], vert, values, res, peaks[i])
                for i in range(len(P))]

    print("ready", flush=True)
    for line in sys.stdin:
        start = time.process_time()
        results = scan(line.strip())
        seconds = time.process_time() - start
        digest = hashlib.sha1(np.array([np.asarray(r, dtype=float) for r in results]).tobytes()).hexdigest()[:10]
        print(f"{seconds:.4f} {digest}", flush=True)


def main(argv=None) -> int:
    args = parse(argv)
    if args.worker:
        worker(args.worker)
        return 0
    names = args.cases.split(",")
    with tempfile.TemporaryDirectory(prefix="rockstudy-scans-") as tmp:
        tmp = Path(tmp)
        cases = tmp / "cases.npz"
        pack(names, args.realisations, cases)
        workers = {}
        for label in ("before", "after"):
            version = getattr(args, label)
            env = dict(os.environ, PYTHONPATH=str(source(version, tmp)), NUMBA_NUM_THREADS="1",
                       NUMBA_CACHE_DIR=str(tmp / f"numba-{label}"))
            workers[label] = subprocess.Popen([sys.executable, __file__, "--worker", str(cases)], env=env,
                                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, cwd=tmp)
        for label, process in workers.items():
            if process.stdout.readline().strip() != "ready":
                raise SystemExit(f"the {label} worker did not start ({getattr(args, label)})")
        times = {(label, name): [] for label in workers for name in names}
        digests = {}
        print(f"before {args.before}, after {args.after}: {len(names)} cases of {args.realisations} realisations, "
              f"{args.rounds} rounds after one to compile", flush=True)
        for r in range(args.rounds + 1):
            for name in names:
                for label in (("before", "after") if r % 2 else ("after", "before")):
                    workers[label].stdin.write(name + "\n")
                    workers[label].stdin.flush()
                    seconds, digest = workers[label].stdout.readline().split()
                    if r:  # the first round compiles
                        times[(label, name)].append(float(seconds))
                    digests[(label, name)] = digest
        for process in workers.values():
            process.stdin.close()
            process.wait()
    print(f"{'case':6s} {'before: fastest, median':>24s} {'after: fastest, median':>24s} {'ratio':>16s}  thresholds")
    for name in names:
        b, a = times[("before", name)], times[("after", name)]
        same = "same" if digests[("before", name)] == digests[("after", name)] else "DIFFER"
        print(f"{name:6s} {min(b):11.3f} {statistics.median(b):8.3f} s {min(a):11.3f} {statistics.median(a):8.3f} s "
              f"{min(a) / min(b):7.3f} {statistics.median(a) / statistics.median(b):6.3f}x  {same}")
    print("ratio: after / before, of the fastest and of the medians")
    return 0


if __name__ == "__main__":
    sys.exit(main())
