"""Ground motions: one-sine pulse, the amplitude-modulated harmonic of Eq. (23), and
sampled records (noise-contaminated versions, see :mod:`rockstudy.model.noise`).

A :class:`GroundMotion` is what the integrators consume. Analytic kinds are evaluated
exactly; a ``record`` is linearly interpolated between its samples at ``i·record_dt``.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from rockstudy.core._inline import inline_into, njit
from rockstudy.core.limits import EXCITATIONS, MAX_GROUND_ACCELERATION
from rockstudy.core.quantities import SIZES, check_arguments, declares
from rockstudy.core.validation import (
    MAX_CONTROLLER_SAMPLES,
    MAX_RECORD_SAMPLES,
    MAX_STEPS,
    MAX_TIME_SPAN,
    fail,
)

KIND_CODE = {"one-sine": 0, "modulated": 1, "record": 2, "rectangular": 3}
"""Integer code of each kind of ground motion, the one the compiled engine reads."""
ONE_SINE, MODULATED, RECORD, RECTANGULAR = (KIND_CODE[k] for k in ("one-sine", "modulated", "record", "rectangular"))
MODULATED_CYCLES = 5
"""T_d = 5 · 2π/ω_p for Eq. (23)."""
ENVELOPE_PEAK = 90.0 * 0.25**2 * 0.75**6
"""Peak of Eq. (23)'s envelope 90 t²(t−T_d)⁶/T_d⁸, reached at t = T_d/4 (≈ 1.00113). [-]"""


def modulated_duration(omega: float) -> float:
    """T_d = 5·2π/ω_p, the duration of Eq. (23). [s]

    Parameters
    ----------
    omega : float
        Excitation frequency ω_p, > 0. [rad/s]
    """
    return MODULATED_CYCLES * 2.0 * math.pi / omega


def excitation_duration(kind: str, omega: float) -> float:
    """Duration after which the analytic excitation is zero. [s]

    Parameters
    ----------
    kind : {"one-sine", "modulated"}
        The analytic excitation: 2π/ω_p for the pulse, T_d = 5·2π/ω_p for Eq. (23).
    omega : float
        Excitation frequency ω_p, > 0. [rad/s]
    """
    if kind == "one-sine":
        return 2.0 * math.pi / omega
    if kind == "modulated":
        return modulated_duration(omega)
    raise ValueError(f"excitation must be one of {', '.join(EXCITATIONS)}, got {kind!r}")


def sample_count(duration: float, dt: float) -> int:
    """n = ceil(duration / dt): the index of the last sample of an excitation lasting ``duration`` [s]
    sampled every ``dt`` [s] (its record has n + 1 samples). [-]

    A quotient within 1e-9 (relative) of an integer is taken as that integer, so that
    floating-point error in ``duration / dt`` does not add a trailing sample.

    Parameters
    ----------
    duration : float
        Duration of the excitation. [s]
    dt : float
        Sampling step, > 0. [s]
    """
    q = duration / dt
    nearest = round(q)
    if abs(q - nearest) <= 1e-9 * max(1.0, abs(q)):
        return int(nearest)
    return int(math.ceil(q))


@njit(cache=True)
def one_sine_acceleration(t, amplitude, omega):
    """One-sine pulse a_p·sin(ω_p t), for 0 <= t <= 2π/ω_p (the caller checks the range). [m/s^2]

    Parameters
    ----------
    t : float
        Time. [s]
    amplitude : float
        a_p. [m/s^2]
    omega : float
        ω_p. [rad/s]
    """
    return amplitude * math.sin(omega * t)


@njit(cache=True)
def modulated_acceleration(t, amplitude, omega, duration):
    """Eq. (23): 90 t²(t − T_d)⁶/T_d⁸ · a_p · sin(ω_p (t − T_d)), for 0 <= t <= T_d
    (the caller checks the range). Both engines evaluate the excitation with this. [m/s^2]

    Parameters
    ----------
    t : float
        Time. [s]
    amplitude : float
        a_p. [m/s^2]
    omega : float
        ω_p. [rad/s]
    duration : float
        T_d = 5·2π/ω_p. [s]
    """
    s = t / duration
    return 90.0 * s * s * (s - 1.0) ** 6 * amplitude * math.sin(omega * (t - duration))


@njit(cache=True, inline=inline_into("ground_acceleration"))
def interpolate_record(t, dt, samples):
    """Linear interpolation of ``samples`` taken at i·dt, for t >= 0; the last sample after the end. [-]

    Parameters
    ----------
    t : float
        Time. [s]
    dt : float
        Sampling step. [s]
    samples : ndarray
        Values at 0, dt, 2dt, ...
    """
    x = t / dt
    i = int(x)
    n = samples.shape[0]
    if i >= n - 1:
        return samples[n - 1]
    f = x - i
    return samples[i] + f * (samples[i + 1] - samples[i])


