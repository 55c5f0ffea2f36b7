"""Ground motion as the compiled engine reads it: Ẍg(t) and Ÿg(t) from the parameter vector."""
from __future__ import annotations

from numba import njit

from ..excitation import MODULATED, ONE_SINE, RECORD, interpolate_record, modulated_acceleration, one_sine_acceleration
from .layout import I_AMP, I_DUR, I_KIND, I_OMEGA, I_RDT, I_VDT


@njit(cache=True)
def ground_acceleration(t, P, rec):
    """Horizontal ground acceleration Ẍg(t) while the excitation lasts, zero outside. [m/s^2]"""
    dur = P[I_DUR]
    if t < 0.0 or t > dur:
        return 0.0
    kind = int(P[I_KIND])
    amp = P[I_AMP]
    if kind == ONE_SINE:
        return one_sine_acceleration(t, amp, P[I_OMEGA])
    if kind == MODULATED:
        return modulated_acceleration(t, amp, P[I_OMEGA], dur)
    if kind == RECORD:
        return amp * interpolate_record(t, P[I_RDT], rec)
    return amp  # rectangular pulse on [0, dur]


@njit(cache=True)
def vertical_acceleration(t, P, vert):
    """Vertical ground acceleration Ÿg(t), linear between samples, zero outside. [m/s^2]"""
    n = vert.shape[0]
    if n == 0 or t < 0.0:
        return 0.0
    x = t / P[I_VDT]
    i = int(x)
    if i >= n - 1:
        return vert[n - 1] if i == n - 1 and x - i == 0.0 else 0.0
    f = x - i
    return vert[i] + f * (vert[i + 1] - vert[i])
