"""The scenario of a study: everything but frequency, amplitude and noise realisation that defines a
simulation (block, anchorage, control law, excitation, noise level and reading, seed, overturn
criterion, free time), and the ground motion it gives at one frequency and amplitude (paper §5).
"""
from __future__ import annotations

from dataclasses import InitVar, dataclass, field
from typing import NamedTuple

import numpy as np

from rockstudy.core import validation
from rockstudy.core.quantities import check_arguments, declares
from rockstudy.engine.simulate import (
    DEFAULT_FREE_TIME,
    OVERTURN_CRITERIA,
    kernel_record,
    pack_parameters,
    simulate,
)
from rockstudy.engine.simulation_result import SimulationResult
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import Block
from rockstudy.model.control import Control
from rockstudy.model.excitation import (
    EXCITATIONS,
    GroundMotion,
    check_time_span,
    excitation_duration,
    modulated_peak,
)
from rockstudy.model.noise import DEFAULT_READING, DEFAULT_SEED, NoiseReading, NoisyRecord, noisy_record, record_motion

DEFAULT_BLOCK = "BLC06"
"""The study's block preset (:data:`rockstudy.model.block.BLOCK_PRESETS`)."""
DEFAULT_EXCITATION = "modulated"
"""The study's excitation: the amplitude-modulated harmonic of Eq. 23."""
DEFAULT_OVERTURN_CRITERION = "flat"
"""Overturned at |θ| >= π/2 (the block lies flat)."""


class ScenarioRun(NamedTuple):
    """One simulation of a scenario: its result, the ground motion that drove it and the noisy record
    behind that motion (None without noise)."""

    result: SimulationResult
    motion: GroundMotion
    record: NoisyRecord | None


class KernelCase(NamedTuple):
    """One (frequency, realisation) case of a scenario packed for the fast engine's amplitude scans: the
    kernel's parameter row and samples at unit amplitude, the unit motion's peak, and the noisy record's
    achieved energy and PGA ratios (1 without noise)."""

    parameters: np.ndarray
    samples: np.ndarray
    vertical: np.ndarray
    peak: float
    energy_ratio: float
    pga_ratio: float


