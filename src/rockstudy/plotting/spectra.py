"""Overturning spectra: thresholds a_min,OVER against ω_p/p (Figs. 5–8), curves that coincide named together."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from rockstudy.plotting.layout import label_clear_of_lines, limits_of
from rockstudy.plotting.style import (
    A_MAX0_STYLE,
    ABOVE_MARKER,
    AMPLITUDE_LABEL,
    CURVE_COLOURS,
    CURVE_DASHES,
    FREQUENCY_LABEL,
    GUIDE_LINE,
    HISTORY_WIDTH,
    PAPER_MARKER,
    REFERENCE_STYLE,
    ZERO_LINE,
    curve_widths,
    level_label,
    plain_text,
    styled,
)


def same_curve(a, b) -> bool:
    """True when two curves are the same: the same dimensions, the same coordinate values along them
    and the same values (NaN where both have none, e.g. no overturning).

    Parameters
    ----------
    a, b : xarray.DataArray
        The two curves, e.g. thresholds over ω_p/p or J_OS over the noise level.
    """
    if a.dims != b.dims or a.sizes != b.sizes:
        return False
    for dim in a.dims:
        if (dim in a.coords) != (dim in b.coords) or (dim in a.coords and not np.array_equal(a[dim].values,
                                                                                           b[dim].values)):
            return False
    return np.array_equal(np.asarray(a.values, float), np.asarray(b.values, float), equal_nan=True)


def group_same_curves(curves):
    """Group ``(name, threshold)`` pairs whose thresholds are the same curve (:func:`same_curve`),
    in order of first appearance; returns a list of (names, threshold).

    Parameters
    ----------
    curves : iterable of (str, xarray.DataArray)
        Name and curve of each compared case, in legend order.
    """
    groups = []
    for name, thr in curves:
        for names, first in groups:
            if same_curve(first, thr):
                names.append(name)
                break
        else:
            groups.append(([name], thr))
    return groups


def spectrum_axes(ax, title: str | None = None):
    """Label an overturning-spectrum axis: ω_p/p against a_p/(g·tanα); returns ``ax``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to label (a grid is switched on).
    title : str, optional
        The axes' title (none when None or empty).
    """
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
    Returns the line.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    threshold : xarray.DataArray
        Lower threshold a_min,OVER/(g·tanα) over ``frequency_ratio``; NaN where nothing overturned. [-]
    mark_above : bool, default True
        Mark the NaN points with triangles at the top edge (gid :data:`ABOVE_GID`).
    **kwargs : dict
        Passed to ``ax.plot`` (colour, line style, label).
    """
    x = threshold["frequency_ratio"].values
    y = threshold.values
    (line,) = ax.plot(x, y, **kwargs)
    above = np.isnan(y)
    if mark_above and above.any():
        ax.plot(x[above], np.full(above.sum(), 0.985), **ABOVE_MARKER, color=line.get_color(),
                transform=ax.get_xaxis_transform(), clip_on=False, gid=ABOVE_GID)
    return line


ABOVE_GID = "no-overturning-up-to-the-scan-top"
"""``gid`` of the triangles :func:`plot_threshold` draws where nothing overturned up to the scan's top."""


def spectrum_legend(ax, **kwargs):
    """The axis legend, with an entry for the top-edge triangles of :func:`plot_threshold` when
    there are any; returns the legend.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes whose labelled artists make the legend.
    **kwargs : dict
        Passed to ``ax.legend`` (e.g. ``loc``).
    """
    from matplotlib.lines import Line2D
    handles, labels = ax.get_legend_handles_labels()
    if any(line.get_gid() == ABOVE_GID for line in ax.get_lines()):
        handles.append(Line2D([], [], **ABOVE_MARKER, color=A_MAX0_STYLE["color"]))
        labels.append("no overturning up to the scan's top")
    return ax.legend(handles, labels, **kwargs)


def plot_a_max0(ax, value: float, label: str = r"$a_{max,0}$"):
    """Horizontal line at the protection level a_max,0 (as an amplitude ratio); returns the line.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    value : float
        a_max,0/(g·tanα). [-]
    label : str, default "$a_{max,0}$"
        The line's legend entry.
    """
    return ax.axhline(value, **A_MAX0_STYLE, label=label)


