"""The ground motion as scalar functions of time, with the instants where it is not smooth.

``solve_ivp`` calls the right-hand side and the event functions with one time at a time, so
the reference engine evaluates Ẍg(t) and Ÿg(t) on plain floats, through the same compiled
formulas as the fast engine (:func:`rockstudy.model.excitation.one_sine_acceleration`, Eq. 23's
:func:`rockstudy.model.excitation.modulated_acceleration`).

The controller may read Ẍg through a sensor (:mod:`rockstudy.model.sensor`): ``Excitation.sensed`` is
what it reads (the driving Ẍg itself without a sensor), and CS02's sign of Ẍg is taken from it.
"""
from __future__ import annotations

import math

import numpy as np

from rockstudy.model.excitation import (
    ENVELOPE_PEAK,
    GroundMotion,
    interpolate_record,
    modulated_acceleration,
    modulated_duration,
    one_sine_acceleration,
)
from rockstudy.model.sensor import sensed_samples

ZERO_GROUND = 1e-9
"""|Ẍg| below this fraction of the peak counts as Ẍg = 0 when reading its sign after a stop. [-]"""

LOCATE_STEPS_PER_PERIOD = 128
"""Steps per excitation period allowed when locating an event that depends on time only. [-]"""


class PiecewiseLinear:
    """Linear interpolation of ``factor·samples`` given at i·dt, zero outside the record.

    Parameters
    ----------
    samples : array_like
        Values at t = i·dt. [m/s^2] (or [-] when ``factor`` carries the units)
    dt : float
        Sampling step. [s]
    factor : float, default 1
        Scale applied to every value (a record's amplitude a_p). [m/s^2]
    end : float, optional
        Zero after this time too (the sensed Ẍg after the end of the excitation: the controller
        knows the excitation is over, :mod:`rockstudy.model.sensor`). [s]
    """

    def __init__(self, samples, dt: float, factor: float = 1.0, end: float = math.inf):
        self.values = np.array(samples, dtype=float)
        self.dt = float(dt)
        self.factor = factor
        self.last = min((len(self.values) - 1) * dt, end)  # zero after this time [s]

    def __call__(self, t: float) -> float:
        """Interpolated value at t (the fast engine's ``excitation.interpolate_record``); zero before 0
        and after the last sample (or ``end``). [m/s^2]"""
        if t < 0.0 or t > self.last:
            return 0.0
        return self.factor * interpolate_record(float(t), self.dt, self.values)


def _no_vertical(t: float) -> float:
    """Ÿg of a motion without a vertical component. [m/s^2]"""
    return 0.0


class Excitation:
    """Scalar Ẍg(t), Ÿg(t) of a :class:`~rockstudy.model.excitation.GroundMotion` and its breakpoints.

    Parameters
    ----------
    motion : GroundMotion
        The ground motion the block feels.
    sensor_band : float or None, default None
        Cut-off of the controller's sensor (:mod:`rockstudy.model.sensor`); None: it reads Ẍg itself. [Hz]

    Attributes
    ----------
    horizontal, vertical : callable
        Ẍg(t) and Ÿg(t) on one float. [m/s^2]
    sensed : callable
        Ẍg(t) as the controller reads it (``horizontal`` itself without a sensor). [m/s^2]
    horizontal_end : float
        Instant after which Ẍg is zero. [s]
    end : float
        Instant after which both components are zero. [s]
    knots : ndarray
        Every instant > 0 at which Ẍg or Ÿg is not smooth (record samples, ends of pulses);
        integration pieces never step across one. [s]
    piecewise_linear : bool
        Ẍg and Ÿg are linear (or constant) between knots (records, the rectangular pulse).
    time_scale : float
        Largest step when locating an event that depends on time only. [s]
    peak : float
        Scale of |Ẍg| for "Ẍg is zero" (the envelope peak bounds Eq. 23 without sampling it). [m/s^2]
    """

    def __init__(self, motion: GroundMotion, sensor_band: float | None = None):
        kind = motion.kind
        self.amplitude = float(motion.amplitude)
        self.omega = float(motion.omega)
        knots = []
        self.time_scale = math.inf
        if kind == "one-sine":
            self.horizontal_end = 2.0 * math.pi / self.omega
            self.horizontal = self._one_sine
            self.time_scale = self.horizontal_end / LOCATE_STEPS_PER_PERIOD
        elif kind == "modulated":
            self.horizontal_end = modulated_duration(self.omega)
            self.horizontal = self._modulated
            self.time_scale = 2.0 * math.pi / self.omega / LOCATE_STEPS_PER_PERIOD
        elif kind == "rectangular":
            self.horizontal_end = float(motion.duration)
            self.horizontal = self._rectangular
        else:  # "record"
            self.horizontal = PiecewiseLinear(motion.record, motion.record_dt, self.amplitude)
            self.horizontal_end = self.horizontal.last
            knots.extend(np.arange(len(motion.record)) * motion.record_dt)
        self.piecewise_linear = kind in ("record", "rectangular")
        vertical_end = 0.0
        self.vertical = _no_vertical
        if len(motion.vertical):
            self.vertical = PiecewiseLinear(motion.vertical, motion.vertical_dt)
            vertical_end = self.vertical.last
            knots.extend(np.arange(len(motion.vertical)) * motion.vertical_dt)
        self.end = max(float(motion.end_time), self.horizontal_end, vertical_end)
        knots.extend([self.horizontal_end, vertical_end, self.end])
        self.knots = np.unique(np.asarray([k for k in knots if k > 0.0], dtype=float))
        self.peak = abs(self.amplitude) * ENVELOPE_PEAK if kind == "modulated" else float(motion.peak())
        self.sensed = self.horizontal
        if sensor_band is not None:
            values, step = sensed_samples(motion, sensor_band)
            self.sensed = PiecewiseLinear(values, step, self.amplitude, end=self.horizontal_end)

    def _one_sine(self, t: float) -> float:
        """One-sine pulse on [0, 2π/ω_p], zero outside. [m/s^2]"""
        if 0.0 <= t <= self.horizontal_end:
            return one_sine_acceleration(t, self.amplitude, self.omega)
        return 0.0

    def _modulated(self, t: float) -> float:
        """Eq. (23) on [0, T_d], zero outside. [m/s^2]"""
        if 0.0 <= t <= self.horizontal_end:
            return modulated_acceleration(t, self.amplitude, self.omega, self.horizontal_end)
        return 0.0

    def _rectangular(self, t: float) -> float:
        """a_p on [0, duration), zero outside. [m/s^2]"""
        return self.amplitude if 0.0 <= t < self.horizontal_end else 0.0

    def next_knot(self, t: float) -> float:
        """First breakpoint strictly after ``t`` (inf if none). [s]

        Parameters
        ----------
        t : float
            Time now. [s]
        """
        i = int(np.searchsorted(self.knots, t, side="right"))
        return float(self.knots[i]) if i < len(self.knots) else math.inf

    def sign_after(self, t: float) -> int:
        """Sign of Ẍg as the controller reads it just after ``t``; 0 after the excitation's end. [-]

        Parameters
        ----------
        t : float
            Time now; where the sensed Ẍg is (near) zero at ``t``, it is read a little later. [s]
        """
        if t >= self.horizontal_end:
            return 0
        value = self.sensed(t)
        if abs(value) <= ZERO_GROUND * self.peak:
            value = self.sensed(t + ZERO_GROUND * max(1.0, t))
        return (value > 0.0) - (value < 0.0)
