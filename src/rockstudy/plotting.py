"""Figures of the paper from the workflow's netCDF outputs (the only module using matplotlib).

Axis-level functions take an ``ax`` and return the artists they draw; ``figure_*`` functions
compose the paper's multi-panel figures from those and return the :class:`Figure`.
Frequencies are ω_p/p, amplitudes a_p/(g·tanα).
"""
from __future__ import annotations

from functools import partial
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import BoundaryNorm, ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from rockstudy.core.io import atomic_write

FREQUENCY_LABEL = r"$\omega_p/p$ [-]"
AMPLITUDE_LABEL = r"$a_p/(g\,\tan\alpha)$ [-]"
OUTCOME_COLOURS = {"no_uplift": "#f2f2f2", "safe": "#a6d96a", "overturned_without_impact": "#d7191c",
                   "overturned_after_impact": "#fdae61", "undetermined": "#7f7f7f"}
LEVEL_STYLE = {0.0: ("k", "-"), 0.01: ("tab:blue", "--"), 0.05: ("tab:orange", "-."), 0.1: ("tab:red", ":")}


def _level_label(level: float) -> str:
    return "no noise (R000)" if level == 0 else f"R{round(level * 100):03d} ({level:.0%} noise)"


# --- axis-level ----------------------------------------------------------------------------------
def spectrum_axes(ax, title: str | None = None):
    """Label an overturning-spectrum axis: ω_p/p against a_p/(g·tanα)."""
    ax.set_xlabel(FREQUENCY_LABEL)
    ax.set_ylabel(AMPLITUDE_LABEL)
    ax.grid(True, lw=0.3, alpha=0.5)
    if title:
        ax.set_title(title, fontsize=10)
    return ax


def plot_threshold(ax, threshold, mark_above: bool = True, **kwargs):
    """Lower threshold of the overturning region a_min,OVER against ω_p/p.

    NaN (no overturning up to the scan's upper bound) leaves a gap in the line and, with
    ``mark_above``, a small triangle in the line's colour at the top edge of the axes.
    """
    x = threshold["frequency_ratio"].values
    y = threshold.values
    (line,) = ax.plot(x, y, **kwargs)
    above = np.isnan(y)
    if mark_above and above.any():
        ax.plot(x[above], np.full(above.sum(), 0.985), ls="none", marker="^", ms=4, color=line.get_color(),
                transform=ax.get_xaxis_transform(), clip_on=False)
    return line


def plot_a_max0(ax, value: float, label: str = r"$a_{max,0}$"):
    """Horizontal line at the protection level a_max,0 (as an amplitude ratio)."""
    return ax.axhline(value, color="0.3", lw=1.0, ls=(0, (6, 3)), label=label)


def plot_outcome_map(ax, ds, realisation: int = 0):
    """Outcome at every (ω_p/p, a_p/(g·tanα)) grid point, with the safe islands visible."""
    meanings = ds["outcome"].attrs["flag_meanings"].split()
    cmap = ListedColormap([OUTCOME_COLOURS[m] for m in meanings])
    norm = BoundaryNorm(np.arange(len(meanings) + 1) - 0.5, cmap.N)
    out = ds["outcome"].isel(realisation=realisation).transpose("amplitude_ratio", "frequency_ratio")
    mesh = ax.pcolormesh(ds["frequency_ratio"].values, ds["amplitude_ratio"].values, out.values,
                         cmap=cmap, norm=norm, shading="nearest", rasterized=True)
    handles = [Patch(color=OUTCOME_COLOURS[m], label=m.replace("_", " ")) for m in meanings]
    return mesh, handles


def plot_history(ax, hist):
    """Normalised ground motion Ẍ_g/(g·tanα), rotation θ/α and velocity θ̇/(p·α) against time."""
    t = hist["time"].values
    return [ax.plot(hist["ground_time"].values, hist["ground_ratio"], color="0.5", ls="--", lw=0.9,
                    label=r"$\ddot X_g/(g\tan\alpha)$")[0],
            ax.plot(t, hist["rotation_ratio"], color="tab:blue", lw=1.3, label=r"$\theta/\alpha$")[0],
            ax.plot(t, hist["velocity_ratio"], color="tab:red", lw=0.9, label=r"$\dot\theta/(p\,\alpha)$")[0]]


