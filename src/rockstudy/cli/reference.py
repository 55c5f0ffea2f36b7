"""The command-line reference as a Markdown page (``docs/cli.md``), generated from the parser itself, so that
it lists every option of every command with the default and the help ``rockstudy COMMAND --help`` shows.

The documentation build writes it (``docs/conf.py``); ``tests/test_docs_cli.py`` checks that the committed
page is the one the parser gives.
"""
from __future__ import annotations

import argparse

HEADER = """# Command-line reference

Every option of every `rockstudy` command, with its default, as `rockstudy COMMAND --help` prints it. This
page is generated from the command's parser at every documentation build (`rockstudy.cli.reference`); the
[usage guide](usage.md) shows the commands at work.

"""


def _cell(text: str) -> str:
    """``text`` on one line of a Markdown table (pipes escaped)."""
    return " ".join(str(text).split()).replace("|", "\\|")


def _sentence(text: str) -> str:
    """``text`` with a capital first letter (the rest as written: "JSON" stays)."""
    return text[:1].upper() + text[1:]


def _option(action: argparse.Action) -> str:
    """How the option is written: ``--strategy {FS,PASSIVE,CS01,CS02}``, ``--output OUTPUT``, ``--map``."""
    names = ", ".join(f"`{name}`" for name in action.option_strings)
    if action.nargs == 0:
        return names
    if action.choices is not None:
        value = "{" + ",".join(map(str, action.choices)) + "}"
    else:
        value = action.metavar or action.dest.upper()
    return f"{names} `{value}`"


def _help(parser: argparse.ArgumentParser, action: argparse.Action) -> str:
    """The option's help as ``--help`` prints it (its default stated, ``%(default)s`` filled in)."""
    formatter = parser._get_formatter()
    text = formatter._get_help_string(action) or ""
    params = {**vars(action), "prog": parser.prog}
    params = {k: (getattr(v, "__name__", v) if k == "type" else v) for k, v in params.items()}
    if params.get("choices") is not None:
        params["choices"] = ", ".join(map(str, params["choices"]))
    try:
        return text % params
    except (KeyError, TypeError, ValueError):
        return text


def command_reference(parser: argparse.ArgumentParser) -> str:
    """The Markdown reference of every subcommand of ``parser``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command line's parser (:func:`rockstudy.cli.build_parser`).
    """
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    helps = {choice.dest: choice.help for choice in sub._choices_actions}
    lines = [HEADER]
    for name, command in sub.choices.items():
        lines.append(f"## `rockstudy {name}`\n\n{_sentence(helps.get(name, ''))}.\n")
        groups = [(group.title, [a for a in group._group_actions if a.option_strings and a.help != argparse.SUPPRESS
                                 and not isinstance(a, argparse._HelpAction)]) for group in command._action_groups]
        for title, actions in groups:
            if not actions:
                continue
            if title not in ("options", "optional arguments"):
                lines.append(f"{title[0].upper()}{title[1:]}:\n")
            lines.append("| option | what it is |\n|---|---|")
            lines += [f"| {_option(a)}{' (required)' if a.required else ''} | {_cell(_help(command, a))} |"
                      for a in actions]
            lines.append("")
    return "\n".join(lines).rstrip() + "\n"
