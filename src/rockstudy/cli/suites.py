"""``rockstudy records``: the record suites and their records, and ``records --export SUITE:ID``, one record of a
suite as a file other tools read.

``--format one-column`` writes one acceleration sample a line, the layout OpenSees'
``timeSeries Path -dt DT -filePath FILE`` reads (and SAP2000, SeismoStruct and most others);
``two-column`` writes time and acceleration; ``at2`` the PEER NGA layout. The samples keep the
record's unit (g for the FEMA P695 sets); the summary printed as JSON gives the step ``dt``, the
number of samples, the unit, the factor to m/s² and the OpenSees line that reads the file.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

from rockstudy.cli import COMMANDS


def register(sub) -> None:
    """Add ``records`` to the subparsers ``sub``.

    Parameters
    ----------
    sub : argparse._SubParsersAction
        The subparsers of the top-level parser (``parser.add_subparsers()``).
    """
    pr = sub.add_parser("records", help=COMMANDS["records"].help)
    pr.add_argument("--suite", help="list only this suite's records (default: every suite)")
    add_export_arguments(pr)
    pr.set_defaults(run=_cmd_records)


def _cmd_records(args, parser):
    """``records``: the suites and their records (``--export``: one record to a file)."""
    if args.export is not None:
        return run_export(args, parser)
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


FORMATS = ("one-column", "two-column", "at2")
"""What ``--format`` accepts."""


def add_export_arguments(parser) -> None:
    """Add ``--export``, ``--format`` and ``--output`` to the ``records`` subparser.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The ``records`` subparser.
    """
    parser.add_argument("--export", metavar="SUITE:ID",
                        help="write this record to a file (--format, --output) and print its dt as JSON")
    parser.add_argument("--format", choices=FORMATS, default="one-column",
                        help="one-column: one sample a line (OpenSees timeSeries Path); two-column: time and "
                             "acceleration; at2: PEER NGA [default: one-column]")
    parser.add_argument("--output", help="file to write [default: SUITE_ID.txt, or .AT2 with --format at2]")


def export_text(times, acceleration, fmt: str) -> str:
    """The samples as text: one a line (``one-column``) or time and sample a line (``two-column``).

    Parameters
    ----------
    times : array_like
        Sample times, written by ``two-column``. [s]
    acceleration : array_like
        The samples, in the record's unit.
    fmt : {"one-column", "two-column"}
        The layout.
    """
    import numpy as np

    acceleration = np.asarray(acceleration, dtype=float)
    if fmt == "one-column":
        return "".join(f"{a:.9e}\n" for a in acceleration)
    if fmt == "two-column":
        return "".join(f"{t:.6f} {a:.9e}\n" for t, a in zip(np.asarray(times, float), acceleration))
    raise ValueError(f"format: {fmt!r} is not one of {', '.join(FORMATS)}")


def run_export(args, parser) -> dict:
    """``records --export``: write the record and print (and return) the summary.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``rockstudy records``: ``export`` (``SUITE:ID``), ``format`` and ``output``.
    parser : argparse.ArgumentParser
        The command's parser; a bad record name is reported through it (exit status 2).
    """
    from rockstudy.core.io import write_text
    from rockstudy.model import record_suites
    from rockstudy.model.records import unit_factor, write_at2

    try:
        info, record = record_suites.load_record(args.export, "--export")
    except record_suites.RecordSuiteError as exc:
        parser.error(f"argument {exc}")
    default = f"{info.suite}_{info.id}" + (".AT2" if args.format == "at2" else ".txt")
    path = Path(args.output or default)
    times = record_suites.record_time(record)
    if args.format == "at2":
        write_at2(record, path, title=f"{info.name} {info.event} {info.station}")
    else:
        write_text(export_text(times, record.acceleration, args.format), path)
    factor = unit_factor(record.unit)
    summary = {"record": info.name, "event": info.event, "station": info.station, "file": str(path),
               "format": args.format, "dt_s": record.dt, "npts": int(record.acceleration.size),
               "duration_s": float(times[-1]) if times.size else 0.0, "unit": record.unit,
               "to_m_per_s2": factor,
               "opensees": f"timeSeries Path 1 -dt {record.dt:g} -filePath {path} -factor {factor:g}"
                           if args.format == "one-column" else None}
    print(json.dumps(summary, indent=2))
    return summary
