"""Placing things on a figure from its data: axis limits, labels clear of the curves."""
from __future__ import annotations

import numpy as np
from matplotlib.text import Text

from rockstudy.plotting.style import LABEL_ARROW, LABEL_BOX


def limits_of(curves, include=(), margin: float = 0.05) -> tuple[float, float]:
    """Axis limits that hold every finite value of ``curves`` and ``include``, widened by ``margin``.

    Without a finite value the limits are (-1, 1); with a single value, ±0.5 around it.

    Parameters
    ----------
    curves : sequence of array_like
        The values drawn (any shapes); NaN and inf are left out.
    include : sequence of float, default ()
        Further values to hold, e.g. guide lines.
    margin : float, default 0.05
        Padding on each side, as a fraction of the values' span. [-]
    """
    values = np.concatenate([np.ravel(np.asarray(c, dtype=float)) for c in curves] + [np.asarray(include, float)])
    values = values[np.isfinite(values)]
    if values.size == 0:
        return (-1.0, 1.0)
    low, high = float(values.min()), float(values.max())
    pad = margin * (high - low) if high > low else 0.5
    return low - pad, high + pad


LABEL_OFFSETS = ((14, 18), (-14, 18), (14, -22), (-14, -22), (28, 0), (-28, 0))
"""Where :func:`label_clear_of_lines` may put a point's label, in points from the point."""


def label_clear_of_lines(ax, xy, text: str, offsets=LABEL_OFFSETS):
    """Write ``text`` next to the point ``xy``, with a thin line to the point, clear of the lines drawn.

    The label goes at the one of ``offsets`` where its box lies inside the axes, off the legend, and
    farthest from every line drawn on ``ax``; measured on the page with the layout as it is now, so
    call it after the figure's layout is done. Returns the annotation.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes with the lines to keep clear of.
    xy : (float, float)
        The point labelled, in data coordinates.
    text : str
        The label.
    offsets : sequence of (float, float), default LABEL_OFFSETS
        Candidate positions of the label, from ``xy``. [pt]
    """
    ax.autoscale_view()
    renderer = ax.figure.canvas.get_renderer()
    inside = ax.get_window_extent(renderer)
    legend = ax.get_legend().get_window_extent(renderer) if ax.get_legend() is not None else None
    points = []
    for line in ax.get_lines():
        x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
        if x.size == 0 or x.size != y.size:
            continue
        page = line.get_transform().transform(np.column_stack([x, y]))
        if len(page) > 1:  # points along each segment, so that a long straight segment counts too
            s = np.linspace(0.0, 1.0, 16)[:, None, None]
            page = (page[:-1][None] * (1 - s) + page[1:][None] * s).reshape(-1, 2)
        points.append(page[np.isfinite(page).all(axis=1)])
    points = np.concatenate(points) if points else np.empty((0, 2))

    def placed(offset):
        note = ax.annotate(text, xy, xytext=offset, textcoords="offset points", va="center",
                           ha="left" if offset[0] > 0 else "right" if offset[0] < 0 else "center",
                           bbox=LABEL_BOX, arrowprops=LABEL_ARROW)
        note.update_positions(renderer)
        box = Text.get_window_extent(note, renderer).padded(3.0)  # the text, with its box's padding
        if not (inside.x0 <= box.x0 and box.x1 <= inside.x1 and inside.y0 <= box.y0 and box.y1 <= inside.y1) \
                or (legend is not None and box.overlaps(legend)):
            return note, -np.inf
        if not points.size:
            return note, np.inf
        dx = np.maximum.reduce([box.x0 - points[:, 0], np.zeros(len(points)), points[:, 0] - box.x1])
        dy = np.maximum.reduce([box.y0 - points[:, 1], np.zeros(len(points)), points[:, 1] - box.y1])
        return note, float(np.hypot(dx, dy).min())

    best, best_clearance = None, -np.inf
    for offset in offsets:
        note, clearance = placed(offset)
        if clearance > best_clearance:
            if best is not None:
                best.remove()
            best, best_clearance = note, clearance
        else:
            note.remove()
    return best