def plot_stiffness(ax, hist):
    """Anchorage stiffness K/K_max set by the control law (piecewise constant)."""
    (line,) = ax.step(hist["time"].values, hist["stiffness_ratio"].values, where="post", color="tab:green",
                      lw=1.0, label=r"$K/K_{max}$")
    ax.set_ylim(-0.15, 1.15)
    ax.set_yticks([0, 1], [r"$K_{min}$", r"$K_{max}$"])
    return line


def plot_excitation(ax, time, values, **kwargs):
    """A unit-amplitude excitation Ẍ_g/a_p against time."""
    (line,) = ax.plot(time, values, **kwargs)
    ax.set_xlabel("time $t$ [s]")
    ax.set_ylabel(r"$\ddot X_g/a_p$ [-]")
    return line


# --- figures ---------------------------------------------------------------------------------------
def figure_control_history(hist, paper_figure: str):
    """Figs. 2–3: normalised time history of a controlled block and its stiffness K."""
    fig, (ax, axk) = plt.subplots(2, 1, sharex=True, figsize=(7, 4.6), height_ratios=(3, 1))
    plot_history(ax, hist)
    ax.axhline(0, color="k", lw=0.4)
    ax.set_ylabel("normalised response [-]")
    ax.legend(loc="upper right", fontsize=8, ncol=3)
    plot_stiffness(axk, hist)
    axk.set_xlabel("time $t$ [s]")
    end = min(float(hist["time"][-1]), 1.3 * hist.attrs["excitation_end_s"])
    axk.set_xlim(0, end)
    a = hist.attrs
    ax.set_title(f"Fig. {paper_figure}: {a['control_strategy']}, $\\omega_p/p$ = {a['frequency_ratio']:g}, "
                 f"$a_p/(g\\tan\\alpha)$ = {a['amplitude_ratio']:g} ({a['status']})", fontsize=10)
    fig.tight_layout()
    return fig


def figure_excitation(noise):
    """Fig. 4: (a) baseline Eq. 23 excitation; (b) the same contaminated with noise."""
    fig, (a, b) = plt.subplots(2, 1, sharex=True, sharey=True, figsize=(7, 4.8))
    t = noise["time"].values
    plot_excitation(a, t, noise["baseline"].values, color="k", lw=1.0, label="baseline, Eq. (23)")
    env = np.abs(noise["baseline"].values).max()
    a.axhline(env, color="0.5", lw=0.6, ls=":")
    a.axhline(-env, color="0.5", lw=0.6, ls=":")
    k = int(noise["record_realisation"][0])
    plot_excitation(b, t, noise["record"].sel(record_realisation=k).values, color="tab:red", lw=0.6,
                    label=f"noisy, realisation {k}")
    plot_excitation(b, t, noise["baseline"].values, color="k", lw=1.0, label="baseline")
    a.set_xlabel("")
    lev = noise.attrs["noise_level"]
    e, p = float(noise["energy_ratio"].sel(realisation=k).mean()), float(noise["pga_ratio"].sel(realisation=k).mean())
    a.set_title(f"(a) baseline harmonic excitation with variable amplitude, "
                f"$\\omega_p/p$ = {noise.attrs['reference_frequency_ratio']:g}", fontsize=10)
    b.set_title(f"(b) contaminated with {lev:.0%} noise (energy ratio {e:.3f}, PGA ratio {p:.3f})", fontsize=10)
    for ax in (a, b):
        ax.legend(loc="upper right", fontsize=8)
        ax.grid(True, lw=0.3, alpha=0.5)
    fig.tight_layout()
    return fig


