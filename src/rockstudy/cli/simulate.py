"""``rockstudy simulate`` (one run) and ``rockstudy threshold`` (the smallest overturning amplitude at one
frequency), under the paper's excitations or a record."""
from __future__ import annotations

import math

from rockstudy.cli import COMMANDS
from rockstudy.cli.options import (
    RUN_OPTIONS,
    _check_outputs,
    _check_record_options,
    _common,
    _grid,
    _grid_args,
    _number,
    _read_record,
    _record_description,
    _scenario,
    check_no_record_options,
    check_sensor_band,
    record_args,
    write_output,
)
from rockstudy.cli.output import grid_values, print_json
from rockstudy.core import validation
from rockstudy.core.constants import NOISE_DT
from rockstudy.studies import config_model

GRID_KEYS = ("amplitude_ratio", "last_safe_amplitude_ratio", "max_amplitude_ratio", "scan_start_amplitude_ratio",
             "frequency_ratio")
"""Entries of ``threshold``'s result that are levels of its grids or bisection points between them."""


def register(sub) -> None:
    """Add ``simulate`` and ``threshold`` to the subparsers ``sub``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subparsers of the top-level parser (``parser.add_subparsers()``).
    """
    ps = sub.add_parser("simulate", help=COMMANDS["simulate"].help)
    _common(ps)
    ps.add_argument("--amplitude-ratio", type=_number("--amplitude-ratio"), default=2.0, help="a_p/(g tan alpha) [-]")
    ps.add_argument("--output", help="write the time history and every event (impacts, uplifts, returns to rest) "
                    "to this netCDF file; the printed summary has their counts")
    ps.add_argument("--plot", help="draw theta, theta_dot, K and the ground motion over the whole run to this PNG")
    record_args(ps)
    pt = sub.add_parser("threshold", help=COMMANDS["threshold"].help)
    _common(pt)
    _grid_args(pt)
    record_args(pt, scan=True)
    ps.set_defaults(run=_cmd_simulate)
    pt.set_defaults(run=_cmd_threshold)


def noise_fields(scenario) -> dict:
    """The noise reading of ``scenario`` as the result prints it (``noise_band_hz`` null for white noise).

    Parameters
    ----------
    scenario : rockstudy.analysis.scenario.Scenario
        The case run.
    """
    return {**scenario.noise.to_attrs(), "noise_band_hz": scenario.noise.band}


def _cmd_simulate(args, parser):
    if args.record is not None:
        return _cmd_simulate_record(args, parser)
    check_no_record_options(args, parser)
    scenario = _scenario(args, parser)
    _check_outputs(args, parser)
    motion, rec = scenario.motion(args.frequency_ratio, args.amplitude_ratio, args.realisation, names=RUN_OPTIONS)
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
               **noise_fields(scenario))
    if res is not None and (args.output or args.plot):
        from rockstudy.studies.datasets import history_dataset
        ds = history_dataset(res, scenario, motion, args.frequency_ratio, args.amplitude_ratio, args.realisation)
        if args.output:
            write_output(ds, args.output)
            out["output"] = args.output
        if args.plot:
            from rockstudy.plotting import figure_control_history, save_figure
            save_figure(figure_control_history(ds, "2-3 style", whole_run=True), args.plot)
            out["plot"] = args.plot
    print_json(out)


