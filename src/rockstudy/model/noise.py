"""Noise-contaminated excitations ("SVN" records, paper §5) and the reading of the paper's loose noise model.

The baseline (a one-sine pulse or the modulated harmonic of Eq. 23, unit amplitude
a_p = 1) is sampled every ``step``; zero-mean Gaussian noise whose energy Σ n_i²·dt is a
fraction of the baseline's energy Σ b_i²·dt is added; the sum is then rescaled. The paper
leaves every one of these choices loose (§5: "1 %, 5 % and 10 % of the excitation energy",
"without altering the energy content and the PGA value"; the captions of Figs. 7-8 say
"noise RMS of 5 %"; no sampling step, no bandwidth), so each is a named field of a
:class:`NoiseReading`:

* ``step`` [s]: the sampling step of the record (baseline and noise), default 2.5 ms;
* ``rescale``: ``"energy"`` (the sum keeps the baseline's energy, default), ``"pga"`` (its
  peak |.|), ``"both"`` (energy rescaling with soft limiting at the baseline PGA, see
  :func:`rescale_both`) or ``"none"`` (the sum as it is: energy about (1 + r)×);
* ``level_means``: the level r is the noise **energy** over the baseline energy (default) or
  the noise **RMS** over the baseline RMS (then the energy fraction is r²);
* ``band`` [Hz]: optional upper band limit of the noise (ideal low-pass on its DFT); white
  up to the Nyquist frequency 1/(2·step) when ``None`` (default);
* ``span`` [s]: noise also for ``span`` seconds after the intense part [0, T_d] (default 0:
  the intense part only). The noise keeps the same RMS after T_d; the level is measured on
  the intense part.

The default reading reproduces, bit for bit, the records of rockstudy before these options
existed (``tests/model/test_noise.py::test_default_reading_is_bit_for_bit_the_old_records``).
The achieved energy and PGA ratios are reported on every record
(``NoisyRecord.energy_ratio``, ``NoisyRecord.pga_ratio``).

Randomness: realisation ``k`` at noise ``level`` comes from
``SeedSequence(seed, spawn_key=(level_key(level), k))``, so the record is the same whichever
job computes it and in whatever order; every reading of a level uses the same draws
(common random numbers), so readings are compared realisation by realisation.
"""
from __future__ import annotations

import functools
import math
from dataclasses import InitVar, dataclass

import numpy as np

from rockstudy.core import validation
from rockstudy.core.constants import NOISE_DT
from rockstudy.core.limits import LEVEL_MEANINGS, RESCALES
from rockstudy.core.quantities import QUANTITIES, check_arguments, declares
from rockstudy.core.recent import Recent
from rockstudy.model.excitation import GroundMotion, analytic, excitation_duration, sample_count

NOISE_LEVELS = {"R000": 0.0, "R001": 0.01, "R005": 0.05, "R010": 0.10}
"""The paper's noise levels: noise energy over baseline energy (§5, Table 1). [-]"""


_LEVEL_KEY_SCALE = 10000


def level_key(level: float) -> int:
    """Integer key of a noise level for the seed sequence: round(level · 10000). [-]

    Parameters
    ----------
    level : float
        Noise level r. [-]
    """
    return int(round(level * _LEVEL_KEY_SCALE))


def _check_level(level) -> float:
    return QUANTITIES["noise_level"].check("level", level)


DEFAULT_SEED = 20190101
"""Root seed of the study's noise realisations (``seed`` of config.yaml, ``--seed`` of the CLI)."""


def _check_rescale(rescale, name: str = "rescale") -> str:
    if rescale not in RESCALES:
        raise ValueError(f"{name} must be one of {', '.join(repr(m) for m in RESCALES)}, got {rescale!r}")
    return rescale


