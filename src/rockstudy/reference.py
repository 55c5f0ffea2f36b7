"""Reference engine: event-driven integration with ``scipy.integrate.solve_ivp`` (paper §2–3).

The motion of the block is a sequence of smooth pieces separated by instants at which the
state or the right-hand side jumps. This module integrates each piece with
:func:`scipy.integrate.solve_ivp` (``DOP853``, tight tolerances) and stops at every such
instant with a terminal event or a time breakpoint, applies the jump, and carries on:

* impacts, θ = 0: θ̇⁺ = e·θ̇⁻ (Eq. 14) and the block continues on the other corner;
* uplift from rest when |Ẍg| > (g + Ÿg)·tanα, onto the side −sgn Ẍg (see docs/model.md, item 4);
  rest after an impact whose rebound is negligible (|θ̇⁺| < ``rest_velocity``, Eq. 15 as read
  in docs/model.md, item 5);
* brittle fracture of the working spring / damper when θ reaches ±θ_K,u / ±θ_D,u (Eqs. 8–13);
* switches of the control law (Eqs. 16–17): θ̇ = 0 for CS01, zeros of Ẍg for CS02, the end of
  the excitation. With sampled control (T_s > 0) the law's output is still tracked at these
  events, so the decision read at t_k = k·T_s is known without stopping there; the device
  changes only at the actuation instants t_k + Δτ where the decision differs from the one in
  force (zero-order hold, K_max before the first decision acts), and pieces stop there;
* the Filippov sliding mode of continuous CS01 at θ̇ = 0 (docs/model.md item 6,
  MODEL-NOTES §1): the block is held (θ̇ = 0, θ constant) and the release instant is located
  with the same event machinery on the trivial ODE;
* kinks of sampled records (horizontal and vertical) at their knots i·dt;
* overturning, |θ| ≥ π/2 (``"flat"``) or |θ| ≥ α (``"alpha"``).

It is slow but transparent, and serves as the oracle for the compiled engine.

The right-hand side is :func:`rockstudy.motion.angular_acceleration` (Eqs. 1–7).

Notes
-----
No early overturn stop is made: once the block is past α with no intact spring on that
side and no more excitation, the integration simply goes on until the overturning criterion
is met, so ``overturn_time`` is always the instant the criterion is reached.
"""
from __future__ import annotations

import math
from collections import deque

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from .anchorage import Anchorage
from .block import Block
from .constants import FREE_TIME, REFERENCE_ATOL, REFERENCE_RTOL
from .constants import rest_velocity as default_rest_velocity
from .control import STRATEGY_CODE, Control, stiffness_on
from .excitation import ENVELOPE_PEAK, GroundMotion, modulated_acceleration, modulated_duration, one_sine_acceleration
from .motion import angular_acceleration
from .result import STATUS_OVERTURNED, STATUS_REST, STATUS_TIME_LIMIT, SimulationResult

METHOD = "DOP853"
"""Runge–Kutta method passed to ``solve_ivp`` for the rocking pieces."""
HISTORY_STEP = 2e-3
"""Spacing of the regular history samples (events are added on top). [s]"""
MAX_EVENTS = 5_000_000
"""Cap on the number of pieces of one run (guards against an endless event loop)."""
MAX_STALLED_EVENTS = 10_000
"""Cap on consecutive pieces that do not advance time (guards against Zeno loops)."""
OVERTURN_CRITERIA = ("flat", "alpha")

_ROCKING, _REST, _HELD = "rocking", "rest", "held"
_ELEMENTS = ("spring_left", "spring_right", "damper_left", "damper_right")


# --------------------------------------------------------------------------------------
# Excitation as scalar functions plus the instants where they are not smooth
# --------------------------------------------------------------------------------------
def _piecewise_linear(samples: np.ndarray, dt: float, factor: float = 1.0):
    """Scalar linear interpolation of ``factor·samples`` at i·dt, zero outside. [m/s^2]"""
    values = [float(v) for v in samples]
    n = len(values)
    last = (n - 1) * dt

    def evaluate(t):
        if t < 0.0 or t > last:
            return 0.0
        i = min(int(t / dt), n - 2)
        t_i = i * dt
        slope = (values[i + 1] - values[i]) / dt
        return factor * (slope * (t - t_i) + values[i])

    return evaluate, last


