"""Figures of the paper from the workflow's netCDF outputs (the only module using matplotlib).

Axis-level functions take an ``ax`` and return the artists they draw; ``figure_*`` functions
compose the paper's multi-panel figures from those and return the :class:`Figure`.
Frequencies are ω_p/p, amplitudes a_p/(g·tanα).
"""
from __future__ import annotations

from functools import partial, wraps
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

OKABE_ITO = {"black": "#000000", "orange": "#E69F00", "sky_blue": "#56B4E9", "bluish_green": "#009E73",
             "yellow": "#F0E442", "blue": "#0072B2", "vermillion": "#D55E00", "reddish_purple": "#CC79A7"}
"""The Okabe–Ito palette (Okabe & Ito 2008), distinguishable with every common colour-vision deficiency."""

CURVE_COLOURS = tuple(OKABE_ITO[c] for c in ("blue", "vermillion", "bluish_green", "orange", "reddish_purple",
                                             "sky_blue", "yellow"))
"""Colours of the curves of one figure in drawing order (black is kept for references)."""

CURVE_DASHES = ("-", "--", "-.", ":", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 1)), (0, (8, 2)))
"""Line styles paired with :data:`CURVE_COLOURS`, so that curves also differ in grey-scale print."""

REFERENCE_STYLE = {"color": OKABE_ITO["black"], "lw": 1.2, "ls": "-", "marker": "o", "ms": 3.0, "zorder": 5}
"""A reference curve (continuous control, no delay, no noise, the decisive N): black, thin, with
dots, drawn on top of the thicker coloured curves so that both stay visible where they overlap."""

CURVE_WIDTH = 2.4
"""Line width of the compared curves (wider than the reference drawn on top of them). [pt]"""

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

def styled(figure_function):
    """Draw ``figure_function``'s figure in the study's :data:`STYLE`."""
    @wraps(figure_function)
    def draw(*args, **kwargs):
        with matplotlib.rc_context(STYLE):
            return figure_function(*args, **kwargs)
    return draw


def _level_label(level: float) -> str:
    return "no noise (R000)" if level == 0 else f"R{round(level * 100):03d} ({level:.0%} noise)"


def same_curve(a, b) -> bool:
    """True when two curves (DataArrays, e.g. thresholds over ω_p/p or J_OS over the noise level) are
    the same: the same dimensions, the same coordinate values along them and the same values (NaN
    where both have none, e.g. no overturning)."""
    if a.dims != b.dims or a.sizes != b.sizes:
        return False
    for dim in a.dims:
        if (dim in a.coords) != (dim in b.coords) or (dim in a.coords and not np.array_equal(a[dim].values,
                                                                                           b[dim].values)):
            return False
    return np.array_equal(np.asarray(a.values, float), np.asarray(b.values, float), equal_nan=True)


def group_same_curves(curves):
    """Group ``(name, threshold)`` pairs whose thresholds are the same curve (:func:`same_curve`),
    in order of first appearance; returns a list of (names, threshold)."""
    groups = []
    for name, thr in curves:
        for names, first in groups:
            if same_curve(first, thr):
                names.append(name)
                break
        else:
            groups.append(([name], thr))
    return groups


# --- axis-level ----------------------------------------------------------------------------------
def spectrum_axes(ax, title: str | None = None):
    """Label an overturning-spectrum axis: ω_p/p against a_p/(g·tanα)."""
    ax.set_xlabel(FREQUENCY_LABEL)
    ax.set_ylabel(AMPLITUDE_LABEL)
    ax.grid(True)
    if title:
        ax.set_title(title)
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
                transform=ax.get_xaxis_transform(), clip_on=False, gid=ABOVE_GID)
    return line


ABOVE_GID = "no-overturning-up-to-the-scan-top"
"""``gid`` of the triangles :func:`plot_threshold` draws where nothing overturned up to the scan's top."""


def spectrum_legend(ax, **kwargs):
    """The axis legend, with an entry for the top-edge triangles of :func:`plot_threshold` when
    there are any; returns the legend."""
    from matplotlib.lines import Line2D
    handles, labels = ax.get_legend_handles_labels()
    if any(line.get_gid() == ABOVE_GID for line in ax.get_lines()):
        handles.append(Line2D([], [], ls="none", marker="^", ms=4, color="0.3"))
        labels.append("no overturning up to the scan's top")
    return ax.legend(handles, labels, **kwargs)


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


def velocity_with_impacts(hist):
    """Times and θ̇/(p·α) of a history with the velocity just before each impact put back in front of
    the value just after it, so that a line shows the jump (older files without an ``impact``
    dimension are returned as they are)."""
    t, v = hist["t"].values, hist["velocity_ratio"].values
    if "velocity_before_impact_ratio" not in hist or hist.sizes.get("impact", 0) == 0:
        return t, v
    ti, vi = hist["impact_time"].values, hist["velocity_before_impact_ratio"].values
    keep = np.isfinite(vi)
    times = np.concatenate([ti[keep], t])
    order = np.argsort(np.concatenate([np.zeros(keep.sum()), np.ones(len(t))]), kind="stable")
    order = order[np.argsort(times[order], kind="stable")]
    return times[order], np.concatenate([vi[keep], v])[order]


