"""Command line: ``rockstudy simulate | threshold | spectrum | jos``.

Every command validates its arguments before any heavy work and exits with status 2 and a
message naming the argument and what is allowed.
"""
from __future__ import annotations

import argparse
import json
import logging
import math
import sys

from .block import BLOCK_PRESETS
from .control import STRATEGIES

EXCITATION_CHOICES = ("one-sine", "modulated")


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # exit 2 with the argument named (argparse already names it)
        self.print_usage(sys.stderr)
        self.exit(2, f"rockstudy: error: {message}\n")


def _nonneg(name):
    def conv(text):
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number, got {text!r}")
        if not (math.isfinite(v) and v >= 0):
            raise argparse.ArgumentTypeError(f"{name} must be a finite number >= 0, got {text!r}")
        return v
    return conv


def _pos(name):
    def conv(text):
        v = _nonneg(name)(text)
        if v <= 0:
            raise argparse.ArgumentTypeError(f"{name} must be > 0, got {text!r}")
        return v
    return conv


def _noise(text):
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--noise-level must be a number in [0, 1), got {text!r}")
    if not (0 <= v < 1):
        raise argparse.ArgumentTypeError(f"--noise-level must lie in [0, 1) (noise energy / baseline energy), got {text!r}")
    return v


def _nonneg_int(name):
    def conv(text):
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be an integer >= 0, got {text!r}")
        if v < 0:
            raise argparse.ArgumentTypeError(f"{name} must be an integer >= 0, got {text!r}")
        return v
    return conv


def _common(p: argparse.ArgumentParser, single_frequency=True):
    p.add_argument("--block", default="BLC06", choices=sorted(BLOCK_PRESETS), help="block preset (default BLC06)")
    p.add_argument("--strategy", default="CS01", choices=STRATEGIES, help="control strategy")
    p.add_argument("--excitation", default="modulated", choices=EXCITATION_CHOICES,
                   help="one-sine pulse or the amplitude-modulated harmonic of Eq. 23")
    if single_frequency:
        p.add_argument("--frequency-ratio", type=_pos("--frequency-ratio"), default=2.0, help="omega_p/p [-]")
    p.add_argument("--noise-level", type=_noise, default=0.0, help="noise energy / baseline energy, in [0, 1)")
    p.add_argument("--realisation", type=_nonneg_int("--realisation"), default=0, help="noise realisation k")
    p.add_argument("--seed", type=_nonneg_int("--seed"), default=0, help="root seed of the noise")
    p.add_argument("--noise-step", type=_pos("--noise-step"), default=0.0025, metavar="SECONDS",
                   help="sampling step of the noisy record [s] (default 0.0025)")
    p.add_argument("--noise-rescale", "--match", dest="match", default="energy",
                   choices=("energy", "pga", "both", "none"),
                   help="what the noisy record keeps of the baseline: energy (default), pga, both, none")
    p.add_argument("--noise-level-means", default="energy", choices=("energy", "rms"),
                   help="--noise-level is noise/baseline energy (default) or noise/baseline RMS")
    p.add_argument("--noise-band", type=_pos("--noise-band"), default=None, metavar="HZ",
                   help="upper band limit of the noise [Hz] (default: white up to 1/(2 step))")
    p.add_argument("--noise-span", type=_nonneg("--noise-span"), default=0.0, metavar="SECONDS",
                   help="noise also this long after the intense part [s] (default 0)")
    p.add_argument("--sampling-time", type=_nonneg("--sampling-time"), default=0.0,
                   help="controller sampling time T_s [s] (0: continuous)")
    p.add_argument("--delay", type=_nonneg("--delay"), default=0.0, help="actuation delay [s] (needs T_s > 0)")
    p.add_argument("--kappa-max", type=_nonneg("--kappa-max"), default=1.0, help="4 K_max b^2/(m g R) [-]")
    p.add_argument("--kappa-min", type=_nonneg("--kappa-min"), default=0.0, help="4 K_min b^2/(m g R) [-]")
    p.add_argument("--damping-ratio", type=_nonneg("--damping-ratio"), default=0.05, help="xi [-]")
    p.add_argument("--overturn-criterion", default="flat", choices=("flat", "alpha"),
                   help="overturned at |theta| >= pi/2 (flat) or >= alpha")
    p.add_argument("--free-time", type=_nonneg("--free-time"), default=30.0,
                   help="free motion allowed after the excitation [s]")
    p.add_argument("--engine", default="fast", choices=("fast", "reference"), help="integration engine")


