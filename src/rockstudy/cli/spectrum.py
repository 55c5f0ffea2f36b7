"""``rockstudy spectrum`` (an overturning spectrum to netCDF) and ``rockstudy jos`` (the utility index J_OS of
two spectrum files)."""
from __future__ import annotations

import logging
import math
import sys

from rockstudy.analysis.spectra import DEFAULT_FREQUENCY_GRID
from rockstudy.analysis.utility_index import DEFAULT_A_MAX0
from rockstudy.cli import COMMANDS
from rockstudy.cli.options import (
    _check_outputs,
    _check_time_span,
    _common,
    _grid,
    _grid_args,
    _integer,
    _numeric,
    _scenario,
    write_output,
)
from rockstudy.cli.output import print_json
from rockstudy.cli.progress import progress_bar
from rockstudy.core import validation
from rockstudy.studies import config_model

FREQUENCY_OPTIONS = {"start": "--frequency-start", "stop": "--frequency-stop", "step": "--frequency-step"}
"""The option that sets each argument of :func:`~rockstudy.analysis.spectra.frequency_grid`."""

SECONDS_PER_SIMULATION = 1e-3
"""Rough cost of one simulation on one core, for the estimate printed before a spectrum. [s]"""


def register(sub) -> None:
    """Add ``spectrum`` and ``jos`` to the subparsers ``sub``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subparsers of the top-level parser (``parser.add_subparsers()``).
    """
    pp = sub.add_parser("spectrum", help=COMMANDS["spectrum"].help)
    _common(pp, single_frequency=False, realisation=False)
    _grid_args(pp)
    start, stop, step = (DEFAULT_FREQUENCY_GRID[key] for key in ("start", "stop", "step"))
    _numeric(pp, "--frequency-start", start, "first omega_p/p [-]")
    _numeric(pp, "--frequency-stop", stop, "last omega_p/p [-]")
    _numeric(pp, "--frequency-step", step, "omega_p/p step [-]")
    pp.add_argument("--realisations", type=_integer("--realisations"), default=1,
                    help="number of noise realisations N (0..N-1)")
    pp.add_argument("--map", action="store_true", help="also store the outcome at every grid point")
    pp.add_argument("--threads", type=_integer("--threads"), default=1, help="numba threads")
    pp.add_argument("--output", required=True, help="netCDF file to write")
    pp.add_argument("--plot", help="PNG of the spectrum")
    pj = sub.add_parser("jos", help=COMMANDS["jos"].help)
    pj.add_argument("--reference", required=True, help="spectrum netCDF of the reference system")
    pj.add_argument("--system", required=True, help="spectrum netCDF of the investigated system")
    _numeric(pj, "--a-max0", DEFAULT_A_MAX0, "a_max,0 in units of g")
    pj.add_argument("--allow-mismatch", action="append", metavar="ATTR",
                    help="compare spectra that differ in this setting (an attribute such as noise_seed, "
                         "free_time_s or block_width; 'all': any); repeatable. Without it, spectra made under "
                         "different excitations, criteria, free times, noise readings, seeds, numbers of "
                         "realisations, blocks, devices or amplitude scans are refused")
    pp.set_defaults(run=_cmd_spectrum)
    pj.set_defaults(run=_cmd_jos)