def figure_realisations(spectrum, histories, point: dict):
    """Fig. 5: (a) thresholds for two noise realisations; (b) rotation histories at "Ex01"."""
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    colours = ("tab:blue", "tab:red", "tab:green", "tab:purple")
    for i, hist in enumerate(histories):
        k = hist.attrs["noise_realisation"]
        plot_threshold(a, spectrum["threshold_realisation"].sel(realisation=k), color=colours[i], marker=".",
                       label=f"noise realisation N°{i + 1} (k = {k})")
        b.plot(hist["time"], hist["rotation_ratio"], color=colours[i], lw=1.0,
               label=f"N°{i + 1} (k = {k}): {hist.attrs['status']}")
    plot_a_max0(a, point["a_max0_ratio"])
    a.plot(point["frequency_ratio"], point["amplitude_ratio"], "k*", ms=11, label=point["label"])
    a.annotate(point["label"], (point["frequency_ratio"], point["amplitude_ratio"]), xytext=(6, 6),
               textcoords="offset points")
    spectrum_axes(a, f"(a) {spectrum['strategy'].item()}, {_level_label(float(spectrum['noise_level']))}")
    a.legend(fontsize=8, loc="upper left")
    b.axhline(0, color="k", lw=0.4)
    for s in (-1, 1):
        b.axhline(s, color="0.5", lw=0.6, ls=":")
    b.set_xlabel("time $t$ [s]")
    b.set_ylabel(r"$\theta/\alpha$ [-]")
    b.set_xlim(0, 1.3 * histories[0].attrs["excitation_end_s"])
    b.set_ylim(-7, 7)
    b.set_title(f"(b) rotation at {point['label']}", fontsize=10)
    b.legend(fontsize=8, loc="upper left")
    b.grid(True, lw=0.3, alpha=0.5)
    fig.tight_layout()
    return fig


def figure_noise_sensitivity(convergence, spectra, a_max0: float, panels=("FS", "CS01", "CS02"),
                             shown=(1, 5, 10, 20, 40)):
    """Fig. 6: (a) threshold against the number of realisations N; (b–d) thresholds per noise level."""
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True, sharey=True)
    a = axes.flat[0]
    n_all = convergence.sizes["n_realisations"]
    for i, n in enumerate(sorted({min(n, n_all) for n in shown})):
        plot_threshold(a, convergence["threshold_convergence"].sel(n_realisations=n),
                       color=plt.cm.viridis(i / max(1, len(shown) - 1)), label=f"N = {n}")
    plot_a_max0(a, a_max0)
    spectrum_axes(a, f"(a) {convergence['strategy'].item()}, {_level_label(float(convergence['noise_level']))}: "
                     "increasing number of realisations")
    a.legend(fontsize=8, loc="upper left")
    for ax, letter, strategy in zip(axes.flat[1:], "bcd", panels):
        mine = (d for d in spectra if d["strategy"].item() == strategy)
        for ds in sorted(mine, key=lambda d: float(d["noise_level"])):
            level = float(ds["noise_level"])
            colour, ls = LEVEL_STYLE.get(round(level, 4), ("0.3", "-"))
            plot_threshold(ax, ds["threshold"], color=colour, ls=ls, lw=1.3, label=_level_label(level))
        plot_a_max0(ax, a_max0)
        spectrum_axes(ax, f"({letter}) {strategy}")
        ax.legend(fontsize=8, loc="upper left")
    for ax in axes.flat:
        ax.label_outer()
    fig.tight_layout()
    return fig


def figure_timing(sweeps, variable: str, a_max0: float, paper_figure: str, references=()):
    """Figs. 7–8: overlapping thresholds for each sampling time T_s (or delay Δτ), per strategy,
    with the same strategy without it (``references``: continuous control, or no delay) in black."""
    strategies = sorted({d["strategy"].item() for d in sweeps})
    fig, axes = plt.subplots(1, len(strategies), figsize=(5.5 * len(strategies), 4.3), sharex=True, sharey=True,
                             squeeze=False)
    symbol = {"sampling_time": "T_s", "delay": r"\Delta\tau"}[variable]
    for ax, letter, strategy in zip(axes.flat, "abcd", strategies):
        runs = sorted((d for d in sweeps if d["strategy"].item() == strategy), key=lambda d: float(d[variable]))
        for ref in (d for d in references if d["strategy"].item() == strategy):
            plot_threshold(ax, ref["threshold"], color="k", lw=1.6, label=f"${symbol}$ = 0"
                           + (" (continuous)" if variable == "sampling_time" else ""))
        for i, ds in enumerate(runs):
            label = f"${symbol}$ = {float(ds[variable]) * 1000:g} ms"
            plot_threshold(ax, ds["threshold"], color=plt.cm.plasma(i / max(1, len(runs))), lw=1.2, label=label)
        plot_a_max0(ax, a_max0)
        lev = float(runs[0]["noise_level"])
        extra = f", $T_s$ = {float(runs[0]['sampling_time']) * 1000:g} ms" if variable == "delay" else ""
        spectrum_axes(ax, f"({letter}) {strategy}, {lev:.0%} noise{extra}")
        ax.legend(fontsize=8, loc="upper left")
        ax.label_outer()
    fig.suptitle(f"Fig. {paper_figure}", fontsize=10)
    fig.tight_layout()
    return fig