def plot_history(ax, hist):
    """Normalised ground motion Ẍ_g/(g·tanα), rotation θ/α and velocity θ̇/(p·α) against time."""
    t = hist["t"].values
    tv, v = velocity_with_impacts(hist)
    return [ax.plot(hist["t_ground"].values, hist["ground_ratio"], color="0.55", ls="--", lw=0.9,
                    label=r"$\ddot X_g/(g\tan\alpha)$")[0],
            ax.plot(t, hist["rotation_ratio"], color=OKABE_ITO["blue"], lw=1.4, label=r"$\theta/\alpha$")[0],
            ax.plot(tv, v, color=OKABE_ITO["vermillion"], lw=0.8, label=r"$\dot\theta/(p\,\alpha)$")[0]]


def plot_stiffness(ax, hist):
    """Anchorage stiffness K/K_max set by the control law (piecewise constant)."""
    (line,) = ax.step(hist["t"].values, hist["stiffness_ratio"].values, where="post",
                      color=OKABE_ITO["bluish_green"], lw=1.0, label=r"$K/K_{max}$")
    ax.set_ylim(-0.15, 1.15)
    ax.set_yticks([0, 1], [r"$K_{min}$", r"$K_{max}$"])
    return line


def plot_threshold_family(ax, curves, prefix: str = "", reference=None, suffix: str = "",
                          reference_last: bool = False):
    """Several thresholds on one axis, with curves that coincide named together.

    Parameters
    ----------
    curves : list of (str, DataArray)
        Name (e.g. ``"2.5 ms"``) and threshold of each compared curve, in legend order; coloured
        from :data:`CURVE_COLOURS` and drawn :data:`CURVE_WIDTH` wide.
    prefix : str
        Put before the names in the legend (e.g. ``"$T_s$ = "``).
    reference : (str, DataArray), optional
        The reference (continuous control, no delay, no noise), drawn last, on top, in
        :data:`REFERENCE_STYLE`, and named ``prefix + name + suffix``.
    suffix : str
        Put after the reference's names in the legend (e.g. ``", reference"``).
    reference_last : bool
        The reference comes after the curves in the order of names (e.g. the largest N), not
        before them (T_s = 0, Δτ = 0, no noise).

    Curves whose thresholds are the same (:func:`same_curve`, computed from the data) are drawn
    once with a legend entry naming all of them (``"Δτ = 0 = 2.5 ms"``).

    Returns
    -------
    list of Line2D
        One line per distinct curve, the reference's last.
    """
    ref = [reference] if reference is not None else []
    every = list(curves) + ref if reference_last else ref + list(curves)
    groups = group_same_curves(every)
    lines, ref_line, colour = [], None, 0
    for names, thr in groups:
        label = prefix + " = ".join(names)
        if reference is not None and reference[0] in names and same_curve(thr, reference[1]):
            ref_line = (label + suffix, thr)
            continue
        style = {"color": CURVE_COLOURS[colour % len(CURVE_COLOURS)],
                 "ls": CURVE_DASHES[colour % len(CURVE_DASHES)], "lw": CURVE_WIDTH}
        colour += 1
        lines.append(plot_threshold(ax, thr, label=label, **style))
    if ref_line is not None:
        lines.append(plot_threshold(ax, ref_line[1], label=ref_line[0], **REFERENCE_STYLE))
    return lines


def plot_excitation(ax, time, values, **kwargs):
    """A unit-amplitude excitation Ẍ_g/a_p against time."""
    (line,) = ax.plot(time, values, **kwargs)
    ax.set_xlabel("time $t$ [s]")
    ax.set_ylabel(r"$\ddot X_g/a_p$ [-]")
    return line


# --- figures ---------------------------------------------------------------------------------------
@styled
def figure_control_history(hist, paper_figure: str):
    """Figs. 2–3: normalised time history of a controlled block and its stiffness K (``paper_figure``
    names the paper's figure in the file, not in the title, which says what is shown)."""
    fig, (ax, axk) = plt.subplots(2, 1, sharex=True, figsize=(7, 4.6), height_ratios=(3, 1))
    plot_history(ax, hist)
    ax.axhline(0, color="k", lw=0.4)
    ax.set_ylabel("normalised response [-]")
    ax.legend(loc="upper right", ncol=3)
    plot_stiffness(axk, hist)
    axk.set_xlabel("time $t$ [s]")
    end = min(float(hist["t"][-1]), 1.3 * hist.attrs["excitation_end_s"])
    axk.set_xlim(0, end)
    a = hist.attrs
    ax.set_title(f"Response of the block under {a['control_strategy']} control and the anchorage stiffness it "
                 f"sets\n$\\omega_p/p$ = {a['frequency_ratio']:g}, $a_p/(g\\tan\\alpha)$ = {a['amplitude_ratio']:g}, "
                 f"{_level_label(float(a.get('noise_level', 0.0)))}; the run ends: {a['status']}")
    fig.tight_layout()
    return fig


