"""The control law in force and the device it drives (Eqs. 16–17, docs/model.md items 6–7).

Between stops the law's output is constant, so the reference engine evaluates it from the
*regime* of the block (the signs of θ, θ̇ and Ẍg), through the shared compiled formula
:func:`rockstudy.model.control.stiffness_on`. With sampled control (T_s > 0) the output is read at
t_k = k·T_s and acts at t_k + Δτ (zero-order hold; κ_max before the first decision acts).
"""
from __future__ import annotations

import math
from collections import deque

from rockstudy.model.control import STRATEGY_CODE, stiffness_on

SAMPLE_SLACK = 1e-9
"""A change at t within this fraction of T_s after a sample instant is read at that sample. [-]"""


class Controller:
    """Held stiffness and the queue of sampled decisions of one run.

    Parameters
    ----------
    strategy : {"FS", "PASSIVE", "CS01", "CS02"}
        Control strategy (FS also for an inert anchorage).
    kappa_max, kappa_min : float
        Dimensionless stiffnesses of the on and off states. [-]
    sampling_time : float
        T_s; 0 for continuous control. [s]
    delay : float
        Actuation delay Δτ. [s]

    Attributes
    ----------
    queue : deque of (int, bool)
        Decisions (sample index k, κ_max?) not yet acting, in time order.
    active_on : bool
        The decision in force with sampled control (κ_max before the first one acts).
    """

    def __init__(self, strategy: str, kappa_max: float, kappa_min: float, sampling_time: float, delay: float):
        self.strategy = strategy
        self.code = STRATEGY_CODE[strategy]
        self.switching = strategy in ("CS01", "CS02")
        self.kappa_max, self.kappa_min = kappa_max, kappa_min
        self.sampled = self.switching and sampling_time > 0
        self.sampling_time = sampling_time
        self.delay = delay
        self.queue: deque = deque()
        self.law_last = None  # last output of the law pushed [bool]
        self.applied = None  # last decision that acted [bool]
        self.active_on = True

    def feedback_mode(self, ground_sign: int) -> bool:
        """True when the law in force is CS01 (Eq. 16): CS01 itself, or CS02 while Ẍg = 0.

        Parameters
        ----------
        ground_sign : int
            Sign of the ground acceleration Ẍg now: -1, 0 or 1. [-]
        """
        return self.strategy == "CS01" or (self.strategy == "CS02" and ground_sign == 0)

    def law_on(self, resting: bool, side: int, vel_sign: int, ground_sign: int) -> bool:
        """Output of Eq. (16)/(17) in a regime: True for κ_max.

        Parameters
        ----------
        resting : bool
            θ = θ̇ = 0 (the law then reads κ_max).
        side, vel_sign, ground_sign : int
            Signs standing for the values: θ ~ side, θ̇ ~ side·vel_sign, Ẍg ~ ground_sign. [-]
        """
        if resting:
            return True
        return stiffness_on(self.code, float(side), float(side * vel_sign), float(ground_sign))

    def kappa(self, law_on: bool) -> float:
        """Stiffness the device applies now. [-]

        Parameters
        ----------
        law_on : bool
            The continuous law's output now (True for κ_max, :meth:`law_on`); with sampled control the
            decision in force is used instead.
        """
        if self.strategy == "FS":
            return 0.0
        if self.strategy == "PASSIVE":
            return self.kappa_max
        on = self.active_on if self.sampled else law_on
        return self.kappa_max if on else self.kappa_min

    def push(self, t: float, on: bool) -> None:
        """Register that the law output became ``on`` at ``t``; it is read at the next sample.

        Parameters
        ----------
        t : float
            Time of the change. [s]
        on : bool
            The law's new output (True for κ_max).
        """
        if not self.sampled or on == self.law_last:
            return
        self.law_last = on
        k = max(0, math.ceil(t / self.sampling_time - SAMPLE_SLACK))
        if self.queue and self.queue[-1][0] == k:
            self.queue.pop()  # an earlier change in the same sampling interval is never read
        previous = self.queue[-1][1] if self.queue else self.applied
        if previous is None or previous != on:
            self.queue.append((k, on))

    def actuation_time(self, k: int) -> float:
        """Instant k·T_s + Δτ at which the decision of sample k acts. [s]

        Parameters
        ----------
        k : int
            Index of the sample, k >= 0. [-]
        """
        return k * self.sampling_time + self.delay

    def apply_due(self, t: float) -> None:
        """Let every decision whose actuation instant is ≤ ``t`` act.

        Parameters
        ----------
        t : float
            Time now. [s]
        """
        while self.queue and self.actuation_time(self.queue[0][0]) <= t:
            _, self.applied = self.queue.popleft()
            self.active_on = self.applied

    def next_actuation(self) -> float:
        """Next actuation instant (inf if none is pending). [s]"""
        if self.sampled and self.queue:
            return self.actuation_time(self.queue[0][0])
        return math.inf

    def kappa_at(self, times, law_on: bool) -> list | float:
        """Stiffness at each of ``times`` during a rest piece, the queue not yet applied. [-]

        Continuous control: the stiffness now, one float.

        Parameters
        ----------
        times : sequence of float
            Instants of the rest piece, increasing. [s]
        law_on : bool
            The continuous law's output now, as in :meth:`kappa` (continuous control only).
        """
        if not self.sampled:
            return self.kappa(law_on)
        values = []
        for u in times:
            on = self.active_on
            for k, decision in self.queue:
                if self.actuation_time(k) > u:
                    break
                on = decision
            values.append(self.kappa_max if on else self.kappa_min)
        return values


def filippov_stiffness(a_max: float, a_min: float, kappa_max: float, kappa_min: float) -> float:
    """Equivalent stiffness that keeps θ̈ = 0 on the CS01 sliding surface θ̇ = 0 (Filippov). [-]

    θ̈ is affine in κ, so the convex combination of κ_min and κ_max with θ̈ = 0 is
    κ_min + (κ_max − κ_min)·a_min / (a_min − a_max) (docs/model.md item 6).

    Parameters
    ----------
    a_max, a_min : float
        θ̈ with κ_max and with κ_min at the held state. [rad/s^2]
    kappa_max, kappa_min : float
        The two stiffnesses. [-]
    """
    if a_min == a_max:
        return kappa_max
    return kappa_min + (kappa_max - kappa_min) * a_min / (a_min - a_max)