@declares(step="noise_step", band="band", span="noise_span")
@dataclass(frozen=True)
class NoiseReading:
    """One reading of the paper's noise model (§5): how a noisy record is made from a baseline.

    Parameters
    ----------
    step : float, default NOISE_DT
        Sampling step of the record, baseline and noise alike (linear interpolation between
        samples). [s]
    rescale : {"energy", "pga", "both", "none"}, default "energy"
        What the sum baseline + noise keeps of the baseline: its energy, its peak |.| (PGA),
        both (:func:`rescale_both`), or nothing (the sum is not rescaled).
    level_means : {"energy", "rms"}, default "energy"
        The level r is noise energy / baseline energy, or noise RMS / baseline RMS (then the
        noise energy is r² × the baseline's). [-]
    band : float or None, default None
        Upper band limit of the noise, below the Nyquist frequency 1/(2·step); ``None``: white
        up to the Nyquist frequency. [Hz]
    span : float, default 0.0
        Noise continues for this long after the intense part [0, T_d], at the same RMS; 0:
        noise on the intense part only. [s]
    names : dict, optional
        The caller's name of each field in error messages (``{"step": "--noise-step"}``); a field missing from
        it is named ``NoiseReading.<field>``. Not stored.

    Raises
    ------
    ValueError
        Naming the field, its value and what is allowed: the one check of a reading, at construction
        (:meth:`check`).
    """

    step: float = NOISE_DT
    rescale: str = "energy"
    level_means: str = "energy"
    band: float | None = None
    span: float = 0.0
    names: InitVar[dict | None] = None

    def __post_init__(self, names):
        for key, value in self.check(names, **self.__dict__).items():
            object.__setattr__(self, key, value)

    @staticmethod
    def check(names=None, *, step=NOISE_DT, rescale="energy", level_means="energy", band=None, span=0.0) -> dict:
        """Refuse a bad field with a ``ValueError`` naming it ``names[field]`` (the caller's option or config
        key), else ``NoiseReading.<field>``; returns the numbers as floats.

        Parameters
        ----------
        names : dict or None, default None
            Name of each field in the error message, e.g. ``{"step": "noise.step"}``; a field missing from it
            is named ``NoiseReading.<field>``.
        step : float
            Sampling step, > 0 and at most ``MAX_NOISE_STEP``. [s]
        rescale : {"energy", "pga", "both", "none"}
            What the sum baseline + noise keeps of the baseline.
        level_means : {"energy", "rms"}
            What the level r measures.
        band : float or None
            Upper band limit of the noise, > 0 and below 1/(2·step), or None for white noise. [Hz]
        span : float
            Noise after the intense part, >= 0. [s]
        """
        name = validation.field_names("NoiseReading", names)
        checked = check_arguments("NoiseReading", {"step": step, "band": band, "span": span}, names)
        step, band, span = checked["step"], checked["band"], checked["span"]
        _check_rescale(rescale, name("rescale"))
        if level_means not in LEVEL_MEANINGS:
            raise ValueError(f"{name('level_means')} must be one of {', '.join(map(repr, LEVEL_MEANINGS))}, "
                             f"got {level_means!r}")
        if band is not None:
            if band >= 0.5 / step:
                raise ValueError(f"{name('band')} must be below the Nyquist frequency 1/(2 {name('step')}) = "
                                 f"{0.5 / step:g} Hz, got {band!r} (use None for white noise)")
        return {"step": step, "band": band, "span": span}

    @property
    def nyquist(self) -> float:
        """Nyquist frequency of the record, 1/(2·step). [Hz]"""
        return 0.5 / self.step

    def energy_fraction(self, level: float) -> float:
        """Noise energy over baseline energy on the intense part for level r: r, or r² for ``rms``. [-]

        Parameters
        ----------
        level : float
            Noise level r in [0, 1). [-]
        """
        level = _check_level(level)
        return level if self.level_means == "energy" else level * level

    def to_attrs(self) -> dict:
        """Flat attributes recording the reading (``noise_band_hz`` is "none" for white noise)."""
        return {"noise_step_s": self.step, "noise_rescale": self.rescale, "noise_level_means": self.level_means,
                "noise_band_hz": "none" if self.band is None else self.band, "noise_span_s": self.span}

    def label(self) -> str:
        """Short human-readable description, e.g. "2.5 ms, energy rescale, r = energy"."""
        text = f"{self.step * 1000:g} ms, {self.rescale} rescale, r = {self.level_means}"
        if self.band is not None:
            text += f", band {self.band:g} Hz"
        if self.span > 0:
            text += f", +{self.span:g} s after T_d"
        return text


DEFAULT_READING = NoiseReading()
"""The study's reading: 2.5 ms, energy rescaling (§5 keeps the excitation's energy), r = energy
fraction, white, intense part only."""


