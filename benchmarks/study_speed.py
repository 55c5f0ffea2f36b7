"""Two versions of the study side by side: fresh clones of BEFORE and AFTER (commits of this repository),
the default study run in each, one after the other on this machine with the same settings and an empty
numba cache, and the CPU and wall ratios, overall and per family of jobs, from the jobs' own logs.

    python benchmarks/study_speed.py [--before 2d3e047] [--after HEAD] [--jobs 2] [--workdir DIR]
                                     [--target TARGET ...] [--repeat N] [--keep] [--logs-only]

Each job's log under ``results/logs/`` ends with its run time, CPU time and peak memory; the families
are the compile (``compile_engine``), the noise records (``noise/``), the threshold scans (``spectra/``,
``timing/``, ``maps/``) and the rest. The whole run's wall time and the CPU time of every process it
started are measured around ``snakemake``. ``--logs-only`` reads the logs of clones a previous run kept
(``--keep``) without running again. ``--repeat N`` runs the pair N times, in alternating order and
each time from fresh clones, prints each pair's ratios and then the medians: the CPU time of one
version's study moves by a few per cent from run to run. The machine may be shared: say what else ran
(``uptime``, ``ps``).
Prints the figures and asserts nothing; the results folders are left for
``.ci/slurm/compare_results.py`` when ``--keep`` is given.
"""
from __future__ import annotations

import argparse
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

RESOURCES = re.compile(r"resources: ([0-9.]+) s run time, ([0-9.]+) s CPU")
FAMILIES = (("compile", ("compile_engine",)), ("noise", ("noise/",)), ("scans", ("spectra/", "timing/", "maps/")))


def family(log: Path, logs: Path) -> str:
    """The family of a job from its log's path under ``logs``."""
    rel = log.relative_to(logs).as_posix()
    for name, prefixes in FAMILIES:
        if rel.startswith(prefixes):
            return name
    return "other"


def job_times(results: Path) -> dict:
    """{family: [jobs, run time, CPU time]} summed over the jobs' logs under ``results/logs``. [s]"""
    logs = results / "logs"
    out = {name: [0, 0.0, 0.0] for name in ("compile", "noise", "scans", "other")}
    for log in sorted(logs.rglob("*.log")):
        found = RESOURCES.findall(log.read_text(encoding="utf-8", errors="replace"))
        if found:
            run, cpu = map(float, found[-1])
            row = out[family(log, logs)]
            row[0] += 1
            row[1] += run
            row[2] += cpu
    return out


def clone(repo: Path, commit: str, where: Path) -> None:
    if where.exists():
        shutil.rmtree(where)
    subprocess.run(["git", "clone", "--quiet", "--no-hardlinks", str(repo), str(where)], check=True)
    subprocess.run(["git", "-C", str(where), "checkout", "--quiet", commit], check=True)


def run_study(where: Path, jobs: int, targets: list[str]) -> tuple[float, float]:
    """Run the study in the clone ``where`` with its own sources first on the path; (wall, CPU) of all
    the processes it started. [s]"""
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_CACHE")}
    env["PYTHONPATH"] = str(where / "src")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    with open(where / "study_speed.log", "w", encoding="utf-8") as log:
        subprocess.run(["snakemake", "-j", str(jobs), *targets], cwd=where, env=env, stdout=log,
                       stderr=subprocess.STDOUT, check=True)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def report(label: dict, totals: dict, families: dict) -> None:
    a, b = label["before"], label["after"]
    print(f"{'':>10} {a:>22} {b:>22}  ratio")
    if totals:
        for i, name in enumerate(("wall", "CPU")):
            x, y = totals["before"][i], totals["after"][i]
            print(f"{'study ' + name:>10} {x:>20.1f} s {y:>20.1f} s  {y / x:.2f}x")
    for name in ("compile", "noise", "scans", "other"):
        x, y = families["before"][name], families["after"][name]
        if x[2] > 0:
            print(f"{name:>10} {x[2]:>10.1f} s CPU ({x[0]:>3} jobs) {y[2]:>10.1f} s CPU ({y[0]:>3} jobs)  "
                  f"{y[2] / x[2]:.2f}x CPU, {y[1] / x[1]:.2f}x run time")
    x = [sum(v[2] for v in families[k].values()) for k in ("before", "after")]
    print(f"{'jobs':>10} {x[0]:>20.1f} s {x[1]:>20.1f} s  {x[1] / x[0]:.2f}x CPU (the jobs' own logs)")
    if totals:  # Snakemake itself, and each job's process before and after its own account (start, exit)
        y = [totals[k][1] - x[i] for i, k in enumerate(("before", "after"))]
        print(f"{'outside':>10} {y[0]:>20.1f} s {y[1]:>20.1f} s  CPU outside the jobs' logs (Snakemake, exits)")