def _cmd_simulate_record(args, parser):
    """``simulate --record FILE``: one run under a recorded (or synthetic) ground motion."""
    _check_record_options(args, parser)
    config_model.check_option("--record-scale", args.record_scale)
    scenario = _scenario(args, parser, record=True)
    _check_outputs(args, parser)
    info, record = _read_record(args, parser)
    check_sensor_band(args, parser, record.dt)
    motion = record.motion(args.record_scale)
    pga_ratio = motion.peak() / scenario.block.uplift_acceleration
    top = validation.MAX_AMPLITUDE_RATIO * args.record_scale / pga_ratio if pga_ratio > 0 else None
    validation.check_positive("--record-scale", args.record_scale, high=top,
                              why=f"the scaled record's PGA/(g tan alpha) is {pga_ratio:.4g}, at most "
                                  f"{validation.MAX_AMPLITUDE_RATIO:g} is allowed")
    validation.check_nonnegative("--free-time", args.free_time, "s", validation.MAX_TIME_SPAN - record.duration,
                                 why=f"the record lasts {record.duration:.4g} s and a simulation at most "
                                     f"{validation.MAX_TIME_SPAN:g} s")
    history_dt = min(record.dt, NOISE_DT)  # the stored history samples the ground motion at most every 2.5 ms
    if args.output or args.plot:
        samples = (record.duration + args.free_time) / history_dt
        if samples > validation.MAX_HISTORY_SAMPLES:
            validation.fail("--record", args.record,
                            f"its DT = {record.dt:g} s over {record.duration:.4g} s plus --free-time "
                            f"{args.free_time:g} s gives a history of {samples:.3g} samples, the limit is "
                            f"{validation.MAX_HISTORY_SAMPLES:.0e} (resample the record, lower --free-time, or "
                            "run without --output/--plot)")
    try:
        res = scenario.simulate_motion(motion, engine=args.engine, record_history=bool(args.output or args.plot))
    except RuntimeError as exc:  # the reference engine's piece cap: an undetermined result, no file written
        res = None
        message = str(exc)
    else:
        message = res.message
    if res is None or res.status == "undetermined":  # the fast engine's event cap: no outcome, no file
        print_json({"status": "undetermined", "overturned": None, "message": message,
                    "strategy": args.strategy, "record": args.record})
        return
    out = res.compact_summary()
    out.update(strategy=args.strategy, excitation="record", record=args.record, record_name=record.name,
               record_unit=record.unit, record_scale=args.record_scale, record_dt_s=record.dt,
               record_npts=int(record.acceleration.size), record_duration_s=record.duration,
               pga_m_s2=motion.peak(), pga_uplift_ratio=pga_ratio, sampling_time_s=args.sampling_time,
               delay_s=args.delay, sensor_band_hz=args.sensor_band, **_record_description(info))
    if args.output or args.plot:
        from rockstudy.studies.datasets import history_dataset
        ds = history_dataset(res, scenario, motion, math.nan, pga_ratio, 0, dt=history_dt)
        ds.attrs.update(record.to_attrs(), **({} if info is None else info.to_attrs()), excitation="record",
                        record_scale=args.record_scale,
                        excitation_end_s=record.duration,
                        amplitude_ratio_note="PGA/(g tan(alpha)) of the scaled record",
                        title=f"Time history, {args.strategy}, record {record.name}, scale {args.record_scale:g}")
        if args.output:
            write_output(ds, args.output)
            out["output"] = args.output
        if args.plot:
            from rockstudy.plotting import figure_control_history, plain_text, save_figure
            fig = figure_control_history(ds, "record", whole_run=True)
            fig.axes[0].set_title(f"{args.strategy}, record {plain_text(record.name)} x {args.record_scale:g}, "
                                  f"PGA/(g tan(alpha)) = {pga_ratio:.3g} ({res.status})", fontsize=10)
            save_figure(fig, args.plot)
            out["plot"] = args.plot
    print_json(out)


def _cmd_threshold_record(args, parser):
    """``threshold --record``: the smallest scale of a record that overturns the block (the spectra's scan)."""
    from rockstudy.analysis.record_scan import RecordRun, record_threshold
    from rockstudy.model.records import STANDARD_GRAVITY
    _check_record_options(args, parser)
    scenario = _scenario(args, parser, record=True)
    grid, _ = _grid(args, parser)
    info, record = _read_record(args, parser)
    check_sensor_band(args, parser, record.dt)
    validation.check_nonnegative("--free-time", args.free_time, "s", validation.MAX_TIME_SPAN - record.duration,
                                 why=f"the record lasts {record.duration:.4g} s and a simulation at most "
                                     f"{validation.MAX_TIME_SPAN:g} s")
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
    print_json(grid_values(out, GRID_KEYS))


def _cmd_threshold(args, parser):
    if args.record is not None:
        return _cmd_threshold_record(args, parser)
    check_no_record_options(args, parser)
    from rockstudy.analysis.spectra import threshold
    scenario = _scenario(args, parser)
    grid, _ = _grid(args, parser)
    res = threshold(scenario, args.frequency_ratio, realisation=args.realisation, grid=grid,
                    engine=args.engine, names=RUN_OPTIONS).as_dict()
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
               sensor_band_hz=args.sensor_band, **noise_fields(scenario))
    print_json(grid_values(res, GRID_KEYS))