@styled
def figure_excitation(noise):
    """Fig. 4: (a) baseline Eq. 23 excitation; (b) the same contaminated with noise."""
    fig, (a, b) = plt.subplots(2, 1, sharex=True, sharey=True, figsize=(7, 4.8))
    t = noise["t"].values
    plot_excitation(a, t, noise["baseline"].values, color=OKABE_ITO["black"], lw=1.0, label="baseline, Eq. (23)")
    env = np.abs(noise["baseline"].values).max()
    a.axhline(env, color="0.5", lw=0.6, ls=":")
    a.axhline(-env, color="0.5", lw=0.6, ls=":")
    k = int(noise["record_realisation"][0])
    plot_excitation(b, t, noise["record"].sel(record_realisation=k).values, color=OKABE_ITO["vermillion"], lw=0.6,
                    label=f"noisy, realisation {k}")
    plot_excitation(b, t, noise["baseline"].values, color=OKABE_ITO["black"], lw=1.0, label="baseline")
    a.set_xlabel("")
    lev = noise.attrs["noise_level"]
    e, p = float(noise["energy_ratio"].sel(realisation=k).mean()), float(noise["pga_ratio"].sel(realisation=k).mean())
    a.set_title(f"(a) baseline harmonic excitation with variable amplitude, "
                f"$\\omega_p/p$ = {noise.attrs['reference_frequency_ratio']:g}")
    b.set_title(f"(b) contaminated with {lev:.0%} noise (energy ratio {e:.3f}, PGA ratio {p:.3f})")
    for ax in (a, b):
        ax.legend(loc="upper right")
    fig.suptitle("Ground motion: amplitude-modulated harmonic excitation, without and with noise")
    fig.tight_layout()
    return fig


@styled
def figure_realisations(spectrum, histories, point: dict):
    """Fig. 5: (a) thresholds for two noise realisations; (b) rotation histories at "Ex01"."""
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    names = [f"N°{i + 1} (k = {h.attrs['noise_realisation']})" for i, h in enumerate(histories)]
    plot_threshold_family(a, [(name, spectrum["threshold_realisation"].sel(realisation=h.attrs["noise_realisation"]))
                              for name, h in zip(names, histories)], prefix="noise realisation ")
    for i, (name, hist) in enumerate(zip(names, histories)):
        b.plot(hist["t"], hist["rotation_ratio"], color=CURVE_COLOURS[i % len(CURVE_COLOURS)],
               ls=CURVE_DASHES[i % len(CURVE_DASHES)], lw=1.0, label=f"{name}: {hist.attrs['status']}")
    plot_a_max0(a, point["a_max0_ratio"])
    a.plot(point["frequency_ratio"], point["amplitude_ratio"], ls="none", marker="*", color=OKABE_ITO["black"],
           ms=11, label=point["label"])
    a.annotate(point["label"], (point["frequency_ratio"], point["amplitude_ratio"]), xytext=(6, 6),
               textcoords="offset points")
    spectrum_axes(a, f"(a) {spectrum['strategy'].item()}, {_level_label(float(spectrum['noise_level']))}")
    spectrum_legend(a, loc="upper left")
    b.axhline(0, color="k", lw=0.4)
    for s in (-1, 1):
        b.axhline(s, color="0.5", lw=0.6, ls=":")
    b.set_xlabel("time $t$ [s]")
    b.set_ylabel(r"$\theta/\alpha$ [-]")
    b.set_xlim(0, 1.3 * histories[0].attrs["excitation_end_s"])
    b.set_ylim(-7, 7)
    b.set_title(f"(b) rotation at {point['label']}")
    b.legend(loc="upper left")
    fig.suptitle("Lower threshold of the overturning region for single noise realisations, and the rotation "
                 f"at point {point['label']}")
    fig.tight_layout()
    return fig


@styled
def figure_noise_sensitivity(convergence, spectra, a_max0: float, panels=("FS", "CS01", "CS02"),
                             shown=(1, 5, 10, 20, 40)):
    """Fig. 6: (a) threshold against the number of realisations N; (b–d) thresholds per noise level."""
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True, sharey=True)
    a = axes.flat[0]
    n_all = convergence.sizes["n_realisations"]
    counts = sorted({min(n, n_all) for n in shown})
    conv = convergence["threshold_convergence"]
    plot_threshold_family(a, [(f"{n}", conv.sel(n_realisations=n)) for n in counts[:-1]], prefix="N = ",
                          reference=(f"{counts[-1]}", conv.sel(n_realisations=counts[-1])),
                          suffix=" (all realisations: the spectra)", reference_last=True)
    plot_a_max0(a, a_max0)
    spectrum_axes(a, f"(a) {convergence['strategy'].item()}, {_level_label(float(convergence['noise_level']))}: "
                     "lowest threshold over the first N realisations")
    spectrum_legend(a, loc="upper left")
    for ax, letter, strategy in zip(axes.flat[1:], "bcd", panels):
        mine = sorted((d for d in spectra if d["strategy"].item() == strategy), key=lambda d: float(d["noise_level"]))
        free = [d for d in mine if float(d["noise_level"]) == 0]
        plot_threshold_family(ax, [(_level_label(float(d["noise_level"])), d["threshold"]) for d in mine
                                   if float(d["noise_level"]) > 0],
                              reference=(_level_label(0.0), free[0]["threshold"]) if free else None,
                              suffix=", reference")
        plot_a_max0(ax, a_max0)
        spectrum_axes(ax, f"({letter}) {strategy}: each noise level")
        spectrum_legend(ax, loc="upper left")
    for ax in axes.flat:
        ax.label_outer()
    fig.suptitle("Lower threshold of the overturning region: convergence with the number of noise realisations "
                 "(a) and sensitivity to the noise level (b-d)")
    fig.tight_layout()
    return fig


