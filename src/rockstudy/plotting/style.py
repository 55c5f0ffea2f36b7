"""The one style of the study's figures: palette, line styles, sizes, axis labels.

Every colour, line style and size the figures use is named here, so that one figure cannot drift
from the others and a change of style is one edit. :func:`styled` draws a figure in :data:`STYLE`.
"""
from __future__ import annotations

import sys
from functools import wraps

import matplotlib

if "ipykernel" not in sys.modules:  # files, not windows; a notebook keeps its inline backend
    matplotlib.use("Agg")

FREQUENCY_LABEL = r"$\omega_p/p$ [-]"


AMPLITUDE_LABEL = r"$a_p/(g\,\tan\alpha)$ [-]"


INTENSITY_LABELS = {"pga_ratio": r"PGA$/(g\,\tan\alpha)$ [-]", "pgv_ratio": r"PGV$\cdot p/(g\,\tan\alpha)$ [-]"}


OKABE_ITO = {"black": "#000000", "orange": "#E69F00", "sky_blue": "#56B4E9", "bluish_green": "#009E73",
             "yellow": "#F0E442", "blue": "#0072B2", "vermillion": "#D55E00", "reddish_purple": "#CC79A7"}
"""The Okabe–Ito palette (Okabe & Ito 2008), distinguishable with every common colour-vision deficiency."""


CURVE_COLOURS = tuple(OKABE_ITO[c] for c in ("blue", "vermillion", "bluish_green", "orange", "reddish_purple",
                                             "sky_blue", "yellow"))
"""Colours of the curves of one figure in drawing order (black is kept for references)."""


CURVE_DASHES = ("-", "--", "-.", ":", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 1)), (0, (8, 2)))
"""Line styles paired with :data:`CURVE_COLOURS`, so that curves also differ in grey-scale print."""


REFERENCE_STYLE = {"color": OKABE_ITO["black"], "lw": 1.0, "ls": (0, (4, 2)), "marker": "o", "ms": 3.0,
                   "zorder": 5}
"""A reference curve (continuous control, no delay, no noise, the decisive N): black, dashed, thin,
with dots, drawn on top of the wider coloured curves, which show through its gaps and on either side."""

CURVE_WIDTH = 1.4
"""Line width of the last (narrowest, topmost) of the compared curves. [pt]"""

CURVE_WIDTH_STEP = 1.0
"""How much wider each compared curve is than the one drawn after it: curves that (nearly) coincide
show as nested bands, every one visible, instead of the last hiding the others. [pt]"""


def curve_widths(n: int) -> list[float]:
    """Line widths of ``n`` compared curves in drawing order: the first widest, each next one
    :data:`CURVE_WIDTH_STEP` narrower, the last :data:`CURVE_WIDTH` wide. [pt]

    Parameters
    ----------
    n : int
        Number of curves compared on one axes. [-]
    """
    return [CURVE_WIDTH + CURVE_WIDTH_STEP * (n - 1 - i) for i in range(n)]


STYLE = {"font.size": 9.0, "axes.titlesize": 10.0, "axes.labelsize": 9.0, "legend.fontsize": 8.0,
         "figure.titlesize": 11.0, "xtick.labelsize": 8.5, "ytick.labelsize": 8.5,
         "axes.grid": True, "grid.linewidth": 0.3, "grid.alpha": 0.5, "lines.linewidth": 1.3,
         "legend.framealpha": 0.9, "image.cmap": "viridis", "savefig.dpi": 150,
         "axes.prop_cycle": matplotlib.cycler(color=CURVE_COLOURS)}
"""The one style of every figure of the study (matplotlib rc parameters; see :func:`styled`)."""


OUTCOME_COLOURS = {"no_uplift": "#EEEEEE", "safe": OKABE_ITO["sky_blue"],
                   "overturned_without_impact": OKABE_ITO["vermillion"],
                   "overturned_after_impact": OKABE_ITO["orange"], "undetermined": "#555555"}
"""Outcome map colours: safe in blue against overturning in vermillion/orange (no red against green)."""


STRATEGY_COLOURS = {"FS": OKABE_ITO["black"], "PASSIVE": OKABE_ITO["bluish_green"], "CS01": OKABE_ITO["blue"],
                    "CS02": OKABE_ITO["vermillion"]}


STRATEGY_MARKERS = {"FS": "o", "PASSIVE": "s", "CS01": "^", "CS02": "v"}



A_MAX0_STYLE = {"color": "0.3", "lw": 1.0, "ls": (0, (6, 3))}
"""The protection level a_max,0: a dashed dark-grey line."""

PAPER_LINE_STYLE = {**A_MAX0_STYLE, "color": OKABE_ITO["black"]}
"""A value of the paper drawn as a line: dashed, black."""

PAPER_MARKER = {"ls": "none", "marker": "*", "ms": 12, "color": OKABE_ITO["black"]}
"""A value of the paper, or the example point, drawn as a black star."""

BEST_MARKER = {"marker": "*", "ms": 12, "color": OKABE_ITO["vermillion"], "markeredgecolor": "w"}
"""The best point of a calibration: a vermillion star with a white edge."""

