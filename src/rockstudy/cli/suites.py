"""``rockstudy records``: the record suites and their records."""
from __future__ import annotations

import sys

from rockstudy.cli import COMMANDS


def register(sub) -> None:
    """Add ``records`` to the subparsers ``sub``."""
    pr = sub.add_parser("records", help=COMMANDS["records"].help)
    pr.add_argument("--suite", help="list only this suite's records (default: every suite)")
    pr.set_defaults(run=_cmd_records)


def _cmd_records(args, parser):
    """``records``: the suites and their records."""
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


