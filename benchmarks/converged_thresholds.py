"""Which side of a moved threshold is right: every threshold that differs by more than one amplitude
step between two results folders of the study, recomputed with the integration converged.

    python benchmarks/converged_thresholds.py BEFORE_RESULTS AFTER_RESULTS [--config config.yaml]

``compare_studies.py`` counts the thresholds a change of the engine moves; a move beyond one step
(``--step``) is a realisation whose scan met an outcome that the integration's error decides (a run
that grazes overturning). This script takes each such threshold (a realisation at a frequency of a
spectrum in ``spectra/``, ``timing/sampling``, ``timing/delay``) and scans it again with the fast
engine at rtol 1e-11, atol 1e-13 and at rtol 1e-12, atol 1e-14 (Dormand–Prince throughout, the
steppers checked against each other at the first), and prints which folder's value the converged
one equals, counted once against the first setting and once against the tightest (rtol 1e-12)
alone. The scenario is the study's config (``--config``) with the strategy, noise level, sampling
time and delay of the file.

The fragility files (``fragility/*.nc``, records of the FEMA P695 sets) are checked the same way: every
(strategy, record) whose threshold or stripe outcomes differ is run again at the stripe levels and
bisected, at the converged tolerances, with the config's anchorage and intensity measure.

Exit status 0 when every moved threshold of AFTER equals the converged value and the converged value
does not depend on the tolerance or the stepper, 1 otherwise.
"""
from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path

import numpy as np
import xarray as xr
import yaml

from rockstudy.analysis.spectra import AmplitudeGrid
from rockstudy.engine import _kernel as kernel
from rockstudy.studies.parameters import scenario_from_dict

FOLDERS = ("spectra", "timing/sampling", "timing/delay")
SCENARIO_KEYS = ("block", "anchorage", "control", "noise", "seed", "excitation", "overturn_criterion", "free_time")
CONVERGED = ({"rtol": 1e-11, "atol": 1e-13, "stepper": "dopri"}, {"rtol": 1e-11, "atol": 1e-13, "stepper": "taylor"},
             {"rtol": 1e-12, "atol": 1e-14, "stepper": "dopri"})


def moved(before: Path, after: Path, step: float):
    """(file, dataset of AFTER, realisation, frequency ratio, before, after) of every threshold that
    differs by more than ``step`` (NaN: nothing overturns up to the scan's top)."""
    for folder in FOLDERS:
        for fa in sorted((before / folder).glob("*.nc")):
            fb = after / folder / fa.name
            if not fb.exists():
                continue
            with xr.open_dataset(fa) as da, xr.open_dataset(fb) as db:
                if "threshold_realisation" not in da:
                    continue
                x = da.threshold_realisation.values
                y = db.threshold_realisation.values
                d = np.abs(np.nan_to_num(x, nan=1e9) - np.nan_to_num(y, nan=1e9))
                for i, j in zip(*np.where(d > step * (1 + 1e-9))):
                    yield (f"{folder}/{fa.name}", db.load(), int(db.realisation[i]), float(db.frequency_ratio[j]),
                           float(x[i, j]), float(y[i, j]))


def threshold(scenario, ds: xr.Dataset, realisation: int, frequency_ratio: float, integration: dict) -> float:
    """The scan of the study (its grid from the file) for one realisation, with other integration settings."""
    grid = AmplitudeGrid(ds.attrs["grid_amplitude_start"], ds.attrs["grid_amplitude_stop"],
                         ds.attrs["grid_amplitude_step"], ds.attrs["grid_amplitude_resolution"])
    case = scenario.kernel_case(frequency_ratio, realisation, integration=integration)
    thr, _, _, _ = kernel.threshold_kernel(case.parameters, kernel.writable(case.samples),
                                           kernel.writable(case.vertical), grid.values(), float(grid.resolution),
                                           float(case.peak))
    return float(thr)


def _same(a: float, b: float) -> bool:
    return (np.isnan(a) and np.isnan(b)) or a == b


