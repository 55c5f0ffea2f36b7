"""One reference simulation: the regime of the block, the pieces of motion and the jumps between them.

The run follows the paper's §3. The block is at rest, held on the CS01 sliding surface, or
rocking on one corner. Each loop turn integrates one smooth piece of the current regime up
to its first event (:mod:`.events`), then applies the jump the event stands for:

* rest → rocking at uplift, |Ẍg| > (g + Ÿg)·tanα (docs/model.md item 4);
* rocking → rocking at an impact, θ̇⁺ = e·θ̇⁻ (Eq. 14) on the other corner, or → rest when the
  rebound is negligible (Eq. 15, docs/model.md item 5);
* a spring or damper breaks at its ultimate rotation (Eqs. 8–13);
* the control law switches (Eqs. 16–17): at θ̇ = 0 for CS01, where the block may also be held
  (Filippov sliding, docs/model.md item 6), and at Ẍg = 0 for CS02; sampled decisions act at
  k·T_s + Δτ (:mod:`.controller`);
* the run ends at overturning, at rest after the excitation, or at the time limit.
"""
from __future__ import annotations

import math

import numpy as np

from rockstudy.core import limits
from rockstudy.engine.reference.controller import Controller, filippov_stiffness
from rockstudy.engine.reference.dynamics import Dynamics, Restrainers, RockingRHS
from rockstudy.engine.reference.events import (
    Apex,
    Fracture,
    GroundZero,
    HoldExit,
    Impact,
    Overturn,
    TurningPoint,
    UpliftFromRest,
    locate_in_time,
)
from rockstudy.engine.reference.ground import Excitation
from rockstudy.engine.reference.piece import integrate_piece
from rockstudy.engine.reference.recorder import Recorder, history_grid
from rockstudy.engine.simulation_result import STATUS_OVERTURNED, STATUS_REST, STATUS_TIME_LIMIT, SimulationResult
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import Block
from rockstudy.model.control import Control
from rockstudy.model.excitation import GroundMotion

METHOD = "DOP853"
"""Runge–Kutta method passed to ``solve_ivp`` for the rocking pieces."""
MAX_EVENTS = limits.REFERENCE_MAX_EVENTS
"""Cap on the number of pieces of one run (guards against an endless event loop)."""
MAX_STALLED_EVENTS = limits.REFERENCE_MAX_STALLED_EVENTS
"""Cap on consecutive pieces that do not advance time (guards against Zeno loops)."""
TINY_VELOCITY_FACTOR = 1e-12
"""|θ̇| below this times p counts as θ̇ = 0 at a stop. [-]"""
EMPTY_PIECE = 4.0 * np.finfo(float).eps
"""A piece shorter than this times max(1, t) is skipped (the stop is applied at once). [-]"""

ROCKING, REST, HELD = "rocking", "rest", "held"
"""Regimes of the block: on one corner, at rest on its base, held on θ̇ = 0 (CS01 sliding)."""