@styled
def figure_timing(sweeps, variable: str, a_max0: float, paper_figure: str, references=()):
    """Figs. 7–8: overlapping thresholds for each sampling time T_s (or delay Δτ), per strategy,
    with the same strategy without it (``references``: continuous control, or no delay) on top as
    the named reference (:data:`REFERENCE_STYLE`); curves that coincide share one legend entry.
    ``paper_figure`` is the paper's figure number (the file's name carries it; the title says what
    is shown)."""
    strategies = sorted({d["strategy"].item() for d in sweeps})
    fig, axes = plt.subplots(1, len(strategies), figsize=(5.5 * len(strategies), 4.5), sharex=True, sharey=True,
                             squeeze=False)
    symbol = {"sampling_time": "T_s", "delay": r"\Delta\tau"}[variable]
    reference_name = "0 (continuous)" if variable == "sampling_time" else "0"
    for ax, letter, strategy in zip(axes.flat, "abcd", strategies):
        runs = sorted((d for d in sweeps if d["strategy"].item() == strategy), key=lambda d: float(d[variable]))
        refs = [d for d in references if d["strategy"].item() == strategy]
        plot_threshold_family(ax, [(f"{float(ds[variable]) * 1000:g} ms", ds["threshold"]) for ds in runs],
                              prefix=f"${symbol}$ = ",
                              reference=(reference_name, refs[0]["threshold"]) if refs else None,
                              suffix=", reference")
        plot_a_max0(ax, a_max0)
        extra = f", $T_s$ = {float(runs[0]['sampling_time']) * 1000:g} ms" if variable == "delay" else ""
        spectrum_axes(ax, f"({letter}) {strategy}{extra}")
        spectrum_legend(ax, loc="upper left")
        ax.label_outer()
    lev = float(sweeps[0]["noise_level"])
    what = {"sampling_time": "sampling times $T_s$ of the controller",
            "delay": r"actuation delays $\Delta\tau$ of the controller"}[variable]
    fig.suptitle(f"Lower threshold of the overturning region for several {what}, {lev:.0%} noise")
    fig.tight_layout()
    return fig


@styled
def figure_maps(maps, a_max0: float):
    """Overturning maps (outcome per grid point) of the noise-free strategies, threshold on top."""
    fig, axes = plt.subplots(1, len(maps), figsize=(4.2 * len(maps), 4.4), sharey=True, squeeze=False)
    handles = []
    for ax, ds in zip(axes.flat, maps):
        _, handles = plot_outcome_map(ax, ds)
        plot_threshold(ax, ds["threshold"], mark_above=False, color=OKABE_ITO["black"], lw=1.2,
                       label=r"$a_{min,OVER}$")
        plot_a_max0(ax, a_max0)
        spectrum_axes(ax, f"{ds['strategy'].item()}, no noise")
        ax.grid(False)
        ax.label_outer()
    from matplotlib.lines import Line2D
    handles = handles + [Line2D([], [], color=OKABE_ITO["black"], lw=1.2, label=r"lower threshold $a_{min,OVER}$")]
    fig.legend(handles=handles, loc="lower center", ncol=3, frameon=False)
    fig.suptitle("Outcome of every run of the amplitude scan, without noise")
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    return fig


@styled
def figure_spectrum(ds, label: str | None = None):
    """One overturning spectrum: the lower threshold (the aggregate over realisations) and a_max,0."""
    fig, ax = plt.subplots(figsize=(6, 4))
    plot_threshold(ax, ds["threshold"], label=label, color=CURVE_COLOURS[0])
    plot_a_max0(ax, ds.attrs["a_max0_ratio"])
    spectrum_axes(ax)
    spectrum_legend(ax)
    return fig


def save_figure(fig, *paths) -> list[Path]:
    """Save ``fig`` to each path atomically (format from the suffix; :func:`rockstudy.core.io.atomic_write`)
    and close it."""
    written = []
    for path in map(Path, paths):
        fmt = path.suffix.lstrip(".").lower()
        # no creation date in a PDF: the same figure gives the same bytes on every run
        metadata = {"CreationDate": None} if fmt == "pdf" else None
        atomic_write(path, partial(fig.savefig, dpi=150, format=fmt, metadata=metadata))
        written.append(path)
    plt.close(fig)
    return written