def plot_threshold_family(ax, curves, prefix: str = "", reference=None, suffix: str = "",
                          reference_last: bool = False):
    """Several thresholds on one axis, with curves that coincide named together.

    Curves whose thresholds are the same (:func:`same_curve`, computed from the data) are drawn
    once with a legend entry naming all of them (``"Δτ = 0 = 2.5 ms"``).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    curves : list of (str, DataArray)
        Name (e.g. ``"2.5 ms"``) and threshold of each compared curve, in legend order; coloured
        from :data:`CURVE_COLOURS`, the first drawn widest and each next one narrower
        (:func:`~rockstudy.plotting.style.curve_widths`), so that curves that nearly coincide show
        as nested bands.
    prefix : str
        Put before the names in the legend (e.g. ``"$T_s$ = "``).
    reference : (str, DataArray), optional
        The reference (continuous control, no delay, no noise), drawn last, on top, thin and
        dashed (:data:`REFERENCE_STYLE`), and named ``prefix + name + suffix``.
    suffix : str
        Put after the reference's names in the legend (e.g. ``", reference"``).
    reference_last : bool
        The reference comes after the curves in the order of names (e.g. the largest N), not
        before them (T_s = 0, Δτ = 0, no noise).

    Returns
    -------
    list of Line2D
        One line per distinct curve, the reference's last.
    """
    ref = [reference] if reference is not None else []
    every = list(curves) + ref if reference_last else ref + list(curves)
    groups = group_same_curves(every)
    compared, ref_line = [], None
    for names, thr in groups:
        label = prefix + " = ".join(names)
        if reference is not None and reference[0] in names and same_curve(thr, reference[1]):
            ref_line = (label + suffix, thr)
        else:
            compared.append((label, thr))
    lines = []
    for colour, ((label, thr), width) in enumerate(zip(compared, curve_widths(len(compared)))):
        style = {"color": CURVE_COLOURS[colour % len(CURVE_COLOURS)],
                 "ls": CURVE_DASHES[colour % len(CURVE_DASHES)], "lw": width}
        lines.append(plot_threshold(ax, thr, label=label, **style))
    if ref_line is not None:
        lines.append(plot_threshold(ax, ref_line[1], label=ref_line[0], **REFERENCE_STYLE))
    return lines


@styled
def figure_spectrum(ds, label: str | None = None):
    """One overturning spectrum: the lower threshold (the aggregate over realisations) and a_max,0.

    Parameters
    ----------
    ds : xarray.Dataset
        A spectrum (:func:`rockstudy.analysis.spectra.spectrum`) with ``threshold`` and the attribute
        ``a_max0_ratio``.
    label : str, optional
        Legend entry of the threshold.
    """
    fig, ax = plt.subplots(figsize=(6, 4))
    plot_threshold(ax, ds["threshold"], label=label, color=CURVE_COLOURS[0])
    plot_a_max0(ax, ds.attrs["a_max0_ratio"])
    spectrum_axes(ax)
    spectrum_legend(ax)
    return fig


@styled
def figure_realisations(spectrum, histories, point: dict):
    """Fig. 5: (a) thresholds for two noise realisations; (b) rotation histories at "Ex01".

    Parameters
    ----------
    spectrum : xarray.Dataset
        A noisy spectrum with ``threshold_realisation`` over (realisation, frequency_ratio) and scalar
        ``strategy`` and ``noise_level``.
    histories : sequence of xarray.Dataset
        One history per realisation compared (:func:`rockstudy.studies.datasets.history_dataset`), with
        ``rotation_ratio`` and the attributes ``noise_realisation``, ``status`` and ``excitation_end_s``.
    point : dict
        The example point: ``label``, ``frequency_ratio`` [-], ``amplitude_ratio`` [-] and
        ``a_max0_ratio`` [-].
    """
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    names = [f"N°{i + 1} (k = {h.attrs['noise_realisation']})" for i, h in enumerate(histories)]
    plot_threshold_family(a, [(name, spectrum["threshold_realisation"].sel(realisation=h.attrs["noise_realisation"]))
                              for name, h in zip(names, histories)], prefix="noise realisation ")
    for i, (name, hist) in enumerate(zip(names, histories)):
        b.plot(hist["t"], hist["rotation_ratio"], color=CURVE_COLOURS[i % len(CURVE_COLOURS)],
               ls=CURVE_DASHES[i % len(CURVE_DASHES)], lw=HISTORY_WIDTH,
               label=f"{name}: {plain_text(hist.attrs['status'])}")
    plot_a_max0(a, point["a_max0_ratio"])
    label = plain_text(point["label"])
    a.plot(point["frequency_ratio"], point["amplitude_ratio"], **{**PAPER_MARKER, "ms": 11}, label=label)
    spectrum_axes(a, f"(a) {spectrum['strategy'].item()}, {level_label(float(spectrum['noise_level']))}")
    spectrum_legend(a, loc="upper left")
    b.axhline(0, **ZERO_LINE)
    for s in (-1, 1):
        b.axhline(s, **GUIDE_LINE)
    b.set_xlabel("time $t$ [s]")
    b.set_ylabel(r"$\theta/\alpha$ [-]")
    end = 1.3 * histories[0].attrs["excitation_end_s"]
    b.set_xlim(0, end)
    b.set_ylim(*limits_of([h["rotation_ratio"].where(h["t"] <= end) for h in histories], include=(-1.0, 1.0)))
    b.set_title(f"(b) rotation at {label}")
    b.legend(loc="best")
    fig.suptitle("Lower threshold of the overturning region for single noise realisations, and the rotation "
                 f"at point {label}")
    fig.tight_layout()
    label_clear_of_lines(a, (point["frequency_ratio"], point["amplitude_ratio"]), label)
    return fig


