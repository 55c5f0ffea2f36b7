"""What the controller senses of the ground acceleration: the record itself, or its measurement through an
accelerometer and controller filter of a stated bandwidth (docs/model.md "What the controller senses").

CS02 (Eq. 17) switches on the sign of Ẍg, so under noise what the controller reads of Ẍg can decide its
performance. :class:`rockstudy.model.control.Control` carries ``sensor_band`` [Hz]:

* ``None`` (default): the controller reads the very Ẍg that drives the block (the paper's ideal
  sensor; results bit-identical to rockstudy before this option);
* a band f_c: the controller reads the driving record through a **causal second-order Butterworth
  low-pass** with cut-off f_c, discretised by the bilinear (Tustin) transform with the cut-off
  pre-warped, run on the samples of the record at the record's step Δt from rest (zero initial
  state), and interpolated linearly between samples like the record itself.

Why this model: a force-balance or MEMS accelerometer is a damped oscillator whose response to
ground acceleration is a second-order low-pass; with damping 1/√2 it is exactly the Butterworth
filter (maximally flat pass band), and a digital controller implements such a filter at its own
sampling rate (the bilinear transform keeps it stable and makes its gain exactly −3 dB at f_c).
The filter is causal: the measurement at t_i depends only on samples up to t_i, as a real controller's.

Gain: |H(f)| = 1 / √(1 + (tan(π f Δt) / tan(π f_c Δt))⁴) for 0 <= f < 1/(2Δt) (:func:`butterworth_gain`):
1 at f = 0, 1/√2 (−3 dB) at f = f_c, → 0 at the Nyquist frequency. Its group delay at low
frequency is about √2 / (2π f_c) (22 ms at 10 Hz): the controller reads Ẍg late and smoothed.

An analytic excitation (the one-sine pulse, Eq. 23, a rectangular pulse) is sampled for the sensor
at a step of :data:`SENSOR_STEP` (the noisy records' step, 2.5 ms), i = 0 … ceil(T/Δt), like the
baselines of the noisy records; the block still feels the exact analytic excitation.

In both engines the sensed acceleration is zero outside the excitation [0, T] (T the end of the horizontal
excitation): the controller knows when the excitation is over, so CS02 switches to CS01 at T as it
does with the ideal sensor (the filter's decaying tail after T is not read).
"""
from __future__ import annotations

import math

import numpy as np

from rockstudy.core import validation
from rockstudy.core.constants import NOISE_DT
from rockstudy.model.excitation import EXCITATIONS, GroundMotion, analytic, sample_count

SENSOR_STEP = NOISE_DT
"""Sampling step at which an analytic excitation is read by the sensor (the noisy records' step). [s]"""

__all__ = ["SENSOR_STEP", "check_band", "butterworth_coefficients", "butterworth_gain", "sense",
           "sensed_step", "sensed_samples"]


def check_band(band, step: float, name: str = "sensor_band") -> float:
    """``band`` as a float, refused unless 0 < band < 1/(2·step), the Nyquist frequency. [Hz]

    Parameters
    ----------
    band : float
        Cut-off frequency f_c of the sensor. [Hz]
    step : float
        Sampling step of the samples the sensor reads. [s]
    name : str
        How the caller names ``band`` in the error message.
    """
    band = validation.check_positive(name, band, "Hz", why="or None, the ideal sensor")
    return validation.check_range(name, band, high=0.5 / step, unit="Hz", high_open=True,
                         why=f"the Nyquist frequency 1/(2 step) of the record it reads, step {step:g} s; "
                             "None is the ideal sensor")


