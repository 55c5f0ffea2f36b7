"""Time histories: a controlled block's response and stiffness (Figs. 2–3), the excitation (Fig. 4)."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from rockstudy.plotting.style import (
    BURST_SHADE,
    GUIDE_LINE,
    HISTORY_STYLES,
    NOTE_FONT,
    ZERO_LINE,
    level_label,
    plain_text,
    styled,
)


def velocity_with_impacts(hist):
    """Times and θ̇/(p·α) of a history with the velocity just before each impact put back in front of
    the value just after it, so that a line shows the jump (older files without an ``impact``
    dimension are returned as they are).

    Parameters
    ----------
    hist : xarray.Dataset
        A run's history (:func:`rockstudy.studies.datasets.history_dataset`), with
        ``velocity_ratio`` on ``t`` and, per impact, ``impact_time`` [s] and
        ``velocity_before_impact_ratio``.

    Returns
    -------
    t, velocity_ratio : numpy.ndarray
        Times [s] and θ̇/(p·α) [-], in time order.
    """
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
    """Normalised ground motion Ẍ_g/(g·tanα), rotation θ/α and velocity θ̇/(p·α) against time.

    Returns the three lines.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    hist : xarray.Dataset
        A run's history (:func:`rockstudy.studies.datasets.history_dataset`), with
        ``ground_ratio`` on ``t_ground``, ``rotation_ratio`` and ``velocity_ratio``
        on ``t``.
    """
    t = hist["t"].values
    tv, v = velocity_with_impacts(hist)
    return [ax.plot(hist["t_ground"].values, hist["ground_ratio"], **HISTORY_STYLES["ground"],
                    label=r"$\ddot X_g/(g\tan\alpha)$")[0],
            ax.plot(t, hist["rotation_ratio"], **HISTORY_STYLES["rotation"], label=r"$\theta/\alpha$")[0],
            ax.plot(tv, v, **HISTORY_STYLES["velocity"], label=r"$\dot\theta/(p\,\alpha)$")[0]]


def plot_stiffness(ax, hist):
    """Anchorage stiffness K/K_max set by the control law (piecewise constant); returns the line.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    hist : xarray.Dataset
        A run's history (:func:`rockstudy.studies.datasets.history_dataset`), with
        ``stiffness_ratio`` on ``t``.
    """
    (line,) = ax.step(hist["t"].values, hist["stiffness_ratio"].values, where="post",
                      **HISTORY_STYLES["stiffness"], label=r"$K/K_{max}$")
    ax.set_ylim(-0.15, 1.15)
    ax.set_yticks([0, 1], [r"$K_{min}$", r"$K_{max}$"])
    return line


def plot_excitation(ax, time, values, **kwargs):
    """A unit-amplitude excitation Ẍ_g/a_p against time; returns the line.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    time : array_like
        Times of the samples. [s]
    values : array_like
        The excitation Ẍ_g/a_p at those times. [-]
    **kwargs : dict
        Passed to ``ax.plot`` (colour, line style, label).
    """
    (line,) = ax.plot(time, values, **kwargs)
    ax.set_xlabel("time $t$ [s]")
    ax.set_ylabel(r"$\ddot X_g/a_p$ [-]")
    return line


def switch_bursts(time, stiffness, end: float, min_switches: int = 20, gap_fraction: float = 0.005):
    """Stretches of ``time`` up to ``end`` in which the stiffness switches so often that its step
    line fills a solid band: at least ``min_switches`` switches, each within ``gap_fraction`` of
    ``end`` of the previous one. Returns a list of (first switch, last switch, number of switches) [s].

    Parameters
    ----------
    time : array_like
        Times of the history. [s]
    stiffness : array_like
        Stiffness at those times (any scale: K/K_max, say); a change between samples is a switch.
    end : float
        Last time looked at; also the scale of the gaps. [s]
    min_switches : int, default 20
        Fewest switches a stretch has.
    gap_fraction : float, default 0.005
        Longest gap between two switches of a stretch, as a fraction of ``end``. [-]
    """
    time, stiffness = np.asarray(time, float), np.asarray(stiffness, float)
    switches = time[1:][np.diff(stiffness) != 0]
    switches = switches[switches <= end]
    if switches.size < min_switches:
        return []
    breaks = np.flatnonzero(np.diff(switches) > gap_fraction * end)
    starts, stops = np.r_[0, breaks + 1], np.r_[breaks, switches.size - 1]
    return [(float(switches[i]), float(switches[j]), int(j - i + 1)) for i, j in zip(starts, stops)
            if j - i + 1 >= min_switches]


def mark_switch_burst(ax, axk, hist, end: float):
    """Shade the stretch of ``hist`` where K switches most densely (:func:`switch_bursts`) on both
    panels and say why in a note under the figure: there the block makes many ever-smaller rocks,
    one impact each, and the law switches K with every one (e.g. CS01, Eq. 16: K_max moving
    outward, K_min coming back). Returns the note's text, or None when there is no such stretch.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The response panel (:func:`plot_history`); the note goes under its figure.
    axk : matplotlib.axes.Axes
        The stiffness panel (:func:`plot_stiffness`).
    hist : xarray.Dataset
        A run's history (:func:`rockstudy.studies.datasets.history_dataset`), with
        ``stiffness_ratio`` on ``t`` and ``impact_time`` [s].
    end : float
        Last time shown. [s]
    """
    bursts = switch_bursts(hist["t"].values, hist["stiffness_ratio"].values, end)
    if not bursts:
        return None
    t0, t1, n = max(bursts, key=lambda b: b[2])
    for a in (ax, axk):
        a.axvspan(t0, t1, **BURST_SHADE)
    impacts = hist["impact_time"].values if "impact_time" in hist.variables else np.array([])
    rocks = int(np.sum((impacts >= t0) & (impacts <= t1)))
    why = (f"the block makes {rocks} ever-smaller rocks (one impact each) and the control law switches K "
           "with each" if rocks else "the control law switches K back and forth")
    return ax.figure.text(0.01, 0.01, f"Shaded, t = {t0:.2f}–{t1:.2f} s: K switches {n} times; {why}.",
                          fontsize=NOTE_FONT, ha="left", va="bottom", wrap=True)


@styled
def figure_control_history(hist, paper_figure: str, whole_run: bool = False):
    """Figs. 2–3: normalised time history of a controlled block and its stiffness K.

    Parameters
    ----------
    hist : xarray.Dataset
        A run's history (:func:`rockstudy.studies.datasets.history_dataset`), with
        the variables of :func:`plot_history` and :func:`plot_stiffness` and the
        attributes ``excitation_end_s``, ``control_strategy``, ``frequency_ratio``, ``amplitude_ratio``,
        ``status`` and ``noise_level``.
    paper_figure : str
        The paper's figure reproduced (``"2"``, ``"3"``); not drawn: the caller's file name carries it, and
        the title says what is shown.
    whole_run : bool, default False
        Draw the whole run (the time axis ends at its last sample); otherwise, as the paper's Figs. 2–3, up to
        1.3 times the end of the excitation.
    """
    fig, (ax, axk) = plt.subplots(2, 1, sharex=True, figsize=(7, 4.6), height_ratios=(3, 1))
    plot_history(ax, hist)
    ax.axhline(0, **ZERO_LINE)
    ax.set_ylabel("normalised response [-]")
    ax.legend(loc="upper right", ncol=3)
    plot_stiffness(axk, hist)
    axk.set_xlabel("time $t$ [s]")
    end = float(hist["t"][-1])
    if not whole_run:
        end = min(end, 1.3 * hist.attrs["excitation_end_s"])
    axk.set_xlim(0, end)
    a = hist.attrs
    ax.set_title(f"Response of the block under {plain_text(a['control_strategy'])} control and the anchorage "
                 f"stiffness it sets\n$\\omega_p/p$ = {a['frequency_ratio']:g}, "
                 f"$a_p/(g\\tan\\alpha)$ = {a['amplitude_ratio']:g}, "
                 f"{level_label(float(a.get('noise_level', 0.0)))}; the run ends: {plain_text(a['status'])}")
    note = mark_switch_burst(ax, axk, hist, end)
    fig.tight_layout(rect=(0, 0.04, 1, 1) if note else None)
    return fig


@styled
def figure_excitation(noise):
    """Fig. 4: (a) baseline Eq. 23 excitation; (b) the same contaminated with noise.

    Parameters
    ----------
    noise : xarray.Dataset
        The noise realisations of one level (:func:`rockstudy.studies.datasets.noise_dataset`): ``baseline``
        and ``record`` on ``t``, ``energy_ratio`` and ``pga_ratio``, attributes ``noise_level`` and
        ``reference_frequency_ratio``.
    """
    fig, (a, b) = plt.subplots(2, 1, sharex=True, sharey=True, figsize=(7, 4.8))
    t = noise["t"].values
    plot_excitation(a, t, noise["baseline"].values, **HISTORY_STYLES["baseline"], label="baseline, Eq. (23)")
    env = np.abs(noise["baseline"].values).max()
    a.axhline(env, **GUIDE_LINE)
    a.axhline(-env, **GUIDE_LINE)
    k = int(noise["record_realisation"][0])
    plot_excitation(b, t, noise["record"].sel(record_realisation=k).values, **HISTORY_STYLES["noisy"],
                    label=f"noisy, realisation {k}")
    plot_excitation(b, t, noise["baseline"].values, **HISTORY_STYLES["baseline"], label="baseline")
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