ABOVE_MARKER = {"ls": "none", "marker": "^", "ms": 4}
"""Where nothing overturned up to the scan's top: a small triangle at the top edge (in the curve's colour)."""

ZERO_LINE = {"color": "k", "lw": 0.4}
"""The zero line of a time history."""

GUIDE_LINE = {"color": "0.5", "lw": 0.6, "ls": ":"}
"""A guide line (θ/α = ±1, the excitation's envelope)."""

HISTORY_STYLES = {"ground": {"color": "0.55", "ls": "--", "lw": 0.9},
                  "rotation": {"color": OKABE_ITO["blue"], "lw": 1.4},
                  "velocity": {"color": OKABE_ITO["vermillion"], "lw": 0.8},
                  "stiffness": {"color": OKABE_ITO["bluish_green"], "lw": 1.0},
                  "baseline": {"color": OKABE_ITO["black"], "lw": 1.0},
                  "noisy": {"color": OKABE_ITO["vermillion"], "lw": 0.6}}
"""Lines of a time history: the ground motion, θ/α, θ̇/(p·α), K/K_max; the baseline and noisy excitation."""

HISTORY_WIDTH = 1.0
"""Line width of the compared rotation histories (Fig. 5(b)). [pt]"""

MAP_THRESHOLD_STYLE = {"color": OKABE_ITO["black"], "lw": 1.2}
"""The lower threshold a_min,OVER drawn over an outcome map."""

ENVELOPE_STYLE = {"color": OKABE_ITO["bluish_green"], "lw": 1.4, "ls": "--"}
"""The lowest threshold over the realisations drawn over a probability map."""

PROBABILITY_CMAP = "magma_r"
"""Colour map of P(overturn) (perceptually uniform, readable in grey)."""

HALF_CONTOUR_STYLE = {"colors": OKABE_ITO["sky_blue"], "linewidths": 1.2}
"""The P = 0.5 contour of a probability map."""

FRAGILITY_DOTS = {"ls": "none", "marker": "o", "ms": 3, "alpha": 0.7}
"""The fraction of records that overturn the block at each intensity."""

RECORD_BAR_COLOUR = "0.85"
"""The grey bar of a record's own PGA."""

MARKER_SIZE = 4
"""Size of the markers of compared points (records' thresholds, design sweeps). [pt]"""

SMALL_FONT = 7
"""Font size of legends in crowded panels and of values written in map cells. [pt]"""

PANEL_TITLE_FONT = 9
"""Font size of a panel's title in the figures beyond the paper. [pt]"""

LIGHT_GRID = {"lw": 0.3, "alpha": 0.5}
"""The grid of figures drawn without :data:`STYLE`."""

LABEL_BOX = {"boxstyle": "round,pad=0.2", "fc": "w", "ec": "0.6", "lw": 0.5, "alpha": 0.9}
"""The box behind a point's label, so that the label reads over a grid or a curve."""

LABEL_ARROW = {"arrowstyle": "-", "color": "0.3", "lw": 0.6, "shrinkA": 0, "shrinkB": 4}
"""The thin line from a point's label to the point."""

BURST_SHADE = {"color": OKABE_ITO["yellow"], "alpha": 0.25, "lw": 0, "zorder": 0}
"""The shading of a stretch where the anchorage stiffness switches densely (Figs. 2–3)."""

NOTE_FONT = 8
"""Font size of a figure's note under its axes (what a shaded stretch is). [pt]"""

RECORD_LABEL_FONT = 8
"""Font size of the record names in front of each row of a record-threshold chart. [pt]"""

RECORD_ROW_HEIGHT = 0.3
"""Height of one record's row in a record-threshold chart: with :data:`RECORD_ROW_SPREAD`, the
strategies' markers of one row stand one marker apart. [in]"""

RECORD_ROW_SPREAD = 0.6
"""Span of the strategies' marker heights within a row (rows are 1 apart)."""

MAP_COLUMNS = 2
"""Panels per row of a figure of maps. [-]"""

MAP_PANEL_SIZE = (4.2, 3.9)
"""Width and height of one map panel. [in]"""


def styled(figure_function):
    """Draw ``figure_function``'s figure in the study's :data:`STYLE`.

    Parameters
    ----------
    figure_function : callable
        A function that makes and returns a figure; the decorated function takes the same arguments
        and calls it inside ``matplotlib.rc_context(STYLE)``.
    """
    @wraps(figure_function)
    def draw(*args, **kwargs):
        with matplotlib.rc_context(STYLE):
            return figure_function(*args, **kwargs)
    return draw


def level_label(level: float) -> str:
    """A noise level as a label: ``"R005 (5% noise)"``, or ``"no noise (R000)"`` for 0.

    Parameters
    ----------
    level : float
        Noise level r as a fraction (0.05 for 5 %). [-]
    """
    return "no noise (R000)" if level == 0 else f"R{round(level * 100):03d} ({level:.0%} noise)"


def plain_text(text) -> str:
    """``text`` escaped for matplotlib, so that a ``$`` in it is drawn as a dollar sign instead of
    starting mathtext (an unbalanced one would fail the whole figure).

    Parameters
    ----------
    text : object
        A name from a file or a configuration (a record's event, a status); turned into a string.
    """
    return str(text).replace("$", r"\$")
