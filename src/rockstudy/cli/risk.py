"""Command group ``rockstudy fragility`` and ``rockstudy risk``: the fragility of one object on a record
suite, and its risk of overturning at a site (:mod:`rockstudy.analysis.risk`).

* ``rockstudy fragility --strategy S --suite SUITE [block and device options] --output F.nc`` runs the
  record-set fragility of the study (:func:`rockstudy.analysis.fragility.suite_fragility_dataset`, the
  study's stripes, threshold resolution and bootstrap by default) for S beside free standing, writes
  the dataset and prints JSON with ``median_g`` and ``dispersion`` of S (the stripes' lognormal fit).
* ``rockstudy risk (--median G --dispersion B | --fragility F.nc --strategy S)
  (--hazard FILE [--hazard-unit U] [--years N] | --scenario mag=7,dist_rup=10,v_s30=400 [--gmm NAME])``
  prints JSON with ``annual_rate`` and ``probability`` (hazard; for a file of several sites, one entry
  of ``sites`` each, with ``lon``, ``lat`` and ``name`` where the file gives them), or ``gmm``,
  ``scenario``, ``median_pga_g``, ``ln_std`` and ``probability`` (scenario).
* ``rockstudy risk --dispersion B --hazard FILE (--target-rate R | --target-probability P --years N)``
  prints JSON with the ``median_g`` that meets the target and ``extrapolated`` (and, with
  ``--devices FILE``, which devices of a design study's device sweep meet it).
"""
from __future__ import annotations

import math
import sys
import warnings

from rockstudy.analysis.fragility import INTENSITY_MEASURES, SUITE_DEFAULTS
from rockstudy.analysis.hazard import EXTENSIONS
from rockstudy.cli import options
from rockstudy.core import validation
from rockstudy.core.quantities import QUANTITIES
from rockstudy.core.risk_inputs import DEFAULT_GMM, DEFAULT_YEARS, GMMS, HAZARD_UNITS
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import BLOCK_PRESETS
from rockstudy.model.control import STRATEGIES, Control
from rockstudy.model.records import STANDARD_GRAVITY_UNITS

CONTROL = options.CONTROL
"""The library's defaults the options show."""
BLOCK_DIMENSIONS = {"width": "base width 2b [m]", "height": "height 2h [m]", "depth": "depth [m]",
                    "density": "density [kg/m^3] (default 2700)",
                    "restitution": "coefficient of restitution e [-] (default: Housner's Eq. 14)"}
"""Block options besides the preset ``--block``."""
RISK_OPTIONS = {"median_g": "--median", "dispersion": "--dispersion", "years": "--years",
                "target_rate": "--target-rate", "target_probability": "--target-probability"}
"""The option that sets each number of a fragility, an exposure time and a target: the library's checks name it."""
FRAGILITY_OPTIONS = {"resolution": "--threshold-resolution", "n_boot": "--bootstrap", "seed": "--seed",
                     "free_time": "--free-time"}
"""The option that sets each argument of :func:`~rockstudy.analysis.fragility.suite_fragility_dataset`: its
check names it."""