# --- reproducing the paper's numbers ----------------------------------------------------------------------
def plot_readings(ax, table, closest: str | None = None):
    """FS J_OS against the noise level, one line per noise reading, the paper's values as markers.

    ``table`` is a readings table (:func:`rockstudy.studies.noise_readings.readings_table`); the closest reading
    is drawn thicker. Readings whose J_OS values coincide at every level (:func:`same_curve`) are drawn
    once, with one legend entry naming all of them ("A = B"). Returns the lines drawn.
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
    lines.append(ax.plot(x, table["paper"].values, ls="none", marker="*", ms=12, color=OKABE_ITO["black"],
                         label="paper, Table 1", zorder=5)[0])
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("noise level r [%]")
    ax.set_ylabel(r"$J_{OS}$ of FS against no noise [%]")
    return lines


@styled
def figure_readings(table):
    """The readings study: FS row of Table 1 under each reading of the noise model."""
    fig, ax = plt.subplots(figsize=(8, 5), constrained_layout=True)
    plot_readings(ax, table, table.attrs.get("closest_reading"))
    ax.set_title("Utility index of the free-standing block against the noise level, under each reading of the "
                 "noise model")
    ax.legend(fontsize=7, loc="best")
    return fig


@styled
def figure_calibration(grid, best: dict | None = None):
    """J_OS of CS01 and CS02 against FS over kappa_max x xi (one panel per strategy and noise level).

    ``grid`` is a calibration grid dataset (:func:`rockstudy.studies.device_calibration.grid_dataset`) with
    ``j_os`` over (strategy, reference, noise_level, ultimate_rotation_ratio, kappa_min_ratio,
    kappa_max, damping_ratio). The maps are drawn at the θ_u/α and κ_min/κ_max of ``best`` (an
    anchorage dict, marked with a star; without it, at the first values of the design); the
    paper's value of each panel is in its title. With a single ξ (or a single κ_max) a map has no
    area: each panel is then J_OS against κ_max (or ξ), one line per ξ (or κ_max), with the paper's
    value as a dashed line. Only panels with at least one J_OS are drawn (Eq. 21 leaves J_OS
    undefined where neither spectrum overturns below a_max,0).
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
                    ax.plot(best["kappa_max"], best["damping_ratio"], marker="*", ms=12,
                            color=OKABE_ITO["vermillion"], markeredgecolor="w")
                ax.set_xlabel(r"$\kappa_{max}$ [-]")
                ax.set_ylabel(r"$\xi$ [-]")
            else:
                along_kappa = len(kx) >= len(xi)
                x, others = (kx, xi) if along_kappa else (xi, kx)
                curves = z.T if along_kappa else z
                other_name = r"$\xi$" if along_kappa else r"$\kappa_{max}$"
                for k, (other, curve) in enumerate(zip(others, curves)):
                    ax.plot(x, curve, marker="o", ms=4, color=CURVE_COLOURS[k % len(CURVE_COLOURS)],
                            ls=CURVE_DASHES[k % len(CURVE_DASHES)], label=f"{other_name} = {other:g}")
                ax.axhline(paper, color=OKABE_ITO["black"], lw=1.0, ls=(0, (6, 3)), label="paper")
                if best is not None:
                    bk = int(np.argmin(np.abs(kx - best["kappa_max"])))
                    bj = int(np.argmin(np.abs(xi - best["damping_ratio"])))
                    ax.plot(kx[bk] if along_kappa else xi[bj], z[bk, bj], ls="none", marker="*", ms=12,
                            color=OKABE_ITO["vermillion"], markeredgecolor="w", label="best", zorder=5)
                ax.set_xlabel(r"$\kappa_{max}$ [-]" if along_kappa else r"$\xi$ [-]")
                ax.set_ylabel(r"$J_{OS}$ vs FS [%]")
                ax.legend(fontsize=7)
            ax.set_title(f"{s} vs FS, {level} (paper {paper:+.1f} %)", fontsize=9)
    fig.suptitle(f"Utility index of CS01 and CS02 against the free-standing block over the device's "
                 f"stiffness and damping ({where})", fontsize=9)
    return fig


# --- beyond the paper: probability of overturning, record fragility ----------------------------------
STRATEGY_COLOURS = {"FS": OKABE_ITO["black"], "PASSIVE": OKABE_ITO["bluish_green"], "CS01": OKABE_ITO["blue"],
                    "CS02": OKABE_ITO["vermillion"]}
INTENSITY_LABELS = {"pga_ratio": r"PGA$/(g\,\tan\alpha)$ [-]", "pgv_ratio": r"PGV$\cdot p/(g\,\tan\alpha)$ [-]"}


def plot_probability(ax, ds, levels=(0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0)):
    """P(overturn) over the noise realisations at every (ω_p/p, a_p/(g·tanα)) point, with the
    P = 0.5 contour; returns the mesh (for a colour bar)."""
    p = ds["probability"].transpose("amplitude_ratio", "frequency_ratio")
    x, y = ds["frequency_ratio"].values, ds["amplitude_ratio"].values
    mesh = ax.pcolormesh(x, y, p.values, cmap="magma_r", vmin=0.0, vmax=1.0, shading="nearest", rasterized=True)
    if float(p.min()) < 0.5 < float(p.max()):
        ax.contour(x, y, p.values, levels=[0.5], colors=OKABE_ITO["sky_blue"], linewidths=1.2)
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