class _Excitation:
    """Scalar Ẍg(t), Ÿg(t) of a :class:`GroundMotion` and its breakpoints.

    ``knots`` holds every instant at which Ẍg or Ÿg is not smooth (record samples, ends of
    pulses); integration pieces never step across one.
    """

    def __init__(self, motion: GroundMotion):
        kind = motion.kind
        a = float(motion.amplitude)
        omega = float(motion.omega)
        knots = []
        self.time_scale = math.inf  # largest safe step when locating time-only events [s]
        if kind == "one-sine":
            end = 2.0 * math.pi / omega

            def horizontal(t):
                return one_sine_acceleration(t, a, omega) if 0.0 <= t <= end else 0.0

            self.time_scale = end / 128.0
        elif kind == "modulated":
            end = modulated_duration(omega)

            def horizontal(t):
                return modulated_acceleration(t, a, omega, end) if 0.0 <= t <= end else 0.0

            self.time_scale = 2.0 * math.pi / omega / 128.0
        elif kind == "rectangular":
            end = float(motion.duration)

            def horizontal(t):
                return a if 0.0 <= t < end else 0.0
        else:  # "record"
            horizontal, end = _piecewise_linear(motion.record, motion.record_dt, a)
            knots.extend(np.arange(len(motion.record)) * motion.record_dt)
        self.horizontal = horizontal
        self.horizontal_end = end
        # Between knots Ẍg and Ÿg are linear (or constant): see _ReferenceRun._rest_piece.
        self.piecewise_linear = kind in ("record", "rectangular")
        if len(motion.vertical):
            self.vertical, vertical_end = _piecewise_linear(motion.vertical, motion.vertical_dt)
            knots.extend(np.arange(len(motion.vertical)) * motion.vertical_dt)
        else:
            def vertical(t):
                return 0.0

            self.vertical = vertical
            vertical_end = 0.0
        self.end = max(float(motion.end_time), end, vertical_end)
        knots.extend([end, vertical_end, self.end])
        self.knots = np.unique(np.asarray([k for k in knots if k > 0.0], dtype=float))
        # scale for "Ẍg is zero" (the envelope peak bounds Eq. 23 without sampling it) [m/s^2]
        self.peak = abs(a) * ENVELOPE_PEAK if kind == "modulated" else float(motion.peak())

    def next_knot(self, t: float) -> float:
        """First breakpoint strictly after t (inf if none). [s]"""
        i = int(np.searchsorted(self.knots, t, side="right"))
        return float(self.knots[i]) if i < len(self.knots) else math.inf

    def sign_after(self, t: float) -> int:
        """Sign of Ẍg just after t: 0 where Ẍg vanishes identically. [-]"""
        if t >= self.horizontal_end:
            return 0
        value = self.horizontal(t)
        if abs(value) <= 1e-9 * self.peak:
            value = self.horizontal(t + 1e-9 * max(1.0, t))
        return (value > 0.0) - (value < 0.0)


def _armed_event(fun, direction: int, terminal: bool, t0: float):
    """Event callable for ``solve_ivp`` that cannot fire at its own starting point.

    A piece often starts on the surface of an event that has just been handled (θ = 0 after
    an impact, θ̇ = 0 after an apex, Ẍg = 0 after a switch). At t0 the value is replaced by
    a tiny number on the side the crossing comes from, so only a genuine crossing after t0
    is reported.
    """
    before = -direction

    def event(t, y):
        value = fun(t, y)
        if t == t0 and before != 0 and not value * before > 0.0:
            return before * 1e-300
        return value

    event.direction = direction
    event.terminal = terminal
    return event


