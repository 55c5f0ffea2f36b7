"""Noise-contaminated excitations ("SVN" records, paper §5).

The baseline (a one-sine pulse or the modulated harmonic of Eq. 23, unit amplitude
a_p = 1) is sampled every ``NOISE_DT``; zero-mean Gaussian white noise whose energy
Σ n_i²·dt is a fraction ``level`` of the baseline's energy Σ b_i²·dt is added; the sum is
then rescaled so that its energy equals the baseline's (``match="energy"``, the default)
or its peak |.| equals the baseline's PGA (``match="pga"``). The paper states both are
preserved; one rescaling can fix only one of them exactly, so the other is reported as a
ratio (``NoisyRecord.energy_ratio``, ``NoisyRecord.pga_ratio``).

Randomness: realisation ``k`` at noise ``level`` comes from
``SeedSequence(seed, spawn_key=(level_key(level), k))``, so the record is the same whichever
job computes it and in whatever order.
"""
from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from .constants import NOISE_DT
from .excitation import GroundMotion, analytic, excitation_duration

NOISE_LEVELS = {"R000": 0.0, "R001": 0.01, "R005": 0.05, "R010": 0.10}
"""The paper's noise levels: noise energy over baseline energy (§5, Table 1). [-]"""

MATCHES = ("energy", "pga")

_LEVEL_KEY_SCALE = 10000


def level_key(level: float) -> int:
    """Integer key of a noise level for the seed sequence: round(level · 10000). [-]"""
    return int(round(level * _LEVEL_KEY_SCALE))


def _check_level(level) -> float:
    if isinstance(level, bool) or not isinstance(level, numbers.Real) or not (0.0 <= level < 1.0):
        raise ValueError(f"level must be a real number in [0, 1) (noise energy / baseline energy), got {level!r}")
    return float(level)


