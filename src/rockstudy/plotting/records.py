"""Recorded ground motions: fragility curves over a record suite, every record's threshold."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from rockstudy.plotting.style import (
    A_MAX0_STYLE,
    FRAGILITY_DOTS,
    INTENSITY_LABELS,
    LIGHT_GRID,
    MARKER_SIZE,
    PANEL_TITLE_FONT,
    RECORD_BAR_COLOUR,
    RECORD_LABEL_FONT,
    RECORD_ROW_HEIGHT,
    RECORD_ROW_SPREAD,
    SMALL_FONT,
    STRATEGY_COLOURS,
    STRATEGY_MARKERS,
    plain_text,
    styled,
)


def plot_fragility(ax, ds, strategy: str, **kwargs):
    """Fraction of the records that overturn the block (markers) and the fitted lognormal (line).

    Returns the markers and the line.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    ds : xarray.Dataset
        A fragility dataset (:func:`rockstudy.analysis.fragility.fragility_dataset`): ``fraction`` over
        (strategy, intensity), ``fragility_median`` and ``fragility_dispersion`` per strategy.
    strategy : str
        The strategy drawn, a value of ``ds.strategy``; it sets the default colour.
    **kwargs : dict
        Passed to ``ax.plot`` for the fitted line; ``color`` also colours the markers.
    """
    d = ds.sel(strategy=strategy)
    colour = kwargs.pop("color", STRATEGY_COLOURS.get(strategy, None))
    x = ds["intensity"].values
    dots = ax.plot(x, d["fraction"].values, **FRAGILITY_DOTS, color=colour)[0]
    median, beta = float(d["fragility_median"]), float(d["fragility_dispersion"])
    fine = np.linspace(x.min(), x.max(), 400)
    if np.isfinite(median) and beta > 0:
        from scipy.special import ndtr  # the standard normal CDF (scipy.stats takes 0.8 s to import)
        curve = ndtr(np.log(fine / median) / beta)
    else:
        curve = np.where(fine >= median, 1.0, 0.0) if np.isfinite(median) else np.full_like(fine, np.nan)
    line = ax.plot(fine, curve, color=colour, label=f"{strategy}: θ = {median:.2f}, β = {beta:.2f}", **kwargs)[0]
    ax.plot([median], [0.5], marker="|", ms=10, color=colour)
    return dots, line


def plot_median_shift(ax, ds):
    """Fragility median over FS's, θ/θ_FS, with the bootstrap 95 % interval over records; returns the bars.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    ds : xarray.Dataset
        A fragility dataset (:func:`rockstudy.analysis.fragility.fragility_dataset`): ``median_ratio``,
        ``median_ratio_low`` and ``median_ratio_high`` over ``strategy``.
    """
    strategies = list(ds["strategy"].values)
    ratio = ds["median_ratio"].values
    low, high = ds["median_ratio_low"].values, ds["median_ratio_high"].values
    x = np.arange(len(strategies))
    bars = ax.bar(x, ratio, color=[STRATEGY_COLOURS.get(s, "0.5") for s in strategies], alpha=0.75)
    ax.errorbar(x, ratio, yerr=[ratio - low, high - ratio], fmt="none", ecolor="0.2", capsize=4)
    ax.axhline(1.0, color=A_MAX0_STYLE["color"], lw=0.8)
    ax.set_xticks(x, strategies)
    for xi, r, top in zip(x, ratio, np.where(np.isfinite(high), high, ratio)):
        ax.annotate(f"{100 * (r - 1):+.0f} %", (xi, top), xytext=(0, 3), textcoords="offset points", ha="center",
                    va="bottom", fontsize=8)
    ax.set_ylim(0, 1.12 * np.nanmax(np.where(np.isfinite(high), high, ratio)))
    ax.set_ylabel(r"$\theta/\theta_{FS}$ [-]")
    return bars


def pga_in_g_axis(ax, tan_alpha: float):
    """A secondary x axis on top of a PGA/(g·tanα) axis giving the same intensity as PGA in g
    (PGA/g = ratio·tanα); returns the secondary axis.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Axes whose x axis is PGA/(g·tanα).
    tan_alpha : float
        tanα of the block, finite and > 0 (else ``ValueError``). [-]
    """
    if not (np.isfinite(tan_alpha) and tan_alpha > 0):
        raise ValueError(f"tan_alpha must be a positive number, got {tan_alpha!r}")
    sec = ax.secondary_xaxis("top", functions=(lambda r: r * tan_alpha, lambda g: g / tan_alpha))
    sec.set_xlabel("PGA [g]")
    return sec


@styled
def figure_fragility(ds):
    """Fragility curves of each strategy over a record suite, and the median shift over FS; with
    the intensity PGA/(g·tanα), a top axis gives it as PGA in g.

    Parameters
    ----------
    ds : xarray.Dataset
        A fragility dataset (:func:`rockstudy.analysis.fragility.fragility_dataset`), as :func:`plot_fragility` and
        :func:`plot_median_shift` take it, with the attributes ``intensity_measure``, ``n_records`` and
        ``n_bootstrap`` (and ``block_alpha`` for the top axis).
    """
    fig, (ax, axr) = plt.subplots(1, 2, figsize=(10, 4.6), width_ratios=(2.2, 1))
    for s in ds["strategy"].values:
        plot_fragility(ax, ds, str(s))
    measure = ds.attrs["intensity_measure"]
    ax.set_xlabel(INTENSITY_LABELS.get(measure, f"{plain_text(ds.attrs['intensity_measure_definition'])} [-]"))
    ax.set_ylabel("fraction of records that overturn the block [-]")
    ax.set_ylim(-0.02, 1.02)
    ax.legend(loc="lower right")
    if measure == "pga_ratio" and "block_alpha" in ds.attrs:
        pga_in_g_axis(ax, float(np.tan(float(ds.attrs["block_alpha"]))))
    ax.set_title(f"Fraction of {ds.attrs['n_records']} records that overturn the block (dots) and lognormal "
                 "fit (lines)", fontsize=PANEL_TITLE_FONT)
    plot_median_shift(axr, ds)
    axr.set_title(f"fragility median over FS's\n(bootstrap 95 % interval, {ds.attrs['n_bootstrap']} draws)",
                  fontsize=PANEL_TITLE_FONT)
    axr.grid(True, axis="y")
    axr.grid(False, axis="x")
    fig.tight_layout()
    return fig


def record_row_offsets(n: int) -> np.ndarray:
    """Offsets of ``n`` strategies' markers within a record's row (rows are 1 apart), spread over
    :data:`RECORD_ROW_SPREAD` so that markers at the same PGA sit one above the other, not on top.

    Parameters
    ----------
    n : int
        Number of strategies; one gives a single offset 0.
    """
    return np.linspace(-0.5, 0.5, n) * RECORD_ROW_SPREAD if n > 1 else np.zeros(1)


def plot_record_thresholds(ax, ds, rows: slice = slice(None)):
    """Threshold PGA [g] of every record (rows, sorted by FS's threshold) for each strategy (markers,
    each strategy at its own height within the row: :func:`record_row_offsets`), and the record's own
    PGA (grey bar): a marker left of the bar's end means the record as recorded overturns the block
    with that strategy. Returns the markers' artists.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    ds : xarray.Dataset
        A record set's fragility (:func:`rockstudy.analysis.fragility.suite_fragility_dataset`):
        ``threshold_pga`` [g] over (strategy, record), ``record_pga`` [g], ``record_id`` and
        ``record_event``.
    rows : slice, optional
        The rows drawn, of the records sorted by FS's threshold (a figure in two columns draws each half).
    """
    fs = ds["threshold_pga"].sel(strategy="FS").values if "FS" in ds.strategy.values else None
    order = np.argsort(np.where(np.isfinite(fs), fs, np.inf)) if fs is not None else np.arange(ds.sizes["record"])
    order = order[rows]
    y = np.arange(order.size)
    ax.barh(y, ds["record_pga"].values[order], color=RECORD_BAR_COLOUR, height=0.8, label="PGA as recorded")
    artists = []
    strategies = [str(s) for s in ds.strategy.values]
    for s, dy in zip(strategies, record_row_offsets(len(strategies))):
        x = ds["threshold_pga"].sel(strategy=s).values[order]
        artists.append(ax.plot(x, y + dy, ls="none", marker=STRATEGY_MARKERS.get(s, "o"), ms=MARKER_SIZE,
                               color=STRATEGY_COLOURS.get(s, None), label=s)[0])
    labels = [plain_text(f"{ds.record_id.values[k]} {str(ds.record_event.values[k])[:22]}") for k in order]
    ax.set_yticks(y, labels, fontsize=RECORD_LABEL_FONT)
    ax.set_ylim(-0.7, order.size - 0.3)
    ax.invert_yaxis()
    ax.set_xlabel("smallest PGA that overturns the block [g]")
    ax.grid(True, axis="x", **LIGHT_GRID)
    ax.grid(False, axis="y")
    return artists


RECORDS_PER_COLUMN = 24
"""Most records of one column of :func:`figure_record_thresholds`."""


@styled
def figure_record_thresholds(ds):
    """Every record's threshold per strategy over one record set (see :func:`plot_record_thresholds`),
    :data:`RECORD_ROW_HEIGHT` per record; more than :data:`RECORDS_PER_COLUMN` records in two columns, so that
    a page that fits the figure to its window keeps its text legible.

    Parameters
    ----------
    ds : xarray.Dataset
        A record set's fragility (:func:`rockstudy.analysis.fragility.suite_fragility_dataset`):
        ``threshold_pga`` [g] and ``threshold_scale`` [-] over (strategy, record), ``record_pga`` [g],
        ``record_id`` and ``record_event``.
    """
    n = ds.sizes["record"]
    columns = 1 if n <= RECORDS_PER_COLUMN else 2
    per_column = -(-n // columns)
    fig, axes = plt.subplots(1, columns, figsize=(7.5 if columns == 1 else 11.0, 1.4 + RECORD_ROW_HEIGHT * per_column),
                             sharex=True, squeeze=False)
    for k, ax in enumerate(axes[0]):
        plot_record_thresholds(ax, ds, slice(k * per_column, (k + 1) * per_column))
    beaten = {str(s): int(np.sum(ds["threshold_scale"].sel(strategy=s).values <= 1.0)) for s in ds.strategy.values}
    ax = axes[0][0]
    title = (f"{plain_text(ds.attrs.get('record_suite', ''))}: records that overturn the block as recorded\n"
             + ", ".join(f"{s} {k}/{n}" for s, k in beaten.items()))
    handles, labels = ax.get_legend_handles_labels()
    if columns == 1:
        ax.set_title(title, fontsize=PANEL_TITLE_FONT, pad=22)
        ax.legend(fontsize=SMALL_FONT, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=len(beaten) + 1,
                  frameon=False)
        fig.tight_layout()
    else:  # the title and one legend above both columns (the records sorted down the left, then the right)
        fig.tight_layout()
        top = 1 - 0.75 / fig.get_size_inches()[1]  # 0.75 in above the axes for the title and the legend
        fig.subplots_adjust(top=top)
        fig.suptitle(title, fontsize=PANEL_TITLE_FONT, y=1 - 0.05 / fig.get_size_inches()[1], va="top")
        fig.legend(handles, labels, fontsize=SMALL_FONT, loc="lower center", bbox_to_anchor=(0.5, top),
                   ncol=len(beaten) + 1, frameon=False)
    return fig