@styled
def figure_noise_sensitivity(convergence, spectra, a_max0: float, panels=("FS", "CS01", "CS02"),
                             shown=(1, 5, 10, 20, 40)):
    """Fig. 6: (a) threshold against the number of realisations N; (b–d) thresholds per noise level.

    Parameters
    ----------
    convergence : xarray.Dataset
        The convergence of one spectrum (:func:`rockstudy.studies.datasets.convergence_dataset`):
        ``threshold_convergence`` over (n_realisations, frequency_ratio), scalar ``strategy`` and ``noise_level``.
    spectra : sequence of xarray.Dataset
        Spectra with ``threshold`` and scalar ``strategy`` and ``noise_level``; the noise-free one of a
        strategy is its reference.
    a_max0 : float
        The protection level a_max,0 as an amplitude ratio a/(g·tanα), drawn as a dashed line in every panel. [-]
    panels : sequence of str, default ("FS", "CS01", "CS02")
        The strategies of panels (b)–(d).
    shown : sequence of int, default (1, 5, 10, 20, 40)
        Numbers of realisations N drawn in (a), capped at the number computed; the largest is the reference.
    """
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True, sharey=True)
    a = axes.flat[0]
    n_all = convergence.sizes["n_realisations"]
    counts = sorted({min(n, n_all) for n in shown})
    conv = convergence["threshold_convergence"]
    plot_threshold_family(a, [(f"{n}", conv.sel(n_realisations=n)) for n in counts[:-1]], prefix="N = ",
                          reference=(f"{counts[-1]}", conv.sel(n_realisations=counts[-1])),
                          suffix=" (all realisations: the spectra)", reference_last=True)
    plot_a_max0(a, a_max0)
    spectrum_axes(a, f"(a) {convergence['strategy'].item()}, {level_label(float(convergence['noise_level']))}: "
                     "lowest threshold over the first N realisations")
    spectrum_legend(a, loc="upper left")
    for ax, letter, strategy in zip(axes.flat[1:], "bcd", panels):
        mine = sorted((d for d in spectra if d["strategy"].item() == strategy), key=lambda d: float(d["noise_level"]))
        free = [d for d in mine if float(d["noise_level"]) == 0]
        plot_threshold_family(ax, [(level_label(float(d["noise_level"])), d["threshold"]) for d in mine
                                   if float(d["noise_level"]) > 0],
                              reference=(level_label(0.0), free[0]["threshold"]) if free else None,
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

    Parameters
    ----------
    sweeps : sequence of xarray.Dataset
        Spectra with ``threshold``, scalar ``strategy``, ``noise_level``, ``sampling_time`` [s] and
        ``delay`` [s]; one panel per strategy.
    variable : {"sampling_time", "delay"}
        The coordinate swept, named in the legend in ms.
    a_max0 : float
        The protection level a_max,0 as an amplitude ratio a/(g·tanα), drawn as a dashed line. [-]
    paper_figure : str
        The paper's figure number (``"7"``, ``"8"``); not drawn: the file's name carries it, and the title
        says what is shown.
    references : sequence of xarray.Dataset, default ()
        Spectra of the same strategies without the sampling time (or delay), drawn as the references.
    """
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