def _check_nonnegative_int(name: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 0:
        raise ValueError(f"{name} must be an integer >= 0, got {value!r}")
    return int(value)


def _check_match(match) -> str:
    if match not in MATCHES:
        raise ValueError(f"match must be one of {', '.join(repr(m) for m in MATCHES)}, got {match!r}")
    return match


def _check_positive(name: str, value, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name} must be a positive finite number [{unit}], got {value!r}")
    return float(value)


def noise_generator(seed: int, level: float, realisation: int) -> np.random.Generator:
    """Random generator for one noise realisation, keyed by what it means.

    Parameters
    ----------
    seed : int
        Study seed, >= 0.
    level : float
        Noise level r in [0, 1): noise energy over baseline energy. [-]
    realisation : int
        Realisation index k, >= 0.

    Returns
    -------
    numpy.random.Generator
        ``default_rng(SeedSequence(seed, spawn_key=(level_key(level), realisation)))``.

    Raises
    ------
    ValueError
        Naming the argument that is out of range.
    """
    seed = _check_nonnegative_int("seed", seed)
    level = _check_level(level)
    realisation = _check_nonnegative_int("realisation", realisation)
    sequence = np.random.SeedSequence(seed, spawn_key=(level_key(level), realisation))
    return np.random.default_rng(sequence)


def sample_count(duration: float, dt: float) -> int:
    """n = ceil(duration / dt), the index of the last sample. [-]

    A quotient within 1e-9 (relative) of an integer is taken as that integer, so that
    floating-point error in ``duration / dt`` does not add a trailing sample.
    """
    q = duration / dt
    nearest = round(q)
    if abs(q - nearest) <= 1e-9 * max(1.0, abs(q)):
        return int(nearest)
    return int(math.ceil(q))


def baseline_samples(kind: str, omega: float, dt: float = NOISE_DT) -> tuple[np.ndarray, float]:
    """Unit-amplitude samples of an analytic excitation at t_i = i·dt, i = 0..n.

    Parameters
    ----------
    kind : {"one-sine", "modulated"}
        One-sine pulse or the modulated harmonic of Eq. (23).
    omega : float
        Excitation circular frequency ω_p. [rad/s]
    dt : float, default NOISE_DT
        Sampling step. [s]

    Returns
    -------
    values : ndarray, shape (n + 1,)
        Ẍ_g(t_i) / a_p with n = ceil(duration / dt) (see :func:`sample_count`). [-]
    dt : float
        The sampling step. [s]
    """
    omega = _check_positive("omega", omega, "rad/s")
    dt = _check_positive("dt", dt, "s")
    duration = excitation_duration(kind, omega)
    n = sample_count(duration, dt)
    t = np.arange(n + 1) * dt
    return np.asarray(analytic(kind, t, 1.0, omega), dtype=float), dt


def energy(values, dt: float) -> float:
    """Discrete energy Σ x_i²·dt of a sampled signal. [unit² s]"""
    values = np.asarray(values, dtype=float)
    return float(np.dot(values, values) * dt)


def scaled_white_noise(size: int, dt: float, target_energy: float, rng: np.random.Generator) -> np.ndarray:
    """Zero-mean Gaussian white noise rescaled to a given discrete energy.

    Draws ``size`` standard normal samples from ``rng`` and scales them so that
    Σ n_i²·dt equals ``target_energy`` exactly (to rounding).

    Parameters
    ----------
    size : int
        Number of samples.
    dt : float
        Sampling step. [s]
    target_energy : float
        Required Σ n_i²·dt, >= 0. [unit² s]
    rng : numpy.random.Generator
        Source of randomness (see :func:`noise_generator`).

    Returns
    -------
    ndarray, shape (size,)
        The noise samples. [unit]
    """
    w = rng.standard_normal(size)
    if target_energy == 0.0:
        return np.zeros(size)
    return w * math.sqrt(target_energy / energy(w, dt))


def contaminate(baseline, dt: float, level: float, rng: np.random.Generator,
                match: str = "energy") -> tuple[np.ndarray, float, float]:
    """Add white noise to a sampled baseline and rescale the sum (§5).

    The noise n has energy Σ n_i²·dt = level × Σ b_i²·dt; the sum b + n is then scaled
    so that its energy equals the baseline's (``match="energy"``) or its peak |.| equals
    the baseline's (``match="pga"``).

    Parameters
    ----------
    baseline : array_like, shape (m,)
        Baseline samples b_i at i·dt. [unit]
    dt : float
        Sampling step. [s]
    level : float
        Noise level r in [0, 1): noise energy over baseline energy. [-]
    rng : numpy.random.Generator
        Source of the noise (not used when ``level == 0``).
    match : {"energy", "pga"}, default "energy"
        Quantity of the baseline the contaminated record keeps exactly.

    Returns
    -------
    record : ndarray, shape (m,)
        The contaminated, rescaled record. For ``level == 0`` a copy of the baseline. [unit]
    energy_ratio : float
        Σ record²·dt / Σ b²·dt achieved. [-]
    pga_ratio : float
        max|record| / max|b| achieved. [-]
    """
    b = np.array(baseline, dtype=float)
    if b.ndim != 1 or b.size < 2 or not np.all(np.isfinite(b)):
        raise ValueError("baseline must be a 1-D array of at least 2 finite samples")
    dt = _check_positive("dt", dt, "s")
    level = _check_level(level)
    match = _check_match(match)
    base_energy = energy(b, dt)
    if base_energy == 0.0:
        raise ValueError("baseline must have non-zero energy: the noise is scaled relative to it")
    if level == 0.0:
        return b, 1.0, 1.0
    summed = b + scaled_white_noise(b.size, dt, level * base_energy, rng)
    base_peak = float(np.max(np.abs(b)))
    if match == "energy":
        record = summed * math.sqrt(base_energy / energy(summed, dt))
    else:
        record = summed * (base_peak / float(np.max(np.abs(summed))))
    return record, energy(record, dt) / base_energy, float(np.max(np.abs(record))) / base_peak


@dataclass(frozen=True)
class NoisyRecord:
    """One noise realisation of a unit-amplitude baseline excitation.

    Parameters
    ----------
    values : ndarray
        Samples at i·dt (read-only); times a_p gives the ground acceleration. [-]
    dt : float
        Sampling step. [s]
    level : float
        Noise level r: noise energy over baseline energy. [-]
    realisation : int
        Realisation index k.
    seed : int
        Study seed.
    match : {"energy", "pga"}
        Quantity of the baseline kept exactly by the rescaling.
    energy_ratio : float
        Achieved energy over baseline energy. [-]
    pga_ratio : float
        Achieved peak |.| over baseline peak. [-]
    """

    values: np.ndarray
    dt: float
    level: float
    realisation: int
    seed: int
    match: str
    energy_ratio: float
    pga_ratio: float

    def __post_init__(self):
        values = np.array(self.values, dtype=float)
        values.setflags(write=False)
        object.__setattr__(self, "values", values)

    @property
    def duration(self) -> float:
        """Time of the last sample, (len − 1)·dt. [s]"""
        return (len(self.values) - 1) * self.dt

    @property
    def times(self) -> np.ndarray:
        """Sample times i·dt. [s]"""
        return np.arange(len(self.values)) * self.dt

    def to_attrs(self) -> dict:
        """Flat attributes for a self-describing dataset."""
        return {"noise_level": self.level, "noise_realisation": self.realisation, "noise_seed": self.seed,
                "noise_match": self.match, "noise_dt_s": self.dt, "noise_energy_ratio": self.energy_ratio,
                "noise_pga_ratio": self.pga_ratio}


def noisy_record(kind: str, omega: float, level: float, realisation: int, seed: int,
                 match: str = "energy", dt: float = NOISE_DT) -> NoisyRecord:
    """Realisation ``realisation`` of the unit-amplitude ``kind`` excitation at noise ``level``.

    Parameters
    ----------
    kind : {"one-sine", "modulated"}
        Baseline excitation (Eq. 23 for "modulated").
    omega : float
        Excitation circular frequency ω_p. [rad/s]
    level : float
        Noise level r in [0, 1). [-]
    realisation : int
        Realisation index k, >= 0.
    seed : int
        Study seed, >= 0.
    match : {"energy", "pga"}, default "energy"
        Quantity of the baseline kept exactly.
    dt : float, default NOISE_DT
        Sampling step. [s]

    Returns
    -------
    NoisyRecord
        For ``level == 0`` the baseline samples themselves, with ratios 1.
    """
    rng = noise_generator(seed, level, realisation)
    match = _check_match(match)
    baseline, dt = baseline_samples(kind, omega, dt)
    values, energy_ratio, pga_ratio = contaminate(baseline, dt, level, rng, match)
    return NoisyRecord(values, dt, float(level), int(realisation), int(seed), match, energy_ratio, pga_ratio)


def noisy_motion(kind: str, omega: float, amplitude: float, level: float, realisation: int, seed: int,
                 match: str = "energy", dt: float = NOISE_DT) -> GroundMotion:
    """A noise-contaminated ground motion ready for the integrators.

    Parameters
    ----------
    kind : {"one-sine", "modulated"}
        Baseline excitation (Eq. 23 for "modulated").
    omega : float
        Excitation circular frequency ω_p. [rad/s]
    amplitude : float
        Amplitude a_p multiplying the unit record. [m/s^2]
    level : float
        Noise level r in [0, 1). [-]
    realisation : int
        Realisation index k, >= 0.
    seed : int
        Study seed, >= 0.
    match : {"energy", "pga"}, default "energy"
        Quantity of the baseline kept exactly.
    dt : float, default NOISE_DT
        Sampling step. [s]

    Returns
    -------
    GroundMotion
        ``kind="record"`` with the samples of :func:`noisy_record` (linearly interpolated);
        for ``level == 0`` the exact analytic motion instead. The achieved energy and PGA
        ratios are on the :class:`NoisyRecord` returned by :func:`noisy_record`.
    """
    if level == 0:
        noise_generator(seed, level, realisation)  # same argument checks as for level > 0
        _check_match(match)
        _check_positive("dt", dt, "s")
        return GroundMotion(kind=kind, amplitude=amplitude, omega=omega,
                            duration=excitation_duration(kind, omega))
    return record_motion(noisy_record(kind, omega, level, realisation, seed, match, dt), amplitude, omega)


def record_motion(rec: NoisyRecord, amplitude: float, omega: float) -> GroundMotion:
    """The ground motion a_p·(unit record), linearly interpolated between samples. [m/s^2]"""
    return GroundMotion(kind="record", amplitude=amplitude, omega=omega, duration=rec.duration,
                        record_dt=rec.dt, record=rec.values)