def _scenario(args, parser):
    from .anchorage import Anchorage
    from .control import Control
    from .noise import NoiseReading
    from .spectra import Scenario
    try:
        noise = NoiseReading(step=args.noise_step, rescale=args.match, level_means=args.noise_level_means,
                             band=args.noise_band, span=args.noise_span)
    except ValueError as exc:
        parser.error(str(exc).replace("NoiseReading.band", "--noise-band").replace("NoiseReading.", "--noise-"))
    try:
        return Scenario(BLOCK_PRESETS[args.block],
                        Anchorage(kappa_max=args.kappa_max, kappa_min=args.kappa_min,
                                  damping_ratio=args.damping_ratio),
                        Control(args.strategy, sampling_time=args.sampling_time, delay=args.delay),
                        excitation=args.excitation, noise_level=args.noise_level, seed=args.seed,
                        noise=noise, overturn_criterion=args.overturn_criterion, free_time=args.free_time)
    except ValueError as exc:
        msg = str(exc).replace("Control.delay", "--delay").replace("Anchorage.kappa_min", "--kappa-min")
        parser.error(msg)


def _grid(args, parser):
    from .spectra import AmplitudeGrid
    try:
        return AmplitudeGrid(start=args.min_amplitude_ratio, stop=args.max_amplitude_ratio,
                             step=args.amplitude_step, resolution=args.resolution)
    except ValueError as exc:
        parser.error(str(exc).replace("AmplitudeGrid.stop", "--max-amplitude-ratio")
                     .replace("AmplitudeGrid.resolution", "--resolution")
                     .replace("AmplitudeGrid.start", "--min-amplitude-ratio"))


def _grid_args(p):
    p.add_argument("--min-amplitude-ratio", type=_pos("--min-amplitude-ratio"), default=0.9,
                   help="first amplitude ratio of the upward scan [-]")
    p.add_argument("--max-amplitude-ratio", type=_pos("--max-amplitude-ratio"), default=6.0,
                   help="upper bound of the scan [-]")
    p.add_argument("--amplitude-step", type=_pos("--amplitude-step"), default=0.1, help="coarse scan step [-]")
    p.add_argument("--resolution", type=_pos("--resolution"), default=0.01, help="refinement resolution [-]")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="rockstudy", description="Rocking of controlled rigid blocks (overturning spectra study)")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    ps = sub.add_parser("simulate", help="run one case and print a JSON summary")
    _common(ps)
    ps.add_argument("--amplitude-ratio", type=_pos("--amplitude-ratio"), default=2.0, help="a_p/(g tan alpha) [-]")
    ps.add_argument("--output", help="write the time history to this netCDF file")
    ps.add_argument("--plot", help="draw theta, theta_dot, K and the ground motion to this PNG")
    ps.add_argument("--record", help="ground motion from a record file instead of --excitation: PEER NGA .AT2 "
                    "(in g) or two columns time [s], acceleration (--excitation, --frequency-ratio and "
                    "--amplitude-ratio are then not used)")
    ps.add_argument("--record-unit", help="acceleration unit of a two-column record: "
                    "g, m/s^2, cm/s^2 (gal) or mm/s^2 (default: the unit named in its header line)")
    ps.add_argument("--record-scale", type=_pos("--record-scale"), default=1.0,
                    help="factor multiplying the record (default 1) [-]")
    pt = sub.add_parser("threshold", help="minimum overturning amplitude ratio at one frequency (JSON)")
    _common(pt)
    _grid_args(pt)
    pp = sub.add_parser("spectrum", help="overturning spectrum over a frequency grid, written to netCDF")
    _common(pp, single_frequency=False)
    _grid_args(pp)
    pp.add_argument("--frequency-start", type=_pos("--frequency-start"), default=0.25, help="first omega_p/p [-]")
    pp.add_argument("--frequency-stop", type=_pos("--frequency-stop"), default=5.0, help="last omega_p/p [-]")
    pp.add_argument("--frequency-step", type=_pos("--frequency-step"), default=0.1, help="omega_p/p step [-]")
    pp.add_argument("--realisations", type=_pos("--realisations"), default=1,
                    help="number of noise realisations N (0..N-1)")
    pp.add_argument("--map", action="store_true", help="also store the outcome at every grid point")
    pp.add_argument("--threads", type=_pos("--threads"), default=1, help="numba threads")
    pp.add_argument("--output", required=True, help="netCDF file to write")
    pp.add_argument("--plot", help="PNG of the spectrum")
    pj = sub.add_parser("jos", help="utility index J_OS (Eqs. 18-22) of two spectrum files")
    pj.add_argument("--reference", required=True, help="spectrum netCDF of the reference system")
    pj.add_argument("--system", required=True, help="spectrum netCDF of the investigated system")
    pj.add_argument("--a-max0", type=_pos("--a-max0"), default=1.0, help="a_max,0 in units of g (default 1)")
    return parser