def figure_maps(maps, a_max0: float):
    """Overturning maps (outcome per grid point) of the noise-free strategies, threshold on top."""
    fig, axes = plt.subplots(1, len(maps), figsize=(4.2 * len(maps), 4.4), sharey=True, squeeze=False)
    handles = []
    for ax, ds in zip(axes.flat, maps):
        _, handles = plot_outcome_map(ax, ds)
        plot_threshold(ax, ds["threshold"], mark_above=False, color="k", lw=1.0, label=r"$a_{min,OVER}$")
        plot_a_max0(ax, a_max0)
        spectrum_axes(ax, f"{ds['strategy'].item()}, no noise")
        ax.label_outer()
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    return fig


def figure_spectrum(ds, label: str | None = None):
    """One overturning spectrum: the lower threshold (the aggregate over realisations) and a_max,0."""
    fig, ax = plt.subplots(figsize=(6, 4))
    plot_threshold(ax, ds["threshold"], label=label)
    plot_a_max0(ax, ds.attrs["a_max0_ratio"])
    spectrum_axes(ax)
    ax.legend()
    return fig


def save_figure(fig, *paths) -> list[Path]:
    """Save ``fig`` to each path atomically (format from the suffix; :func:`rockstudy.core.io.atomic_write`)
    and close it."""
    written = []
    for path in map(Path, paths):
        atomic_write(path, partial(fig.savefig, dpi=150, format=path.suffix.lstrip(".")))
        written.append(path)
    plt.close(fig)
    return written


# --- reproducing the paper's numbers ----------------------------------------------------------------------
def plot_readings(ax, table, closest: str | None = None):
    """FS J_OS against the noise level, one line per noise reading, the paper's values as markers.

    ``table`` is a readings table (:func:`rockstudy.studies.noise_readings.readings_table`); the closest reading
    is drawn thicker. Returns the lines drawn.
    """
    x = 100 * np.asarray(table["level_value"].values, dtype=float)
    lines = []
    for name in table["reading"].values:
        t = table.sel(reading=name)
        bold = name == closest
        (line,) = ax.plot(x, t["j_os"].values, marker="o", ms=3, lw=2.4 if bold else 1.0,
                          label=f"{name}: {t['label'].item()}" + (" (closest)" if bold else ""))
        lines.append(line)
    lines.append(ax.plot(x, table["paper"].values, ls="none", marker="*", ms=12, color="k", label="paper, Table 1")[0])
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("noise level r [%]")
    ax.set_ylabel(r"$J_{OS}$ of FS against no noise [%]")
    ax.grid(True, lw=0.3, alpha=0.5)
    return lines


def figure_readings(table):
    """The readings study: FS row of Table 1 under each reading of the noise model."""
    fig, ax = plt.subplots(figsize=(8, 5), constrained_layout=True)
    plot_readings(ax, table, table.attrs.get("closest_reading"))
    ax.set_title("Readings of the noise model: FS row of Table 1", fontsize=10)
    ax.legend(fontsize=7, loc="lower left")
    return fig