def record_check(config: dict, before: Path, after: Path):
    """(file, strategy, record, before, after, converged thresholds, stripes agree) of every (strategy,
    record) of the fragility files whose threshold or stripe outcomes differ between the folders."""
    from rockstudy.analysis.fragility import intensity
    from rockstudy.analysis.record_scan import RecordRun, grid_outcomes, is_overturned, record_threshold
    from rockstudy.model.record_suites import load_record

    frag = config["beyond"]["fragility"]
    base = scenario_from_dict({k: config[k] for k in SCENARIO_KEYS if k in config})
    for fa in sorted((before / "fragility").glob("*.nc")):
        fb = after / "fragility" / fa.name
        if not fb.exists():
            continue
        with xr.open_dataset(fa) as da, xr.open_dataset(fb) as db:
            da, db = da.load(), db.load()
        levels = db.intensity.values
        for c, strategy in enumerate(db.strategy.values):
            control = dataclasses.replace(base.control, strategy=str(strategy),
                                          sampling_time=float(db.sampling_time[c]), delay=float(db.delay[c]))
            for r, name in enumerate(db.record.values):
                x, y = float(da.threshold_intensity[c, r]), float(db.threshold_intensity[c, r])
                stripes_differ = not np.array_equal(da.overturned[c, r].values, db.overturned[c, r].values)
                if _same(x, y) and not stripes_differ:
                    continue
                _, record = load_record(str(name))
                per_level = record.pga / base.block.uplift_acceleration / intensity(record, base.block,
                                                                                     frag["intensity_measure"])
                values, stripes = [], []
                for integration in CONVERGED:
                    run = RecordRun(base.block, base.anchorage, control, record,
                                    overturn_criterion=base.overturn_criterion, free_time=base.free_time)
                    run.P[kernel.I_RTOL], run.P[kernel.I_ATOL] = integration["rtol"], integration["atol"]
                    run.P[kernel.I_TAYLOR] = 1.0 if integration["stepper"] == "taylor" else 0.0
                    out = grid_outcomes(run, levels * per_level)
                    res = record_threshold(run, levels * per_level, frag["threshold_resolution"] * per_level, out)
                    values.append(res["amplitude_ratio"] / per_level)
                    stripes.append(is_overturned(out))
                yield (f"fragility/{fa.name}", str(strategy), str(name), x, y, values,
                       all(np.array_equal(stripes[0], v) for v in stripes[1:]),
                       np.array_equal(stripes[0], db.overturned[c, r].values.astype(bool)),
                       np.array_equal(stripes[0], da.overturned[c, r].values.astype(bool)))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("before", type=Path)
    ap.add_argument("after", type=Path)
    ap.add_argument("--config", type=Path, default=Path("config.yaml"))
    ap.add_argument("--step", type=float, default=0.01, help="one amplitude step of the scan's resolution")
    args = ap.parse_args(argv)
    config = yaml.safe_load(args.config.read_text(encoding="utf-8"))
    base = scenario_from_dict({k: config[k] for k in SCENARIO_KEYS if k in config})
    n = n_after = n_before = n_neither = n_unsettled = 0
    tight = {"AFTER": 0, "BEFORE": 0, "neither": 0}  # against the tightest setting (the last of CONVERGED)
    for rel, ds, k, fr, x, y in moved(args.before, args.after, args.step):
        control = dataclasses.replace(base.control, strategy=str(ds.strategy.values),
                                      sampling_time=float(ds.sampling_time), delay=float(ds.delay))
        scenario = dataclasses.replace(base, control=control, noise_level=float(ds.noise_level))
        values = [threshold(scenario, ds, k, fr, integration) for integration in CONVERGED]
        settled = all(_same(values[0], v) for v in values[1:])
        ref = values[0]
        side = "AFTER" if _same(ref, y) else "BEFORE" if _same(ref, x) else "neither"
        n += 1
        n_after += side == "AFTER"
        n_before += side == "BEFORE"
        n_neither += side == "neither"
        n_unsettled += not settled
        tight["AFTER" if _same(values[-1], y) else "BEFORE" if _same(values[-1], x) else "neither"] += 1
        print(f"  {rel} realisation {k} omega_p/p {fr:g}: before {x:.6g}, after {y:.6g}, converged "
              f"{', '.join(f'{v:.6g}' for v in values)} -> {side}{'' if settled else ' (not settled)'}")
    print(f"{n} thresholds moved beyond one step: the converged value equals AFTER in {n_after}, BEFORE in "
          f"{n_before}, neither in {n_neither}; {n_unsettled} not settled by the tolerance or stepper")
    last = CONVERGED[-1]
    print(f"  against the tightest setting alone (rtol {last['rtol']:g}, {last['stepper']}): AFTER in "
          f"{tight['AFTER']}, BEFORE in {tight['BEFORE']}, neither in {tight['neither']}")
    ok = n_after == n and n_unsettled == 0
    m = m_after = m_unsettled = 0
    for rel, strategy, name, x, y, values, settled, stripes_after, stripes_before in record_check(
            config, args.before, args.after):
        ref = values[0]
        side = "AFTER" if _same(ref, y) else "BEFORE" if _same(ref, x) else "neither"
        m += 1
        m_after += side == "AFTER" and stripes_after
        m_unsettled += not settled or not all(_same(ref, v) for v in values[1:])
        print(f"  {rel} {strategy} {name}: threshold before {x:.6g}, after {y:.6g}, converged "
              f"{', '.join(f'{v:.6g}' for v in values)} -> {side}; stripes converged = after {stripes_after}, "
              f"= before {stripes_before}")
    if m:
        print(f"{m} (strategy, record) pairs of the fragility files differ: threshold and stripes equal to the "
              f"converged ones in AFTER for {m_after}; {m_unsettled} not settled")
        ok = ok and m_after == m and m_unsettled == 0
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
