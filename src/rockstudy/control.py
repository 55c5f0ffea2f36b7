"""On-off control of the anchorage stiffness (paper §3, Eqs. 16–17, and §5.2 timing).

Strategies
----------
FS       free standing, no anchorage at all (K = D = 0);
PASSIVE  anchorage with constant K = K_max;
CS01     feedback: K_max while theta·theta_dot >= 0, K_min otherwise (Eq. 16);
CS02     feedback-feedforward: while the ground acceleration is non-zero, K_max when
         Xg_ddot·theta <= 0 and K_min otherwise; CS01 once it is zero (Eq. 17).

Sign convention (Makris): a positive horizontal ground acceleration drives theta
negative, so "the ground pushes the block outward" means Xg_ddot·theta < 0 and CS02
then holds the block with K_max.

Timing: with sampling_time T_s > 0 the controller reads theta, theta_dot and Xg_ddot
at t_k = k·T_s and its decision takes effect at t_k + delay (zero-order hold).
T_s = 0 is continuous control (then delay must be 0).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

STRATEGIES = ("FS", "PASSIVE", "CS01", "CS02")
STRATEGY_CODE = {name: i for i, name in enumerate(STRATEGIES)}


@dataclass(frozen=True)
class Control:
    """Control strategy and its timing.

    Parameters
    ----------
    strategy : {"FS", "PASSIVE", "CS01", "CS02"}
        Control law.
    sampling_time : float, default 0
        Controller sampling time T_s; 0 means continuous control. [s]
    delay : float, default 0
        Actuation delay between a sample and the moment its decision acts. [s]
    """

    strategy: str = "CS01"
    sampling_time: float = 0.0
    delay: float = 0.0

    def __post_init__(self):
        if self.strategy not in STRATEGIES:
            raise ValueError(f"Control.strategy must be one of {', '.join(STRATEGIES)}, got {self.strategy!r}")
        for name in ("sampling_time", "delay"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                raise ValueError(f"Control.{name} must be a finite number >= 0 [s], got {v!r}")
        if self.sampling_time == 0 and self.delay > 0:
            raise ValueError(
                "Control.delay > 0 needs a sampling_time > 0: a delay acts on sampled decisions "
                f"(got sampling_time=0, delay={self.delay})"
            )

    @property
    def code(self) -> int:
        return STRATEGY_CODE[self.strategy]

    def to_attrs(self) -> dict:
        return {"control_strategy": self.strategy, "control_sampling_time_s": self.sampling_time,
                "control_delay_s": self.delay}


def cs01_is_on(theta: float, theta_dot: float) -> bool:
    """Eq. (16): True (K = K_max) when theta·theta_dot >= 0."""
    return theta * theta_dot >= 0.0


def cs02_is_on(theta: float, theta_dot: float, ground_acceleration: float) -> bool:
    """Eq. (17) in the Makris sign convention: True (K = K_max) when the ground pushes outward.

    With Xg_ddot != 0: K_max when Xg_ddot·theta <= 0; with Xg_ddot == 0: CS01.
    """
    if ground_acceleration != 0.0:
        return ground_acceleration * theta <= 0.0
    return cs01_is_on(theta, theta_dot)