class ReferenceRun:
    """State and event handling of one reference simulation; the run owns all mutable state.

    Parameters are those of :func:`rockstudy.engine.reference.simulate_reference`, already checked.

    Attributes
    ----------
    t, theta, theta_dot : float
        Current time [s], rotation [rad] and angular velocity [rad/s].
    side : {1, -1}
        Pivoting corner (+1 for θ > 0).
    vel_sign : {1, -1}
        Sign of s·θ̇: +1 moving away from upright (or still), −1 returning.
    ground_sign : {1, 0, -1}
        Sign of Ẍg just after t (CS02 only).
    mode : {"rocking", "rest", "held"}
        Regime.
    status : str or None
        How the run ended (None while running).
    """

    def __init__(self, block: Block, anchorage: Anchorage, control: Control, motion: GroundMotion,
                 overturn_criterion: str, free_time: float, rest_velocity: float, record_history: bool,
                 rtol: float, atol: float, initial_rotation: float, initial_velocity: float):
        self.alpha = block.alpha
        self.e = block.e
        self.rtol, self.atol = rtol, atol
        self.rest_velocity = rest_velocity
        self.tiny_velocity = TINY_VELOCITY_FACTOR * block.p
        self.theta_overturn = math.pi / 2 if overturn_criterion == "flat" else block.alpha
        # FS (or an anchorage exerting no force at all) means no restrainer elements at all.
        anchored = control.strategy != "FS" and not anchorage.is_inert
        damping_ratio = anchorage.damping_ratio if anchored else 0.0
        self.motion = motion
        self.excitation = Excitation(motion, control.sensor_band)
        self.dynamics = Dynamics(block, float(2.0 * damping_ratio * block.p), self.excitation)  # 2ξp [1/s]
        self.restrainers = Restrainers(anchorage, block, anchored)
        self.controller = Controller(control.strategy if anchored else "FS",
                                     anchorage.kappa_max if anchored else 0.0,
                                     anchorage.kappa_min if anchored else 0.0, control.sampling_time, control.delay)
        self.recorder = Recorder(record_history, initial_rotation)
        self.t_final = self.excitation.end + free_time
        self.t, self.theta, self.theta_dot = 0.0, float(initial_rotation), float(initial_velocity)
        self.side, self.vel_sign, self.ground_sign = 1, 1, 0
        self.mode = REST
        self.status = None
        self.overturn_time = math.nan

    # ---------------------------------------------------------------- the model in the current regime
    def _acceleration(self, t: float, theta: float, theta_dot: float, kappa: float) -> float:
        """θ̈ of Eqs. (1)–(7) on the current corner with stiffness ``kappa``. [rad/s^2]"""
        s = self.side
        return self.dynamics.acceleration(t, theta, theta_dot, s, kappa, self.restrainers.spring_ok(s),
                                          self.restrainers.damper_ok(s))

    def _law_on(self) -> bool:
        """Output of Eq. (16)/(17) in the current regime: True for κ_max."""
        return self.controller.law_on(self.mode == REST, self.side, self.vel_sign, self.ground_sign)

    def _kappa(self) -> float:
        """Dimensionless stiffness the device applies now. [-]"""
        return self.controller.kappa(self._law_on())

    def _held_kappa(self, t: float) -> float:
        """Filippov equivalent stiffness that keeps θ̈ = 0 while held at t. [-]"""
        c = self.controller
        return filippov_stiffness(self._acceleration(t, self.theta, 0.0, c.kappa_max),
                                  self._acceleration(t, self.theta, 0.0, c.kappa_min), c.kappa_max, c.kappa_min)

    def _decide(self, t: float) -> None:
        """Pass the law's output at t to the controller and let due decisions act. [s]"""
        self.controller.push(t, self._law_on())
        self.controller.apply_due(t)

    def _record_state(self) -> None:
        """Record the current state with the stiffness in force."""
        if self.recorder.enabled:
            kappa = self._held_kappa(self.t) if self.mode == HELD else self._kappa()
            self.recorder.sample(self.t, self.theta, self.theta_dot, kappa)

    # ---------------------------------------------------------------- jumps
    def _start(self) -> None:
        """Initial regime from θ(0), θ̇(0); elements already past θ_u break at t = 0."""
        if self.theta == 0.0 and self.theta_dot == 0.0:
            self.mode = REST
        else:
            self.mode = ROCKING
            ref = self.theta if self.theta != 0.0 else self.theta_dot
            self.side = 1 if ref > 0 else -1
            if self.side * self.theta >= self.theta_overturn:
                raise ValueError("initial_rotation is already beyond the overturning criterion")
            for name in self.restrainers.working(self.side):
                if self.side * self.theta >= self.restrainers.theta_ultimate[name]:
                    self.restrainers.fracture(name, 0.0)
            self.vel_sign = 1 if self.side * self.theta_dot >= 0 else -1
        self._refresh(0.0)
        self._decide(0.0)
        self._record_state()

    def _refresh(self, t: float, ground_switched: bool = False, decided: bool = False) -> None:
        """Update the control regime after a stop at t (state already updated). [s]

        A stop with θ̇ = 0 and θ ≠ 0 is treated as an apex unless ``decided`` says that the
        way the block leaves has just been settled (release from the held state).
        """
        if self.controller.strategy == "CS02" and not ground_switched:
            self.ground_sign = self.excitation.sign_after(t)
        if self.mode == ROCKING:
            if abs(self.theta_dot) > self.tiny_velocity:
                self.vel_sign = 1 if self.side * self.theta_dot > 0 else -1
            elif self.theta != 0.0 and not decided:
                self._apex(t)
                return
        self._decide(t)

    def _apex(self, t: float) -> None:
        """θ̇ = 0 with θ ≠ 0: decide how the block leaves (docs/model.md item 6). [s]"""
        self.theta_dot = 0.0
        s, c = self.side, self.controller
        if c.switching and not c.sampled and c.feedback_mode(self.ground_sign):
            a_max = self._acceleration(t, self.theta, 0.0, c.kappa_max)
            a_min = self._acceleration(t, self.theta, 0.0, c.kappa_min)
            if s * a_max >= 0.0:
                self.vel_sign = 1  # leaves outward with K_max
            elif s * a_min <= 0.0:
                self.vel_sign = -1  # turns back with K_min
            else:
                self.mode = HELD  # Filippov sliding on θ̇ = 0
        else:
            a = s * self._acceleration(t, self.theta, 0.0, self._kappa())
            self.vel_sign = 1 if a > 0 else (-1 if a < 0 else -self.vel_sign)
        self._decide(t)

    def _uplift(self, t: float, side: int) -> None:
        """Rest → rocking on corner ``side`` at t (docs/model.md item 4). [s]"""
        self.mode = ROCKING
        self.theta = 0.0
        self.theta_dot = 0.0
        self.side = side
        self.vel_sign = 1
        self.recorder.uplift_times.append(t)
        self._refresh(t)

    def _uplift_side(self, t: float) -> int:
        """Corner the ground lifts the block onto at t: −sgn Ẍg. [-]"""
        return -1 if self.excitation.horizontal(t) > 0 else 1

    def _impact(self, t: float, theta_dot_minus: float) -> None:
        """Eq. (14) at θ = 0, then rest or uplift when the rebound is negligible (Eq. 15). [s], [rad/s]"""
        self.recorder.impact_times.append(t)
        self.theta = 0.0
        rebound = self.e * theta_dot_minus
        self.side = -self.side
        if not abs(rebound) < self.rest_velocity:
            self.theta_dot = rebound
            self.vel_sign = 1
            self._refresh(t)
        elif self.dynamics.uplift_margin(t) > 0.0:
            self._uplift(t, self._uplift_side(t))
        else:
            self.mode = REST
            self.theta_dot = 0.0
            self.recorder.rest_times.append(t)
            self._refresh(t)
            if t >= self.excitation.end:
                self.status = STATUS_REST

    def _after_stop(self, event, t: float) -> None:
        """Apply the jump of the event that ended a rocking piece at t (None: a time breakpoint). [s]"""
        name = None if event is None else event.name
        if name is None:
            self._refresh(t)
        elif name == "impact":
            self._impact(t, self.theta_dot)
        elif name == "overturn":
            self.status = STATUS_OVERTURNED
            self.overturn_time = t
        elif name == "apex":
            self._apex(t)
        elif name == "ground":
            # Ẍg changed sign (or the excitation ended on this zero).
            self.ground_sign = -self.ground_sign if self.excitation.sign_after(t) != 0 else 0
            self._refresh(t, ground_switched=True)
        else:
            self.restrainers.fracture(name, t)
            self._refresh(t)

    # ---------------------------------------------------------------- pieces
    def _next_stop(self, t: float, with_actuation: bool = True) -> float:
        """End of the piece starting at t: next knot, CS02's excitation end, actuation, time limit. [s]"""
        stop = min(self.t_final, self.excitation.next_knot(t))
        if self.controller.strategy == "CS02" and t < self.excitation.horizontal_end:
            stop = min(stop, self.excitation.horizontal_end)
        if with_actuation:
            stop = min(stop, self.controller.next_actuation())
        return stop

    def _rest_piece(self) -> None:
        """At rest: stay until uplift (located as a zero of the margin) or the end of the piece."""
        t = self.t
        if t >= self.excitation.end:
            self.status = STATUS_REST
            return
        if self.dynamics.uplift_margin(t) > 0.0:
            self._uplift(t, self._uplift_side(t))
            self._record_state()
            return
        t1 = self._next_stop(t, with_actuation=False)
        if self.excitation.piecewise_linear:
            window = self.dynamics.uplift_window(t, self.motion)
            if window is None:
                self._rest_until(self.excitation.end)
                return
            t_before, t1 = window
            if t_before > t:
                self._rest_until(float(t_before))
                t = self.t
        events = [UpliftFromRest(self.dynamics, 1, t), UpliftFromRest(self.dynamics, -1, t)]
        hit = locate_in_time(t, t1, events, self.excitation.time_scale)
        if hit is None:
            self._rest_until(t1)
        else:
            self._rest_until(hit[0], record_end=False)
            self._uplift(hit[0], -1 if hit[1] == 0 else 1)
            self._record_state()

    def _rest_until(self, t_end: float, record_end: bool = True) -> None:
        """Stay at rest (θ = θ̇ = 0) until t_end. [s]"""
        grid = history_grid(self.t, t_end)
        if self.recorder.enabled and len(grid):
            self.recorder.sample(grid, 0.0, 0.0, self.controller.kappa_at(grid, self._law_on()))
        self.t = t_end
        self.controller.apply_due(t_end)
        if record_end:
            self._record_state()

    def _held_piece(self) -> None:
        """Held on θ̇ = 0 (CS01 sliding): stay until one stiffness pushes the block off, or a breakpoint."""
        t = self.t
        if t >= self.excitation.end:
            # No more excitation: the balance of the held block cannot change any more.
            if self.recorder.enabled:
                self.recorder.sample(history_grid(t, self.t_final), self.theta, 0.0, self._held_kappa(t))
            self.t = self.t_final
            self._record_state()
            return
        t1 = self._next_stop(t, with_actuation=False)
        s, c, r = self.side, self.controller, self.restrainers
        events = [HoldExit(self.dynamics, s, self.theta, c.kappa_max, r.spring_ok(s), r.damper_ok(s), 1, t),
                  HoldExit(self.dynamics, s, self.theta, c.kappa_min, r.spring_ok(s), r.damper_ok(s), -1, t)]
        hit = locate_in_time(t, t1, events, self.excitation.time_scale)
        t_end = t1 if hit is None else hit[0]
        self._record_held(history_grid(t, t_end))
        self.t = t_end
        self.mode = ROCKING
        if hit is None:
            self._refresh(t_end)  # re-decides at the breakpoint (may stay held)
        else:
            self.vel_sign = 1 if hit[1] == 0 else -1
            self._refresh(t_end, decided=True)
        self._record_state()

    def _record_held(self, grid: np.ndarray) -> None:
        """Record the held state at the instants ``grid`` with the Filippov stiffness. [s]"""
        if self.recorder.enabled and len(grid):
            self.recorder.sample(grid, self.theta, 0.0, [self._held_kappa(u) for u in grid])

    def _rocking_events(self, t0: float) -> list:
        """The events of a rocking piece starting at t0 on the current corner. [s]"""
        s = self.side
        events = [Impact(s, t0), Overturn(s, self.theta_overturn, t0)]
        events += [Fracture(name, s, self.restrainers.theta_ultimate[name], t0)
                   for name in self.restrainers.working(s)]
        if self.controller.switching and self.controller.feedback_mode(self.ground_sign):
            events.append(Apex(s, self.vel_sign, t0))
        else:
            events.append(TurningPoint(s))
        if self.controller.strategy == "CS02" and self.ground_sign != 0:
            events.append(GroundZero(self.excitation, self.ground_sign, t0))
        return events

    def _rocking_piece(self) -> None:
        """On one corner: integrate Eq. (1) with ``solve_ivp`` to the first event, then jump."""
        t0 = self.t
        t1 = self._next_stop(t0)
        if t1 - t0 <= EMPTY_PIECE * max(1.0, abs(t0)):
            self.t = t1
            self._refresh(t1)
            return
        s, r = self.side, self.restrainers
        kappa = self._kappa()
        rhs = RockingRHS(self.dynamics, s, kappa * r.spring_ok(s), self.dynamics.damping * r.damper_ok(s))
        events = self._rocking_events(t0)
        thresholds = [(r.theta_ultimate[name], name) for name in r.working(s)] + [(self.theta_overturn, "overturn")]
        sol, (t_end, theta_end, theta_dot_end), fired = integrate_piece(
            rhs, events, thresholds, s, (t0, t1), np.array([self.theta, self.theta_dot]), METHOD, self.rtol,
            self.atol, self.recorder.enabled)
        self.recorder.piece_peak(sol, t_end, theta_end)
        theta_end, theta_dot_end = self._on_surface(fired, theta_end, theta_dot_end)
        if self.recorder.enabled:
            self._record_piece(sol, t0, (t_end, theta_end, theta_dot_end), kappa)
        self.t, self.theta, self.theta_dot = t_end, theta_end, theta_dot_end
        self._after_stop(fired, t_end)
        self._record_state()

    def _on_surface(self, event, theta: float, theta_dot: float) -> tuple[float, float]:
        """The end state put exactly on the surface of the event that stopped the piece. [rad], [rad/s]"""
        name = None if event is None else event.name
        if name == "impact":
            return 0.0, theta_dot
        if name == "overturn":
            return self.side * self.theta_overturn, theta_dot
        if name == "apex":
            return theta, 0.0
        return theta, theta_dot

    def _record_piece(self, sol, t0: float, end: tuple, kappa: float) -> None:
        """Record a rocking piece: the regular grid on its dense output, then its end state. [s], [-]"""
        grid = history_grid(t0, end[0])
        if len(grid):
            y_grid = sol.sol(grid)
            self.recorder.sample(grid, y_grid[0], y_grid[1], kappa)
        self.recorder.sample(*end, kappa)

    # ---------------------------------------------------------------- driver
    def _check_progress(self, count: int, stalled: int) -> None:
        """Raise if the loop has run too many pieces, or too many without advancing time."""
        if count > MAX_EVENTS:
            raise RuntimeError(f"simulate_reference: more than {MAX_EVENTS} pieces (t = {self.t} s)")
        if stalled > MAX_STALLED_EVENTS:
            raise RuntimeError(
                f"simulate_reference: {MAX_STALLED_EVENTS} events without progress at t = {self.t} s "
                f"(theta = {self.theta} rad, theta_dot = {self.theta_dot} rad/s, mode {self.mode})")

    def run(self) -> SimulationResult:
        """Integrate piece by piece until the run ends; return its result."""
        self._start()
        count, stalled, t_last = 0, 0, -math.inf
        while self.status is None:
            count += 1
            if self.t > t_last:
                stalled, t_last = 0, self.t
            else:
                stalled += 1
            self._check_progress(count, stalled)
            if self.t >= self.t_final:
                self.status = STATUS_TIME_LIMIT
                break
            if self.mode == REST:
                self._rest_piece()
            elif self.mode == HELD:
                self._held_piece()
            else:
                self._rocking_piece()
        self.recorder.peak(abs(self.theta))
        return self.recorder.result(self.status, self.overturn_time, self.t, self.alpha,
                                    self.restrainers.fracture_times, self.motion)
