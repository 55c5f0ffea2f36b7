"""Design charts: the block sweep over (R, α) and the device sweep over (κ_max, ξ)."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import ListedColormap
from matplotlib.patches import Patch

from rockstudy.plotting.style import (
    A_MAX0_STYLE,
    LIGHT_GRID,
    PANEL_TITLE_FONT,
    SMALL_FONT,
    STRATEGY_COLOURS,
    STRATEGY_MARKERS,
    plain_text,
)


def plot_design_map(ax, values, R, alpha, cmap="viridis", vmin=None, vmax=None, fmt="{:.0f}"):
    """A map over (alpha, R) of one quantity with its values written in the cells; returns the mesh.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    values : numpy.ndarray
        The quantity, shape (len(R), len(alpha)); NaN cells are left unwritten.
    R : sequence of float
        Half diagonals of the blocks, one row each. [m]
    alpha : sequence of float
        Slenderness angles of the blocks, one column each. [rad]
    cmap : str or matplotlib.colors.Colormap, default "viridis"
        Colour map of the cells.
    vmin, vmax : float, optional
        Ends of the colour scale (the data's when None).
    fmt : str, default "{:.0f}"
        Format of the value written in each cell (``""`` writes nothing).
    """
    mesh = ax.pcolormesh(np.arange(len(alpha) + 1), np.arange(len(R) + 1), values, cmap=cmap, vmin=vmin, vmax=vmax)
    for i in range(len(R)):
        for j in range(len(alpha)):
            if np.isfinite(values[i, j]):
                ax.text(j + 0.5, i + 0.5, fmt.format(values[i, j]), ha="center", va="center", fontsize=SMALL_FONT,
                        color="w" if mesh.norm(values[i, j]) < 0.5 else "k")
    ax.set_xticks(np.arange(len(alpha)) + 0.5, [f"{a:g}" for a in alpha])
    ax.set_yticks(np.arange(len(R)) + 0.5, [f"{r:g}" for r in R])
    ax.set_xlabel(r"slenderness $\alpha$ [rad]")
    ax.set_ylabel("half diagonal R [m]")
    return mesh


def figure_design_jos_maps(blocks, strategies=("CS01", "CS02")):
    """J_OS over FS (noise-free Eq. 23) and the fragility median shift over FS, over (R, alpha).

    Parameters
    ----------
    blocks : xarray.Dataset
        The block sweep (:func:`rockstudy.studies.design.gather_blocks`): ``jos`` [%] and ``fragility_median``
        [g] over (strategy, R, alpha), with the attribute ``record_suite``.
    strategies : sequence of str, default ("CS01", "CS02")
        The strategies compared with FS, one column of panels each.
    """
    R, alpha = blocks.R.values, blocks.alpha.values
    suite = plain_text(blocks.attrs["record_suite"])
    fig, axes = plt.subplots(2, len(strategies), figsize=(4.6 * len(strategies), 7.6), squeeze=False)
    fs = blocks.fragility_median.sel(strategy="FS").values
    for k, s in enumerate(strategies):
        mesh = plot_design_map(axes[0, k], blocks.jos.sel(strategy=s).values, R, alpha, vmin=0, vmax=100)
        axes[0, k].set_title(f"{s}: J_OS over FS [%] (Eq. 23, no noise)", fontsize=PANEL_TITLE_FONT)
        fig.colorbar(mesh, ax=axes[0, k])
        shift = 100 * (blocks.fragility_median.sel(strategy=s).values / fs - 1)
        mesh = plot_design_map(axes[1, k], shift, R, alpha, cmap="magma", vmin=0)
        axes[1, k].set_title(f"{s}: median over FS, {suite} [%]", fontsize=PANEL_TITLE_FONT)
        fig.colorbar(mesh, ax=axes[1, k])
    fig.tight_layout()
    return fig


def figure_design_winner(blocks):
    """Which strategy wins where: the highest J_OS (left) and the highest fragility median (right) over (R, alpha).

    Parameters
    ----------
    blocks : xarray.Dataset
        The block sweep (:func:`rockstudy.studies.design.gather_blocks`): ``jos`` [%] and ``fragility_median``
        [g] over (strategy, R, alpha), with the attribute ``record_suite``.
    """
    R, alpha = blocks.R.values, blocks.alpha.values
    suite = plain_text(blocks.attrs["record_suite"])
    strategies = [str(s) for s in blocks.strategy.values if str(s) != "FS"]
    cmap = ListedColormap([STRATEGY_COLOURS.get(s, "0.5") for s in strategies])
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    for ax, var, title in ((axes[0], "jos", "highest J_OS (Eq. 23, no noise)"),
                           (axes[1], "fragility_median", f"highest median on {suite}")):
        values = blocks[var].sel(strategy=strategies).values
        best = np.argmax(np.nan_to_num(values, nan=-np.inf), axis=0).astype(float)
        plot_design_map(ax, best, R, alpha, cmap=cmap, vmin=-0.5, vmax=len(strategies) - 0.5, fmt="")
        for i in range(len(R)):
            for j in range(len(alpha)):
                ax.text(j + 0.5, i + 0.5, strategies[int(best[i, j])], ha="center", va="center", fontsize=SMALL_FONT,
                        color="w")
        ax.set_title(title, fontsize=PANEL_TITLE_FONT)
    fig.legend(handles=[Patch(color=STRATEGY_COLOURS.get(s, "0.5"), label=s) for s in strategies],
               loc="lower center", ncol=len(strategies), frameon=False, fontsize=8)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    return fig


def _median_panels(ds, panel, x, xlabel, title, panel_size, target_g=None):
    """Fragility median [g] of every strategy against ``x`` (log axis), one panel per value of
    ``panel`` titled ``title.format(value)``; a dashed target line when ``target_g`` is given."""
    values = ds[panel].values
    fig, axes = plt.subplots(1, len(values), figsize=(panel_size[0] * len(values), panel_size[1]), sharey=True,
                             squeeze=False)
    for j, v in enumerate(values):
        ax = axes[0, j]
        for s in ds.strategy.values:
            ax.plot(ds[x].values, ds.fragility_median.sel({"strategy": s, panel: v}).values,
                    marker=STRATEGY_MARKERS.get(str(s), "o"), color=STRATEGY_COLOURS.get(str(s)), label=str(s))
        if target_g is not None:
            ax.axhline(target_g, color=A_MAX0_STYLE["color"], ls="--", lw=0.8, label=f"target {target_g:g} g")
        ax.set_xscale("log")
        ax.set_xlabel(xlabel)
        ax.set_title(title.format(v), fontsize=PANEL_TITLE_FONT)
        ax.grid(True, **LIGHT_GRID)
    axes[0, 0].set_ylabel(f"fragility median PGA [g], {plain_text(ds.attrs['record_suite'])}")
    axes[0, 0].legend(fontsize=SMALL_FONT)
    fig.tight_layout()
    return fig


def figure_design_size_effect(blocks):
    """The size effect: fragility median [g] against R for every strategy, one panel per alpha.

    Parameters
    ----------
    blocks : xarray.Dataset
        The block sweep (:func:`rockstudy.studies.design.gather_blocks`): ``jos`` [%] and ``fragility_median``
        [g] over (strategy, R, alpha), with the attribute ``record_suite``.
    """
    return _median_panels(blocks, "alpha", "R", "R [m]", r"$\alpha$ = {:g} rad", (2.6, 3.4))


def figure_design_devices(devices, target_g: float):
    """Fragility median [g] of every strategy against kappa_max, one panel per xi, with the target.

    Parameters
    ----------
    devices : xarray.Dataset
        The device sweep (:func:`rockstudy.studies.design.gather_devices`): ``fragility_median`` [g] over
        (strategy, kappa_max, damping_ratio), with the attribute ``record_suite``.
    target_g : float
        The design target, a median PGA drawn as a dashed line. [g]
    """
    return _median_panels(devices, "damping_ratio", "kappa_max", r"$\kappa_{max}$ [-]", r"$\xi$ = {:g}", (4.2, 3.6),
                          target_g=target_g)
