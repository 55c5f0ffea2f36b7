"""Synthetic earthquake records: filtered white noise with a time envelope.

The repository can ship no real record, so the record studies run by default on a suite of
synthetic ones. Each is a sample of a non-stationary stochastic ground-motion model:

* **Spectral content**: Gaussian white noise passed through the Kanai–Tajimi filter [1]_ [2]_
  (the ground as a damped oscillator of frequency ω_g and damping ζ_g) and the high-pass
  filter of Clough and Penzien [3]_ (frequency ω_f, damping ζ_f), which removes the
  unbounded low-frequency displacement of the Kanai–Tajimi model. The one-sided power
  spectral density of the stationary process is, up to a constant,

      S(ω) ∝ (ω_g⁴ + 4ζ_g²ω_g²ω²) / ((ω_g² − ω²)² + 4ζ_g²ω_g²ω²) · ω⁴ / ((ω_f² − ω²)² + 4ζ_f²ω_f²ω²).

  It is realised by filtering the white noise in the frequency domain (FFT, amplitude √S).
* **Time envelope**: the gamma-type envelope of Saragoni and Hart [4]_, e(t) = a·t^b·exp(−c·t),
  written here with its peak time t_m and shape b as e(t) = (t/t_m)^b·exp(b·(1 − t/t_m)), so
  that max e = e(t_m) = 1.
* **Scale**: the record is scaled to a stated peak ground acceleration.

The suite draws each record's ω_g, ζ_g and t_m uniformly from stated ranges (ω_f = 0.1·ω_g and
ζ_f = ζ_g as in [3]_), so that the suite has record-to-record variability in frequency content
and duration; the ranges are our choice (firm to medium soil, moderate events), not a
calibration to a catalogue. Record ``i`` of a suite comes from
``SeedSequence(seed, spawn_key=(SYNTHETIC_KEY, i))``: it is the same in whatever suite, job or
order it is made.

References
----------
.. [1] K. Kanai (1957). Semi-empirical formula for the seismic characteristics of the ground.
   Bulletin of the Earthquake Research Institute, University of Tokyo 35, 309–325.
.. [2] H. Tajimi (1960). A statistical method of determining the maximum response of a building
   structure during an earthquake. Proc. 2nd World Conference on Earthquake Engineering, Tokyo, 781–798.
.. [3] R. W. Clough, J. Penzien (1975). *Dynamics of Structures*. McGraw-Hill, New York.
.. [4] G. R. Saragoni, G. C. Hart (1974). Simulation of artificial earthquakes. Earthquake
   Engineering and Structural Dynamics 2(3), 249–267.
"""
from __future__ import annotations

import math
import numbers
from dataclasses import asdict, dataclass

import numpy as np

from rockstudy._version import __version__
from rockstudy.core import validation
from rockstudy.model.records import STANDARD_GRAVITY, Record

SYNTHETIC_KEY = 13
"""First spawn-key entry of the synthetic records' seed sequences (distinct from noise levels)."""

MODEL_REFERENCE = ("Kanai-Tajimi filtered white noise (Kanai 1957, Tajimi 1960) with the Clough-Penzien "
                   "high-pass filter (Clough and Penzien 1975), Saragoni-Hart envelope (Saragoni and Hart 1974)")