@styled
def figure_probability(surfaces, a_max0: float):
    """P(overturn) surfaces: one row per noise level, one column per strategy, lower envelope on top."""
    levels = sorted({float(ds["noise_level"]) for ds in surfaces})
    strategies = list(dict.fromkeys(str(ds["strategy"].values) for ds in surfaces))
    fig, axes = plt.subplots(len(levels), len(strategies), figsize=(1.0 + 4.2 * len(strategies),
                                                                     0.6 + 3.8 * len(levels)),
                             sharex=True, sharey=True, squeeze=False, layout="constrained")
    mesh = None
    for ds in surfaces:
        ax = axes[levels.index(float(ds["noise_level"])), strategies.index(str(ds["strategy"].values))]
        mesh = plot_probability(ax, ds)
        plot_threshold(ax, ds["threshold"], mark_above=False, color=OKABE_ITO["bluish_green"], lw=1.4, ls="--",
                       label=r"$a_{min,OVER}$ (lowest of N)")
        plot_a_max0(ax, a_max0)
        spectrum_axes(ax, f"{ds['strategy'].item()}, {_level_label(float(ds['noise_level']))}, "
                          f"N = {int(ds['n_realisations'])}")
        ax.label_outer()
    from matplotlib.lines import Line2D
    handles, _ = axes.flat[0].get_legend_handles_labels()
    handles.append(Line2D([], [], color=OKABE_ITO["sky_blue"], lw=1.2, label="P = 0.5"))
    axes.flat[0].legend(handles=handles, fontsize=7, loc="upper left")
    fig.suptitle("Probability of overturning over the noise realisations")
    fig.colorbar(mesh, ax=axes, shrink=0.85, pad=0.015, label="P(overturn) over the realisations [-]")
    return fig


def pga_in_g_axis(ax, tan_alpha: float):
    """A secondary x axis on top of a PGA/(g·tanα) axis giving the same intensity as PGA in g
    (PGA/g = ratio·tanα); returns the secondary axis."""
    if not (np.isfinite(tan_alpha) and tan_alpha > 0):
        raise ValueError(f"tan_alpha must be a positive number, got {tan_alpha!r}")
    sec = ax.secondary_xaxis("top", functions=(lambda r: r * tan_alpha, lambda g: g / tan_alpha))
    sec.set_xlabel("PGA [g]")
    return sec


@styled
def figure_fragility(ds):
    """Fragility curves of each strategy over a record suite, and the median shift over FS; with
    the intensity PGA/(g·tanα), a top axis gives it as PGA in g."""
    fig, (ax, axr) = plt.subplots(1, 2, figsize=(10, 4.6), width_ratios=(2.2, 1))
    for s in ds["strategy"].values:
        plot_fragility(ax, ds, str(s))
    measure = ds.attrs["intensity_measure"]
    ax.set_xlabel(INTENSITY_LABELS.get(measure, f"{ds.attrs['intensity_measure_definition']} [-]"))
    ax.set_ylabel("fraction of records that overturn the block [-]")
    ax.set_ylim(-0.02, 1.02)
    ax.legend(loc="lower right")
    if measure == "pga_ratio" and "block_alpha" in ds.attrs:
        pga_in_g_axis(ax, float(np.tan(float(ds.attrs["block_alpha"]))))
    ax.set_title(f"Fraction of {ds.attrs['n_records']} records that overturn the block (dots) and lognormal "
                 "fit (lines)", fontsize=9)
    plot_median_shift(axr, ds)
    axr.set_title(f"fragility median over FS's\n(bootstrap 95 % interval, {ds.attrs['n_bootstrap']} draws)",
                  fontsize=9)
    axr.grid(True, axis="y")
    axr.grid(False, axis="x")
    fig.tight_layout()
    return fig


# --- records: every record's threshold per strategy ---------------------------------------------------
STRATEGY_MARKERS = {"FS": "o", "PASSIVE": "s", "CS01": "^", "CS02": "v"}


def plot_record_thresholds(ax, ds):
    """Threshold PGA [g] of every record (rows, sorted by FS's threshold) for each strategy (markers), and
    the record's own PGA (grey bar): a marker left of the bar's end means the record as recorded
    overturns the block with that strategy. Returns the markers' artists."""
    fs = ds["threshold_pga"].sel(strategy="FS").values if "FS" in ds.strategy.values else None
    order = np.argsort(np.where(np.isfinite(fs), fs, np.inf)) if fs is not None else np.arange(ds.sizes["record"])
    y = np.arange(order.size)
    ax.barh(y, ds["record_pga"].values[order], color="0.85", height=0.7, label="PGA as recorded")
    artists = []
    for s in ds.strategy.values:
        s = str(s)
        x = ds["threshold_pga"].sel(strategy=s).values[order]
        artists.append(ax.plot(x, y, ls="none", marker=STRATEGY_MARKERS.get(s, "o"), ms=4,
                               color=STRATEGY_COLOURS.get(s, None), label=s)[0])
    labels = [f"{ds.record_id.values[k]} {str(ds.record_event.values[k])[:22]}" for k in order]
    ax.set_yticks(y, labels, fontsize=6)
    ax.set_ylim(-0.7, order.size - 0.3)
    ax.invert_yaxis()
    ax.set_xlabel("smallest PGA that overturns the block [g]")
    ax.grid(True, axis="x", lw=0.3, alpha=0.5)
    return artists