def reading_from_dict(spec: dict | None, key: str = "noise") -> NoiseReading:
    """A :class:`NoiseReading` from a plain dict (the ``noise:`` section of the config); None: the default.

    Parameters
    ----------
    spec : dict or None
        Fields of :class:`NoiseReading` (``step``, ``rescale``, ``level_means``, ``band``, ``span``); None
        gives :data:`DEFAULT_READING`.
    key : str, default "noise"
        Where the dict sits in the caller's config: errors name each field ``<key>.<field>``.
    """
    if spec is None:
        return DEFAULT_READING
    fields = ("step", "rescale", "level_means", "band", "span")
    unknown = set(spec) - set(fields)
    if unknown:
        raise ValueError(f"{key}: unknown key(s) {sorted(unknown)}; allowed: {', '.join(fields)}")
    return NoiseReading(**spec, names={field: f"{key}.{field}" for field in fields})


def _as_reading(reading) -> NoiseReading:
    """The reading given, or :data:`DEFAULT_READING` for None."""
    if reading is None:
        return DEFAULT_READING
    if not isinstance(reading, NoiseReading):
        raise ValueError(f"reading must be a NoiseReading or None, got {reading!r}")
    return reading


@declares(seed="seed", level="noise_level", realisation="realisation")
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
    checked = check_arguments("noise_generator", {"seed": seed, "level": level, "realisation": realisation})
    seed, level, realisation = checked["seed"], checked["level"], checked["realisation"]
    sequence = np.random.SeedSequence(seed, spawn_key=(level_key(level), realisation))
    return np.random.default_rng(sequence)


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
    omega = validation.check_positive("omega", omega, "rad/s")
    dt = validation.check_positive("dt", dt, "s")
    return _baseline(kind, float(omega), float(dt)).copy(), dt


@functools.lru_cache(maxsize=256)
def _baseline(kind: str, omega: float, dt: float) -> np.ndarray:
    """:func:`baseline_samples`' values, made once per (kind, ω_p, dt) in a process and kept read-only:
    every realisation of a frequency shares its baseline (Eq. 23's envelope is most of a record's cost)."""
    duration = excitation_duration(kind, omega)
    n = sample_count(duration, dt)
    t = np.arange(n + 1) * dt
    values = np.asarray(analytic(kind, t, 1.0, omega), dtype=float)
    values.setflags(write=False)
    return values


def energy(values, dt: float) -> float:
    """Discrete energy Σ x_i²·dt of a sampled signal. [unit² s]

    Summed by numpy's pairwise summation, whose order is fixed by the array's length alone, not
    by a BLAS dot product, whose order depends on how many threads the BLAS library runs and on the
    processor it picked its kernel for: the energy rescales every noisy record, so a record's
    samples are then the same bits in the study's jobs, the CLI and a user's script on any machine.

    Parameters
    ----------
    values : array_like
        Samples x_i of the signal.
    dt : float
        Sampling step. [s]
    """
    values = np.asarray(values, dtype=float)
    return float(np.sum(np.square(values)) * dt)


def scaled_white_noise(size: int, dt: float, target_energy: float, rng: np.random.Generator,
                       band: float | None = None, measured: int | None = None) -> np.ndarray:
    """Zero-mean Gaussian noise rescaled to a given discrete energy.

    Draws ``size`` standard normal samples from ``rng``, removes (when ``band`` is given)
    every DFT component above ``band``, and scales them so that Σ n_i²·dt over the first
    ``measured`` samples equals ``target_energy`` exactly (to rounding).

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
    band : float or None, default None
        Ideal low-pass limit of the noise; None: white up to 1/(2·dt). [Hz]
    measured : int or None, default None
        Number of leading samples the energy is measured on; None: all. [-]

    Returns
    -------
    ndarray, shape (size,)
        The noise samples. [unit]
    """
    w = rng.standard_normal(size)
    if target_energy == 0.0:
        return np.zeros(size)
    if band is not None:
        spectrum = np.fft.rfft(w)
        spectrum[np.fft.rfftfreq(size, dt) > band] = 0.0
        w = np.fft.irfft(spectrum, n=size)
    part = w if measured is None else w[:measured]
    return w * math.sqrt(target_energy / energy(part, dt))


