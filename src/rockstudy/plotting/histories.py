"""Time histories: a controlled block's response and stiffness (Figs. 2–3), the excitation (Fig. 4)."""
from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from rockstudy.plotting.style import (
    GUIDE_LINE,
    HISTORY_STYLES,
    ZERO_LINE,
    level_label,
    styled,
)


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
    return [ax.plot(hist["t_ground"].values, hist["ground_ratio"], **HISTORY_STYLES["ground"],
                    label=r"$\ddot X_g/(g\tan\alpha)$")[0],
            ax.plot(t, hist["rotation_ratio"], **HISTORY_STYLES["rotation"], label=r"$\theta/\alpha$")[0],
            ax.plot(tv, v, **HISTORY_STYLES["velocity"], label=r"$\dot\theta/(p\,\alpha)$")[0]]


def plot_stiffness(ax, hist):
    """Anchorage stiffness K/K_max set by the control law (piecewise constant)."""
    (line,) = ax.step(hist["t"].values, hist["stiffness_ratio"].values, where="post",
                      **HISTORY_STYLES["stiffness"], label=r"$K/K_{max}$")
    ax.set_ylim(-0.15, 1.15)
    ax.set_yticks([0, 1], [r"$K_{min}$", r"$K_{max}$"])
    return line


def plot_excitation(ax, time, values, **kwargs):
    """A unit-amplitude excitation Ẍ_g/a_p against time."""
    (line,) = ax.plot(time, values, **kwargs)
    ax.set_xlabel("time $t$ [s]")
    ax.set_ylabel(r"$\ddot X_g/a_p$ [-]")
    return line


@styled
def figure_control_history(hist, paper_figure: str):
    """Figs. 2–3: normalised time history of a controlled block and its stiffness K (``paper_figure``
    names the paper's figure in the file, not in the title, which says what is shown)."""
    fig, (ax, axk) = plt.subplots(2, 1, sharex=True, figsize=(7, 4.6), height_ratios=(3, 1))
    plot_history(ax, hist)
    ax.axhline(0, **ZERO_LINE)
    ax.set_ylabel("normalised response [-]")
    ax.legend(loc="upper right", ncol=3)
    plot_stiffness(axk, hist)
    axk.set_xlabel("time $t$ [s]")
    end = min(float(hist["t"][-1]), 1.3 * hist.attrs["excitation_end_s"])
    axk.set_xlim(0, end)
    a = hist.attrs
    ax.set_title(f"Response of the block under {a['control_strategy']} control and the anchorage stiffness it "
                 f"sets\n$\\omega_p/p$ = {a['frequency_ratio']:g}, $a_p/(g\\tan\\alpha)$ = {a['amplitude_ratio']:g}, "
                 f"{level_label(float(a.get('noise_level', 0.0)))}; the run ends: {a['status']}")
    fig.tight_layout()
    return fig


@styled
def figure_excitation(noise):
    """Fig. 4: (a) baseline Eq. 23 excitation; (b) the same contaminated with noise."""
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