def figure_record_thresholds(ds):
    """Every record's threshold per strategy over one record set (see :func:`plot_record_thresholds`)."""
    n = ds.sizes["record"]
    fig, ax = plt.subplots(figsize=(7.5, 1.2 + 0.16 * n))
    plot_record_thresholds(ax, ds)
    beaten = {str(s): int(np.sum(ds["threshold_scale"].sel(strategy=s).values <= 1.0)) for s in ds.strategy.values}
    ax.set_title(f"{ds.attrs.get('record_suite', '')}: records that overturn the block as recorded\n"
                 + ", ".join(f"{s} {k}/{n}" for s, k in beaten.items()), fontsize=9, pad=22)
    ax.legend(fontsize=7, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=len(beaten) + 1, frameon=False)
    fig.tight_layout()
    return fig


# --- design charts: block sweep over (R, alpha), device sweep over (kappa_max, xi) ---------------------
def plot_design_map(ax, values, R, alpha, cmap="viridis", vmin=None, vmax=None, fmt="{:.0f}"):
    """A map over (alpha, R) of one quantity with its values written in the cells; returns the mesh."""
    mesh = ax.pcolormesh(np.arange(len(alpha) + 1), np.arange(len(R) + 1), values, cmap=cmap, vmin=vmin, vmax=vmax)
    for i in range(len(R)):
        for j in range(len(alpha)):
            if np.isfinite(values[i, j]):
                ax.text(j + 0.5, i + 0.5, fmt.format(values[i, j]), ha="center", va="center", fontsize=7,
                        color="w" if mesh.norm(values[i, j]) < 0.5 else "k")
    ax.set_xticks(np.arange(len(alpha)) + 0.5, [f"{a:g}" for a in alpha])
    ax.set_yticks(np.arange(len(R)) + 0.5, [f"{r:g}" for r in R])
    ax.set_xlabel(r"slenderness $\alpha$ [rad]")
    ax.set_ylabel("half diagonal R [m]")
    return mesh


def figure_design_jos_maps(blocks, strategies=("CS01", "CS02")):
    """J_OS over FS (noise-free Eq. 23) and the fragility median shift over FS, over (R, alpha)."""
    R, alpha = blocks.R.values, blocks.alpha.values
    fig, axes = plt.subplots(2, len(strategies), figsize=(4.6 * len(strategies), 7.6), squeeze=False)
    fs = blocks.fragility_median.sel(strategy="FS").values
    for k, s in enumerate(strategies):
        mesh = plot_design_map(axes[0, k], blocks.jos.sel(strategy=s).values, R, alpha, vmin=0, vmax=100)
        axes[0, k].set_title(f"{s}: J_OS over FS [%] (Eq. 23, no noise)", fontsize=9)
        fig.colorbar(mesh, ax=axes[0, k])
        shift = 100 * (blocks.fragility_median.sel(strategy=s).values / fs - 1)
        mesh = plot_design_map(axes[1, k], shift, R, alpha, cmap="magma", vmin=0)
        axes[1, k].set_title(f"{s}: median over FS, {blocks.attrs['record_suite']} [%]", fontsize=9)
        fig.colorbar(mesh, ax=axes[1, k])
    fig.tight_layout()
    return fig


def figure_design_winner(blocks):
    """Which strategy wins where: the highest J_OS (left) and the highest fragility median (right) over (R, alpha)."""
    R, alpha = blocks.R.values, blocks.alpha.values
    strategies = [str(s) for s in blocks.strategy.values if str(s) != "FS"]
    cmap = ListedColormap([STRATEGY_COLOURS.get(s, "0.5") for s in strategies])
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    for ax, var, title in ((axes[0], "jos", "highest J_OS (Eq. 23, no noise)"),
                           (axes[1], "fragility_median", f"highest median on {blocks.attrs['record_suite']}")):
        values = blocks[var].sel(strategy=strategies).values
        best = np.argmax(np.nan_to_num(values, nan=-np.inf), axis=0).astype(float)
        plot_design_map(ax, best, R, alpha, cmap=cmap, vmin=-0.5, vmax=len(strategies) - 0.5, fmt="")
        for i in range(len(R)):
            for j in range(len(alpha)):
                ax.text(j + 0.5, i + 0.5, strategies[int(best[i, j])], ha="center", va="center", fontsize=7,
                        color="w")
        ax.set_title(title, fontsize=9)
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
            ax.axhline(target_g, color="0.3", ls="--", lw=0.8, label=f"target {target_g:g} g")
        ax.set_xscale("log")
        ax.set_xlabel(xlabel)
        ax.set_title(title.format(v), fontsize=9)
        ax.grid(True, lw=0.3, alpha=0.5)
    axes[0, 0].set_ylabel(f"fragility median PGA [g], {ds.attrs['record_suite']}")
    axes[0, 0].legend(fontsize=7)
    fig.tight_layout()
    return fig


def figure_design_size_effect(blocks):
    """The size effect: fragility median [g] against R for every strategy, one panel per alpha."""
    return _median_panels(blocks, "alpha", "R", "R [m]", r"$\alpha$ = {:g} rad", (2.6, 3.4))