def modulation_envelope(t, duration):
    """Envelope of Eq. (23), 90 t²(t − T_d)⁶ / T_d⁸, zero outside [0, T_d]. [-]

    Parameters
    ----------
    t : float or array_like
        Time. [s]
    duration : float
        T_d, the duration of Eq. (23). [s]
    """
    t = np.asarray(t, dtype=float)
    s = t / duration
    env = 90.0 * s**2 * (s - 1.0) ** 6
    return np.where((t >= 0) & (t <= duration), env, 0.0)


def one_sine(t, amplitude, omega):
    """One-sine pulse a_p·sin(ω_p t) on [0, 2π/ω_p], zero elsewhere. [m/s^2]

    Parameters
    ----------
    t : float or array_like
        Time. [s]
    amplitude : float
        a_p. [m/s^2]
    omega : float
        ω_p, > 0. [rad/s]
    """
    t = np.asarray(t, dtype=float)
    end = 2.0 * math.pi / omega
    return np.where((t >= 0) & (t <= end), amplitude * np.sin(omega * t), 0.0)


def modulated(t, amplitude, omega):
    """Amplitude-modulated harmonic, Eq. (23), zero outside [0, T_d], on an array of times. [m/s^2]

    The sampled baselines of the noisy records are built with this array form; the engines use
    :func:`modulated_acceleration`. Both evaluate the same polynomial; their products are rounded
    in a different order (agreement within 1e-15 relative, tests/model/test_excitation.py).

    Parameters
    ----------
    t : float or array_like
        Time. [s]
    amplitude : float
        a_p. [m/s^2]
    omega : float
        ω_p, > 0; it sets T_d = 5·2π/ω_p. [rad/s]
    """
    t = np.asarray(t, dtype=float)
    td = modulated_duration(omega)
    return modulation_envelope(t, td) * amplitude * np.sin(omega * (t - td))


def analytic(kind: str, t, amplitude, omega):
    """Evaluate an analytic excitation by name. [m/s^2]

    Parameters
    ----------
    kind : {"one-sine", "modulated"}
        The excitation: :func:`one_sine` or :func:`modulated`.
    t : float or array_like
        Time. [s]
    amplitude : float
        a_p. [m/s^2]
    omega : float
        ω_p, > 0. [rad/s]
    """
    if kind == "one-sine":
        return one_sine(t, amplitude, omega)
    if kind == "modulated":
        return modulated(t, amplitude, omega)
    raise ValueError(f"excitation must be one of {', '.join(EXCITATIONS)}, got {kind!r}")


@declares(sizes={"record": MAX_RECORD_SAMPLES, "vertical": MAX_RECORD_SAMPLES}, amplitude="acceleration",
          omega="angular_rate", duration="duration", record_dt="record_dt", vertical_dt="record_dt")