def _cmd_simulate(args, parser):
    if args.record is not None:
        return _cmd_simulate_record(args, parser)
    if args.record_unit is not None or args.record_scale != 1.0:
        parser.error("--record-unit and --record-scale need --record FILE")
    from .simulate import simulate
    scenario = _scenario(args, parser)
    motion, rec = scenario.motion(args.frequency_ratio, args.amplitude_ratio, args.realisation)
    res = simulate(scenario.block, scenario.anchorage, scenario.control, motion, engine=args.engine,
                   overturn_criterion=scenario.overturn_criterion, free_time=scenario.free_time,
                   record_history=bool(args.output or args.plot))
    out = res.summary()
    out.update(frequency_ratio=args.frequency_ratio, amplitude_ratio=args.amplitude_ratio,
               strategy=args.strategy, excitation=args.excitation, noise_level=args.noise_level,
               realisation=args.realisation, sampling_time_s=args.sampling_time, delay_s=args.delay,
               energy_ratio=1.0 if rec is None else rec.energy_ratio,
               pga_ratio=1.0 if rec is None else rec.pga_ratio, **scenario.noise.to_attrs())
    if args.output or args.plot:
        from .study import history_dataset
        ds = history_dataset(res, scenario, motion, args.frequency_ratio, args.amplitude_ratio, args.realisation)
        if args.output:
            from .io import write_netcdf
            write_netcdf(ds, args.output)
            out["output"] = args.output
        if args.plot:
            from .plotting import figure_control_history, save_figure
            save_figure(figure_control_history(ds, "2-3 style"), args.plot)
            out["plot"] = args.plot
    print(json.dumps(out, indent=2))


def _cmd_simulate_record(args, parser):
    """``simulate --record FILE``: one run under a recorded (or synthetic) ground motion."""
    from .records import read_record, unit_factor
    from .simulate import simulate
    if args.noise_level != 0:
        parser.error("argument --noise-level: noise contaminates the analytic excitations; not with --record")
    if args.record_unit is not None:
        try:
            unit_factor(args.record_unit)
        except ValueError as exc:
            parser.error(f"argument --record-unit: {exc}")
    try:
        record = read_record(args.record, args.record_unit)
    except (OSError, ValueError) as exc:
        parser.error(f"argument --record: {exc}")
    scenario = _scenario(args, parser)
    motion = record.motion(args.record_scale)
    res = simulate(scenario.block, scenario.anchorage, scenario.control, motion, engine=args.engine,
                   overturn_criterion=scenario.overturn_criterion, free_time=scenario.free_time,
                   record_history=bool(args.output or args.plot))
    pga_ratio = motion.peak() / scenario.block.uplift_acceleration
    out = res.summary()
    out.update(strategy=args.strategy, excitation="record", record=args.record, record_name=record.name,
               record_unit=record.unit, record_scale=args.record_scale, record_dt_s=record.dt,
               record_npts=int(record.acceleration.size), record_duration_s=record.duration,
               pga_m_s2=motion.peak(), pga_uplift_ratio=pga_ratio, sampling_time_s=args.sampling_time,
               delay_s=args.delay)
    if args.output or args.plot:
        from .study import history_dataset
        ds = history_dataset(res, scenario, motion, math.nan, pga_ratio, 0, dt=min(record.dt, 0.0025))
        ds.attrs.update(record.to_attrs(), excitation="record", record_scale=args.record_scale,
                        excitation_end_s=record.duration,
                        amplitude_ratio_note="PGA/(g tan(alpha)) of the scaled record",
                        title=f"Time history, {args.strategy}, record {record.name}, scale {args.record_scale:g}")
        if args.output:
            from .io import write_netcdf
            write_netcdf(ds, args.output)
            out["output"] = args.output
        if args.plot:
            from .plotting import figure_control_history, save_figure
            fig = figure_control_history(ds, "record")
            fig.axes[0].set_title(f"{args.strategy}, record {record.name} x {args.record_scale:g}, "
                                  f"PGA/(g tan(alpha)) = {pga_ratio:.3g} ({res.status})", fontsize=10)
            save_figure(fig, args.plot)
            out["plot"] = args.plot
    print(json.dumps(out, indent=2))


