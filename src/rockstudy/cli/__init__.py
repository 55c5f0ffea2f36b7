"""Command line: ``rockstudy simulate | threshold | spectrum | jos | records | fragility | risk``
(``rockstudy --version``).

A block is a preset (``--block BLC06``) or its dimensions (``--width --height --depth``, with
``--density`` and ``--restitution``); ``--config FILE`` takes a study's settings (block, anchorage,
control options, excitation, noise reading, seed, overturning criterion, free time, grids) from
its ``config.yaml``, and any option given on the command line overrides them. Every ``--help``
states each option's default.

Every command checks all its arguments before any heavy work against their declarations
(:mod:`rockstudy.studies.config_model`, and the relations of :mod:`rockstudy.core.validation`) and exits
with status 2 and a message naming the argument, the value and what is allowed; ``--config FILE`` is
checked like any study config (an unknown key or a bad value is refused, naming the key). A run that hits
the fast engine's event cap ends with an "undetermined" result, not a traceback. A closed pipe
(``rockstudy records | head -1``) ends the command quietly. A dependency that fails to import is one line
naming it (exit 1); an output that cannot be written is one line (exit 2) saying why and where the computed
result was kept instead (:func:`rockstudy.core.io.atomic_write`).

The commands live in modules of this package, one per group: each exposes ``register(sub)``, which adds
its subparsers to argparse's subparsers ``sub`` and sets ``run=<function(args, parser)>`` on each;
:data:`COMMANDS` names the module and the one-line help of every command. Only the module of the command
given is imported, so ``rockstudy --help`` and ``rockstudy --version`` load neither numba nor xarray.
"""
from __future__ import annotations

import argparse
import importlib
import os
import sys
from typing import NamedTuple

from rockstudy._version import __version__
from rockstudy.cli.output import NonFiniteOutputError


class Command(NamedTuple):
    module: str
    help: str


COMMANDS = {
    "simulate": Command("simulate", "run one case and print a JSON summary"),
    "threshold": Command("simulate", "minimum overturning amplitude ratio at one frequency (JSON)"),
    "spectrum": Command("spectrum", "overturning spectrum over a frequency grid, written to netCDF"),
    "jos": Command("spectrum", "utility index J_OS (Eqs. 18-22) of two spectrum files"),
    "records": Command("suites", "list the record suites and their records (id, event, year, magnitude, station, "
                                 "distance, site class, PGA, PGV, pulse)"),
    "fragility": Command("risk", "fragility of one object on a record suite (netCDF; JSON with median_g and "
                                 "dispersion)"),
    "risk": Command("risk", "rate and probability of overturning from a hazard curve or a scenario, or the "
                            "fragility median that meets a target"),
}
"""Every command: the module of this package that registers it, and its one-line help."""

_OPTIONS = ("_apply_config", "_scenario")


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

    def error(self, message):
        """Exit 2 with the argument named (argparse already names it) in at most three lines: the error and
        where the options are listed (not the usage, which runs over many lines)."""
        lines = str(message).splitlines() or [""]
        text = "\n".join(line if len(line) <= 400 else line[:397] + "..." for line in lines[:2])
        self.exit(2, f"rockstudy: error: {text}\n(the options: {self.prog} --help)\n")


