"""Risk at a site: hazard curves, the fragilities a risk uses, and where the risk comes from."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from rockstudy.plotting.style import CURVE_COLOURS, CURVE_DASHES, STRATEGY_COLOURS, plain_text, styled


def plot_hazard_curves(ax, risk):
    """The risk dataset's hazard curves, annual rate of exceedance against PGA (log-log); returns the lines.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    risk : xarray.Dataset
        A risk dataset (:func:`rockstudy.analysis.risk_sites.risk_dataset`) with hazard curves: ``hazard_pga`` [g] and
        ``hazard_rate`` [1/yr] over (hazard, hazard_point), NaN-padded.
    """
    lines = []
    for j, name in enumerate(risk["hazard"].values):
        x, rate = risk["hazard_pga"].values[j], risk["hazard_rate"].values[j]
        keep = np.isfinite(x)
        lines.append(ax.loglog(x[keep], rate[keep], color=CURVE_COLOURS[j % len(CURVE_COLOURS)],
                               ls=CURVE_DASHES[j % len(CURVE_DASHES)], label=plain_text(name))[0])
    ax.set_xlabel("PGA [g]")
    ax.set_ylabel("annual rate of exceedance [1/yr]")
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    ax.legend(fontsize=7)
    return lines


def plot_risk_fragilities(ax, risk):
    """The lognormal fragility in PGA [g] each strategy's risk uses, and each scenario's median PGA (dotted)
    with its ±1 σ range (shaded); returns the fragility lines.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    risk : xarray.Dataset
        A risk dataset (:func:`rockstudy.analysis.risk_sites.risk_dataset`): ``fragility_median`` [g] and
        ``fragility_dispersion`` [-] over ``strategy``; with scenarios, ``median_pga`` [g] and ``ln_std_pga`` [-]
        over ``scenario``.
    """
    from scipy.special import ndtr  # the standard normal CDF (scipy.stats takes 0.8 s to import)
    medians = risk["fragility_median"].values
    top = 3.0 * float(np.nanmax(medians)) if np.any(np.isfinite(medians)) else 3.0
    x = np.linspace(top / 400, top, 400)
    lines = []
    for s, median, beta in zip(risk["strategy"].values, medians, risk["fragility_dispersion"].values):
        if not np.isfinite(median):
            continue
        y = ndtr(np.log(x / median) / beta) if beta > 0 else (x >= median).astype(float)
        lines.append(ax.plot(x, y, color=STRATEGY_COLOURS.get(str(s)),
                             label=f"{s}: θ = {median:.2f} g, β = {beta:.2f}")[0])
    for j, name in enumerate(risk["scenario"].values if "scenario" in risk.coords else []):
        mu, sigma = float(risk["median_pga"].values[j]), float(risk["ln_std_pga"].values[j])
        ax.axvspan(mu * np.exp(-sigma), min(mu * np.exp(sigma), top), color="0.85", alpha=0.5, lw=0)
        ax.axvline(mu, color="0.3", ls=":", lw=1.2)
        ax.annotate(f"{plain_text(name)}\nmedian PGA {mu:.2f} g", (mu, 0.98), xytext=(3, 0), textcoords="offset points",
                    va="top", fontsize=7)
    ax.set_xlim(0, top)
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("PGA [g]")
    ax.set_ylabel("P(overturn | PGA) [-]")
    ax.legend(fontsize=7, loc="lower right")
    return lines


def plot_disaggregation(ax, risk, hazard: int = 0):
    """Share of each strategy's annual rate of overturning from each PGA band (stacked bars); returns the bars.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    risk : xarray.Dataset
        A risk dataset (:func:`rockstudy.analysis.risk_sites.risk_dataset`) with hazard curves: ``disaggregation``
        [-] over (strategy, hazard, pga_band), ``pga_band_low`` and ``pga_band_high`` [g].
    hazard : int, default 0
        Position of the hazard curve along ``hazard``.
    """
    shares = risk["disaggregation"].values[:, hazard, :]
    low, high = risk["pga_band_low"].values, risk["pga_band_high"].values
    strategies = [str(s) for s in risk["strategy"].values]
    bottom = np.zeros(len(strategies))
    cmap = plt.get_cmap("cividis", len(low))
    bars = []
    for b in range(len(low)):
        label = f"> {low[b]:g} g" if not np.isfinite(high[b]) else f"{low[b]:g}–{high[b]:g} g"
        bars.append(ax.bar(strategies, np.nan_to_num(shares[:, b]), bottom=bottom, color=cmap(b), label=label))
        bottom += np.nan_to_num(shares[:, b])
    ax.set_ylabel(f"share of the annual rate ({plain_text(risk['hazard'].values[hazard])}) [-]")
    ax.set_ylim(0, 1)
    ax.legend(fontsize=6, title="PGA band", title_fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    return bars


def plot_scenario_probabilities(ax, risk):
    """P(overturn | scenario) of each strategy (bars) with the range from the median's 95 % interval.

    Returns the bars, one container per scenario.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    risk : xarray.Dataset
        A risk dataset (:func:`rockstudy.analysis.risk_sites.risk_dataset`) with scenarios: ``scenario_probability``,
        ``scenario_probability_low`` and ``scenario_probability_high`` [-] over (strategy, scenario).
    """
    strategies = [str(s) for s in risk["strategy"].values]
    names = list(risk["scenario"].values)
    width = 0.8 / len(names)
    bars = []
    for j, name in enumerate(names):
        x = np.arange(len(strategies)) + (j - (len(names) - 1) / 2) * width
        p = risk["scenario_probability"].values[:, j]
        lo, hi = risk["scenario_probability_low"].values[:, j], risk["scenario_probability_high"].values[:, j]
        bars.append(ax.bar(x, p, width=width, color=[STRATEGY_COLOURS.get(s, "0.5") for s in strategies],
                           alpha=0.5 + 0.5 / (j + 1), label=plain_text(name)))
        ax.errorbar(x, p, yerr=[np.nan_to_num(p - lo), np.nan_to_num(hi - p)], fmt="none", ecolor="0.2", capsize=3)
    ax.set_xticks(np.arange(len(strategies)), strategies)
    ax.set_ylabel("P(overturn | scenario) [-]")
    top = np.nanmax(np.concatenate([risk["scenario_probability_high"].values.ravel(),
                                    risk["scenario_probability"].values.ravel(), [0.0]]))
    ax.set_ylim(0, min(1.0, 1.2 * top) if top > 0 else 1.0)  # from the data: small probabilities stay readable
    return bars


@styled
def figure_risk(risk):
    """Risk of overturning on one record set: the hazard curves (if any), the fragilities used with the
    scenarios' median PGA, and the disaggregation over PGA bands (hazard) or the scenario probabilities.

    Parameters
    ----------
    risk : xarray.Dataset
        A risk dataset (:func:`rockstudy.analysis.risk_sites.risk_dataset`); with a ``hazard`` coordinate, three panels
        on two rows: :func:`plot_hazard_curves` and the fragilities above, :func:`plot_disaggregation` (first
        hazard curve) below; else two side by side: the fragilities and :func:`plot_scenario_probabilities`.
    """
    has_hazard = "hazard" in risk.coords
    if has_hazard:  # two rows as wide as the two-panel figure, so that a page draws them at the same scale
        fig = plt.figure(figsize=(8.8, 7.6))
        grid = fig.add_gridspec(2, 2)
        plot_hazard_curves(fig.add_subplot(grid[0, 0]), risk)
        plot_risk_fragilities(fig.add_subplot(grid[0, 1]), risk)
        plot_disaggregation(fig.add_subplot(grid[1, :]), risk)
    else:
        fig, (left, right) = plt.subplots(1, 2, figsize=(8.8, 4.0))
        plot_risk_fragilities(left, risk)
        plot_scenario_probabilities(right, risk)
    suite = plain_text(risk.attrs.get("record_suite", ""))
    fig.suptitle(f"Risk of overturning on {suite} (fragility: the stripes' lognormal "
                 "fit)", fontsize=9)
    fig.tight_layout()
    return fig