@dataclass(frozen=True)
class GroundMotionModel:
    """Parameters of one synthetic record (Kanai–Tajimi–Clough–Penzien, Saragoni–Hart envelope).

    Parameters
    ----------
    ground_frequency : float
        Kanai–Tajimi ground frequency ω_g. [rad/s]
    ground_damping : float
        Kanai–Tajimi ground damping ratio ζ_g. [-]
    filter_frequency : float
        Clough–Penzien high-pass frequency ω_f (< ω_g). [rad/s]
    filter_damping : float
        Clough–Penzien damping ratio ζ_f. [-]
    peak_time : float
        Time t_m of the envelope's peak. [s]
    envelope_shape : float
        Exponent b of the Saragoni–Hart envelope (larger: a sharper build-up). [-]
    duration : float
        Record length. [s]
    dt : float
        Sampling step. [s]
    pga : float
        Peak ground acceleration of the record. [m/s^2]
    """

    ground_frequency: float = 5.0 * math.pi
    ground_damping: float = 0.6
    filter_frequency: float = 0.5 * math.pi
    filter_damping: float = 0.6
    peak_time: float = 4.0
    envelope_shape: float = 2.0
    duration: float = 20.0
    dt: float = 0.01
    pga: float = 0.3 * STANDARD_GRAVITY

    def __post_init__(self):
        units = {"ground_frequency": "rad/s", "ground_damping": "-", "filter_frequency": "rad/s",
                 "filter_damping": "-", "peak_time": "s", "envelope_shape": "-", "duration": "s", "dt": "s",
                 "pga": "m/s^2"}
        for name, unit in units.items():
            value = validation.check_positive(f"GroundMotionModel.{name}", getattr(self, name), unit)
            object.__setattr__(self, name, value)
        if self.filter_frequency >= self.ground_frequency:
            raise ValueError(f"GroundMotionModel.filter_frequency ({self.filter_frequency}) must be below "
                             f"ground_frequency ({self.ground_frequency}) [rad/s]")
        if self.peak_time >= self.duration:
            raise ValueError(f"GroundMotionModel.peak_time ({self.peak_time}) must be below duration "
                             f"({self.duration}) [s]")
        if self.duration < 10 * self.dt:
            raise ValueError(f"GroundMotionModel.duration ({self.duration}) must be at least 10 dt ({self.dt}) [s]")
        if math.pi / self.dt <= 2 * self.ground_frequency:
            raise ValueError(f"GroundMotionModel.dt ({self.dt} s) must resolve the ground frequency: "
                             f"pi/dt > 2 ground_frequency ({self.ground_frequency} rad/s)")

    def to_attrs(self, prefix: str = "model_") -> dict:
        """Flat attributes for a self-describing dataset (SI units).

        Parameters
        ----------
        prefix : str, default ``"model_"``
            Prefix of every attribute name (``model_ground_frequency``, ``model_pga``, ...).
        """
        return {f"{prefix}{k}": v for k, v in asdict(self).items()}


def spectral_density_shape(omega, model: GroundMotionModel) -> np.ndarray:
    """S(ω)/S₀ of the Kanai–Tajimi–Clough–Penzien model (module docstring, [1]_–[3]_). [-]

    Parameters
    ----------
    omega : array_like
        Circular frequency ω >= 0. [rad/s]
    model : GroundMotionModel
        The record's parameters (ω_g, ζ_g, ω_f, ζ_f).
    """
    w2 = np.asarray(omega, dtype=float) ** 2
    wg2, wf2 = model.ground_frequency**2, model.filter_frequency**2
    kt = (wg2**2 + 4 * model.ground_damping**2 * wg2 * w2) / ((wg2 - w2) ** 2 + 4 * model.ground_damping**2 * wg2 * w2)
    cp = w2**2 / ((wf2 - w2) ** 2 + 4 * model.filter_damping**2 * wf2 * w2)
    return kt * cp


def envelope(t, peak_time: float, shape: float) -> np.ndarray:
    """Saragoni–Hart envelope (t/t_m)^b·exp(b·(1 − t/t_m)) for t >= 0, zero before; peak 1 at t_m. [-]

    Parameters
    ----------
    t : array_like
        Time. [s]
    peak_time : float
        t_m. [s]
    shape : float
        b. [-]
    """
    s = np.maximum(np.asarray(t, dtype=float), 0.0) / peak_time
    return s**shape * np.exp(shape * (1.0 - s))


def filtered_noise(n: int, dt: float, model: GroundMotionModel, rng: np.random.Generator) -> np.ndarray:
    """Stationary Gaussian noise of ``n`` samples with the spectral shape of ``model`` (unit-free).

    White noise of 2n samples is multiplied in the frequency domain by √(S(ω)/S₀) and
    transformed back (a circular filter, so the result is stationary); only the first ``n``
    samples are returned, so that the record's end is not correlated with its start. [-]

    Parameters
    ----------
    n : int
        Number of samples returned.
    dt : float
        Sampling step. [s]
    model : GroundMotionModel
        Gives the spectral shape S(ω)/S₀.
    rng : numpy.random.Generator
        Source of the white noise (2n standard normal draws).
    """
    m = 2 * n
    white = rng.standard_normal(m)
    freqs = 2.0 * math.pi * np.fft.rfftfreq(m, dt)
    return np.fft.irfft(np.fft.rfft(white) * np.sqrt(spectral_density_shape(freqs, model)), m)[:n]