def medians(rows: list) -> tuple[tuple[float, float], dict]:
    """((wall, CPU), {family: [jobs, run time, CPU time]}), each the median over the runs ``rows`` of
    (wall, CPU, :func:`job_times`). [s]"""
    totals = (statistics.median(r[0] for r in rows), statistics.median(r[1] for r in rows))
    families = {name: [rows[0][2][name][0]] + [statistics.median(r[2][name][i] for r in rows) for i in (1, 2)]
                for name in rows[0][2]}
    return totals, families


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--before", default="2d3e047", help="commit of the first side (default: release 0.2.0)")
    ap.add_argument("--after", default="HEAD", help="commit of the second side (default: HEAD)")
    ap.add_argument("--repo", type=Path, default=Path("."), help="repository to clone (default: here)")
    ap.add_argument("--workdir", type=Path, default=Path("/tmp/study_speed"))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--target", nargs="*", default=[], help="snakemake targets (default: the default study)")
    ap.add_argument("--repeat", type=int, default=1, help="pairs run, in alternating order; medians printed")
    ap.add_argument("--keep", action="store_true", help="keep the clones and their results (of the last pair)")
    ap.add_argument("--logs-only", action="store_true", help="read the logs of kept clones; run nothing")
    args = ap.parse_args(argv)
    repo = args.repo.resolve()
    sides = {}
    for side in ("before", "after"):
        commit = subprocess.run(["git", "-C", str(repo), "rev-parse", "--short", getattr(args, side)],
                                check=True, capture_output=True, text=True).stdout.strip()
        sides[side] = (commit, args.workdir / side)
    if args.repeat < 1:
        ap.error(f"--repeat must be 1 or more, got {args.repeat}")
    labels = {side: f"{side} {commit}" for side, (commit, _) in sides.items()}
    if args.logs_only:
        report(labels, {}, {side: job_times(where / "results") for side, (_, where) in sides.items()})
        return 0
    runs: dict = {"before": [], "after": []}
    for r in range(args.repeat):
        for side in ("before", "after") if r % 2 == 0 else ("after", "before"):
            commit, where = sides[side]
            clone(repo, commit, where)
            print(f"{side} ({commit}): running the study in {where}", flush=True)
            wall, cpu = run_study(where, args.jobs, args.target)
            runs[side].append((wall, cpu, job_times(where / "results")))
            print(f"  {wall:.1f} s wall, {cpu:.1f} s CPU", flush=True)
        if args.repeat > 1:
            (wa, ca, _), (wb, cb, _) = runs["before"][-1], runs["after"][-1]
            print(f"pair {r + 1}: study CPU {cb / ca:.2f}x, wall {wb / wa:.2f}x", flush=True)
    if args.repeat > 1:
        print(f"medians of {args.repeat} pairs:")
    middle = {side: medians(rows) for side, rows in runs.items()}
    report(labels, {side: m[0] for side, m in middle.items()}, {side: m[1] for side, m in middle.items()})
    if not args.keep:
        for _, where in sides.values():
            shutil.rmtree(where, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
