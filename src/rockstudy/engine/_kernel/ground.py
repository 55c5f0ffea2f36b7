"""Ground motion as the compiled engine reads it: Ẍg(t) and Ÿg(t) from the parameter vector, and Ẍg as
the controller senses it (:mod:`rockstudy.model.sensor`).

``rec`` holds the driving record's samples and, when the sensor is on (slot ``I_SENSE``), the
sensed samples after them, from index ``P[I_SOFF]`` on (an analytic excitation has no driving
samples, so its sensed samples start at 0)."""
from __future__ import annotations

from rockstudy.core._inline import NO_REFCOUNT, inline_into, njit
from rockstudy.engine._kernel.layout import I_AMP, I_DUR, I_KIND, I_OMEGA, I_RDT, I_SDT, I_SENSE, I_SOFF, I_VDT
from rockstudy.model.excitation import (
    MODULATED,
    ONE_SINE,
    RECORD,
    interpolate_record,
    modulated_acceleration,
    one_sine_acceleration,
)


@njit(cache=True, inline=inline_into("rhs", "step", "sensed_acceleration", "pass_quiet_knots", "exit_value",
                                      "integrate"),
      **NO_REFCOUNT)
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
        if P[I_SENSE] != 0.0:  # the sensed samples follow the driving ones
            return amp * interpolate_record(t, P[I_RDT], rec[:int(P[I_SOFF])])
        return amp * interpolate_record(t, P[I_RDT], rec)
    return amp  # rectangular pulse on [0, dur]


@njit(cache=True, inline=inline_into("_illinois"),
      **NO_REFCOUNT)
def sensed_acceleration(t, P, rec):
    """Ẍg(t) as the controller reads it: the driving Ẍg without a sensor, else the sensed samples
    (times a_p) interpolated linearly; zero outside the excitation [0, dur], as Ẍg. [m/s^2]"""
    if P[I_SENSE] == 0.0:
        return ground_acceleration(t, P, rec)
    if t < 0.0 or t > P[I_DUR]:
        return 0.0
    return P[I_AMP] * interpolate_record(t, P[I_SDT], rec[int(P[I_SOFF]):])


@njit(cache=True, inline=inline_into("rhs", "step", "exit_value"))
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