def synthetic_record(model: GroundMotionModel, rng: np.random.Generator, name: str = "synthetic") -> Record:
    """One sample of the model: filtered noise × envelope, scaled to ``model.pga``.

    Parameters
    ----------
    model : GroundMotionModel
        The record's parameters.
    rng : numpy.random.Generator
        Source of the noise.
    name : str, default "synthetic"
        The record's name.

    Returns
    -------
    Record
        ``acceleration`` [m/s^2] at i·dt, i = 0..round(duration/dt); its peak |.| is ``model.pga``.
    """
    n = int(round(model.duration / model.dt)) + 1
    t = np.arange(n) * model.dt
    values = filtered_noise(n, model.dt, model, rng) * envelope(t, model.peak_time, model.envelope_shape)
    return Record(name=name, dt=model.dt, acceleration=values * (model.pga / np.max(np.abs(values))),
                  source="rockstudy.model.synthetic", unit="m/s^2")


@dataclass(frozen=True)
class SuiteRanges:
    """Ranges from which each synthetic record's parameters are drawn (uniformly).

    Parameters
    ----------
    ground_frequency_hz : (float, float)
        ω_g/2π. [Hz]
    ground_damping : (float, float)
        ζ_g (ζ_f = ζ_g). [-]
    peak_time : (float, float)
        Envelope peak time t_m. [s]
    envelope_shape : float
        Envelope exponent b (fixed). [-]
    filter_ratio : float
        ω_f/ω_g (fixed, 0.1 in [3]_). [-]
    duration, dt, pga : float
        Record length [s], sampling step [s] and peak ground acceleration [m/s^2] (fixed).
    """

    ground_frequency_hz: tuple = (1.5, 5.0)
    ground_damping: tuple = (0.3, 0.7)
    peak_time: tuple = (2.0, 6.0)
    envelope_shape: float = 2.0
    filter_ratio: float = 0.1
    duration: float = 20.0
    dt: float = 0.01
    pga: float = 0.3 * STANDARD_GRAVITY

    def __post_init__(self):
        for name in ("ground_frequency_hz", "ground_damping", "peak_time"):
            lo, hi = getattr(self, name)
            validation.check_positive(f"SuiteRanges.{name}", lo)
            if hi < lo:
                raise ValueError(f"SuiteRanges.{name} must be (low, high) with low <= high, got {(lo, hi)!r}")
            object.__setattr__(self, name, (float(lo), float(hi)))
        for name in ("envelope_shape", "filter_ratio", "duration", "dt", "pga"):
            validation.check_positive(f"SuiteRanges.{name}", getattr(self, name))
        if self.filter_ratio >= 1:
            raise ValueError(f"SuiteRanges.filter_ratio must be below 1, got {self.filter_ratio!r}")

    def to_attrs(self, prefix: str = "suite_") -> dict:
        """Flat attributes for a self-describing dataset (the ranges as two-element lists).

        Parameters
        ----------
        prefix : str, default ``"suite_"``
            Prefix of every attribute name (``suite_ground_frequency_hz``, ``suite_pga``, ...).
        """
        return {f"{prefix}{k}": (list(v) if isinstance(v, tuple) else v) for k, v in asdict(self).items()}


def record_generator(seed: int, index: int) -> np.random.Generator:
    """Generator of synthetic record ``index``: ``SeedSequence(seed, spawn_key=(SYNTHETIC_KEY, index))``.

    Parameters
    ----------
    seed : int
        Root seed of the suite, >= 0.
    index : int
        Index of the record in the suite, >= 0.
    """
    for name, value in (("seed", seed), ("index", index)):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < 0:
            raise ValueError(f"{name} must be an integer >= 0, got {value!r}")
    return np.random.default_rng(np.random.SeedSequence(int(seed), spawn_key=(SYNTHETIC_KEY, int(index))))


def suite_model(rng: np.random.Generator, ranges: SuiteRanges = SuiteRanges()) -> GroundMotionModel:
    """Draw one record's model parameters from ``ranges`` (uniform).

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of the draws (ω_g/2π, then ζ_g, then t_m).
    ranges : SuiteRanges, default SuiteRanges()
        Ranges of the drawn parameters and the fixed ones.
    """
    omega_g = 2.0 * math.pi * rng.uniform(*ranges.ground_frequency_hz)
    zeta = rng.uniform(*ranges.ground_damping)
    return GroundMotionModel(ground_frequency=omega_g, ground_damping=zeta,
                             filter_frequency=ranges.filter_ratio * omega_g, filter_damping=zeta,
                             peak_time=rng.uniform(*ranges.peak_time), envelope_shape=ranges.envelope_shape,
                             duration=ranges.duration, dt=ranges.dt, pga=ranges.pga)


