"""CS02's rows of Table 1 for several sensor bands (docs/model.md, "What the controller senses").

Computes, with the study settings of a config file, the CS02 spectra at every noise level for each
sensor band (and the FS spectra), stores them in ``--out`` (an existing file is reused), and prints
J_OS (Eq. 21) of CS02 against no noise with the same sensor, against the ideal-sensor noise-free
CS02, and against FS, as a Markdown table.

    PYTHONPATH=src NUMBA_NUM_THREADS=1 python benchmarks/sensor_table1.py --realisations 40 \
        --bands none 20 10 5 --out /tmp/sensor_spectra
"""
from __future__ import annotations

import argparse
import os

import yaml

from rockstudy.analysis.jos import jos
from rockstudy.analysis.spectra import spectrum
from rockstudy.core.io import read_netcdf, write_netcdf
from rockstudy.studies import parameters


def spectrum_file(cfg, out, strategy, level, band, n):
    path = f"{out}/{strategy}_{level}_band{band}_N{n}.nc"
    if not os.path.exists(path):
        spec = {"block": cfg["block"], "anchorage": cfg["anchorage"],
                "control": {"strategy": strategy, "sensor_band": band}, "excitation": cfg["excitation"],
                "noise_level": cfg["noise_levels"][level], "seed": cfg["seed"], "noise": cfg["noise"],
                "overturn_criterion": cfg["overturn_criterion"], "free_time": cfg["free_time"]}
        write_netcdf(spectrum(parameters.scenario_from_dict(spec), parameters.frequency_ratios(cfg["frequency_grid"]),
                              realisations=range(n), grid=parameters.amplitude_grid(cfg["amplitude_grid"]),
                              progress_chunks=1), path)
    return read_netcdf(path)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--config", default="config.yaml")
    p.add_argument("--realisations", type=int, default=40)
    p.add_argument("--bands", nargs="+", default=["none", "20", "10", "5"], help="sensor cut-offs [Hz] or none")
    p.add_argument("--out", required=True, help="folder for the spectra (reused when present)")
    args = p.parse_args()
    cfg = yaml.safe_load(open(args.config))
    os.makedirs(args.out, exist_ok=True)
    bands = [None if b == "none" else float(b) for b in args.bands]
    free = parameters.noise_free_level(cfg["noise_levels"])
    noisy = [name for name, value in cfg["noise_levels"].items() if value > 0]
    n = args.realisations
    fs = {lvl: spectrum_file(cfg, args.out, "FS", lvl, None, 1 if lvl == free else n) for lvl in [free] + noisy}
    ideal_free = spectrum_file(cfg, args.out, "CS02", free, None, 1)
    a_max0 = cfg["a_max0"]
    print(f"| sensor [Hz] | CS02 vs no noise, same sensor ({' / '.join(noisy)}) | vs ideal-sensor no noise "
          "| vs FS | noise-free vs ideal sensor |")
    print("|---|---|---|---|---|")
    for band in bands:
        cs_free = spectrum_file(cfg, args.out, "CS02", free, band, 1)
        cs = {lvl: spectrum_file(cfg, args.out, "CS02", lvl, band, n) for lvl in noisy}
        references = ({lvl: cs_free for lvl in noisy}, {lvl: ideal_free for lvl in noisy}, fs)
        cells = [[jos(cs[lvl], ref[lvl], a_max0).j_os for lvl in noisy] for ref in references]
        row = [" / ".join(f"{x:+.2f}" for x in c) for c in cells]
        j_free = jos(cs_free, ideal_free, a_max0).j_os
        print(f"| {'ideal' if band is None else f'{band:g}'} | " + " | ".join(row) + f" | {j_free:+.2f} |")
    print("\nFS vs no noise: " + " / ".join(f"{jos(fs[lvl], fs[free], a_max0).j_os:+.2f}" for lvl in noisy)
          + f"  (N = {n} realisations, a_max,0 = {a_max0:g} g)")


if __name__ == "__main__":
    main()