def rescale_both(summed, dt: float, target_energy: float, peak: float) -> np.ndarray:
    """Scale a record to a target energy while limiting it at a peak (``rescale="both"``).

    Returns sgn(x)·min(s·|x|, peak) with the scale s chosen so that Σ(.)²·dt equals
    ``target_energy`` exactly: the energy rescaling of the record, with the samples that
    would exceed the baseline PGA clipped at it (a saturating sensor) and the rest raised so
    that the energy stays exact. Both the energy and the PGA of the baseline are then kept.
    If the energy-rescaled record never reaches ``peak``, it is returned as it is (energy
    kept, PGA ratio below 1, reported).

    Parameters
    ----------
    summed : ndarray
        Baseline + noise. [unit]
    dt : float
        Sampling step. [s]
    target_energy : float
        Required Σ x_i²·dt (> 0). [unit² s]
    peak : float
        Largest |x_i| allowed (> 0); must satisfy peak²·len·dt >= target_energy. [unit]
    """
    x = np.asarray(summed, dtype=float)
    s0 = math.sqrt(target_energy / energy(x, dt))
    if s0 * float(np.max(np.abs(x))) <= peak:
        return x * s0
    a = np.sort(np.abs(x))[::-1]
    tail = np.concatenate([np.cumsum((a * a)[::-1])[::-1], [0.0]])  # tail[k] = Σ_{i>=k} a_i²
    need = target_energy / dt
    for k in range(1, len(a) + 1):  # k samples clipped: the k largest
        rest = need - k * peak * peak
        if rest < 0 or tail[k] == 0.0:
            break
        s = math.sqrt(rest / tail[k])
        if s * a[k - 1] >= peak and (k == len(a) or s * a[k] <= peak):
            return np.sign(x) * np.minimum(s * np.abs(x), peak)
    raise ValueError(f"rescale='both': no scale keeps energy {target_energy:g} under peak {peak:g}")


def contaminate(baseline, dt: float, level: float, rng: np.random.Generator,
                reading: NoiseReading | None = None, *, extra_samples: int = 0) -> tuple[np.ndarray, float, float]:
    """Add noise to a sampled baseline and rescale the sum (§5).

    The noise n has energy Σ n_i²·dt = f × Σ b_i²·dt on the baseline's samples, with
    f = ``reading.energy_fraction(level)`` (r, or r² when the level means an RMS ratio); it is
    white, or limited to ``reading.band``. The sum b + n (b padded with ``extra_samples`` zeros,
    the noise after the intense part) is then rescaled per ``reading.rescale``.

    Parameters
    ----------
    baseline : array_like, shape (m,)
        Baseline samples b_i at i·dt. [unit]
    dt : float
        Sampling step. [s]
    level : float
        Noise level r in [0, 1). [-]
    rng : numpy.random.Generator
        Source of the noise (not used when ``level == 0``).
    reading : NoiseReading, optional
        The reading (None: :data:`DEFAULT_READING`); its ``step`` is not used here (``dt`` is).
    extra_samples : int, default 0
        Noise samples after the baseline (the ``span`` of the reading, in samples).

    Returns
    -------
    record : ndarray, shape (m + extra_samples,)
        The contaminated, rescaled record. For ``level == 0`` a copy of the baseline. [unit]
    energy_ratio : float
        Σ record²·dt / Σ b²·dt achieved. [-]
    pga_ratio : float
        max|record| / max|b| achieved. [-]
    """
    b = np.array(baseline, dtype=float)
    if b.ndim != 1 or b.size < 2 or not np.all(np.isfinite(b)):
        raise ValueError("baseline must be a 1-D array of at least 2 finite samples")
    dt = validation.check_positive("dt", dt, "s")
    level = _check_level(level)
    reading = _as_reading(reading)
    extra_samples = QUANTITIES["sample_count"].check("extra_samples", extra_samples)
    base_energy = energy(b, dt)
    if base_energy == 0.0:
        raise ValueError("baseline must have non-zero energy: the noise is scaled relative to it")
    if level == 0.0:
        return b, 1.0, 1.0
    target = reading.energy_fraction(level) * base_energy
    if extra_samples:
        noise = scaled_white_noise(b.size + extra_samples, dt, target, rng, reading.band, measured=b.size)
        summed = np.concatenate([b, np.zeros(extra_samples)]) + noise
    else:
        summed = b + scaled_white_noise(b.size, dt, target, rng, reading.band)
    base_peak = float(np.max(np.abs(b)))
    if reading.rescale == "energy":
        record = summed * math.sqrt(base_energy / energy(summed, dt))
    elif reading.rescale == "pga":
        record = summed * (base_peak / float(np.max(np.abs(summed))))
    elif reading.rescale == "both":
        record = rescale_both(summed, dt, base_energy, base_peak)
    else:
        record = summed
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
        Noise level r (its meaning: ``reading.level_means``). [-]
    realisation : int
        Realisation index k.
    seed : int
        Study seed.
    energy_ratio : float
        Achieved energy over baseline energy. [-]
    pga_ratio : float
        Achieved peak |.| over baseline peak. [-]
    reading : NoiseReading
        The reading the record was made with.
    """

    values: np.ndarray
    dt: float
    level: float
    realisation: int
    seed: int
    energy_ratio: float
    pga_ratio: float
    reading: NoiseReading = DEFAULT_READING

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
        return {**self.reading.to_attrs(), "noise_level": self.level, "noise_realisation": self.realisation,
                "noise_seed": self.seed,
                "noise_energy_ratio": self.energy_ratio, "noise_pga_ratio": self.pga_ratio}


@declares(omega="circular_frequency", level="noise_level", realisation="realisation", seed="seed")
def noisy_record(kind: str, omega: float, level: float, realisation: int, seed: int,
                 reading: NoiseReading | None = None) -> NoisyRecord:
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
    reading : NoiseReading or None, default None
        The reading (None: :data:`DEFAULT_READING`).

    Returns
    -------
    NoisyRecord
        For ``level == 0`` the baseline samples themselves, with ratios 1. Samples at
        i·step, i = 0 … ceil(T_d/step) + round(span/step).
    """
    check_arguments("noisy_record", {"omega": omega, "level": level, "realisation": realisation, "seed": seed})
    reading = _as_reading(reading)

    def make() -> NoisyRecord:
        rng = noise_generator(seed, level, realisation)
        baseline, step = baseline_samples(kind, omega, reading.step)
        extra = int(round(reading.span / step)) if level > 0 else 0
        values, energy_ratio, pga_ratio = contaminate(baseline, step, level, rng, reading=reading, extra_samples=extra)
        return NoisyRecord(values, step, float(level), int(realisation), int(seed), energy_ratio, pga_ratio, reading)

    return RECENT_RECORDS.get((kind, float(omega), float(level), int(realisation), int(seed), reading), make)