# --------------------------------------------------------------------------------------
# One simulation
# --------------------------------------------------------------------------------------
class _ReferenceRun:
    """State and event handling of one reference simulation (owned by the integrator)."""

    def __init__(self, block, anchorage, control, motion, overturn_criterion, free_time,
                 rest_velocity, record_history, rtol, atol, initial_rotation, initial_velocity):
        self.block = block
        self.p = block.p
        self.alpha = block.alpha
        self.gravity = block.gravity
        self.tan_alpha = block.b / block.h
        self.e = block.e
        self.rtol, self.atol = rtol, atol
        self.rest_velocity = rest_velocity
        self.tiny_velocity = 1e-12 * self.p  # below this, θ̇ counts as zero at a stop [rad/s]
        self.theta_overturn = math.pi / 2 if overturn_criterion == "flat" else self.alpha

        # FS (or an anchorage exerting no force at all) means no restrainer elements at all.
        self.anchored = control.strategy != "FS" and not anchorage.is_inert
        self.strategy = control.strategy if self.anchored else "FS"
        self.kappa_max = anchorage.kappa_max if self.anchored else 0.0
        self.kappa_min = anchorage.kappa_min if self.anchored else 0.0
        self.damping_ratio = anchorage.damping_ratio if self.anchored else 0.0
        self.damping = float(2.0 * self.damping_ratio * self.p)  # 3 D b²/(m R²) = 2ξp [1/s]
        self.sin_alpha, self.cos_alpha = math.sin(self.alpha), math.cos(self.alpha)
        self.theta_ultimate = {
            "spring_left": anchorage.theta_spring(block), "spring_right": anchorage.theta_spring(block),
            "damper_left": anchorage.theta_damper(block), "damper_right": anchorage.theta_damper(block),
        }
        self.intact = {name: self.anchored for name in _ELEMENTS}
        self.fracture_times: dict[str, float] = {}

        # Controller: continuous laws are evaluated from the regime; sampled decisions are
        # queued as (sample index k, K_max?) and act at k·T_s + delay (zero-order hold).
        self.sampled = self.strategy in ("CS01", "CS02") and control.sampling_time > 0
        self.sampling_time = control.sampling_time
        self.delay = control.delay
        self.queue: deque = deque()
        self.law_last = None
        self.applied = None
        self.active_on = True  # K_max before the first decision acts

        self.excitation = _Excitation(motion)
        self.motion = motion
        self.t_final = self.excitation.end + free_time

        self.t = 0.0
        self.theta = float(initial_rotation)
        self.theta_dot = float(initial_velocity)
        self.side = 1
        self.vel_sign = 1  # sign of s·θ̇: +1 moving away from upright (or still), −1 returning
        self.ground_sign = 0  # sign of Ẍg just after t (CS02 only)
        self.mode = _REST
        self.status = None
        self.overturn_time = math.nan
        self.max_abs_theta = abs(self.theta)
        self.impact_times, self.uplift_times, self.rest_times = [], [], []
        self.record_history = record_history
        self._hist = {"t": [], "theta": [], "theta_dot": [], "kappa": []}

    # ---------------------------------------------------------------- model pieces
    def _spring_ok(self, side):
        return self.intact["spring_left" if side > 0 else "spring_right"]

    def _damper_ok(self, side):
        return self.intact["damper_left" if side > 0 else "damper_right"]

    def _acceleration(self, t, theta, theta_dot, kappa):
        """θ̈ of Eqs. (1)–(7) on the current side. [rad/s^2]"""
        s = self.side
        return angular_acceleration(theta, theta_dot, float(s), float(kappa * self._spring_ok(s)),
                                    self.damping * self._damper_ok(s), self.excitation.horizontal(t),
                                    self.excitation.vertical(t), self.p, self.gravity, self.sin_alpha,
                                    self.cos_alpha)

    def _uplift_margin(self, t):
        """|Ẍg| − (g + Ÿg)·tanα: positive when the ground lifts a block at rest. [m/s^2]"""
        ex = self.excitation
        return abs(ex.horizontal(t)) - (self.gravity + ex.vertical(t)) * self.tan_alpha

    def _feedback_mode(self):
        """True when the law in force is CS01 (Eq. 16): CS01 itself, or CS02 with Ẍg = 0."""
        return self.strategy == "CS01" or (self.strategy == "CS02" and self.ground_sign == 0)

    def _law_on(self):
        """Output of Eq. (16)/(17) in the current regime: True for K_max."""
        if self.mode == _REST:
            return True  # θ = θ̇ = 0
        # the signs stand for the values: θ ~ s, θ̇ ~ s·vel_sign, Ẍg ~ ground_sign
        return stiffness_on(STRATEGY_CODE[self.strategy], float(self.side), float(self.side * self.vel_sign),
                            float(self.ground_sign))

    def _kappa(self):
        """Dimensionless stiffness currently applied by the device. [-]"""
        if self.strategy == "FS":
            return 0.0
        if self.strategy == "PASSIVE":
            return self.kappa_max
        on = self.active_on if self.sampled else self._law_on()
        return self.kappa_max if on else self.kappa_min

    def _held_kappa(self, t):
        """Filippov equivalent stiffness that keeps θ̈ = 0 while held. [-]"""
        a_max = self._acceleration(t, self.theta, 0.0, self.kappa_max)
        a_min = self._acceleration(t, self.theta, 0.0, self.kappa_min)
        if a_min == a_max:
            return self.kappa_max
        return self.kappa_min + (self.kappa_max - self.kappa_min) * a_min / (a_min - a_max)

    # ---------------------------------------------------------------- sampled control
    def _push_law(self, t, on):
        """Register that the law output became ``on`` at t; it is read at the next sample."""
        if not self.sampled or on == self.law_last:
            return
        self.law_last = on
        k = max(0, math.ceil(t / self.sampling_time - 1e-9))
        if self.queue and self.queue[-1][0] == k:
            self.queue.pop()  # an earlier change in the same sampling interval is never read
        previous = self.queue[-1][1] if self.queue else self.applied
        if previous is None or previous != on:
            self.queue.append((k, on))

    def _apply_due(self, t):
        while self.queue and self.queue[0][0] * self.sampling_time + self.delay <= t:
            _, self.applied = self.queue.popleft()
            self.active_on = self.applied

    def _rest_kappa(self, times):
        """Stiffness applied at the given instants of a rest piece (queue not yet applied). [-]"""
        if not self.sampled:
            return self._kappa()
        values = []
        for u in np.atleast_1d(times):
            on = self.active_on
            for k, decision in self.queue:
                if k * self.sampling_time + self.delay > u:
                    break
                on = decision
            values.append(self.kappa_max if on else self.kappa_min)
        return values

    def _next_actuation(self):
        if self.sampled and self.queue:
            return self.queue[0][0] * self.sampling_time + self.delay
        return math.inf

    # ---------------------------------------------------------------- history
    def _record(self, t, theta, theta_dot, kappa):
        if self.record_history:
            t = np.atleast_1d(np.asarray(t, dtype=float))
            h = self._hist
            h["t"].append(t)
            h["theta"].append(np.broadcast_to(np.asarray(theta, dtype=float), t.shape).copy())
            h["theta_dot"].append(np.broadcast_to(np.asarray(theta_dot, dtype=float), t.shape).copy())
            h["kappa"].append(np.broadcast_to(np.asarray(kappa, dtype=float), t.shape).copy())

    def _record_state(self):
        kappa = self._held_kappa(self.t) if self.mode == _HELD else self._kappa()
        self._record(self.t, self.theta, self.theta_dot, kappa)

    @staticmethod
    def _grid(t0, t1):
        """Regular history instants strictly inside (t0, t1). [s]"""
        k0 = math.floor(t0 / HISTORY_STEP) + 1
        k1 = math.ceil(t1 / HISTORY_STEP) - 1
        if k1 < k0:
            return np.zeros(0)
        grid = np.arange(k0, k1 + 1) * HISTORY_STEP
        return grid[(grid > t0) & (grid < t1)]

    # ---------------------------------------------------------------- transitions
    def _start(self):
        if self.theta == 0.0 and self.theta_dot == 0.0:
            self.mode = _REST
        else:
            self.mode = _ROCKING
            ref = self.theta if self.theta != 0.0 else self.theta_dot
            self.side = 1 if ref > 0 else -1
            if self.side * self.theta >= self.theta_overturn:
                raise ValueError("initial_rotation is already beyond the overturning criterion")
            for name in self._working_elements():
                if self.side * self.theta >= self.theta_ultimate[name]:
                    self._fracture(name, 0.0)
            self.vel_sign = 1 if self.side * self.theta_dot >= 0 else -1
        self._refresh(0.0)
        self._push_law(0.0, self._law_on())
        self._apply_due(0.0)
        self._record_state()

    def _working_elements(self):
        suffix = "left" if self.side > 0 else "right"
        return [name for name in _ELEMENTS if name.endswith(suffix) and self.intact[name]]

    def _fracture(self, name, t):
        self.intact[name] = False
        self.fracture_times[name] = t

    def _refresh(self, t, ground_switched=False, decided=False):
        """Update the control regime after a stop at t (state already updated).

        A stop with θ̇ = 0 and θ ≠ 0 is treated as an apex unless ``decided`` says that the
        way the block leaves has just been settled (release from the held state).
        """
        if self.strategy == "CS02" and not ground_switched:
            self.ground_sign = self.excitation.sign_after(t)
        if self.mode == _ROCKING:
            if abs(self.theta_dot) > self.tiny_velocity:
                self.vel_sign = 1 if self.side * self.theta_dot > 0 else -1
            elif self.theta != 0.0 and not decided:
                self._apex(t)
                return
        self._push_law(t, self._law_on())
        self._apply_due(t)

    def _apex(self, t):
        """θ̇ = 0 with θ ≠ 0: decide how the block leaves (docs/model.md item 6)."""
        self.theta_dot = 0.0
        s = self.side
        if self.strategy in ("CS01", "CS02") and not self.sampled and self._feedback_mode():
            a_max = self._acceleration(t, self.theta, 0.0, self.kappa_max)
            a_min = self._acceleration(t, self.theta, 0.0, self.kappa_min)
            if s * a_max >= 0.0:
                self.vel_sign = 1  # leaves outward with K_max
            elif s * a_min <= 0.0:
                self.vel_sign = -1  # turns back with K_min
            else:
                self.mode = _HELD  # Filippov sliding on θ̇ = 0
        else:
            a = s * self._acceleration(t, self.theta, 0.0, self._kappa())
            self.vel_sign = 1 if a > 0 else (-1 if a < 0 else -self.vel_sign)
        self._push_law(t, self._law_on())
        self._apply_due(t)

    def _uplift(self, t, side):
        self.mode = _ROCKING
        self.theta = 0.0
        self.theta_dot = 0.0
        self.side = side
        self.vel_sign = 1
        self.uplift_times.append(t)
        self._refresh(t)

    def _impact(self, t, theta_dot_minus):
        """Eq. (14) at θ = 0, then rest or uplift when the rebound is negligible (Eq. 15)."""
        self.impact_times.append(t)
        self.theta = 0.0
        rebound = self.e * theta_dot_minus
        self.side = -self.side
        if abs(rebound) < self.rest_velocity:
            if self._uplift_margin(t) > 0.0:
                self._uplift(t, -1 if self.excitation.horizontal(t) > 0 else 1)
            else:
                self.mode = _REST
                self.theta_dot = 0.0
                self.rest_times.append(t)
                self._refresh(t)
                if t >= self.excitation.end:
                    self.status = STATUS_REST
        else:
            self.theta_dot = rebound
            self.vel_sign = 1
            self._refresh(t)

    # ---------------------------------------------------------------- time-only events
    def _locate(self, t0, t1, functions):
        """First crossing in (t0, t1] of functions of time only, located by ``solve_ivp``.

        ``functions`` is a list of (f(t), direction). The trivial ODE y' = 0 is integrated
        with the functions as terminal events and a step no longer than a fraction of the
        excitation period (pieces end at record knots, where the functions are linear).
        Returns (t, index) or None.
        """
        events = [_armed_event(lambda t, y, f=f: f(t), d, True, t0) for f, d in functions]
        sol = solve_ivp(lambda t, y: np.zeros(1), (t0, t1), np.zeros(1), method="RK23",
                        events=events, max_step=self.excitation.time_scale, rtol=1e-3, atol=1.0)
        if sol.status == 1:
            for i, te in enumerate(sol.t_events):
                if len(te):
                    return float(te[-1]), i
        return None

    def _next_stop(self, t, with_actuation=True):
        stop = min(self.t_final, self.excitation.next_knot(t))
        if self.strategy == "CS02" and t < self.excitation.horizontal_end:
            stop = min(stop, self.excitation.horizontal_end)
        if with_actuation:
            stop = min(stop, self._next_actuation())
        return stop

    def _rest_piece(self):
        t = self.t
        if t >= self.excitation.end:
            self.status = STATUS_REST
            return
        margin = self._uplift_margin(t)
        if margin > 0.0:
            self._uplift(t, -1 if self.excitation.horizontal(t) > 0 else 1)
            self._record_state()
            return
        t1 = self._next_stop(t, with_actuation=False)
        ex, tan_alpha, g = self.excitation, self.tan_alpha, self.gravity
        if ex.piecewise_linear:
            # The margin |Ẍg| − (g + Ÿg)·tanα is convex between knots, so it can only become
            # positive in the interval that ends at the first knot where it is positive.
            ahead = ex.knots[ex.knots > t]
            margin = (np.abs(self.motion.horizontal(ahead))
                      - (g + self.motion.vertical_acceleration(ahead)) * tan_alpha)
            positive = np.nonzero(margin > 0.0)[0]
            if len(positive) == 0:  # no uplift before the excitation ends
                self._rest_until(ex.end)
                return
            else:
                j = positive[0]
                t_before = ahead[j - 1] if j > 0 else t
                if t_before > t:
                    self._rest_until(float(t_before))
                    t = self.t
                t1 = float(ahead[j])
        hit = self._locate(t, t1, [
            (lambda u: ex.horizontal(u) - (g + ex.vertical(u)) * tan_alpha, 1),   # onto θ < 0
            (lambda u: -ex.horizontal(u) - (g + ex.vertical(u)) * tan_alpha, 1),  # onto θ > 0
        ])
        if hit is None:
            self._rest_until(t1)
        else:
            self._rest_until(hit[0], record_end=False)
            self._uplift(hit[0], -1 if hit[1] == 0 else 1)
            self._record_state()

    def _rest_until(self, t_end, record_end=True):
        """Stay at rest (θ = θ̇ = 0) until t_end. [s]"""
        grid = self._grid(self.t, t_end)
        if self.record_history and len(grid):
            self._record(grid, 0.0, 0.0, self._rest_kappa(grid))
        self.t = t_end
        self._apply_due(t_end)
        if record_end:
            self._record_state()

    def _held_piece(self):
        t = self.t
        if t >= self.excitation.end:
            # No more excitation: the balance of the held block cannot change any more.
            grid = self._grid(t, self.t_final)
            self._record(grid, self.theta, 0.0, self._held_kappa(t))
            self.t = self.t_final
            self._record_state()
            return
        t1 = self._next_stop(t, with_actuation=False)
        s, theta = self.side, self.theta
        hit = self._locate(t, t1, [
            (lambda u: s * self._acceleration(u, theta, 0.0, self.kappa_max), 1),   # leaves outward
            (lambda u: s * self._acceleration(u, theta, 0.0, self.kappa_min), -1),  # turns back
        ])
        t_end = t1 if hit is None else hit[0]
        grid = self._grid(t, t_end)
        if len(grid):
            self._record(grid, theta, 0.0, [self._held_kappa(u) for u in grid])
        self.t = t_end
        self.mode = _ROCKING
        if hit is None:
            self._refresh(t_end)  # re-decides at the breakpoint (may stay held)
        else:
            self.vel_sign = 1 if hit[1] == 0 else -1
            self._refresh(t_end, decided=True)
        self._record_state()

    # ---------------------------------------------------------------- rocking pieces
    def _rocking_piece(self):
        t0 = self.t
        t1 = self._next_stop(t0)
        if t1 - t0 <= 4.0 * np.finfo(float).eps * max(1.0, abs(t0)):
            self.t = t1
            self._refresh(t1)
            return
        s = self.side
        kappa = self._kappa()
        spring_ok, damper_ok = self._spring_ok(s), self._damper_ok(s)
        ex = self.excitation
        p, gravity, sin_alpha, cos_alpha = self.p, self.gravity, self.sin_alpha, self.cos_alpha
        side, kappa_acting, damping = float(s), float(kappa * spring_ok), float(self.damping * damper_ok)

        def rhs(t, y):
            return (y[1], angular_acceleration(float(y[0]), float(y[1]), side, kappa_acting, damping,
                                               ex.horizontal(t), ex.vertical(t), p, gravity, sin_alpha,
                                               cos_alpha))

        names, events = [], []

        def add(name, fun, direction, terminal=True, armed=True):
            names.append(name)
            if armed:
                events.append(_armed_event(fun, direction, terminal, t0))
            else:
                fun.direction, fun.terminal = direction, terminal
                events.append(fun)

        add("impact", lambda t, y: s * y[0], -1)
        theta_overturn = self.theta_overturn
        add("overturn", lambda t, y: s * y[0] - theta_overturn, 1)
        for name in self._working_elements():
            add(name, lambda t, y, u=self.theta_ultimate[name]: s * y[0] - u, 1)
        switching_on_velocity = self.strategy in ("CS01", "CS02") and self._feedback_mode()
        if switching_on_velocity:
            add("apex", lambda t, y: s * y[1], -self.vel_sign)
        else:
            add("turn", lambda t, y: s * y[1], 0, terminal=False, armed=False)
        if self.strategy == "CS02" and self.ground_sign != 0:
            add("ground", lambda t, y: ex.horizontal(t), -self.ground_sign)

        y0 = np.array([self.theta, self.theta_dot])
        sol = solve_ivp(rhs, (t0, t1), y0, method=METHOD, rtol=self.rtol, atol=self.atol,
                        events=events, dense_output=self.record_history)
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed at t = {t0} s: {sol.message}")
        t_end = float(sol.t[-1])
        theta_end, theta_dot_end = float(sol.y[0, -1]), float(sol.y[1, -1])
        fired = None
        if sol.status == 1:
            for name, event, te in zip(names, events, sol.t_events):
                if event.terminal and len(te) and te[-1] == t_end:
                    fired = name
                    break

        # Turning points (θ̇ = 0) inside the piece: a crossing of θ = 0, θ_u or the overturning
        # rotation that starts and ends within one solver step shows up only there.
        turning = [(float(te), ye) for name, te_all, ye_all in zip(names, sol.t_events, sol.y_events)
                   if name in ("turn", "apex") for te, ye in zip(te_all, ye_all)]
        thresholds = [(self.theta_ultimate[name], name) for name in self._working_elements()]
        thresholds.append((theta_overturn, "overturn"))
        watched = [(name, event) for name, event in zip(names, events) if event.terminal and name != fired]
        missed = self._missed_crossing(sol, rhs, s, sorted(turning, key=lambda item: item[0]), thresholds,
                                       watched, fired)
        if missed is not None:
            t_end, (theta_end, theta_dot_end), fired = missed

        keep = sol.t <= t_end
        self.max_abs_theta = max(self.max_abs_theta, float(np.max(np.abs(sol.y[0, keep]))), abs(theta_end))
        for te, ye in zip(sol.t_events, sol.y_events):
            if len(te) and te[0] <= t_end:
                self.max_abs_theta = max(self.max_abs_theta, float(np.max(np.abs(ye[te <= t_end, 0]))))
        # Put the state exactly on the surface of the event that stopped the piece.
        if fired == "impact":
            theta_end = 0.0
        elif fired == "overturn":
            theta_end = s * theta_overturn
        elif fired == "apex":
            theta_dot_end = 0.0
        if self.record_history:
            grid = self._grid(t0, t_end)
            if len(grid):
                yg = sol.sol(grid)
                self._record(grid, yg[0], yg[1], kappa)
            self._record(t_end, theta_end, theta_dot_end, kappa)

        self.t = t_end
        self.theta, self.theta_dot = theta_end, theta_dot_end
        if fired is None:
            self._refresh(t_end)
        elif fired == "impact":
            self._impact(t_end, self.theta_dot)
        elif fired == "overturn":
            self.status = STATUS_OVERTURNED
            self.overturn_time = t_end
        elif fired == "apex":
            self._apex(t_end)
        elif fired == "ground":
            # Ẍg changed sign (or the excitation ended on this zero).
            self.ground_sign = -self.ground_sign if self.excitation.sign_after(t_end) != 0 else 0
            self._refresh(t_end, ground_switched=True)
        else:
            self._fracture(fired, t_end)
            self._refresh(t_end)
        self._record_state()

    def _missed_crossing(self, sol, rhs, s, turning, thresholds, watched, fired):
        """The earliest event crossing that ``solve_ivp`` stepped over in this piece, if any.

        Event functions are only compared at step ends, so a surface crossed twice within one
        step goes unnoticed. Two symptoms reveal it:

        * a turning point (θ̇ = 0, itself an event) beyond a threshold: s·θ above an intact
          θ_u or the overturning rotation, or below 0 (a grazing impact);
        * a terminal event function that is past its surface at the end of the piece, when
          another event cut the step after the first of the two crossings (e.g. the apex of a
          small rock missed in the step that ends at the next impact).

        The step is then re-integrated with dense output and the crossing located with a root
        finder.

        Parameters
        ----------
        turning : list of (t, y)
            Turning points of the piece in time order. [s], ([rad], [rad/s])
        thresholds : list of (float, str)
            Rotations s·θ that end the piece when reached from below, with the event name. [rad]
        watched : list of (str, callable)
            Terminal events that did not stop the piece.
        fired : str or None
            Name of the event that stopped the piece.

        Returns
        -------
        (t, (theta, theta_dot), name) or None
        """
        t_end, y_end = float(sol.t[-1]), sol.y[:, -1]
        candidates = []  # (upper time bound, gap function of (t, y) crossing from < 0 to > 0, name)
        for t_turn, y_turn in turning:
            reached = [(u, name) for u, name in thresholds if s * y_turn[0] >= u]
            if reached:
                level, name = min(reached)
                candidates.append((t_turn, lambda t, y, u=level: s * y[0] - u, name))
                break
            if s * y_turn[0] < -self.atol:  # deeper than the integration noise
                candidates.append((t_turn, lambda t, y: -s * y[0], "impact"))
                break
        for name, event in watched:
            if event.direction * event(t_end, y_end) > 0.0:
                candidates.append((t_end, lambda t, y, ev=event: ev.direction * ev(t, y), name))
        best = None
        steps = {}
        for t_hi, gap, name in candidates:
            j = int(np.searchsorted(sol.t, t_hi, side="left")) - 1
            if j < 0:
                continue
            t_lo = float(sol.t[j])
            if (j, t_hi) not in steps:
                steps[(j, t_hi)] = solve_ivp(rhs, (t_lo, t_hi), sol.y[:, j], method=METHOD, rtol=self.rtol,
                                             atol=self.atol, dense_output=True).sol
            dense = steps[(j, t_hi)]

            def along(t, gap=gap, dense=dense):
                return gap(t, dense(t))

            if along(t_lo) >= 0.0:
                t_cross = t_lo
            elif along(t_hi) <= 0.0:  # the excess is below the integration tolerance
                t_cross = t_hi
            else:
                t_cross = brentq(along, t_lo, t_hi, xtol=4 * np.finfo(float).eps, rtol=4 * np.finfo(float).eps)
            if fired is not None and t_cross >= t_end:
                continue  # simultaneous with the event that stopped the piece: that one wins
            if best is None or t_cross < best[0]:
                y_cross = dense(t_cross)
                best = (t_cross, (float(y_cross[0]), float(y_cross[1])), name)
        return best

    # ---------------------------------------------------------------- driver
    def run(self) -> SimulationResult:
        self._start()
        count, stalled, t_last = 0, 0, -math.inf
        while self.status is None:
            count += 1
            if count > MAX_EVENTS:
                raise RuntimeError(f"simulate_reference: more than {MAX_EVENTS} pieces (t = {self.t} s)")
            if self.t > t_last:
                stalled, t_last = 0, self.t
            else:
                stalled += 1
                if stalled > MAX_STALLED_EVENTS:
                    raise RuntimeError(
                        f"simulate_reference: {MAX_STALLED_EVENTS} events without progress at t = {self.t} s "
                        f"(theta = {self.theta} rad, theta_dot = {self.theta_dot} rad/s, mode {self.mode})")
            if self.t >= self.t_final:
                self.status = STATUS_TIME_LIMIT
                break
            if self.mode == _REST:
                self._rest_piece()
            elif self.mode == _HELD:
                self._held_piece()
            else:
                self._rocking_piece()
        self.max_abs_theta = max(self.max_abs_theta, abs(self.theta))
        return self._result()

    def _result(self) -> SimulationResult:
        history = None
        if self.record_history:
            h = {k: np.concatenate(v) if v else np.zeros(0) for k, v in self._hist.items()}
            # Drop exact repeats (a piece end followed by the unchanged start of the next).
            keep = np.ones(len(h["t"]), dtype=bool)
            if len(keep) > 1:
                same = ((h["t"][1:] == h["t"][:-1]) & (h["theta"][1:] == h["theta"][:-1])
                        & (h["theta_dot"][1:] == h["theta_dot"][:-1]) & (h["kappa"][1:] == h["kappa"][:-1]))
                keep[1:] = ~same
            history = {k: v[keep] for k, v in h.items()}
            history["ground_acceleration"] = np.asarray(self.motion.horizontal(history["t"]), dtype=float)
        overturned = self.status == STATUS_OVERTURNED
        return SimulationResult(
            status=self.status,
            overturned=overturned,
            overturn_time=self.overturn_time if overturned else math.nan,
            end_time=self.t,
            max_rotation_ratio=self.max_abs_theta / self.alpha,
            impact_times=np.asarray(self.impact_times, dtype=float),
            uplift_times=np.asarray(self.uplift_times, dtype=float),
            rest_times=np.asarray(self.rest_times, dtype=float),
            fracture_times=dict(self.fracture_times),
            history=history,
            engine="reference",
        )