@dataclass(frozen=True)
class GroundMotion:
    """A horizontal (and optional vertical) ground acceleration history.

    Parameters
    ----------
    kind : {"one-sine", "modulated", "record", "rectangular"}
        Analytic pulse, Eq. (23), a sampled record, or a rectangular pulse (tests).
    amplitude : float
        a_p; for a record, the factor multiplying ``record``. [m/s^2]
    omega : float
        ω_p (unused for "rectangular"). [rad/s]
    duration : float
        Time after which the horizontal excitation is zero. [s]
    record_dt : float
        Sampling step of ``record``. [s]
    record : ndarray
        Samples at i·record_dt (dimensionless; times ``amplitude`` gives m/s^2).
    vertical_dt : float
        Sampling step of ``vertical``. [s]
    vertical : ndarray
        Vertical ground acceleration samples at i·vertical_dt, zero after. [m/s^2]
    """

    kind: str
    amplitude: float
    omega: float
    duration: float
    record_dt: float = 0.0
    record: np.ndarray = field(default_factory=lambda: np.zeros(0))
    vertical_dt: float = 0.0
    vertical: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def __post_init__(self):
        if not isinstance(self.kind, str) or self.kind not in KIND_CODE:
            raise ValueError(f"GroundMotion.kind must be one of {', '.join(KIND_CODE)}, got {self.kind!r}")
        # each field's type and range (core.quantities); the steps only where there are samples
        given = {"amplitude": self.amplitude, "omega": self.omega, "duration": self.duration}
        if self.kind == "record":
            given["record_dt"] = self.record_dt
        if np.size(self.vertical):
            given["vertical_dt"] = self.vertical_dt
        checked = check_arguments("GroundMotion", given)
        if self.kind != "rectangular" and not checked["omega"] > 0:
            fail("GroundMotion.omega", checked["omega"], "it must be > 0", "rad/s")
        for key in ("amplitude", "omega", "duration"):
            object.__setattr__(self, key, checked[key])
        for name in ("record", "vertical"):
            try:
                samples = np.ascontiguousarray(getattr(self, name), dtype=float)
            except (TypeError, ValueError):
                raise ValueError(f"GroundMotion.{name} must be an array of numbers") from None
            if samples.ndim != 1 or samples.size > SIZES["GroundMotion", name]:
                fail(f"GroundMotion.{name}", f"an array of shape {samples.shape}",
                     f"it must be 1-D with at most {SIZES['GroundMotion', name]} samples")
            if not np.all(np.isfinite(samples)):
                bad = int(np.flatnonzero(~np.isfinite(samples))[0])
                fail(f"GroundMotion.{name}", f"sample {bad} = {samples[bad]}", "every sample must be finite")
            object.__setattr__(self, name, samples)
        self._check_peak()
        if self.kind == "record":
            if len(self.record) < 2:
                fail("GroundMotion.record", f"{len(self.record)} sample(s)", "a record needs at least 2 samples")

    def _check_peak(self) -> None:
        """The peak ground acceleration, horizontal (amplitude times the record's peak, for a record) and
        vertical, within :data:`~rockstudy.core.limits.MAX_GROUND_ACCELERATION`."""
        peaks = {"amplitude": abs(self.amplitude) * (float(np.max(np.abs(self.record))) if self.kind == "record"
                                                     else 1.0),
                 "vertical": float(np.max(np.abs(self.vertical))) if self.vertical.size else 0.0}
        for name, peak in peaks.items():
            if not peak <= MAX_GROUND_ACCELERATION:
                what = "amplitude x the record's peak" if name == "amplitude" and self.kind == "record" else "its peak"
                fail(f"GroundMotion.{name}", f"{what} {peak:.6g}", f"allowed is a peak ground acceleration <= "
                     f"{MAX_GROUND_ACCELERATION:g} (2000 g)", "m/s^2")

    @property
    def code(self) -> int:
        return KIND_CODE[self.kind]

    def horizontal(self, t):
        """Horizontal ground acceleration Ẍ_g(t). [m/s^2]

        Parameters
        ----------
        t : float or array_like
            Time; zero outside [0, duration]. [s]
        """
        t = np.asarray(t, dtype=float)
        if self.kind in EXCITATIONS:
            return analytic(self.kind, t, self.amplitude, self.omega)
        if self.kind == "rectangular":
            return np.where((t >= 0) & (t < self.duration), self.amplitude, 0.0)
        # as the engines read a record: linear between samples, the last sample held up to the duration (a
        # record that ends before it), zero outside [0, duration]
        grid = np.arange(len(self.record)) * self.record_dt
        values = np.interp(t, grid, self.record, left=0.0, right=self.record[-1])
        return self.amplitude * np.where((t >= 0) & (t <= self.duration), values, 0.0)

    def vertical_acceleration(self, t):
        """Vertical ground acceleration Ÿ_g(t) (zero when not given). [m/s^2]

        Parameters
        ----------
        t : float or array_like
            Time; zero outside the vertical record. [s]
        """
        t = np.asarray(t, dtype=float)
        if len(self.vertical) == 0:
            return np.zeros_like(t)
        grid = np.arange(len(self.vertical)) * self.vertical_dt
        return np.interp(t, grid, self.vertical, left=0.0, right=0.0)

    def scaled(self, amplitude: float) -> "GroundMotion":
        """The same motion with a different amplitude a_p. [m/s^2]

        Parameters
        ----------
        amplitude : float
            The new a_p (for a record, the factor multiplying its samples). [m/s^2]
        """
        return GroundMotion(self.kind, amplitude, self.omega, self.duration, self.record_dt, self.record,
                            self.vertical_dt, self.vertical)

    @property
    def end_time(self) -> float:
        """Time after which both components are zero. [s]"""
        end = self.duration
        if len(self.vertical):
            end = max(end, (len(self.vertical) - 1) * self.vertical_dt)
        return end

    def peak(self) -> float:
        """Peak |Ẍ_g| (PGA). [m/s^2]"""
        if self.kind == "record":
            return abs(self.amplitude) * float(np.max(np.abs(self.record)))
        if self.kind == "modulated":
            return abs(self.amplitude) * modulated_peak()
        return abs(self.amplitude)