def register(sub) -> None:
    """Add ``fragility`` and ``risk`` to the subparsers ``sub`` (each with ``run``).

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subparsers of the top-level parser (``parser.add_subparsers()``).
    """
    from rockstudy.analysis.scenario import DEFAULT_BLOCK
    from rockstudy.model.record_suites import suite_names
    pf = sub.add_parser("fragility", help="fragility of one object on a record suite (netCDF; JSON with median_g "
                        "and dispersion)")
    pf.add_argument("--strategy", default=CONTROL.strategy, choices=STRATEGIES,
                    help=f"control strategy, run beside FS (default {CONTROL.strategy})")
    pf.add_argument("--suite", required=True, choices=suite_names(), help="record suite (see 'rockstudy records')")
    pf.add_argument("--max-records", type=options._integer("--max-records"), default=None, metavar="N",
                    help="only the suite's first N records (default: all)")
    pf.add_argument("--block", default=DEFAULT_BLOCK, choices=sorted(BLOCK_PRESETS),
                    help=f"block preset (default {DEFAULT_BLOCK}); or give --width, --height, --depth")
    dims = pf.add_argument_group("block by its dimensions (instead of --block)")
    for name, text in BLOCK_DIMENSIONS.items():
        dims.add_argument(f"--{name}", type=options._number(f"--{name}"), default=None, help=text)
    options._numeric(pf, "--sampling-time", CONTROL.sampling_time, "controller sampling time T_s [s] (0: continuous)")
    options._numeric(pf, "--delay", CONTROL.delay, "actuation delay [s] (needs T_s > 0)")
    options.device_and_end_options(pf, "the record")
    levels = SUITE_DEFAULTS["intensity_levels"]
    pf.add_argument("--intensity-measure", default=SUITE_DEFAULTS["intensity_measure"], choices=INTENSITY_MEASURES,
                    help=f"intensity measure of the stripes (default {SUITE_DEFAULTS['intensity_measure']})")
    options._numeric(pf, "--levels-start", levels["start"], "first stripe level [IM]")
    options._numeric(pf, "--levels-stop", levels["stop"], "last stripe level [IM]")
    options._numeric(pf, "--levels-step", levels["step"], "step of the stripe levels [IM]")
    options._numeric(pf, "--threshold-resolution", SUITE_DEFAULTS["threshold_resolution"],
         "resolution of each record's threshold [IM]")
    pf.add_argument("--bootstrap", type=options._integer("--bootstrap"), default=SUITE_DEFAULTS["bootstrap"],
                    help="bootstrap draws over records for the median shift's interval")
    pf.add_argument("--seed", type=options._integer("--seed"), default=SUITE_DEFAULTS["seed"], help="bootstrap seed")
    pf.add_argument("--output", required=True, help="netCDF file to write")
    pf.set_defaults(run=run_fragility)

    pr = sub.add_parser("risk", help="rate and probability of overturning from a hazard curve or a scenario, or "
                        "the median meeting a target (JSON)")
    src = pr.add_argument_group("the fragility: --median and --dispersion, or --fragility and --strategy")
    src.add_argument("--median", type=options._number("--median"), metavar="G", help="fragility median PGA theta [g]")
    src.add_argument("--dispersion", type=options._number("--dispersion"), metavar="B",
                     help="fragility dispersion beta [-]")
    src.add_argument("--fragility", metavar="F.nc", help="a fragility dataset ('rockstudy fragility' or the "
                     "study's fragility/<set>.nc): its stripes' lognormal fit in PGA")
    src.add_argument("--strategy", choices=STRATEGIES, help="the strategy of --fragility")
    site = pr.add_argument_group("the site: --hazard, or --scenario")
    site.add_argument("--hazard", metavar="FILE", help="hazard file of one or many sites: two columns (PGA [g], "
                      "annual rate of exceedance [1/yr]), an OpenQuake hazard-curve CSV, an nshmp-haz curves CSV "
                      "or a USGS hazard tool JSON")
    units = ", ".join(HAZARD_UNITS).replace("%", "%%")  # argparse formats help with %: "%g" must be "%%g"
    site.add_argument("--hazard-unit", choices=tuple(HAZARD_UNITS), metavar="UNIT",
                      help=f"unit of the hazard file's PGA levels ({units}); default: the file's, "
                           "else g, refused when the curve cannot be in g")
    site.add_argument("--scenario", metavar="KEY=VALUE,...", help="earthquake scenario, e.g. "
                      "mag=7,dist_rup=10,v_s30=400 (optional: mechanism, dip, depth_tor, dist_jb, dist_x)")
    site.add_argument("--gmm", default=DEFAULT_GMM, choices=sorted(GMMS), help="ground-motion model of --scenario")
    site.add_argument("--outside-gmm-range", action="store_true",
                      help="answer a scenario outside the model's published range with a warning instead of refusing")
    options._numeric(pr, "--years", DEFAULT_YEARS, "exposure time T of the probability 1 - exp(-lambda T) [yr]")
    pr.add_argument("--extension", default=EXTENSIONS[0], choices=EXTENSIONS,
                    help="below the first and beyond the last point of the hazard curve, extend its end "
                         "segments' power laws (loglog) or count nothing (none)")
    pr.add_argument("--bands", metavar="G,G,...", help="PGA band edges [g] of a disaggregation to print")
    target = pr.add_argument_group("risk-targeted design (with --dispersion and --hazard)")
    target.add_argument("--target-rate", type=options._number("--target-rate"), metavar="R",
                        help="the median meeting this annual rate of overturning [1/yr]")
    target.add_argument("--target-probability", type=options._number("--target-probability"), metavar="P",
                        help="the median meeting this probability of overturning in --years")
    target.add_argument("--allow-extrapolation", action="store_true",
                        help="answer a median outside the hazard curve's PGA range (extrapolated: true, a warning) "
                             "instead of refusing")
    target.add_argument("--devices", metavar="FILE", help="a design study's device sweep (design/devices.nc): "
                        "which devices meet the target")
    pr.set_defaults(run=run_risk)