def butterworth_coefficients(band: float, step: float) -> tuple[np.ndarray, np.ndarray]:
    """Numerator b and denominator a (a₀ = 1) of the second-order Butterworth low-pass, bilinear transform.

    With K = tan(π f_c Δt): b = (K², 2K², K²)/d, a = (1, 2(K² − 1)/d, (1 − √2 K + K²)/d),
    d = 1 + √2 K + K² (the analog prototype 1/(s² + √2 s + 1) with s = (1/K)(1 − z⁻¹)/(1 + z⁻¹)).

    Parameters
    ----------
    band : float
        Cut-off f_c, 0 < f_c < 1/(2Δt). [Hz]
    step : float
        Sampling step Δt. [s]
    """
    band = check_band(band, step)
    k = math.tan(math.pi * band * step)
    k2 = k * k
    d = 1.0 + math.sqrt(2.0) * k + k2
    b = np.array([k2, 2.0 * k2, k2]) / d
    a = np.array([1.0, 2.0 * (k2 - 1.0) / d, (1.0 - math.sqrt(2.0) * k + k2) / d])
    return b, a


def butterworth_gain(frequency, band: float, step: float):
    """|H(f)| of :func:`butterworth_coefficients`: 1/√(1 + (tan(π f Δt)/tan(π f_c Δt))⁴). [-]

    Parameters
    ----------
    frequency : float or array_like
        Frequencies f in [0, 1/(2Δt)). [Hz]
    band : float
        Cut-off f_c. [Hz]
    step : float
        Sampling step Δt. [s]
    """
    band = check_band(band, step)
    ratio = np.tan(np.pi * np.asarray(frequency, dtype=float) * step) / math.tan(math.pi * band * step)
    return 1.0 / np.sqrt(1.0 + ratio**4)


def sense(values, step: float, band: float) -> np.ndarray:
    """The samples as the sensor reads them: the causal Butterworth low-pass, from rest. [unit of values]

    Parameters
    ----------
    values : array_like
        Samples x_i at i·Δt (the record the block feels). [any unit]
    step : float
        Sampling step Δt. [s]
    band : float
        Cut-off f_c. [Hz]

    Returns
    -------
    ndarray
        y_i = b₀x_i + b₁x_{i−1} + b₂x_{i−2} − a₁y_{i−1} − a₂y_{i−2}, with x and y zero before i = 0.
    """
    b, a = butterworth_coefficients(band, step)
    x = np.asarray(values, dtype=float)
    if x.ndim != 1:
        raise ValueError(f"values must be a 1-D array of samples, got shape {x.shape}")
    # imported here, not at the top: scipy.signal takes ~0.8 s to import, every workflow job imports
    # rockstudy, and only runs with a sensor need it
    from scipy.signal import lfilter

    return lfilter(b, a, x)


def sensed_step(motion: GroundMotion) -> float:
    """Sampling step of the sensed record of ``motion``: the record's step, else :data:`SENSOR_STEP`. [s]

    Parameters
    ----------
    motion : GroundMotion
        The ground motion the sensor reads.
    """
    return float(motion.record_dt) if motion.kind == "record" else SENSOR_STEP


def _unit_samples(motion: GroundMotion, step: float) -> np.ndarray:
    """Unit-amplitude samples of an analytic or rectangular motion at i·step, i = 0 … ceil(T/step). [-]"""
    n = sample_count(motion.duration, step)
    t = np.arange(n + 1) * step
    if motion.kind in EXCITATIONS:
        return np.asarray(analytic(motion.kind, t, 1.0, motion.omega), dtype=float)
    return np.where(t < motion.duration, 1.0, 0.0)  # rectangular


def sensed_samples(motion: GroundMotion, band: float) -> tuple[np.ndarray, float]:
    """What the sensor of cut-off ``band`` reads of ``motion``'s horizontal component, per unit amplitude.

    Times the motion's ``amplitude`` (a_p, or the record's factor) it is the sensed Ẍg [m/s^2],
    as the record times ``amplitude`` is the driving Ẍg (the filter is linear).

    Parameters
    ----------
    motion : GroundMotion
        The ground motion the block feels.
    band : float
        Cut-off f_c, below the Nyquist frequency of :func:`sensed_step`. [Hz]

    Returns
    -------
    values : ndarray
        Sensed samples at i·step. [-]
    step : float
        Their step (:func:`sensed_step`). [s]
    """
    step = sensed_step(motion)
    check_band(band, step, "Control.sensor_band")
    raw = motion.record if motion.kind == "record" else _unit_samples(motion, step)
    return sense(raw, step, band), step
