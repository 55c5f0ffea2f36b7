"""The progress bar of long commands at a terminal (``rockstudy spectrum``), drawn by rich on standard error.

Where standard error is not a terminal (a pipe, a file, a workflow job's log) there is no bar: the library
logs a line after each tenth of the work, as in the jobs' logs.
"""
from __future__ import annotations

import os
import sys
from contextlib import contextmanager


def at_terminal(stream=None) -> bool:
    """Whether ``stream`` is a terminal that can draw a bar (not ``TERM=dumb``).

    Parameters
    ----------
    stream : file-like, optional
        The stream; standard error when None.
    """
    stream = sys.stderr if stream is None else stream
    isatty = getattr(stream, "isatty", None)
    return bool(isatty and isatty()) and os.environ.get("TERM") != "dumb"


@contextmanager
def progress_bar(enabled: bool | None = None, file=None):
    """A progress bar for :func:`rockstudy.analysis.spectra.spectrum`'s ``progress=``: yields
    ``update(done, total, label)``, one bar per label, or None where no bar is drawn.

    Parameters
    ----------
    enabled : bool or None, default None
        Draw the bar; None: when ``file`` is a terminal (:func:`at_terminal`).
    file : file-like, optional
        Where the bar is drawn; standard error when None.
    """
    file = sys.stderr if file is None else file
    if not (at_terminal(file) if enabled is None else enabled):
        yield None
        return
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )
    console = Console(file=file, force_terminal=True if enabled else None)
    columns = (TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TextColumn("cases,"),
               TimeElapsedColumn(), TextColumn("elapsed,"), TimeRemainingColumn(), TextColumn("left"))
    with Progress(*columns, console=console) as bar:
        tasks = {}

        def update(done: int, total: int, label: str) -> None:
            if label not in tasks:
                tasks[label] = bar.add_task(label, total=total)
            bar.update(tasks[label], completed=done)

        yield update
