#!/usr/bin/env python3
"""Compare two result trees (e.g. a local and a SLURM run of the same workflow).

Usage:
    python .ci/slurm/compare_results.py REFERENCE_DIR CANDIDATE_DIR
        [--ignore-attr NAME ...] [--exclude GLOB ...] [--only-nc]

* Both trees must contain the same set of files (after --exclude).
* ``*.nc`` files are opened with xarray and must be identical
  (``xarray.testing.assert_identical``: same variables, coords, dims, dtypes,
  values -- NaN == NaN -- and attributes) after removing attributes that
  legitimately differ between runs (global and per-variable), by default
  %(ignored)s; add more with ``--ignore-attr``.
  The on-disk encoding (compression, chunking) is not compared.
* Every other file is compared byte by byte (text, csv, json, png, ...).

Exit status 0 if everything matches, 1 if any file differs or is missing
(each one is reported), 2 on usage errors.
"""
from __future__ import annotations

import argparse
import filecmp
import fnmatch
import os
import sys
from pathlib import Path

DEFAULT_IGNORED_ATTRS = (
    "history",
    "date_created",
    "date_modified",
    "creation_date",
    "created",
    "hostname",
    "host",
    "wall_time_s",
    "elapsed_s",
)
DEFAULT_EXCLUDES = (
    "*.log",
    "logs/*",
    "*/logs/*",
    "benchmarks/*",
    "*/benchmarks/*",
    ".snakemake/*",
    "*/.snakemake/*",
    "*.pyc",
)

__doc__ = __doc__ % {"ignored": ", ".join(DEFAULT_IGNORED_ATTRS)}


def list_files(root: Path, excludes: list[str]) -> set[str]:
    out = set()
    for dirpath, _dirs, files in os.walk(root):
        for f in files:
            rel = (Path(dirpath) / f).relative_to(root).as_posix()
            if any(fnmatch.fnmatch(rel, pat) for pat in excludes):
                continue
            out.add(rel)
    return out


def _strip(ds, ignored: set[str]):
    ds = ds.copy()
    ds.attrs = {k: v for k, v in ds.attrs.items() if k not in ignored}
    for name in list(ds.variables):
        ds[name].attrs = {k: v for k, v in ds[name].attrs.items() if k not in ignored}
    return ds


def _value_summary(da, db) -> str:
    """Where values differ: number of differing elements and max |difference|."""
    import numpy as np

    lines = []
    for name in sorted(set(da.variables) & set(db.variables), key=str):
        a, b = da[name].values, db[name].values
        if a.shape != b.shape:
            lines.append(f"{name}: shape {a.shape} vs {b.shape}")
            continue
        try:
            same = (a == b) | (np.asarray(a != a) & np.asarray(b != b))  # NaN == NaN
        except TypeError:
            same = a == b
        n = int(np.size(same) - np.count_nonzero(same))
        if n:
            msg = f"{name}: {n} of {np.size(same)} values differ"
            if np.issubdtype(a.dtype, np.number) and np.issubdtype(b.dtype, np.number):
                with np.errstate(invalid="ignore"):
                    msg += f", max |diff| = {np.nanmax(np.abs(a.astype(float) - b.astype(float))):.3g}"
            lines.append(msg)
    return ("\n" + "\n".join(lines)) if lines else ""


def compare_nc(a: Path, b: Path, ignored: set[str]) -> str | None:
    import xarray as xr

    try:
        with xr.open_dataset(a, decode_timedelta=False) as da, xr.open_dataset(
            b, decode_timedelta=False
        ) as db:
            da, db = _strip(da.load(), ignored), _strip(db.load(), ignored)
            try:
                xr.testing.assert_identical(da, db)
            except AssertionError as exc:
                return (str(exc).strip() + _value_summary(da, db)).strip()
    except Exception as exc:  # unreadable file etc.
        return f"could not compare: {type(exc).__name__}: {exc}"
    return None


def compare_bytes(a: Path, b: Path) -> str | None:
    if filecmp.cmp(a, b, shallow=False):
        return None
    sa, sb = a.stat().st_size, b.stat().st_size
    msg = f"bytes differ ({sa} vs {sb} bytes)"
    try:
        la = a.read_text().splitlines()
        lb = b.read_text().splitlines()
        for i, (x, y) in enumerate(zip(la, lb), 1):
            if x != y:
                return f"{msg}; first difference at line {i}:\n  - {x[:200]}\n  + {y[:200]}"
        return f"{msg}; line counts {len(la)} vs {len(lb)}"
    except UnicodeDecodeError:
        return msg


def main(argv=None) -> int:
    p = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    p.add_argument("reference", type=Path)
    p.add_argument("candidate", type=Path)
    p.add_argument("--ignore-attr", action="append", default=[],
                   help="extra netCDF attribute to ignore (repeatable)")
    p.add_argument("--exclude", action="append", default=[],
                   help="glob on the relative path to skip (repeatable)")
    p.add_argument("--only-nc", action="store_true",
                   help="compare only *.nc files")
    args = p.parse_args(argv)

    for d in (args.reference, args.candidate):
        if not d.is_dir():
            print(f"compare_results: not a directory: {d}", file=sys.stderr)
            return 2

    excludes = list(DEFAULT_EXCLUDES) + args.exclude
    ignored = set(DEFAULT_IGNORED_ATTRS) | set(args.ignore_attr)
    fa = list_files(args.reference, excludes)
    fb = list_files(args.candidate, excludes)
    if args.only_nc:
        fa = {f for f in fa if f.endswith(".nc")}
        fb = {f for f in fb if f.endswith(".nc")}

    problems: list[tuple[str, str]] = []
    for f in sorted(fa - fb):
        problems.append((f, f"missing in {args.candidate}"))
    for f in sorted(fb - fa):
        problems.append((f, f"only in {args.candidate} (not in reference)"))

    n_nc = n_bytes = 0
    for f in sorted(fa & fb):
        a, b = args.reference / f, args.candidate / f
        if f.endswith(".nc"):
            n_nc += 1
            err = compare_nc(a, b, ignored)
        else:
            n_bytes += 1
            err = compare_bytes(a, b)
        if err:
            problems.append((f, err))

    if not fa and not fb:
        print("compare_results: no files to compare -- refusing to call that a match",
              file=sys.stderr)
        return 1

    for f, err in problems:
        print(f"DIFFERS: {f}\n    " + err.replace("\n", "\n    "))
    status = "FAIL" if problems else "OK"
    print(
        f"compare_results {status}: {n_nc} netCDF + {n_bytes} other files compared, "
        f"{len(problems)} problem(s); reference={args.reference} candidate={args.candidate}"
    )
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
