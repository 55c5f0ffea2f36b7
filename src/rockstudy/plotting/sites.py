"""Risk at many sites: a map of the probability of overturning of each strategy at every site of a hazard file."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import LogNorm

from rockstudy.plotting.style import PROBABILITY_CMAP, plain_text, styled


def mapped_sites(risk) -> np.ndarray:
    """Indices of the ``hazard`` entries of a risk dataset that have coordinates (``lon`` and ``lat``).

    Parameters
    ----------
    risk : xarray.Dataset
        A risk dataset (:func:`rockstudy.analysis.risk_sites.risk_dataset`).
    """
    if "hazard" not in risk.dims or "lon" not in risk.coords:
        return np.array([], dtype=int)
    return np.flatnonzero(np.isfinite(risk["lon"].values) & np.isfinite(risk["lat"].values))


def plot_site_probability(ax, risk, strategy: str, norm):
    """The probability of overturning of ``strategy`` at every site with coordinates, coloured on ``norm``
    (longitude against latitude, equal degrees); returns the scatter.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    risk : xarray.Dataset
        A risk dataset with ``probability`` over (strategy, hazard) and ``lon``, ``lat`` on ``hazard``.
    strategy : str
        A value of its ``strategy`` coordinate.
    norm : matplotlib.colors.Normalize
        The colour scale, shared by the panels.
    """
    keep = mapped_sites(risk)
    p = risk["probability"].sel(strategy=strategy).values[keep]
    lon, lat = risk["lon"].values[keep], risk["lat"].values[keep]
    shown = np.isfinite(p) & (p > 0)
    points = ax.scatter(lon[shown], lat[shown], c=p[shown], cmap=PROBABILITY_CMAP, norm=norm, s=36,
                        edgecolors="0.3", linewidths=0.4)
    if np.any(~shown):  # no fitted fragility (NaN) or a probability of 0: drawn hollow, not coloured
        ax.scatter(lon[~shown], lat[~shown], facecolors="none", edgecolors="0.5", s=36, linewidths=0.6)
    ax.set_title(plain_text(strategy), fontsize=9)
    ax.set_xlabel("longitude [°]")
    ax.set_ylabel("latitude [°]")
    ax.set_aspect(1.0 / max(np.cos(np.radians(np.nanmean(lat))), 0.1) if lat.size else "auto", adjustable="datalim")
    ax.grid(True, lw=0.3, alpha=0.5)
    return points


@styled
def figure_risk_sites(risk):
    """A map per strategy of the probability of overturning in the dataset's exposure time at every site, on
    one logarithmic colour scale (hollow: no probability to colour).

    Parameters
    ----------
    risk : xarray.Dataset
        A risk dataset (:func:`rockstudy.analysis.risk_sites.risk_dataset`) with at least one site with
        coordinates.
    """
    keep = mapped_sites(risk)
    if keep.size == 0:
        raise ValueError("the risk dataset has no site with coordinates (lon, lat) to map")
    strategies = [str(s) for s in risk["strategy"].values]
    p = risk["probability"].values[:, keep]
    positive = p[np.isfinite(p) & (p > 0)]
    low, high = (positive.min(), positive.max()) if positive.size else (1e-6, 1.0)
    norm = LogNorm(vmin=low, vmax=high if high > low else low * 10)
    fig, axes = plt.subplots(1, len(strategies), figsize=(3.6 * len(strategies) + 1.0, 3.8), squeeze=False)
    points = [plot_site_probability(ax, risk, s, norm) for ax, s in zip(axes[0], strategies)]
    fig.colorbar(points[-1], ax=list(axes[0]), label=f"P(overturn in {risk.attrs.get('years', 50):g} years)")
    fig.suptitle(f"Risk of overturning at {keep.size} sites on "
                 f"{plain_text(risk.attrs.get('record_suite', 'the records'))}", fontsize=9)
    return fig