def _fail(parser, exc) -> None:
    parser.error(str(exc))


def run_fragility(args, parser) -> None:
    """``rockstudy fragility``: the suite's fragility of --strategy beside FS; JSON on stdout.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``rockstudy fragility``.
    parser : argparse.ArgumentParser
        The command's parser; a bad option is reported through it (exit status 2).
    """
    from rockstudy.analysis.fragility import suite_fragility_dataset
    from rockstudy.cli.output import print_json
    from rockstudy.model import record_suites
    from rockstudy.studies import parameters
    try:
        validation.check_output_path("--output", args.output, formats=("nc",))
        anchorage = Anchorage(args.kappa_max, args.kappa_min, args.damping_ratio, names=options.OPTION_NAMES)
        block = _block(args)
        levels = parameters.intensity_levels({"start": args.levels_start, "stop": args.levels_stop,
                                              "step": args.levels_step}, "--levels")
        if args.max_records is not None:
            QUANTITIES["suite_records"].check("--max-records", args.max_records)
        strategies = ["FS"] if args.strategy == "FS" else ["FS", args.strategy]
        controls = [Control(s, sampling_time=args.sampling_time, delay=args.delay, names=options.OPTION_NAMES)
                    for s in strategies]
    except ValueError as exc:
        _fail(parser, exc)

    def entries():  # read by suite_fragility_dataset after it has checked its options
        return record_suites.load_suite(args.suite)[:args.max_records]
    try:
        ds = suite_fragility_dataset(block, anchorage, controls, entries, levels, suite=args.suite,
                                     measure=args.intensity_measure, resolution=args.threshold_resolution,
                                     n_boot=args.bootstrap, seed=args.seed, overturn_criterion=args.overturn_criterion,
                                     free_time=args.free_time, names=FRAGILITY_OPTIONS)
    except (validation.InputError, record_suites.RecordSuiteError) as exc:
        _fail(parser, exc)
    options.write_output(ds, args.output)
    d = ds.sel(strategy=args.strategy)
    unit = ds["fragility_median_physical"].attrs["units"]
    key = "median_g" if unit in (STANDARD_GRAVITY_UNITS, "g") else "median_pgv_m_per_s"
    print_json({"strategy": args.strategy, "suite": args.suite, "n_records": ds.sizes["record"],
                      key: _value(d.fragility_median_physical), f"{key}_low": _value(d.median_low_physical),
                      f"{key}_high": _value(d.median_high_physical), "dispersion": _value(d.fragility_dispersion),
                      "fit": str(d.fit_status.values), "intensity_measure": args.intensity_measure,
                      "fit_of": "the stripes' lognormal fit (P(overturn) at each level)", "output": args.output})


def _block(args):
    """The block of the options: its dimensions, or the preset ``--block``."""
    from rockstudy.studies.parameters import block_from_dict
    dims = {name: getattr(args, name) for name in BLOCK_DIMENSIONS if getattr(args, name) is not None}
    if not dims:
        return BLOCK_PRESETS[args.block]
    try:
        return block_from_dict(dims)
    except ValueError as exc:
        message = str(exc)
        for name in BLOCK_DIMENSIONS:
            message = message.replace(f"block.{name}", f"--{name}")
        raise validation.InputError(message.replace("block: missing key(s)", "missing block option(s)")) from None


def _value(da):
    value = float(da)
    return value if math.isfinite(value) else None