def figure_design_devices(devices, target_g: float):
    """Fragility median [g] of every strategy against kappa_max, one panel per xi, with the target."""
    return _median_panels(devices, "damping_ratio", "kappa_max", r"$\kappa_{max}$ [-]", r"$\xi$ = {:g}", (4.2, 3.6),
                          target_g=target_g)


# --- risk at a site -----------------------------------------------------------------------------------
def plot_hazard_curves(ax, risk):
    """The risk dataset's hazard curves, annual rate of exceedance against PGA (log-log)."""
    lines = []
    for j, name in enumerate(risk["hazard"].values):
        x, rate = risk["hazard_pga"].values[j], risk["hazard_rate"].values[j]
        keep = np.isfinite(x)
        lines.append(ax.loglog(x[keep], rate[keep], color=CURVE_COLOURS[j % len(CURVE_COLOURS)],
                               ls=CURVE_DASHES[j % len(CURVE_DASHES)], label=str(name))[0])
    ax.set_xlabel("PGA [g]")
    ax.set_ylabel("annual rate of exceedance [1/yr]")
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    ax.legend(fontsize=7)
    return lines


def plot_risk_fragilities(ax, risk):
    """The lognormal fragility in PGA [g] each strategy's risk uses, and each scenario's median PGA (dotted)
    with its ±1 σ range (shaded)."""
    from scipy.stats import norm
    medians = risk["fragility_median"].values
    top = 3.0 * float(np.nanmax(medians)) if np.any(np.isfinite(medians)) else 3.0
    x = np.linspace(top / 400, top, 400)
    lines = []
    for s, median, beta in zip(risk["strategy"].values, medians, risk["fragility_dispersion"].values):
        if not np.isfinite(median):
            continue
        y = norm.cdf(np.log(x / median) / beta) if beta > 0 else (x >= median).astype(float)
        lines.append(ax.plot(x, y, color=STRATEGY_COLOURS.get(str(s)),
                             label=f"{s}: θ = {median:.2f} g, β = {beta:.2f}")[0])
    for j, name in enumerate(risk["scenario"].values if "scenario" in risk.coords else []):
        mu, sigma = float(risk["median_pga"].values[j]), float(risk["ln_std_pga"].values[j])
        ax.axvspan(mu * np.exp(-sigma), min(mu * np.exp(sigma), top), color="0.85", alpha=0.5, lw=0)
        ax.axvline(mu, color="0.3", ls=":", lw=1.2)
        ax.annotate(f"{name}\nmedian PGA {mu:.2f} g", (mu, 0.98), xytext=(3, 0), textcoords="offset points",
                    va="top", fontsize=7)
    ax.set_xlim(0, top)
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("PGA [g]")
    ax.set_ylabel("P(overturn | PGA) [-]")
    ax.legend(fontsize=7, loc="lower right")
    return lines


def plot_disaggregation(ax, risk, hazard: int = 0):
    """Share of each strategy's annual rate of overturning from each PGA band (stacked bars)."""
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
    ax.set_ylabel(f"share of the annual rate ({risk['hazard'].values[hazard]}) [-]")
    ax.set_ylim(0, 1)
    ax.legend(fontsize=6, title="PGA band", title_fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    return bars


def plot_scenario_probabilities(ax, risk):
    """P(overturn | scenario) of each strategy (bars) with the range from the median's 95 % interval."""
    strategies = [str(s) for s in risk["strategy"].values]
    names = list(risk["scenario"].values)
    width = 0.8 / len(names)
    bars = []
    for j, name in enumerate(names):
        x = np.arange(len(strategies)) + (j - (len(names) - 1) / 2) * width
        p = risk["scenario_probability"].values[:, j]
        lo, hi = risk["scenario_probability_low"].values[:, j], risk["scenario_probability_high"].values[:, j]
        bars.append(ax.bar(x, p, width=width, color=[STRATEGY_COLOURS.get(s, "0.5") for s in strategies],
                           alpha=0.5 + 0.5 / (j + 1), label=str(name)))
        ax.errorbar(x, p, yerr=[np.nan_to_num(p - lo), np.nan_to_num(hi - p)], fmt="none", ecolor="0.2", capsize=3)
    ax.set_xticks(np.arange(len(strategies)), strategies)
    ax.set_ylabel("P(overturn | scenario) [-]")
    ax.set_ylim(0, 1)
    return bars


def figure_risk(risk):
    """Risk of overturning on one record set: the hazard curves (if any), the fragilities used with the
    scenarios' median PGA, and the disaggregation over PGA bands (hazard) or the scenario probabilities."""
    has_hazard = "hazard" in risk.coords
    panels = 3 if has_hazard else 2
    fig, axes = plt.subplots(1, panels, figsize=(4.4 * panels, 4.0))
    ax = list(axes)
    if has_hazard:
        plot_hazard_curves(ax.pop(0), risk)
    plot_risk_fragilities(ax[0], risk)
    if has_hazard:
        plot_disaggregation(ax[1], risk)
    else:
        plot_scenario_probabilities(ax[1], risk)
    fig.suptitle(f"Risk of overturning on {risk.attrs.get('record_suite', '')} (fragility: the stripes' lognormal "
                 "fit)", fontsize=9)
    fig.tight_layout()
    return fig
