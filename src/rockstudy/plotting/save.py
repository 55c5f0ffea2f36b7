"""Writing figures to files."""
from __future__ import annotations

from functools import partial
from pathlib import Path

import matplotlib.pyplot as plt

from rockstudy.core.io import atomic_write


def save_figure(fig, *paths) -> list[Path]:
    """Save ``fig`` to each path atomically (format from the suffix; :func:`rockstudy.core.io.atomic_write`)
    and close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure; it is closed once written.
    *paths : str or pathlib.Path
        The files to write (e.g. ``.png`` and ``.pdf``), at 150 dpi; a PDF carries no creation date.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    written = []
    for path in map(Path, paths):
        fmt = path.suffix.lstrip(".").lower()
        # no creation date in a PDF: the same figure gives the same bytes on every run
        metadata = {"CreationDate": None} if fmt == "pdf" else None
        atomic_write(path, partial(fig.savefig, dpi=150, format=fmt, metadata=metadata))
        written.append(path)
    plt.close(fig)
    return written
