"""Writing figures to files."""
from __future__ import annotations

from functools import partial
from pathlib import Path

import matplotlib.pyplot as plt
from matplotlib.text import Text

from rockstudy.core.io import atomic_write

DPI = 150
"""Resolution of every saved figure [dots per inch]."""
SMALLEST_TEXT_KEY = "rockstudy smallest text px"
"""PNG text chunk holding the height [px] of the figure's smallest text at the PNG's own size: a page that
draws the figure at a scale s shows that text s times as high (the report's check reads it)."""


def smallest_text_px(fig, dpi: float = DPI) -> float | None:
    """Font size [px] of the smallest visible, non-empty text of ``fig`` at ``dpi`` (None: no text).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    dpi : float, default :data:`DPI`
        The resolution it is saved at. [1/in]
    """
    sizes = [t.get_fontsize() for t in fig.findobj(Text) if t.get_visible() and t.get_text().strip()]
    return min(sizes) * dpi / 72 if sizes else None


def save_figure(fig, *paths) -> list[Path]:
    """Save ``fig`` to each path atomically (format from the suffix; :func:`rockstudy.core.io.atomic_write`)
    and close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure; it is closed once written.
    *paths : str or pathlib.Path
        The files to write (e.g. ``.png`` and ``.pdf``), at :data:`DPI`; a PDF carries no creation date, a
        PNG the size of its smallest text (:data:`SMALLEST_TEXT_KEY`).

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    written = []
    # the text as it is laid out (a legend, tick labels), before it is measured: laid out and drawn with
    # no pixels made (the files are drawn anew by savefig)
    fig.draw_without_rendering()
    smallest = smallest_text_px(fig)
    for path in map(Path, paths):
        fmt = path.suffix.lstrip(".").lower()
        # no creation date in a PDF: the same figure gives the same bytes on every run; a PNG says how small
        # its smallest text is
        metadata = {"CreationDate": None} if fmt == "pdf" else None
        if fmt == "png" and smallest is not None:
            metadata = {SMALLEST_TEXT_KEY: f"{smallest:.2f}"}
        atomic_write(path, partial(fig.savefig, dpi=DPI, format=fmt, metadata=metadata))
        written.append(path)
    plt.close(fig)
    return written