@functools.cache
def modulated_peak() -> float:
    """max_t |Eq. 23| for a_p = 1 (slightly below the envelope peak); computed once per process (a
    200,001-point sampling, 25 ms), since every analytic case of a spectrum asks for it. [-]"""
    # Independent of ω_p: in s = t/T_d the carrier is sin(10π(s−1)). Sample densely and polish.
    s = np.linspace(0.0, 1.0, 200001)
    f = np.abs(90 * s**2 * (s - 1) ** 6 * np.sin(10 * np.pi * (s - 1)))
    return float(f.max())


def check_time_span(block, excitation: str, frequency_ratios, free_time: float, sampling_time: float = 0.0, *,
                    frequency_name: str = "frequency_ratio", free_time_name: str = "free_time",
                    sampling_name: str = "sampling_time", record_step: float | None = None,
                    record_span: float = 0.0, step_name: str = "noise.step", span_name: str = "noise.span") -> None:
    """The simulations at these frequency ratios stay within :data:`MAX_TIME_SPAN`, :data:`MAX_STEPS`
    and :data:`MAX_CONTROLLER_SAMPLES` (the worst cases are the lowest and the highest frequency).

    Parameters
    ----------
    block : rockstudy.Block
        The block; its p turns a frequency ratio into ω_p.
    excitation : {"one-sine", "modulated"}
        The analytic excitation, which sets the duration at each frequency.
    frequency_ratios : sequence of float
        omega_p/p values (only the smallest and the largest are checked). [-]
    free_time : float
        Free motion after the excitation. [s]
    sampling_time : float
        Controller sampling time T_s (0: continuous). [s]
    record_step, record_span : float
        For noisy records: their sampling step and the noise after the excitation (the noise reading's
        ``step`` and ``span``, named ``step_name`` and ``span_name``): the record lasts ``record_span``
        longer, and its samples must stay within :data:`MAX_RECORD_SAMPLES`. [s]
    frequency_name, free_time_name, sampling_name, step_name, span_name : str
        Names of ``frequency_ratios``, ``free_time``, ``sampling_time``, ``record_step`` and ``record_span``
        in the error message (the caller's option or config key).

    Raises
    ------
    rockstudy.core.validation.InputError
        If a simulation would exceed one of the limits.
    """
    for f in {min(frequency_ratios), max(frequency_ratios)}:
        omega = f * block.p
        if not omega > 0:  # e.g. a grid start below 5e-11, which the grid rounds to 0
            fail(frequency_name, f, "it must be > 0 (the grids are rounded to 10 decimals)")
        duration = excitation_duration(excitation, omega)
        span = duration + free_time
        if span > MAX_TIME_SPAN:
            fail(frequency_name, f, f"the excitation lasts {span - free_time:.4g} s at this frequency ratio "
                                    f"for this block (p = {block.p:.4g} rad/s); with {free_time_name} = "
                                    f"{free_time:g} s that is {span:.4g} s, the limit is {MAX_TIME_SPAN:g} s")
        if record_step is not None:
            if duration + free_time <= MAX_TIME_SPAN < duration + record_span + free_time:
                fail(span_name, record_span, f"the excitation lasts {duration:.4g} s at {frequency_name} = {f:g}; "
                                             f"with {span_name} and {free_time_name} = {free_time:g} s a simulation "
                                             f"lasts {duration + record_span + free_time:.4g} s, the limit is "
                                             f"{MAX_TIME_SPAN:g} s", "s")
            samples = math.ceil(duration / record_step) + 1 + round(record_span / record_step)
            if samples > MAX_RECORD_SAMPLES:
                fail(step_name, record_step, f"a record of {duration + record_span:.4g} s at {frequency_name} = "
                                             f"{f:g} sampled every {record_step:g} s has {samples:.3g} samples, the "
                                             f"limit is {MAX_RECORD_SAMPLES:.0e} (the engine steps to every sample)",
                     "s")
            span += record_span
        hmax = 0.05 * 2 * math.pi / max(block.p, omega)
        if span / hmax > MAX_STEPS:
            fail(frequency_name, f, f"a simulation of {span:.4g} s at steps of at most {hmax:.3g} s needs "
                                    f"{span / hmax:.3g} steps, the limit is {MAX_STEPS:.0e} (lower the frequency "
                                    f"or {free_time_name}, or use a larger block)")
        if sampling_time > 0 and span / sampling_time > MAX_CONTROLLER_SAMPLES:
            fail(sampling_name, sampling_time, f"a simulation of {span:.4g} s sampled every {sampling_time:g} s "
                                               f"takes {span / sampling_time:.3g} controller samples, the limit is "
                                               f"{MAX_CONTROLLER_SAMPLES:.0e} (the fast engine's event cap)", "s")