def _scenario(text: str, parser) -> dict:
    out = {}
    for item in text.split(","):
        key, sep, value = item.partition("=")
        key, value = key.strip(), value.strip()
        if not sep or not key or not value:
            parser.error(f"argument --scenario: {item!r} is not KEY=VALUE (e.g. mag=7,dist_rup=10,v_s30=400)")
        if key in out:
            parser.error(f"argument --scenario: {key} is given twice")
        if key == "mechanism":
            out[key] = value
            continue
        try:
            out[key] = float(value)
        except ValueError:
            parser.error(f"argument --scenario: {key}={value!r} is not a number")
    return out


def _fragility(args, parser):
    from rockstudy.analysis.risk import LognormalFragility, fragility_from_dataset
    from rockstudy.core.io import read_netcdf
    if args.fragility is not None:
        if args.median is not None or args.dispersion is not None:
            parser.error("give the fragility either as --median and --dispersion or as --fragility and --strategy")
        if args.strategy is None:
            parser.error("--fragility needs --strategy (the strategy whose fragility to use)")
        validation.check_input_file("--fragility", args.fragility, validation.MAX_DATASET_BYTES)
        try:
            ds = read_netcdf(args.fragility)
        except (OSError, ValueError, RuntimeError) as exc:
            parser.error(f"argument --fragility: cannot read {args.fragility!r} as a netCDF file: {exc}")
        if "strategy" not in ds.coords or "fragility_dispersion" not in ds:
            parser.error(f"argument --fragility: {args.fragility!r} is not a fragility dataset")
        return fragility_from_dataset(ds, args.strategy)
    if args.median is None or args.dispersion is None:
        parser.error("give the fragility: --median and --dispersion, or --fragility and --strategy")
    if args.strategy is not None:
        parser.error("--strategy goes with --fragility")
    return LognormalFragility(args.median, args.dispersion, names=RISK_OPTIONS)


def run_risk(args, parser) -> None:
    """``rockstudy risk``: hazard, scenario or target mode; JSON on stdout (:func:`rockstudy.cli.output.print_json`).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``rockstudy risk``.
    parser : argparse.ArgumentParser
        The command's parser; a bad option is reported through it (exit status 2).
    """
    from rockstudy.cli.output import NonFiniteOutputError, print_json
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            out = _risk(args, parser)
        except validation.InputError as exc:
            _fail(parser, exc)
    for w in caught:
        if issubclass(w.category, UserWarning):
            print(f"rockstudy: warning: {w.message}", file=sys.stderr)
    try:
        print_json(out)
    except NonFiniteOutputError as exc:
        _fail(parser, exc)


def _sites(args):
    from rockstudy.analysis.hazard import read_hazard_sites
    sites = read_hazard_sites(args.hazard, f"--hazard {args.hazard}", args.hazard_unit)
    return {(s.label if len(sites) > 1 else args.hazard): s for s in sites}


def _where(site) -> dict:
    """The site's lon, lat and name where the file gives them, and what reading it did."""
    out = {k: getattr(site, k) for k in ("lon", "lat", "name") if getattr(site, k) is not None}
    if site.notes:
        out["hazard_notes"] = list(site.notes)
    return out


def _one_or_many(rows: list[dict], common: dict) -> dict:
    """Today's keys for one site; ``{"sites": [...], ...}`` for several."""
    return {**rows[0], **common} if len(rows) == 1 else {"sites": rows, **common}


def _risk(args, parser) -> dict:
    from rockstudy.analysis import risk
    targets = [t for t in ("target_rate", "target_probability") if getattr(args, t) is not None]
    if (args.hazard is None) == (args.scenario is None):
        parser.error("give the site: --hazard FILE or --scenario KEY=VALUE,...")
    if args.hazard_unit is not None and args.hazard is None:
        parser.error("--hazard-unit goes with --hazard")
    if args.outside_gmm_range and args.scenario is None:
        parser.error("--outside-gmm-range goes with --scenario")
    if args.allow_extrapolation and not targets:
        parser.error("--allow-extrapolation goes with --target-rate or --target-probability")
    if targets:
        return _target(args, parser, targets)
    if args.devices is not None:
        parser.error("--devices goes with --target-rate or --target-probability")
    fragility = _fragility(args, parser)
    base = {"median_g": fragility.median_g, "dispersion": fragility.dispersion}
    if args.fragility is not None:
        base.update(fragility=args.fragility, strategy=args.strategy)
    if args.scenario is not None:
        result = risk.scenario_risk(fragility, _scenario(args.scenario, parser), args.gmm,
                                    outside_range=args.outside_gmm_range)
        out = {"gmm": result.gmm, "scenario": result.scenario, "median_pga_g": result.median_pga_g,
               "ln_std": result.ln_std, "probability": result.probability, **base}
        if result.warnings:
            out["warnings"] = list(result.warnings)
        return out
    edges = None
    if args.bands is not None:
        try:
            edges = [float(v) for v in args.bands.split(",")]
        except ValueError:
            parser.error(f"argument --bands: {args.bands!r} is not a comma-separated list of PGA [g]")
    return _hazard(args, fragility, edges, base)