RECENT_RECORDS = Recent(128 * 2**20, size=lambda record: record.values.nbytes)
"""The noisy records :func:`noisy_record` reuses in this process, up to 128 MiB of samples (the 1,920 records of
a default spectrum at 5 % noise are 41 MiB): a record depends only on its arguments, and the spectra of a sweep
over sampling times, delays or strategies read the same records, which are then made once. A
:class:`NoisyRecord` is frozen and its samples read-only, so sharing it is safe; a record is the same bits
whether made or reused. ``RECENT_RECORDS.clear()`` frees them."""


def noisy_motion(kind: str, omega: float, amplitude: float, level: float, realisation: int, seed: int,
                 reading: NoiseReading | None = None) -> GroundMotion:
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
    reading : NoiseReading or None, default None
        As for :func:`noisy_record`.

    Returns
    -------
    GroundMotion
        ``kind="record"`` with the samples of :func:`noisy_record` (linearly interpolated);
        for ``level == 0`` the exact analytic motion instead. The achieved energy and PGA
        ratios are on the :class:`NoisyRecord` returned by :func:`noisy_record`.
    """
    if level == 0:
        noise_generator(seed, level, realisation)  # same argument checks as for level > 0
        _as_reading(reading)
        return GroundMotion(kind=kind, amplitude=amplitude, omega=omega,
                            duration=excitation_duration(kind, omega))
    return record_motion(noisy_record(kind, omega, level, realisation, seed, reading), amplitude, omega)


def record_motion(rec: NoisyRecord, amplitude: float, omega: float) -> GroundMotion:
    """The ground motion a_p·(unit record), linearly interpolated between samples. [m/s^2]

    Parameters
    ----------
    rec : NoisyRecord
        The noisy unit record (its samples, step and duration).
    amplitude : float
        a_p multiplying the unit record. [m/s^2]
    omega : float
        ω_p of the baseline excitation. [rad/s]
    """
    return GroundMotion(kind="record", amplitude=amplitude, omega=omega, duration=rec.duration,
                        record_dt=rec.dt, record=rec.values)