def _cmd_threshold(args, parser):
    from .spectra import threshold
    scenario = _scenario(args, parser)
    grid = _grid(args, parser)
    res = threshold(scenario, args.frequency_ratio, realisation=args.realisation, grid=grid, engine=args.engine)
    res.update(strategy=args.strategy, excitation=args.excitation, noise_level=args.noise_level,
               realisation=args.realisation, sampling_time_s=args.sampling_time, delay_s=args.delay,
               **scenario.noise.to_attrs())
    print(json.dumps(res, indent=2))


def _cmd_spectrum(args, parser):
    import numba
    from .io import write_netcdf
    from .spectra import frequency_grid, spectrum
    if args.engine != "fast":
        parser.error("argument --engine: spectra run on the fast engine only")
    if args.realisations != int(args.realisations):
        parser.error(f"argument --realisations: must be an integer >= 1, got {args.realisations}")
    scenario = _scenario(args, parser)
    grid = _grid(args, parser)
    try:
        freqs = frequency_grid(args.frequency_start, args.frequency_stop, args.frequency_step)
    except ValueError as exc:
        parser.error(f"argument --frequency-start/--frequency-stop/--frequency-step: {exc}")
    numba.set_num_threads(min(int(args.threads), numba.config.NUMBA_NUM_THREADS))
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(message)s", stream=sys.stderr)
    ds = spectrum(scenario, freqs, realisations=range(int(args.realisations)), grid=grid, with_map=args.map)
    write_netcdf(ds, args.output)
    if args.plot:
        import matplotlib.pyplot as plt
        from .plotting import plot_a_max0, plot_threshold, save_figure, spectrum_axes
        fig, ax = plt.subplots(figsize=(6, 4))
        plot_threshold(ax, ds["threshold"], label=args.strategy)
        plot_a_max0(ax, ds.attrs["a_max0_ratio"])
        spectrum_axes(ax)
        ax.legend()
        save_figure(fig, args.plot)
    print(json.dumps({"output": args.output, "frequencies": len(freqs), "realisations": int(ds.sizes["realisation"]),
                      "simulations": int(ds.n_simulations.sum()), "compute_time_s": ds.attrs["compute_time_s"]}))


def _cmd_jos(args, parser):
    from .io import read_netcdf
    from .utility import utility_index
    import numpy as np
    try:
        ref = read_netcdf(args.reference)
        sys_ = read_netcdf(args.system)
    except (OSError, ValueError) as exc:
        parser.error(f"cannot read a spectrum file: {exc}")
    for name, ds in (("--reference", ref), ("--system", sys_)):
        if "threshold" not in ds or "frequency_ratio" not in ds.coords:
            parser.error(f"argument {name}: not a rockstudy spectrum file (no 'threshold' over 'frequency_ratio')")
    if ref.sizes["frequency_ratio"] != sys_.sizes["frequency_ratio"] or not np.allclose(
            ref.frequency_ratio.values, sys_.frequency_ratio.values):
        parser.error("--reference and --system have different frequency grids; compute them on the same grid")
    for key in ("block_width", "block_height", "block_depth", "block_density"):
        if ref.attrs.get(key) != sys_.attrs.get(key):
            parser.error(f"--reference and --system are for different blocks ({key}: "
                         f"{ref.attrs.get(key)} vs {sys_.attrs.get(key)})")
    a_max0 = args.a_max0 / math.tan(ref.attrs["block_alpha"])
    try:
        j, n = utility_index(sys_.threshold.values, ref.threshold.values, a_max0)
    except ValueError as exc:
        parser.error(str(exc))
    print(json.dumps({"J_OS_percent": j, "N_star": n, "a_max0_ratio": a_max0,
                      "reference": args.reference, "system": args.system}))


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    {"simulate": _cmd_simulate, "threshold": _cmd_threshold, "spectrum": _cmd_spectrum, "jos": _cmd_jos}[
        args.command](args, parser)
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