def figure_calibration(grid, best: dict | None = None):
    """J_OS of CS01 and CS02 against FS over kappa_max x xi (one panel per strategy and noise level).

    ``grid`` is a calibration grid dataset (:func:`rockstudy.studies.device_calibration.grid_dataset`) with
    ``j_os`` over (strategy, reference, noise_level, ultimate_rotation_ratio, kappa_min_ratio,
    kappa_max, damping_ratio). The maps are drawn at the θ_u/α and κ_min/κ_max of ``best`` (an
    anchorage dict, marked with a star; without it, at the first values of the design); the
    paper's value of each panel is in its title.
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
    levels = list(grid["noise_level"].values)
    strategies = list(grid["strategy"].values)
    fig, axes = plt.subplots(len(strategies), len(levels), figsize=(3.6 * len(levels), 3.0 * len(strategies)),
                             squeeze=False, constrained_layout=True)
    kx, xi = grid["kappa_max"].values, grid["damping_ratio"].values
    for i, s in enumerate(strategies):
        for j, level in enumerate(levels):
            ax = axes[i, j]
            z = grid["j_os"].sel(strategy=s, reference="fs_same_noise", noise_level=level).isel(**at).transpose(
                "kappa_max", "damping_ratio").values
            mesh = ax.pcolormesh(kx, xi, z.T, shading="nearest", cmap="viridis")
            paper = float(grid["paper"].sel(strategy=s, reference="fs_same_noise", noise_level=level))
            if min(z.shape) >= 2 and np.nanmin(z) < paper < np.nanmax(z):  # a contour needs a 2 x 2 grid
                cs = ax.contour(kx, xi, z.T, levels=[paper], colors="w", linewidths=1.2)
                ax.clabel(cs, fmt="paper %.1f", fontsize=6)
            fig.colorbar(mesh, ax=ax, label=r"$J_{OS}$ vs FS [%]")
            if best is not None:
                ax.plot(best["kappa_max"], best["damping_ratio"], marker="*", ms=12, color="r")
            ax.set_xlabel(r"$\kappa_{max}$ [-]")
            ax.set_ylabel(r"$\xi$ [-]")
            ax.set_title(f"{s} vs FS, {level} (paper {paper:+.1f} %)", fontsize=9)
    fig.suptitle(where, fontsize=9)
    return fig


# --- beyond the paper: probability of overturning, record fragility ----------------------------------
STRATEGY_COLOURS = {"FS": "k", "PASSIVE": "tab:green", "CS01": "tab:blue", "CS02": "tab:red"}
INTENSITY_LABELS = {"pga_ratio": r"PGA$/(g\,\tan\alpha)$ [-]", "pgv_ratio": r"PGV$\cdot p/(g\,\tan\alpha)$ [-]"}


def plot_probability(ax, ds, levels=(0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0)):
    """P(overturn) over the noise realisations at every (ω_p/p, a_p/(g·tanα)) point, with the
    P = 0.5 contour; returns the mesh (for a colour bar)."""
    p = ds["probability"].transpose("amplitude_ratio", "frequency_ratio")
    x, y = ds["frequency_ratio"].values, ds["amplitude_ratio"].values
    mesh = ax.pcolormesh(x, y, p.values, cmap="magma_r", vmin=0.0, vmax=1.0, shading="nearest", rasterized=True)
    if float(p.min()) < 0.5 < float(p.max()):
        ax.contour(x, y, p.values, levels=[0.5], colors="tab:cyan", linewidths=1.0)
    return mesh


def plot_fragility(ax, ds, strategy: str, **kwargs):
    """Fraction of the records that overturn the block (markers) and the fitted lognormal (line)."""
    d = ds.sel(strategy=strategy)
    colour = kwargs.pop("color", STRATEGY_COLOURS.get(strategy, None))
    x = ds["intensity"].values
    dots = ax.plot(x, d["fraction"].values, ls="none", marker="o", ms=3, color=colour, alpha=0.7)[0]
    median, beta = float(d["fragility_median"]), float(d["fragility_dispersion"])
    fine = np.linspace(x.min(), x.max(), 400)
    if np.isfinite(median) and beta > 0:
        from scipy.stats import norm
        curve = norm.cdf(np.log(fine / median) / beta)
    else:
        curve = np.where(fine >= median, 1.0, 0.0) if np.isfinite(median) else np.full_like(fine, np.nan)
    line = ax.plot(fine, curve, color=colour, label=f"{strategy}: θ = {median:.2f}, β = {beta:.2f}", **kwargs)[0]
    ax.plot([median], [0.5], marker="|", ms=10, color=colour)
    return dots, line


def plot_median_shift(ax, ds):
    """Fragility median over FS's, θ/θ_FS, with the bootstrap 95 % interval over records."""
    strategies = list(ds["strategy"].values)
    ratio = ds["median_ratio"].values
    low, high = ds["median_ratio_low"].values, ds["median_ratio_high"].values
    x = np.arange(len(strategies))
    bars = ax.bar(x, ratio, color=[STRATEGY_COLOURS.get(s, "0.5") for s in strategies], alpha=0.75)
    ax.errorbar(x, ratio, yerr=[ratio - low, high - ratio], fmt="none", ecolor="0.2", capsize=4)
    ax.axhline(1.0, color="0.3", lw=0.8)
    ax.set_xticks(x, strategies)
    for xi, r, top in zip(x, ratio, np.where(np.isfinite(high), high, ratio)):
        ax.annotate(f"{100 * (r - 1):+.0f} %", (xi, top), xytext=(0, 3), textcoords="offset points", ha="center",
                    va="bottom", fontsize=8)
    ax.set_ylim(0, 1.12 * np.nanmax(np.where(np.isfinite(high), high, ratio)))
    ax.set_ylabel(r"$\theta/\theta_{FS}$ [-]")
    return bars