def _cmd_spectrum(args, parser):
    import numba

    from rockstudy.analysis.spectra import frequency_grid, spectrum
    from rockstudy.studies.datasets import document_missing
    if args.engine != "fast":
        parser.error("argument --engine: spectra run on the fast engine only")
    config_model.check_option("--realisations", args.realisations)
    validation.check_int_range("--threads", args.threads, 1, numba.config.NUMBA_NUM_THREADS,
                               why="the CPUs numba can use on this machine")
    scenario = _scenario(args, parser)
    grid, sims_per_case = _grid(args, parser)
    freqs = frequency_grid(args.frequency_start, args.frequency_stop, args.frequency_step, names=FREQUENCY_OPTIONS)
    n_freq = len(freqs)
    _check_time_span(scenario, [args.frequency_start, float(freqs[-1])],
                     "--frequency-start" if args.frequency_start < 1 else "--frequency-stop")
    n_real = 1 if scenario.noise_level == 0 else args.realisations
    record_bytes = scenario.record_bytes(freqs, n_real)  # at the reading's step and span
    validation.check_workload("--realisations" if n_real > 1 else "--frequency-step",
                              args.realisations if n_real > 1 else args.frequency_step,
                              n_real * n_freq, sims_per_case * (2 if args.map else 1), record_bytes)
    _check_outputs(args, parser)
    numba.set_num_threads(args.threads)
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(message)s", stream=sys.stderr)
    n_cases, n_sims = n_real * n_freq, n_real * n_freq * sims_per_case
    logging.getLogger("rockstudy").info(
        "spectrum: %d realisation(s) x %d frequencies = %d cases, at most %d simulations "
        "(at most about %.0f s on %d thread(s) at ~%g s each)", n_real, n_freq, n_cases,
        n_sims, n_sims * SECONDS_PER_SIMULATION / args.threads, args.threads, SECONDS_PER_SIMULATION)
    with progress_bar() as progress:  # a bar at a terminal; elsewhere the log lines
        ds = document_missing(spectrum(scenario, freqs, realisations=range(n_real), grid=grid, with_map=args.map,
                                       progress=progress))
    write_output(ds, args.output)  # the result first: a plot that cannot be written loses nothing computed
    if args.plot:
        from rockstudy.plotting import figure_spectrum, save_figure
        save_figure(figure_spectrum(ds, label=args.strategy), args.plot)
    print_json({"output": args.output, "frequencies": len(freqs), "realisations": int(ds.sizes["realisation"]),
                "simulations": int(ds.n_simulations.sum()), "compute_time_s": ds.attrs["compute_time_s"]})


def _check_pair(ref, sys_, args, parser) -> None:
    """Refuse spectra on different frequency grids or made under different settings (unless allowed)."""
    import numpy as np

    from rockstudy.studies.tables import spectrum_mismatches
    if ref.sizes["frequency_ratio"] != sys_.sizes["frequency_ratio"] or not np.allclose(
            ref.frequency_ratio.values, sys_.frequency_ratio.values):
        parser.error("--reference and --system have different frequency grids; compute them on the same grid")
    allowed = set(args.allow_mismatch or ())
    for attr, a, b in spectrum_mismatches(sys_, ref):
        if attr not in allowed and "all" not in allowed:
            parser.error(f"--reference and --system were made under different settings: {attr} is {a!r} in "
                         f"--system and {b!r} in --reference; J_OS compares strategies under one setting (pass "
                         f"--allow-mismatch {attr} to compare them anyway)")


def _cmd_jos(args, parser):
    from rockstudy.analysis.jos import jos
    from rockstudy.core.io import read_netcdf
    from rockstudy.studies.tables import check_spectrum_file
    datasets = {}

    def read(name, path):  # called by jos after it has checked --a-max0
        validation.check_input_file(name, path, validation.MAX_DATASET_BYTES)
        try:
            datasets[name] = read_netcdf(path)
        except (OSError, ValueError, RuntimeError) as exc:
            parser.error(f"argument {name}: cannot read {path!r} as a netCDF file: {exc}")
        check_spectrum_file(datasets[name], f"argument {name}: {path!r}")
        if name == "--system":
            _check_pair(datasets["--reference"], datasets["--system"], args, parser)
        return datasets[name]
    try:
        result = jos(lambda: read("--system", args.system), lambda: read("--reference", args.reference),
                     args.a_max0, a_max0_name="--a-max0")
        j, n, a_max0 = result.j_os, result.n_star, result.a_max0_ratio
    except ValueError as exc:
        parser.error(str(exc))
    out = {"J_OS_percent": None if math.isnan(j) else j, "N_star": n, "a_max0_g": args.a_max0,
           "a_max0_ratio": a_max0, "reference": args.reference, "system": args.system}
    if n == 0:
        out["note"] = ("N* = 0: no frequency has a threshold below a_max,0 in either file, so J_OS (Eq. 21) is "
                       "undefined")
    print_json(out)


