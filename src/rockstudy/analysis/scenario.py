"""The scenario of a study: everything but frequency, amplitude and noise realisation that defines a
simulation (block, anchorage, control law, excitation, noise level and reading, seed, overturn
criterion, free time), and the ground motion it gives at one frequency and amplitude (paper §5).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from rockstudy.engine.simulate import DEFAULT_FREE_TIME, OVERTURN_CRITERIA
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import Block
from rockstudy.model.control import Control
from rockstudy.model.excitation import EXCITATIONS, GroundMotion, excitation_duration
from rockstudy.model.noise import DEFAULT_READING, NoiseReading, noisy_record, record_motion


@dataclass(frozen=True)
class Scenario:
    """Everything but frequency, amplitude and realisation that defines a simulation.

    Parameters
    ----------
    block, anchorage, control
        The block, its restrainers, and the control law with its timing.
    excitation : {"one-sine", "modulated"}
        Baseline excitation.
    noise_level : float
        Noise energy over baseline energy, in [0, 1). [-]
    seed : int
        Root seed of the noise realisations.
    noise : NoiseReading, default DEFAULT_READING
        How noisy records are made: step, rescaling, meaning of the level, band, span
        (:class:`rockstudy.model.noise.NoiseReading`; the former ``match`` is ``noise.rescale``).
    overturn_criterion : {"flat", "alpha"}
    free_time : float
        Free motion allowed after the excitation. [s]
    """

    block: Block
    anchorage: Anchorage = field(default_factory=Anchorage)
    control: Control = field(default_factory=Control)
    excitation: str = "modulated"
    noise_level: float = 0.0
    seed: int = 0
    noise: NoiseReading = DEFAULT_READING
    overturn_criterion: str = "flat"
    free_time: float = DEFAULT_FREE_TIME

    def __post_init__(self):
        if self.excitation not in EXCITATIONS:
            raise ValueError(f"excitation must be one of {', '.join(EXCITATIONS)}, got {self.excitation!r}")
        if not (0.0 <= self.noise_level < 1.0):
            raise ValueError(f"noise_level must lie in [0, 1), got {self.noise_level!r}")
        if not (isinstance(self.seed, (int, np.integer)) and self.seed >= 0):
            raise ValueError(f"seed must be an integer >= 0, got {self.seed!r}")
        if not isinstance(self.noise, NoiseReading):
            raise ValueError(f"noise must be a rockstudy.model.noise.NoiseReading, got {self.noise!r}")
        if self.overturn_criterion not in OVERTURN_CRITERIA:
            raise ValueError(f"overturn_criterion must be one of {', '.join(OVERTURN_CRITERIA)}, "
                             f"got {self.overturn_criterion!r}")

    @property
    def match(self) -> str:
        """The rescaling of the noisy records (``noise.rescale``; the former field ``match``)."""
        return self.noise.rescale

    def omega(self, frequency_ratio: float) -> float:
        """ω_p for a frequency ratio. [rad/s]"""
        return frequency_ratio * self.block.p

    def motion(self, frequency_ratio: float, amplitude_ratio: float, realisation: int = 0):
        """The ground motion and its noise record info (None without noise)."""
        omega = self.omega(frequency_ratio)
        amplitude = amplitude_ratio * self.block.uplift_acceleration
        if self.noise_level == 0:
            return GroundMotion(self.excitation, amplitude, omega, excitation_duration(self.excitation, omega)), None
        rec = noisy_record(self.excitation, omega, self.noise_level, realisation, self.seed, self.noise)
        return record_motion(rec, amplitude, omega), rec

    def to_attrs(self) -> dict:
        attrs = {}
        attrs.update(self.block.to_attrs())
        attrs.update(self.anchorage.to_attrs(self.block))
        attrs.update(self.control.to_attrs())
        attrs.update(excitation=self.excitation, noise_level=self.noise_level, noise_seed=int(self.seed),
                     **self.noise.to_attrs(), overturn_criterion=self.overturn_criterion, free_time_s=self.free_time)
        return attrs