def figure_probability(surfaces, a_max0: float):
    """P(overturn) surfaces: one row per noise level, one column per strategy, lower envelope on top."""
    levels = sorted({float(ds["noise_level"]) for ds in surfaces})
    strategies = list(dict.fromkeys(str(ds["strategy"].values) for ds in surfaces))
    fig, axes = plt.subplots(len(levels), len(strategies), figsize=(4.2 * len(strategies), 0.6 + 3.8 * len(levels)),
                             sharex=True, sharey=True, squeeze=False)
    mesh = None
    for ds in surfaces:
        ax = axes[levels.index(float(ds["noise_level"])), strategies.index(str(ds["strategy"].values))]
        mesh = plot_probability(ax, ds)
        plot_threshold(ax, ds["threshold"], mark_above=False, color="#00c000", lw=1.2, ls="--",
                       label=r"$a_{min,OVER}$ (lowest of N)")
        plot_a_max0(ax, a_max0)
        spectrum_axes(ax, f"{ds['strategy'].item()}, {_level_label(float(ds['noise_level']))}, "
                          f"N = {int(ds['n_realisations'])}")
        ax.label_outer()
    from matplotlib.lines import Line2D
    handles, _ = axes.flat[0].get_legend_handles_labels()
    handles.append(Line2D([], [], color="tab:cyan", lw=1.0, label="P = 0.5"))
    axes.flat[0].legend(handles=handles, fontsize=7, loc="upper left")
    fig.tight_layout(rect=(0, 0, 0.93, 1))
    cax = fig.add_axes((0.94, 0.15, 0.012, 0.7))
    fig.colorbar(mesh, cax=cax, label="P(overturn) over the realisations [-]")
    return fig


def figure_fragility(ds):
    """Fragility curves of each strategy over a record suite, and the median shift over FS."""
    fig, (ax, axr) = plt.subplots(1, 2, figsize=(10, 4.2), width_ratios=(2.2, 1))
    for s in ds["strategy"].values:
        plot_fragility(ax, ds, str(s))
    measure = ds.attrs["intensity_measure"]
    ax.set_xlabel(INTENSITY_LABELS.get(measure, f"{ds.attrs['intensity_measure_definition']} [-]"))
    ax.set_ylabel("fraction of records that overturn the block [-]")
    ax.set_ylim(-0.02, 1.02)
    ax.grid(True, lw=0.3, alpha=0.5)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title(f"Fragility over {ds.attrs['n_records']} records (dots) and lognormal MLE (lines)", fontsize=10)
    plot_median_shift(axr, ds)
    axr.set_title(f"median over FS (bootstrap 95 %, {ds.attrs['n_bootstrap']} draws)", fontsize=9)
    axr.grid(True, axis="y", lw=0.3, alpha=0.5)
    fig.tight_layout()
    return fig
