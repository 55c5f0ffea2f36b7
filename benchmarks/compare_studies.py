"""Check that two results folders of the study agree within the acceptance rules of a change that
may move results (a new integrator, say), and print the counts.

    python benchmarks/compare_studies.py BEFORE_RESULTS AFTER_RESULTS [--step 0.01]

The rules (all must hold; exit status 0 when they do, 1 otherwise):

* every threshold of every spectrum (in ``spectra/``, ``timing/`` and ``maps/``) is equal, or
  within one amplitude step of the scan's resolution (``--step``), and at most 1 % of them differ
  (``--max-fraction``). Two levels are counted and printed: the spectrum's own curve (``threshold``,
  a_min,OVER at each frequency: the lowest over the realisations, the paper's value) and each
  noise realisation's threshold (``threshold_realisation``; a noise-free spectrum's curve counts at
  both levels). ``--level`` says which of them the rule is applied to (default: both);
* every J_OS of Table 1 and of the timing tables (``tables/*.nc``, variable ``j_os``) moves by less
  than 0.05 percentage points (``--jos``);
* every claim's verdict (``reproduction/claims.csv``) is unchanged.

Files present in one folder only are reported; a rule with nothing to compare is reported as such
and does not fail.
"""
from __future__ import annotations

import argparse
import csv
import sys
from pathlib import Path

import numpy as np
import xarray as xr

SPECTRA_FOLDERS = ("spectra", "timing/sampling", "timing/delay", "maps")


def _pairs(before: Path, after: Path, pattern: str):
    """(relative path, before file, after file) of the files matching ``pattern`` in both folders,
    and the relative paths found in only one of them."""
    a = {p.relative_to(before).as_posix() for p in before.glob(pattern)}
    b = {p.relative_to(after).as_posix() for p in after.glob(pattern)}
    return [(r, before / r, after / r) for r in sorted(a & b)], sorted(a ^ b)


def _thresholds(ds: xr.Dataset, level: str) -> np.ndarray:
    name = "threshold_realisation" if level == "realisation" and "threshold_realisation" in ds else "threshold"
    return np.asarray(ds[name].values, dtype=float).ravel()


def compare_thresholds(before: Path, after: Path, step: float, max_fraction: float,
                       level: str = "realisation") -> bool:
    n = n_equal = n_step = n_beyond = 0
    worst = 0.0
    files = []
    for folder in SPECTRA_FOLDERS:
        pairs, lonely = _pairs(before, after, f"{folder}/*.nc")
        for r in lonely:
            print(f"  only in one folder: {r}")
        for rel, fa, fb in pairs:
            with xr.open_dataset(fa) as da, xr.open_dataset(fb) as db:
                if "threshold" not in da and "threshold_realisation" not in da:
                    continue
                x, y = _thresholds(da, level), _thresholds(db, level)
            if x.shape != y.shape:
                print(f"  {rel}: different shapes {x.shape} and {y.shape}")
                n_beyond += max(x.size, y.size)
                continue
            same = (x == y) | (np.isnan(x) & np.isnan(y))
            d = np.abs(x - y)
            near = ~same & (d <= step * (1 + 1e-9))  # NaN against a number is never near
            far = ~same & ~near
            n += x.size
            n_equal += int(same.sum())
            n_step += int(near.sum())
            n_beyond += int(far.sum())
            if np.any(~same):
                worst = max(worst, float(np.nanmax(np.where(same, 0.0, d))) if np.any(~np.isnan(d[~same])) else np.inf)
                files.append(f"{rel}: {int((~same).sum())} of {x.size}")
    if n == 0:
        print(f"{level} thresholds: nothing to compare")
        return True
    differ = n_step + n_beyond
    ok = n_beyond == 0 and differ <= max_fraction * n
    print(f"{level} thresholds: {n} compared, {n_equal} equal, {n_step} within one step ({step:g}), {n_beyond} beyond; "
          f"{differ} differ = {100.0 * differ / n:.2f} % (at most {100 * max_fraction:g} %), largest change "
          f"{worst:.4g} -> {'PASS' if ok else 'FAIL'}")
    for line in files:
        print(f"  {line}")
    return ok


def compare_jos(before: Path, after: Path, limit: float) -> bool:
    pairs, lonely = _pairs(before, after, "tables/*.nc")
    for r in lonely:
        print(f"  only in one folder: {r}")
    n = n_moved = 0
    worst = 0.0
    bad = []
    for rel, fa, fb in pairs:
        with xr.open_dataset(fa) as da, xr.open_dataset(fb) as db:
            if "j_os" not in da:
                continue
            x, y = da["j_os"].values.ravel(), db["j_os"].values.ravel()
        both_nan = np.isnan(x) & np.isnan(y)
        d = np.where(both_nan, 0.0, np.abs(x - y))
        d = np.where(np.isnan(d), np.inf, d)  # NaN against a number
        n += x.size
        n_moved += int((d > 0).sum())
        worst = max(worst, float(d.max()) if d.size else 0.0)
        if np.any(d >= limit):
            bad.append(f"{rel}: {int((d >= limit).sum())} move by >= {limit:g} points")
    if n == 0:
        print("J_OS: nothing to compare")
        return True
    ok = not bad
    print(f"J_OS: {n} values in {len(pairs)} tables, {n_moved} moved, largest move {worst:.4f} points "
          f"(limit < {limit:g}) -> {'PASS' if ok else 'FAIL'}")
    for line in bad:
        print(f"  {line}")
    return ok


def _verdicts(path: Path) -> dict:
    with open(path, newline="") as f:
        return {row["claim"]: row["verdict"] for row in csv.DictReader(f)}


def compare_claims(before: Path, after: Path) -> bool:
    fa, fb = before / "reproduction/claims.csv", after / "reproduction/claims.csv"
    if not (fa.exists() and fb.exists()):
        print("claims: nothing to compare (reproduction/claims.csv missing)")
        return True
    a, b = _verdicts(fa), _verdicts(fb)
    changed = [k for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)]
    print(f"claims: {len(a)} before, {len(b)} after, {len(changed)} verdicts changed -> "
          f"{'PASS' if not changed else 'FAIL'}")
    for k in changed:
        print(f"  {k}: {a.get(k)} -> {b.get(k)}")
    return not changed


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("before", type=Path, help="results folder of the code before the change")
    ap.add_argument("after", type=Path, help="results folder of the code after the change")
    ap.add_argument("--step", type=float, default=0.01, help="amplitude step a threshold may move by (default 0.01)")
    ap.add_argument("--max-fraction", type=float, default=0.01,
                    help="largest fraction of thresholds that may differ (default 0.01)")
    ap.add_argument("--level", choices=("both", "spectrum", "realisation"), default="both",
                    help="thresholds the rule applies to: the spectrum's curve (threshold), each noise "
                         "realisation's (threshold_realisation) or both (default both; both are printed)")
    ap.add_argument("--jos", type=float, default=0.05, help="J_OS must move by less than this [points] (default 0.05)")
    args = ap.parse_args(argv)
    for folder in (args.before, args.after):
        if not folder.is_dir():
            print(f"not a folder: {folder}", file=sys.stderr)
            return 2
    ok = True
    for level in ("spectrum", "realisation"):
        holds = compare_thresholds(args.before, args.after, args.step, args.max_fraction, level)
        if args.level in ("both", level):
            ok = holds and ok
        else:
            print(f"  (the {level} level is printed only: --level {args.level})")
    ok = compare_jos(args.before, args.after, args.jos) and ok
    ok = compare_claims(args.before, args.after) and ok
    print("all rules hold" if ok else "some rule fails")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
