"""Which side of a moved threshold is right: every threshold that differs by more than one amplitude
step between two results folders of the study, recomputed with the integration converged.

    python benchmarks/converged_thresholds.py BEFORE_RESULTS AFTER_RESULTS [--config config.yaml]

``compare_studies.py`` counts the thresholds a change of the engine moves; a move beyond one step
(``--step``) is a realisation whose scan met an outcome that the integration's error decides (a run
that grazes overturning). This script takes each such threshold (a realisation at a frequency of a
spectrum in ``spectra/``, ``timing/sampling``, ``timing/delay``) and scans it again with the fast
engine at rtol 1e-11, atol 1e-13 and at rtol 1e-12, atol 1e-14 (Dormand–Prince throughout, the
steppers checked against each other at the first), and prints which folder's value the converged
one equals. The scenario is the study's config (``--config``) with the strategy, noise level,
sampling time and delay of the file.

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
        print(f"  {rel} realisation {k} omega_p/p {fr:g}: before {x:.6g}, after {y:.6g}, converged "
              f"{', '.join(f'{v:.6g}' for v in values)} -> {side}{'' if settled else ' (not settled)'}")
    print(f"{n} thresholds moved beyond one step: the converged value equals AFTER in {n_after}, BEFORE in "
          f"{n_before}, neither in {n_neither}; {n_unsettled} not settled by the tolerance or stepper")
    return 0 if n_after == n and n_unsettled == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
