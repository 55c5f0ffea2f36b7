"""Reproducing the paper's numbers: the noise readings and the device calibration grid."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from rockstudy.plotting.spectra import group_same_curves
from rockstudy.plotting.style import (
    BEST_MARKER,
    CURVE_COLOURS,
    CURVE_DASHES,
    MARKER_SIZE,
    PANEL_TITLE_FONT,
    PAPER_LINE_STYLE,
    PAPER_MARKER,
    SMALL_FONT,
    styled,
)


def plot_readings(ax, table, closest: str | None = None):
    """FS J_OS against the noise level, one line per noise reading, the paper's values as markers.

    Readings whose J_OS values coincide at every level (:func:`same_curve`) are drawn
    once, with one legend entry naming all of them ("A = B"). Returns the lines drawn.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    table : xarray.Dataset
        A readings table (:func:`rockstudy.studies.noise_readings.readings_table`): ``j_os`` [%] over
        (reading, level), ``level_value``, ``label`` and the paper's ``paper`` values.
    closest : str, optional
        Name of the reading closest to the paper, drawn thicker.
    """
    x = 100 * np.asarray(table["level_value"].values, dtype=float)
    curves = [(str(name), table["j_os"].sel(reading=name)) for name in table["reading"].values]
    lines = []
    for i, (names, j_os) in enumerate(group_same_curves(curves)):
        bold = closest in names
        label = " = ".join(f"{name}: {table['label'].sel(reading=name).item()}" for name in names)
        (line,) = ax.plot(x, j_os.values, marker="o", ms=3, lw=2.4 if bold else 1.0,
                          color=CURVE_COLOURS[i % len(CURVE_COLOURS)], ls=CURVE_DASHES[i % len(CURVE_DASHES)],
                          label=label + (" (closest)" if bold else ""))
        lines.append(line)
    lines.append(ax.plot(x, table["paper"].values, **PAPER_MARKER,
                         label="paper, Table 1", zorder=5)[0])
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("noise level r [%]")
    ax.set_ylabel(r"$J_{OS}$ of FS against no noise [%]")
    return lines


@styled
def figure_readings(table):
    """The readings study: FS row of Table 1 under each reading of the noise model.

    Parameters
    ----------
    table : xarray.Dataset
        A readings table, as :func:`plot_readings` takes it; its attribute ``closest_reading`` (if any)
        is drawn thicker.
    """
    fig, ax = plt.subplots(figsize=(8, 5), constrained_layout=True)
    plot_readings(ax, table, table.attrs.get("closest_reading"))
    ax.set_title("Utility index of the free-standing block against the noise level, under each reading of the "
                 "noise model")
    ax.legend(fontsize=SMALL_FONT, loc="best")
    return fig


@styled
def figure_calibration(grid, best: dict | None = None):
    """J_OS of CS01 and CS02 against FS over kappa_max x xi (one panel per strategy and noise level).

    The maps are drawn at the θ_u/α and κ_min/κ_max of ``best`` (marked with a star; without it, at the
    first values of the design); the paper's value of each panel is in its title. With a single ξ (or a
    single κ_max) a map has no
    area: each panel is then J_OS against κ_max (or ξ), one line per ξ (or κ_max), with the paper's
    value as a dashed line. Only panels with at least one J_OS are drawn (Eq. 21 leaves J_OS
    undefined where neither spectrum overturns below a_max,0).

    Parameters
    ----------
    grid : xarray.Dataset
        A calibration grid dataset (:func:`rockstudy.studies.device_calibration.grid_dataset`) with
        ``j_os`` [%] over (strategy, reference, noise_level, ultimate_rotation_ratio, kappa_min_ratio,
        kappa_max, damping_ratio).
    best : dict, optional
        The best anchorage (keys ``kappa_max``, ``kappa_min``, ``damping_ratio``,
        ``spring_ultimate_rotation`` [rad] or None for α).

    Raises
    ------
    ValueError
        If the grid has no J_OS at all.
    """
    at = {"ultimate_rotation_ratio": 0, "kappa_min_ratio": 0}
    if best is not None:
        theta = best["spring_ultimate_rotation"]
        ratio = 1.0 if theta is None else theta / float(grid.attrs["block_alpha"])
        at["ultimate_rotation_ratio"] = int(np.argmin(np.abs(grid["ultimate_rotation_ratio"].values - ratio)))
        k_ratio = best["kappa_min"] / best["kappa_max"] if best["kappa_max"] > 0 else 0.0
        at["kappa_min_ratio"] = int(np.argmin(np.abs(grid["kappa_min_ratio"].values - k_ratio)))
    where = (rf"$\theta_u/\alpha$ = {float(grid['ultimate_rotation_ratio'][at['ultimate_rotation_ratio']]):g}, "
             rf"$\kappa_{{min}}/\kappa_{{max}}$ = {float(grid['kappa_min_ratio'][at['kappa_min_ratio']]):g}")
    kx, xi = grid["kappa_max"].values, grid["damping_ratio"].values

    def values(s, level):
        return grid["j_os"].sel(strategy=s, reference="fs_same_noise", noise_level=level).isel(**at).transpose(
            "kappa_max", "damping_ratio").values

    has_data = {(s, level): bool(np.isfinite(values(s, level)).any())
                for s in grid["strategy"].values for level in grid["noise_level"].values}
    strategies = [s for s in grid["strategy"].values if any(has_data[s, lv] for lv in grid["noise_level"].values)]
    levels = [lv for lv in grid["noise_level"].values if any(has_data[s, lv] for s in strategies)]
    if not strategies:
        raise ValueError("figure_calibration: no J_OS in the grid (every panel would be empty)")
    as_map = min(len(kx), len(xi)) >= 2
    fig, axes = plt.subplots(len(strategies), len(levels), figsize=(3.6 * len(levels), 3.0 * len(strategies)),
                             squeeze=False, constrained_layout=True)
    for i, s in enumerate(strategies):
        for j, level in enumerate(levels):
            ax = axes[i, j]
            if not has_data[s, level]:
                ax.remove()
                continue
            z = values(s, level)
            paper = float(grid["paper"].sel(strategy=s, reference="fs_same_noise", noise_level=level))
            if as_map:
                mesh = ax.pcolormesh(kx, xi, z.T, shading="nearest", cmap="viridis")
                if np.nanmin(z) < paper < np.nanmax(z):
                    cs = ax.contour(kx, xi, z.T, levels=[paper], colors="w", linewidths=1.2)
                    ax.clabel(cs, fmt="paper %.1f", fontsize=6)
                fig.colorbar(mesh, ax=ax, label=r"$J_{OS}$ vs FS [%]")
                if best is not None:
                    ax.plot(best["kappa_max"], best["damping_ratio"], **BEST_MARKER)
                ax.set_xlabel(r"$\kappa_{max}$ [-]")
                ax.set_ylabel(r"$\xi$ [-]")
            else:
                along_kappa = len(kx) >= len(xi)
                x, others = (kx, xi) if along_kappa else (xi, kx)
                curves = z.T if along_kappa else z
                other_name = r"$\xi$" if along_kappa else r"$\kappa_{max}$"
                for k, (other, curve) in enumerate(zip(others, curves)):
                    ax.plot(x, curve, marker="o", ms=MARKER_SIZE, color=CURVE_COLOURS[k % len(CURVE_COLOURS)],
                            ls=CURVE_DASHES[k % len(CURVE_DASHES)], label=f"{other_name} = {other:g}")
                ax.axhline(paper, **PAPER_LINE_STYLE, label="paper")
                if best is not None:
                    bk = int(np.argmin(np.abs(kx - best["kappa_max"])))
                    bj = int(np.argmin(np.abs(xi - best["damping_ratio"])))
                    ax.plot(kx[bk] if along_kappa else xi[bj], z[bk, bj], ls="none", **BEST_MARKER, label="best",
                            zorder=5)
                ax.set_xlabel(r"$\kappa_{max}$ [-]" if along_kappa else r"$\xi$ [-]")
                ax.set_ylabel(r"$J_{OS}$ vs FS [%]")
                ax.legend(fontsize=SMALL_FONT)
            ax.set_title(f"{s} vs FS, {level} (paper {paper:+.1f} %)", fontsize=PANEL_TITLE_FONT)
    fig.suptitle(f"Utility index of CS01 and CS02 against the free-standing block over the device's "
                 f"stiffness and damping ({where})", fontsize=PANEL_TITLE_FONT)
    return fig