def suite_record(index: int, seed: int, ranges: SuiteRanges = SuiteRanges()) -> tuple[Record, GroundMotionModel]:
    """Record ``index`` of the synthetic suite with root ``seed``, and the parameters it was drawn with.

    Parameters
    ----------
    index : int
        Index of the record in the suite, >= 0 (its name is ``SYN<index>``).
    seed : int
        Root seed of the suite, >= 0.
    ranges : SuiteRanges, default SuiteRanges()
        Ranges of the records' parameters.
    """
    rng = record_generator(seed, index)
    model = suite_model(rng, ranges)
    return synthetic_record(model, rng, name=f"SYN{index:03d}"), model


def synthetic_suite(n_records: int, seed: int, ranges: SuiteRanges = SuiteRanges()):
    """Records 0..n_records-1 of the synthetic suite (see :func:`suite_record`).

    Parameters
    ----------
    n_records : int
        Number of records, >= 1.
    seed : int
        Root seed of the suite, >= 0.
    ranges : SuiteRanges, default SuiteRanges()
        Ranges of the records' parameters.

    Returns
    -------
    list of (Record, GroundMotionModel)
    """
    if isinstance(n_records, bool) or not isinstance(n_records, numbers.Integral) or n_records < 1:
        raise ValueError(f"n_records must be an integer >= 1, got {n_records!r}")
    return [suite_record(i, seed, ranges) for i in range(n_records)]


def suite_dataset(suite, seed: int, ranges: SuiteRanges = SuiteRanges()):
    """The synthetic suite as a self-describing :class:`xarray.Dataset`: every record's samples and
    the model parameters it was drawn with (ω_g, ζ_g, ω_f, ζ_f, t_m), with the seed and ranges.

    Parameters
    ----------
    suite : list of (Record, GroundMotionModel)
        From :func:`synthetic_suite` (records of one length and step).
    seed : int
        The suite's root seed.
    ranges : SuiteRanges, default SuiteRanges()
        The ranges the records were drawn from, written as ``suite_*`` attributes.
    """
    import xarray as xr


    records = [r for r, _ in suite]
    models = [m for _, m in suite]
    n = min(r.acceleration.size for r in records)
    hz = {"units": "rad/s"}
    return xr.Dataset(
        {"acceleration": (("record", "t"), np.array([r.acceleration[:n] for r in records]),
                          {"units": "m/s^2", "long_name": "horizontal ground acceleration"}),
         "ground_frequency": ("record", [m.ground_frequency for m in models], {**hz, "long_name": "omega_g"}),
         "ground_damping": ("record", [m.ground_damping for m in models], {"units": "1", "long_name": "zeta_g"}),
         "filter_frequency": ("record", [m.filter_frequency for m in models], {**hz, "long_name": "omega_f"}),
         "filter_damping": ("record", [m.filter_damping for m in models], {"units": "1", "long_name": "zeta_f"}),
         "peak_time": ("record", [m.peak_time for m in models], {"units": "s", "long_name": "envelope peak t_m"}),
         "pga": ("record", [r.pga for r in records], {"units": "m/s^2", "long_name": "peak ground acceleration"})},
        coords={"record": ("record", [r.name for r in records]),
                "t": ("t", np.arange(n) * records[0].dt,
                      {"units": "s", "long_name": "time since the start of the record"})},
        attrs={"title": "Synthetic ground-motion suite", "model": MODEL_REFERENCE, "seed": int(seed),
               "seed_sequence": f"SeedSequence(seed, spawn_key=({SYNTHETIC_KEY}, record index))",
               "rockstudy_version": __version__, **ranges.to_attrs()},
    )


def ranges_from_dict(spec: dict) -> SuiteRanges:
    """:class:`SuiteRanges` from plain values, the PGA given in g as ``pga_g`` (other keys as the fields).

    Parameters
    ----------
    spec : dict
        Fields of :class:`SuiteRanges`, with ``pga_g`` [g] instead of ``pga``; ``n_records`` and ``seed``
        are ignored.
    """
    spec = dict(spec)
    spec.pop("n_records", None)
    spec.pop("seed", None)
    if "pga_g" in spec:
        spec["pga"] = float(spec.pop("pga_g")) * STANDARD_GRAVITY
    for name in ("ground_frequency_hz", "ground_damping", "peak_time"):
        if name in spec:
            spec[name] = tuple(spec[name])
    return SuiteRanges(**spec)