def simulate_reference(block: Block, anchorage: Anchorage, control: Control, motion: GroundMotion, *,
                       overturn_criterion: str = "flat", free_time: float = FREE_TIME,
                       rest_velocity: float | None = None, record_history: bool = False,
                       rtol: float = REFERENCE_RTOL, atol: float = REFERENCE_ATOL,
                       initial_rotation: float = 0.0, initial_velocity: float = 0.0) -> SimulationResult:
    """Simulate the rocking block with the event-driven reference integrator.

    Integrates Eq. (1) with Eqs. (2)–(13) (:func:`rockstudy.motion.angular_acceleration`),
    Housner's impact rule, Eq. (14), and the control laws of Eqs. (16)–(17), stopping at
    every impact, uplift, fracture, control switch, sample/actuation instant and record knot.
    See the module docstring and ``docs/model.md`` for how the paper is read.

    Parameters
    ----------
    block : Block
        Geometry, restitution e and frequency parameter p. [-]
    anchorage : Anchorage
        Restrainers; ignored for the ``"FS"`` strategy. [-]
    control : Control
        Strategy (FS, PASSIVE, CS01 Eq. 16, CS02 Eq. 17), sampling time T_s [s] and actuation
        delay [s]; T_s = 0 is continuous control, with CS01's Filippov sliding mode.
    motion : GroundMotion
        Horizontal (and optional vertical) ground acceleration. [m/s^2]
    overturn_criterion : {"flat", "alpha"}
        Overturned when |θ| ≥ π/2 ("flat") or |θ| ≥ α ("alpha").
    free_time : float, default 30
        Free motion simulated after the end of the excitation. [s]
    rest_velocity : float, optional
        Rebound speed below which an impact ends the rocking (Eq. 15); default 1e-6·p·α. [rad/s]
    record_history : bool, default False
        Return the time history (regular 2 ms samples plus every event; at an impact both the
        pre- and post-impact states appear with the same time).
    rtol, atol : float
        Tolerances of ``solve_ivp``. [-], [rad] and [rad/s]
    initial_rotation : float, default 0
        θ(0); its sign sets the pivoting side. [rad]
    initial_velocity : float, default 0
        θ̇(0); sets the side when ``initial_rotation`` is 0. [rad/s]

    Returns
    -------
    SimulationResult
        With ``engine="reference"``. The run ends when the block overturns, when it is at rest
        after the excitation has ended (status "rest"), or at the excitation end plus
        ``free_time`` (status "time limit").

    Raises
    ------
    ValueError
        For an unknown ``overturn_criterion`` or invalid numerical arguments.
    RuntimeError
        If the event loop does not make progress (a guard; it should not happen).
    """
    if overturn_criterion not in OVERTURN_CRITERIA:
        raise ValueError(f"overturn_criterion must be one of {', '.join(OVERTURN_CRITERIA)}, "
                         f"got {overturn_criterion!r}")
    if not (math.isfinite(free_time) and free_time >= 0):
        raise ValueError(f"free_time must be a finite number >= 0 [s], got {free_time!r}")
    if rest_velocity is None:
        rest_velocity = default_rest_velocity(block.p, block.alpha)
    if not (math.isfinite(rest_velocity) and rest_velocity >= 0):
        raise ValueError(f"rest_velocity must be a finite number >= 0 [rad/s], got {rest_velocity!r}")
    for name, value in (("rtol", rtol), ("atol", atol)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a positive number, got {value!r}")
    for name, value in (("initial_rotation", initial_rotation), ("initial_velocity", initial_velocity)):
        if not math.isfinite(value):
            raise ValueError(f"{name} must be finite, got {value!r}")
    run = _ReferenceRun(block, anchorage, control, motion, overturn_criterion, float(free_time),
                        float(rest_velocity), bool(record_history), float(rtol), float(atol),
                        float(initial_rotation), float(initial_velocity))
    return run.run()