@declares(noise_level="noise_level", seed="seed", free_time="free_time")
@dataclass(frozen=True)
class Scenario:
    """Everything but frequency, amplitude and realisation that defines a simulation.

    Parameters
    ----------
    block, anchorage, control : rockstudy.Block, rockstudy.Anchorage, rockstudy.Control
        The block, its restrainers, and the control law with its timing.
    excitation : {"one-sine", "modulated"}
        Baseline excitation.
    noise_level : float
        Noise energy over baseline energy, in [0, 1). [-]
    seed : int, default DEFAULT_SEED
        Root seed of the noise realisations.
    noise : NoiseReading, default DEFAULT_READING
        How noisy records are made: step, rescaling, meaning of the level, band, span
        (:class:`rockstudy.model.noise.NoiseReading`).
    overturn_criterion : {"flat", "alpha"}
        Overturned at |θ| >= π/2 (default) or at |θ| >= α.
    free_time : float
        Free motion allowed after the excitation. [s]
    names : dict, optional
        The caller's name of ``noise_level``, ``seed`` and ``free_time`` in error messages
        (``{"free_time": "--free-time"}``); one missing from it is named ``Scenario.<field>``. Not stored.
    """

    block: Block
    anchorage: Anchorage = field(default_factory=Anchorage)
    control: Control = field(default_factory=Control)
    excitation: str = DEFAULT_EXCITATION
    noise_level: float = 0.0
    seed: int = DEFAULT_SEED
    noise: NoiseReading = DEFAULT_READING
    overturn_criterion: str = DEFAULT_OVERTURN_CRITERION
    free_time: float = DEFAULT_FREE_TIME
    names: InitVar[dict | None] = None

    def __post_init__(self, names):
        for name, kind in (("block", Block), ("anchorage", Anchorage), ("control", Control)):
            if not isinstance(getattr(self, name), kind):
                raise validation.InputError(f"Scenario.{name} must be a rockstudy {kind.__name__}, got "
                                   f"{type(getattr(self, name)).__name__} {getattr(self, name)!r}")
        if not isinstance(self.excitation, str) or self.excitation not in EXCITATIONS:
            raise ValueError(f"excitation must be one of {', '.join(EXCITATIONS)}, got {self.excitation!r}")
        check_arguments("Scenario", {"noise_level": self.noise_level, "seed": self.seed, "free_time": self.free_time},
                        names)
        if not isinstance(self.noise, NoiseReading):
            raise ValueError(f"noise must be a rockstudy.model.noise.NoiseReading, got {self.noise!r}")
        if self.overturn_criterion not in OVERTURN_CRITERIA:
            raise ValueError(f"overturn_criterion must be one of {', '.join(OVERTURN_CRITERIA)}, "
                             f"got {self.overturn_criterion!r}")

    def omega(self, frequency_ratio: float) -> float:
        """ω_p for a frequency ratio. [rad/s]

        Parameters
        ----------
        frequency_ratio : float
            ω_p/p. [-]
        """
        return frequency_ratio * self.block.p

    @declares(frequency_ratio="frequency_ratio", amplitude_ratio="run_amplitude_ratio", realisation="realisation")
    def motion(self, frequency_ratio: float, amplitude_ratio: float, realisation: int = 0, *,
               names: dict | None = None):
        """The ground motion and its noise record info (None without noise), after checking the arguments
        and the simulation's time span (:meth:`check_span`).

        Parameters
        ----------
        frequency_ratio : float
            ω_p/p, > 0. [-]
        amplitude_ratio : float
            a_p/(g·tanα). [-]
        realisation : int, default 0
            Noise realisation index k, >= 0 (unused without noise).
        names : dict, optional
            The caller's name of each argument and, for the time span, of ``free_time``, ``sampling_time``,
            ``step`` and ``span`` in error messages (:data:`SPAN_NAMES`; ``{"frequency_ratio":
            "--frequency-ratio"}``).
        """
        checked = check_arguments("Scenario.motion", {"frequency_ratio": frequency_ratio,
                                                      "amplitude_ratio": amplitude_ratio,
                                                      "realisation": realisation}, names)
        frequency_ratio, amplitude_ratio, realisation = (checked["frequency_ratio"], checked["amplitude_ratio"],
                                                         checked["realisation"])
        self.check_span([frequency_ratio], **span_names(names))
        omega = self.omega(frequency_ratio)
        amplitude = amplitude_ratio * self.block.uplift_acceleration
        if self.noise_level == 0:
            return GroundMotion(self.excitation, amplitude, omega, excitation_duration(self.excitation, omega)), None
        rec = noisy_record(self.excitation, omega, self.noise_level, realisation, self.seed, self.noise)
        return record_motion(rec, amplitude, omega), rec

    def simulate(self, frequency_ratio: float, amplitude_ratio: float, realisation: int = 0, *,
                 engine: str = "fast", record_history: bool = False) -> ScenarioRun:
        """Run the scenario once at a frequency ratio ω_p/p, an amplitude ratio a_p/(g·tanα) and a noise
        realisation.

        Parameters
        ----------
        frequency_ratio : float
            ω_p/p, > 0. [-]
        amplitude_ratio : float
            a_p/(g·tanα). [-]
        realisation : int, default 0
            Noise realisation index k, >= 0 (unused without noise).
        engine : {"fast", "reference"}, default "fast"
            The integrator, as for :func:`rockstudy.engine.simulate.simulate`.
        record_history : bool, default False
            Return time histories of θ, θ̇, κ and Ẍg (:func:`rockstudy.engine.simulate.simulate`).
        """
        motion, rec = self.motion(frequency_ratio, amplitude_ratio, realisation)
        return ScenarioRun(self.simulate_motion(motion, engine=engine, record_history=record_history), motion, rec)

    def simulate_motion(self, motion: GroundMotion, *, engine: str = "fast",
                        record_history: bool = False) -> SimulationResult:
        """Run the scenario's block, anchorage, control, criterion and free time under any ground motion
        (a scaled record, say) instead of the scenario's excitation.

        Parameters
        ----------
        motion : GroundMotion
            The ground motion.
        engine : {"fast", "reference"}, default "fast"
            The integrator, as for :func:`rockstudy.engine.simulate.simulate`.
        record_history : bool, default False
            Return time histories of θ, θ̇, κ and Ẍg.
        """
        return simulate(self.block, self.anchorage, self.control, motion, engine=engine,
                        overturn_criterion=self.overturn_criterion, free_time=self.free_time,
                        record_history=record_history)

    def unit_peak(self, frequency_ratio: float, realisation: int = 0) -> float:
        """Peak |Ẍ_g|/a_p of the unit-amplitude ground motion at a frequency ratio and realisation: the
        block uplifts only above the amplitude ratio 1/peak. [-]

        Parameters
        ----------
        frequency_ratio : float
            ω_p/p, > 0. [-]
        realisation : int, default 0
            Noise realisation index k, >= 0 (unused without noise).
        """
        _, rec = self.motion(frequency_ratio, 1.0, realisation)
        return _unit_peak(self.excitation, rec)

    def kernel_case(self, frequency_ratio: float, realisation: int = 0, *, energy_bound: bool = True,
                    integration: dict | None = None) -> KernelCase:
        """The case at a frequency ratio and realisation packed for the fast engine's amplitude scans.

        Parameters
        ----------
        frequency_ratio : float
            ω_p/p, > 0. [-]
        realisation : int, default 0
            Noise realisation index k, >= 0 (unused without noise).
        energy_bound : bool, default True
            End runs that provably cannot overturn any more (docs/engine.md).
        integration : dict or None, default None
            Other ``rtol``, ``atol`` or ``stepper`` for :func:`~rockstudy.engine.simulate.pack_parameters`,
            as convergence checks use; None: the engine's defaults.
        """
        motion, rec = self.motion(frequency_ratio, 1.0, realisation)
        parameters = pack_parameters(self.block, self.anchorage, self.control, motion,
                                     overturn_criterion=self.overturn_criterion, free_time=self.free_time,
                                     energy_bound=energy_bound, **(integration or {}))
        return KernelCase(parameters, kernel_record(self.control, motion), motion.vertical,
                          _unit_peak(self.excitation, rec), 1.0 if rec is None else rec.energy_ratio,
                          1.0 if rec is None else rec.pga_ratio)

    def check_span(self, frequency_ratios, *, frequency_name: str = "frequency_ratio",
                   free_time_name: str = "Scenario.free_time", sampling_name: str = "Control.sampling_time",
                   step_name: str = "NoiseReading.step", span_name: str = "NoiseReading.span") -> None:
        """The simulations at these frequency ratios stay within the limits of one simulation (time span,
        integrator steps, controller samples and, with noise, the record's samples at the reading's step
        and span: :func:`rockstudy.model.excitation.check_time_span`).

        Parameters
        ----------
        frequency_ratios : sequence of float
            ω_p/p values (only the smallest and the largest are checked). [-]
        frequency_name, free_time_name, sampling_name, step_name, span_name : str
            Names of the frequency ratios, the free time, the sampling time, the noise step and the noise
            span in the error message (the caller's option or config key).
        """
        noisy = self.noise_level > 0
        check_time_span(self.block, self.excitation, frequency_ratios, self.free_time, self.control.sampling_time,
                        frequency_name=frequency_name, free_time_name=free_time_name, sampling_name=sampling_name,
                        record_step=self.noise.step if noisy else None, record_span=self.noise.span if noisy else 0.0,
                        step_name=step_name, span_name=span_name)

    def record_bytes(self, frequency_ratios, n_realisations: int) -> int:
        """Bytes the noise records of ``n_realisations`` realisations at these frequency ratios take while a
        spectrum runs (0 without noise): their samples at the reading's step and span. [B]

        Parameters
        ----------
        frequency_ratios : iterable of float
            ω_p/p values of the spectrum. [-]
        n_realisations : int
            Number of noise realisations held at once.
        """
        if self.noise_level == 0:
            return 0
        samples = validation.record_samples((excitation_duration(self.excitation, self.omega(float(f)))
                                    for f in frequency_ratios), self.noise.step, self.noise.span)
        return int(n_realisations) * samples * validation.RECORD_BYTES_PER_SAMPLE

    def to_attrs(self) -> dict:
        attrs = {}
        attrs.update(self.block.to_attrs())
        attrs.update(self.anchorage.to_attrs(self.block))
        attrs.update(self.control.to_attrs())
        attrs.update(excitation=self.excitation, noise_level=self.noise_level, noise_seed=int(self.seed),
                     **self.noise.to_attrs(), overturn_criterion=self.overturn_criterion, free_time_s=self.free_time)
        return attrs


SPAN_NAMES = {"frequency_ratio": "frequency_name", "free_time": "free_time_name", "sampling_time": "sampling_name",
              "step": "step_name", "span": "span_name"}
"""The keyword of :meth:`Scenario.check_span` that names each input of a simulation's time span."""


def span_names(names: dict | None) -> dict:
    """The keywords of :meth:`Scenario.check_span` naming the inputs ``names`` names (a ``names=`` argument of
    :meth:`Scenario.motion` or :func:`rockstudy.analysis.spectra.threshold`); the others keep their defaults.

    Parameters
    ----------
    names : dict or None
        The caller's name of inputs (``{"free_time": "--free-time"}``), by the keys of :data:`SPAN_NAMES`.
    """
    return {SPAN_NAMES[key]: name for key, name in (names or {}).items() if key in SPAN_NAMES}


def _unit_peak(excitation: str, rec: NoisyRecord | None) -> float:
    if rec is not None:
        return float(np.max(np.abs(rec.values)))
    return modulated_peak() if excitation == "modulated" else 1.0