def _hazard(args, fragility, edges, base: dict) -> dict:
    from rockstudy.analysis.risk_sites import risk_at_sites
    sites: dict = {}

    def read_sites():  # read by risk_at_sites after it has checked --years
        sites.update(_sites(args))
        return sites
    ds = risk_at_sites({"object": fragility}, read_sites, years=args.years, extension=args.extension,
                       band_edges_g=edges, names=RISK_OPTIONS)
    years = float(ds.attrs["years"])
    rows = []
    for name, site in sites.items():
        d = ds.sel(strategy="object", site=name)
        row = {**_where(site), "annual_rate": float(d.annual_rate), "probability": float(d.probability),
               "rate_below_curve": float(d.rate_below), "rate_above_curve": float(d.rate_above),
               "tail_share": float(d.tail_share)}
        if edges is not None:
            lows, highs = ds.pga_band_low.values, ds.pga_band_high.values
            row["disaggregation"] = [{"pga_low_g": float(lo), "pga_high_g": None if math.isinf(hi) else float(hi),
                                      "share": float(sh)} for lo, hi, sh in zip(lows, highs, d.disaggregation.values)]
        rows.append(row)
    return _one_or_many(rows, {"years": years, **base, "hazard": args.hazard, "extension": args.extension})


def _target(args, parser, targets) -> dict:
    from rockstudy.analysis.risk_devices import devices_meeting
    from rockstudy.analysis.risk_sites import targets_at_sites
    if len(targets) > 1:
        parser.error("give one target: --target-rate or --target-probability")
    if args.hazard is None:
        parser.error("a target needs --hazard (the median meeting it on the hazard curve)")
    if args.dispersion is None or args.median is not None or args.fragility is not None:
        parser.error("a target takes --dispersion only (the median is what it finds)")
    sites: dict = {}

    def read_sites():  # read by targets_at_sites after it has checked the target, --years and --dispersion
        sites.update(_sites(args))
        return sites
    try:
        found = targets_at_sites(read_sites, args.dispersion, target_rate=args.target_rate,
                                 target_probability=args.target_probability, years=args.years,
                                 extension=args.extension, allow_extrapolation=args.allow_extrapolation,
                                 names=RISK_OPTIONS)
    except validation.InputError as exc:
        raise validation.InputError(f"--hazard {exc}" if sites else str(exc)) from None
    devices = _read_devices(args, parser) if args.devices is not None else None
    rows = []
    for name, site in sites.items():
        median = found.medians[name]
        row = {**_where(site), "median_g": median.median_g, "extrapolated": median.extrapolated}
        if median.extrapolated:
            row["decades_outside_curve"] = median.decades_outside
        if devices is not None:
            row["devices"] = devices_meeting(devices, median.median_g)
        rows.append(row)
    return _one_or_many(rows, {"dispersion": args.dispersion, "target_rate": found.target_rate,
                               "target_probability": found.target_probability, "years": found.years,
                               "hazard": args.hazard, "extension": args.extension})


def _read_devices(args, parser):
    from rockstudy.core.io import read_netcdf
    validation.check_input_file("--devices", args.devices, validation.MAX_DATASET_BYTES)
    try:
        ds = read_netcdf(args.devices)
    except (OSError, ValueError, RuntimeError) as exc:
        parser.error(f"argument --devices: cannot read {args.devices!r} as a netCDF file: {exc}")
    if not {"kappa_max", "damping_ratio", "strategy"} <= set(ds.coords) or "fragility_median" not in ds:
        parser.error(f"argument --devices: {args.devices!r} is not a device sweep (design/devices.nc)")
    return ds