def build_parser(commands=None) -> argparse.ArgumentParser:
    """The parser of ``commands``; only their modules are imported.

    Parameters
    ----------
    commands : iterable of str or None, default None
        Names of commands (keys of :data:`COMMANDS`) whose options are registered; the others are listed by
        name only. None: every command; ``()``: the top-level parser alone, which loads nothing of the
        library.
    """
    parser = _Parser(prog="rockstudy", description="Rocking of controlled rigid blocks (overturning spectra study)")
    parser.add_argument("--version", action="version", version=f"rockstudy {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    wanted = list(COMMANDS) if commands is None else list(commands)
    modules = []
    for name, command in COMMANDS.items():
        if name in wanted and command.module not in modules:
            modules.append(command.module)
    for module in modules:
        importlib.import_module(f"{__name__}.{module}").register(sub)
    for name, command in COMMANDS.items():  # the others by name only (the top-level help lists them)
        if name not in sub.choices:
            sub.add_parser(name, help=command.help, add_help=False)
    return parser


def _subparser(parser, command):
    """The parser of ``command`` inside ``parser``."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return action.choices[command]
    return parser  # pragma: no cover


def _quiet_broken_pipe() -> int:
    """A reader that closed the pipe (``| head -1``): no traceback, and no second error when Python flushes
    stdout at exit."""
    try:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except OSError:  # pragma: no cover - stdout without a file descriptor
        pass
    return 141  # 128 + SIGPIPE, as a Unix tool killed by the closed pipe


def main(argv=None):
    """Run the command line ``argv``; returns the exit status.

    Parameters
    ----------
    argv : sequence of str or None, default None
        The arguments after the program's name, e.g. ``["spectrum", "--help"]``; None: ``sys.argv[1:]``.
    """
    from rockstudy.core.frames import with_frame_room

    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        return with_frame_room(_main, argv)  # room for numba's calls when it compiles (core.frames)
    except ImportError as exc:  # a dependency that fails to load (a broken compiled library): one line naming it
        return _dependency_failed(exc)


def _main(argv: list) -> int:
    from rockstudy.core.validation import InputError

    given = [word for word in argv if word in COMMANDS][:1]
    parser = build_parser(given)
    try:
        args, unknown = parser.parse_known_args(argv)
        parser = _subparser(parser, args.command)  # its errors name the command: "rockstudy spectrum --help"
        if unknown:  # refused by the command's parser, so that the hint names the command's own --help
            parser.error(f"unrecognized arguments: {' '.join(unknown)}")
        if hasattr(args, "config"):
            from rockstudy.cli.options import _apply_config
            _apply_config(args, argv, parser)
        args.run(args, parser)
        sys.stdout.flush()
    except InputError as exc:  # a check of the library, after parsing: the same exit as argparse's
        parser.error(str(exc))
    except BrokenPipeError:
        return _quiet_broken_pipe()
    except OSError as exc:  # an output could not be written (core.io's OutputError): why, and where the result is
        io = sys.modules.get("rockstudy.core.io")  # loaded by every writer; not by the help
        if io is None or not isinstance(exc, io.OutputError):
            raise
        sys.stderr.write(f"{parser.prog}: error: {str(exc).splitlines()[0]}\n")
        return 2
    except NonFiniteOutputError as exc:  # a result strict JSON cannot carry (NaN, inf): one line, nothing printed
        sys.stderr.write(f"{parser.prog}: error: {exc}\n")
        return 1
    except KeyboardInterrupt:
        return _interrupted()
    except SystemError as exc:  # Ctrl-C while numba's compiled code called back into Python
        from rockstudy.core.interrupts import caused_by_interrupt
        if not caused_by_interrupt(exc):
            raise
        return _interrupted()
    return 0


def _dependency_failed(exc: ImportError) -> int:
    """One line naming the dependency that failed to import, and how to repair it; a module of rockstudy
    itself that is missing is a fault of the package, whose traceback is kept."""
    failing = exc.name or ""
    if failing.startswith("rockstudy"):
        raise exc
    first = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    if first.startswith("rockstudy"):  # the library named the dependency already (rockstudy._import)
        sys.stderr.write(f"{first}\n")
    else:
        sys.stderr.write(f"rockstudy: error: {failing or 'a dependency'} failed to import ({first}); reinstall it "
                         "(pip install -e .)\n")
    return 1


def _interrupted() -> int:
    """Ctrl-C (SIGINT): one line, no traceback; nothing is written, as outputs are written whole at the end."""
    sys.stderr.write("rockstudy: interrupted\n")
    return 130  # 128 + SIGINT, as a Unix tool stopped by Ctrl-C


def __getattr__(name):
    """The shared option helpers of :mod:`rockstudy.cli.options`, imported on first use."""
    if name in _OPTIONS:
        return getattr(importlib.import_module(f"{__name__}.options"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
