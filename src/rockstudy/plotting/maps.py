"""Maps over (ω_p/p, a_p/(g·tanα)): the outcome of every run, the probability of overturning."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.patches import Patch

from rockstudy.plotting.spectra import plot_a_max0, plot_threshold, spectrum_axes
from rockstudy.plotting.style import (
    ENVELOPE_STYLE,
    HALF_CONTOUR_STYLE,
    MAP_COLUMNS,
    MAP_PANEL_SIZE,
    MAP_THRESHOLD_STYLE,
    OUTCOME_COLOURS,
    PROBABILITY_CMAP,
    SMALL_FONT,
    level_label,
    styled,
)


def plot_outcome_map(ax, ds, realisation: int = 0):
    """Outcome at every (ω_p/p, a_p/(g·tanα)) grid point, with the safe islands visible.

    Returns the mesh and one legend handle per outcome.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    ds : xarray.Dataset
        A spectrum computed with its map (:func:`rockstudy.analysis.spectra.spectrum`, ``with_map=True``):
        ``outcome`` over (realisation, frequency_ratio, amplitude_ratio) with ``flag_meanings``.
    realisation : int, default 0
        Position (not label) along ``realisation`` of the noise realisation drawn.
    """
    meanings = ds["outcome"].attrs["flag_meanings"].split()
    cmap = ListedColormap([OUTCOME_COLOURS[m] for m in meanings])
    norm = BoundaryNorm(np.arange(len(meanings) + 1) - 0.5, cmap.N)
    out = ds["outcome"].isel(realisation=realisation).transpose("amplitude_ratio", "frequency_ratio")
    mesh = ax.pcolormesh(ds["frequency_ratio"].values, ds["amplitude_ratio"].values, out.values,
                         cmap=cmap, norm=norm, shading="nearest", rasterized=True)
    handles = [Patch(color=OUTCOME_COLOURS[m], label=m.replace("_", " ")) for m in meanings]
    return mesh, handles


@styled
def figure_maps(maps, a_max0: float):
    """Overturning maps (outcome per grid point) of the noise-free strategies, threshold on top;
    :data:`MAP_COLUMNS` panels a row (four maps: a 2 × 2 grid, readable printed a page wide).

    Parameters
    ----------
    maps : sequence of xarray.Dataset
        One spectrum with its map per panel (as :func:`plot_outcome_map` takes it), with ``threshold``
        and a scalar ``strategy``.
    a_max0 : float
        The protection level a_max,0 as an amplitude ratio a/(g·tanα), drawn as a dashed line. [-]
    """
    ncols = min(len(maps), MAP_COLUMNS)
    nrows = -(-len(maps) // ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(MAP_PANEL_SIZE[0] * ncols, MAP_PANEL_SIZE[1] * nrows + 0.9),
                             sharex=True, sharey=True, squeeze=False)
    for ax in axes.flat[len(maps):]:
        ax.remove()
    handles = []
    for ax, ds in zip(axes.flat, maps):
        _, handles = plot_outcome_map(ax, ds)
        plot_threshold(ax, ds["threshold"], mark_above=False, **MAP_THRESHOLD_STYLE,
                       label=r"$a_{min,OVER}$")
        plot_a_max0(ax, a_max0)
        spectrum_axes(ax, f"{ds['strategy'].item()}, no noise")
        ax.grid(False)
        ax.label_outer()
    from matplotlib.lines import Line2D
    handles = handles + [Line2D([], [], **MAP_THRESHOLD_STYLE, label=r"lower threshold $a_{min,OVER}$")]
    fig.legend(handles=handles, loc="lower center", ncol=3, frameon=False)
    fig.suptitle("Outcome of every run of the amplitude scan, without noise")
    fig.tight_layout(rect=(0, 0.6 / fig.get_figheight(), 1, 1))
    return fig


def plot_probability(ax, ds, levels=(0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0)):
    """P(overturn) over the noise realisations at every (ω_p/p, a_p/(g·tanα)) point, with the
    P = 0.5 contour; returns the mesh (for a colour bar).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    ds : xarray.Dataset
        A probability surface (:func:`rockstudy.analysis.probability.probability_from_outcomes`):
        ``probability`` over (frequency_ratio, amplitude_ratio).
    levels : sequence of float, default (0, 0.1, 0.25, 0.5, 0.75, 0.9, 1)
        Not used: the colour scale runs continuously from 0 to 1 and only the P = 0.5 contour is drawn.
    """
    p = ds["probability"].transpose("amplitude_ratio", "frequency_ratio")
    x, y = ds["frequency_ratio"].values, ds["amplitude_ratio"].values
    mesh = ax.pcolormesh(x, y, p.values, cmap=PROBABILITY_CMAP, vmin=0.0, vmax=1.0, shading="nearest", rasterized=True)
    if float(p.min()) < 0.5 < float(p.max()):
        ax.contour(x, y, p.values, levels=[0.5], **HALF_CONTOUR_STYLE)
    return mesh


@styled
def figure_probability(surfaces, a_max0: float):
    """P(overturn) surfaces: one row per noise level, one column per strategy, lower envelope on top.

    Parameters
    ----------
    surfaces : sequence of xarray.Dataset
        Probability surfaces (as :func:`plot_probability` takes them), each with ``threshold``, scalar
        ``strategy`` and ``noise_level`` coordinates and ``n_realisations``.
    a_max0 : float
        The protection level a_max,0 as an amplitude ratio a/(g·tanα), drawn as a dashed line. [-]
    """
    levels = sorted({float(ds["noise_level"]) for ds in surfaces})
    strategies = list(dict.fromkeys(str(ds["strategy"].values) for ds in surfaces))
    fig, axes = plt.subplots(len(levels), len(strategies), figsize=(1.0 + 4.2 * len(strategies),
                                                                     0.6 + 3.8 * len(levels)),
                             sharex=True, sharey=True, squeeze=False, layout="constrained")
    mesh = None
    for ds in surfaces:
        ax = axes[levels.index(float(ds["noise_level"])), strategies.index(str(ds["strategy"].values))]
        mesh = plot_probability(ax, ds)
        plot_threshold(ax, ds["threshold"], mark_above=False, **ENVELOPE_STYLE,
                       label=r"$a_{min,OVER}$ (lowest of N)")
        plot_a_max0(ax, a_max0)
        spectrum_axes(ax, f"{ds['strategy'].item()}, {level_label(float(ds['noise_level']))}, "
                          f"N = {int(ds['n_realisations'])}")
        ax.label_outer()
    from matplotlib.lines import Line2D
    handles, _ = axes.flat[0].get_legend_handles_labels()
    handles.append(Line2D([], [], color=HALF_CONTOUR_STYLE["colors"], lw=HALF_CONTOUR_STYLE["linewidths"],
                          label="P = 0.5"))
    axes.flat[0].legend(handles=handles, fontsize=SMALL_FONT, loc="upper left")
    fig.suptitle("Probability of overturning over the noise realisations")
    fig.colorbar(mesh, ax=axes, shrink=0.85, pad=0.015, label="P(overturn) over the realisations [-]")
    return fig
