"""``rockstudy records``: the record suites and their records, and ``records --export SUITE:ID``, one record of a
suite as a file other tools read.

``records`` prints a plain table; ``--json`` and ``--csv`` print the same rows for programs, with the NGA-West2
record sequence number (``rsn``) where the suite has one.

``--format one-column`` writes one acceleration sample a line, the layout OpenSees'
``timeSeries Path -dt DT -filePath FILE -factor F`` reads (and SAP2000, SeismoStruct and most others);
``two-column`` writes a header naming the units (``time [s], acceleration [g]``) and then time and
acceleration a line; ``at2`` the PEER NGA layout (in g by the format). The samples are in the record's own
unit (g for the FEMA P695 sets), stated as ``unit``; ``to_m_per_s2`` is the factor that turns them into m/s²,
and the OpenSees line carries it as ``-factor`` so that the model receives m/s².
"""
from __future__ import annotations

import csv
import io
import math
import sys

from rockstudy.cli import COMMANDS
from rockstudy.model.record_export import DEFAULT_FORMAT, FORMATS, export_record, export_text  # noqa: F401

LISTING_FIELDS = ("record", "suite", "id", "rsn", "event", "year", "magnitude", "station", "distance_km",
                  "site_class", "pga_g", "pgv_m_per_s", "pulse", "dt_s", "npts")
"""The columns of ``records --json`` and ``--csv``."""


def register(sub) -> None:
    """Add ``records`` to the subparsers ``sub``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subparsers of the top-level parser (``parser.add_subparsers()``).
    """
    pr = sub.add_parser("records", help=COMMANDS["records"].help)
    pr.add_argument("--suite", help="list only this suite's records (default: every suite)")
    listing = pr.add_mutually_exclusive_group()
    listing.add_argument("--json", action="store_true", help="print the records as JSON (with the NGA RSN)")
    listing.add_argument("--csv", action="store_true", help="print the records as CSV (with the NGA RSN)")
    add_export_arguments(pr)
    pr.set_defaults(run=_cmd_records)


def _cmd_records(args, parser):
    """``records``: the suites and their records (``--export``: one record to a file)."""
    given = [o for o, v in (("--format", args.format), ("--output", args.output)) if v is not None]
    if args.export is not None:
        if args.json or args.csv:
            parser.error("--json and --csv list records; --export writes one (its summary is JSON already)")
        return run_export(args, parser)
    if given:
        parser.error(f"{' and '.join(given)} {'go' if len(given) > 1 else 'goes'} with --export SUITE:ID (the "
                     "record to write)")
    from rockstudy.model import record_suites
    suites = record_suites.suite_names()
    if args.suite is not None:
        try:
            suites = (record_suites.check_suite(args.suite, "--suite"),)
        except record_suites.RecordSuiteError as exc:
            parser.error(f"argument {exc}")
    if args.json or args.csv:
        return _listing(args, parser, suites)
    for suite in suites:
        print(f"{suite}: {record_suites.SUITES[suite]}")
        try:
            print(record_suites.catalogue_table(record_suites.catalogue(suite)))
        except record_suites.MissingPackageError as exc:
            if args.suite is not None:
                parser.error(f"argument --suite: {exc}")
            print(f"  (not available: {exc})\n")
    sys.stdout.flush()


def listing_rows(suite: str) -> list[dict]:
    """One row per record of ``suite`` (:data:`LISTING_FIELDS`), None where a field does not apply.

    Parameters
    ----------
    suite : str
        A suite name.
    """
    from rockstudy.model import record_suites
    rsn = record_suites.record_sequence_numbers(suite)

    def number(value):
        return None if value is None or (isinstance(value, float) and not math.isfinite(value)) else value

    return [{"record": i.name, "suite": i.suite, "id": i.id, "rsn": rsn.get(i.id), "event": i.event,
             "year": i.year or None, "magnitude": number(i.magnitude), "station": i.station,
             "distance_km": number(i.distance_km), "site_class": i.site_class or None, "pga_g": i.pga_g,
             "pgv_m_per_s": i.pgv, "pulse": i.pulse, "dt_s": i.dt, "npts": i.npts}
            for i in record_suites.catalogue(suite)]


def _listing(args, parser, suites) -> None:
    from rockstudy.cli.output import print_json
    from rockstudy.model import record_suites
    rows = []
    for suite in suites:
        try:
            rows += listing_rows(suite)
        except record_suites.MissingPackageError as exc:
            if args.suite is not None:
                parser.error(f"argument --suite: {exc}")
            print(f"rockstudy: warning: {suite} not listed: {exc}", file=sys.stderr)
    if args.json:
        print_json({"records": rows})
        return
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=LISTING_FIELDS, lineterminator="\n")
    writer.writeheader()
    writer.writerows({k: ("" if v is None else v) for k, v in row.items()} for row in rows)
    sys.stdout.write(text.getvalue())
    sys.stdout.flush()


def add_export_arguments(parser) -> None:
    """Add ``--export``, ``--format`` and ``--output`` to the ``records`` subparser.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The ``records`` subparser.
    """
    parser.add_argument("--export", metavar="SUITE:ID",
                        help="write this record to a file (--format, --output) and print its dt as JSON")
    parser.add_argument("--format", choices=FORMATS, default=None,
                        help="with --export: one-column, one sample a line (OpenSees timeSeries Path); "
                             "two-column: a units header, then time and acceleration; at2: PEER NGA "
                             f"[default: {DEFAULT_FORMAT}]")
    parser.add_argument("--output", help="with --export: file to write [default: SUITE_ID.txt, or .AT2 with "
                                         "--format at2]")


def run_export(args, parser) -> dict:
    """``records --export``: write the record and print (and return) the summary.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``rockstudy records``: ``export`` (``SUITE:ID``), ``format`` and ``output``.
    parser : argparse.ArgumentParser
        The command's parser; a bad record name or output is reported through it (exit status 2).
    """
    from rockstudy.cli.output import print_json
    from rockstudy.core import validation
    from rockstudy.model import record_suites

    fmt = args.format or DEFAULT_FORMAT
    try:
        info, record = record_suites.load_record(args.export, "--export")
    except record_suites.RecordSuiteError as exc:
        parser.error(f"argument {exc}")
    default = f"{info.suite}_{info.id}" + (".AT2" if fmt == "at2" else ".txt")
    try:
        path = validation.check_output_path("--output", args.output or default)
    except validation.InputError as exc:
        parser.error(str(exc))
    try:
        written = export_record(record, path, fmt, title=f"{info.name} {info.event} {info.station}")
    except OSError as exc:
        parser.error(f"argument --output: cannot write {str(path)!r}: {exc.strerror or exc}")
    summary = {"record": info.name, "event": info.event, "station": info.station, "file": str(path),
               "dt_s": record.dt, "npts": int(record.acceleration.size),
               "duration_s": record.duration, **written}
    print_json(summary)
    return summary
