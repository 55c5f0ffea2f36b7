"""Reference engine: event-driven integration with ``scipy.integrate.solve_ivp`` (paper §2–3).

The motion of the block is a sequence of smooth pieces separated by instants at which the
state or the right-hand side jumps. This package integrates each piece with
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
  docs/model.md, "CS01 sliding"): the block is held (θ̇ = 0, θ constant) and the release instant is located
  with the same event machinery on the trivial ODE;
* kinks of sampled records (horizontal and vertical) at their knots i·dt;
* overturning, |θ| ≥ π/2 (``"flat"``) or |θ| ≥ α (``"alpha"``).

It is slow but transparent, and serves as the oracle for the compiled engine.

The right-hand side is :func:`rockstudy.model.equation_of_motion.angular_acceleration` (Eqs. 1–7). The parts are
laid out as ``solve_ivp``'s own code is:

* :mod:`.ground` — Ẍg(t), Ÿg(t) on floats and their breakpoints;
* :mod:`.dynamics` — θ̈ on one corner, the right-hand side of a piece, the restrainers;
* :mod:`.controller` — the law in force, the sampled-control queue, the Filippov stiffness;
* :mod:`.events` — event objects with ``terminal``/``direction`` and the time-only locator;
* :mod:`.crossings` — crossings ``solve_ivp`` stepped over within one step;
* :mod:`.piece` — one rocking piece integrated to its first event (the engine's step);
* :mod:`.recorder` — history, event logs and the :class:`~rockstudy.engine.simulation_result.SimulationResult`;
* :mod:`.run` — the regimes (rest, held, rocking), the jumps between them and the loop.

Notes
-----
No early overturn stop is made: once the block is past α with no intact spring on that
side and no more excitation, the integration simply goes on until the overturning criterion
is met, so ``overturn_time`` is always the instant the criterion is reached.
"""
from __future__ import annotations

import math

from rockstudy.core.constants import FREE_TIME, REFERENCE_ATOL, REFERENCE_RTOL
from rockstudy.core.constants import rest_velocity as default_rest_velocity
from rockstudy.core.limits import OVERTURN_CRITERIA
from rockstudy.engine.reference.recorder import HISTORY_STEP
from rockstudy.engine.reference.run import MAX_EVENTS, MAX_STALLED_EVENTS, METHOD, ReferenceRun
from rockstudy.engine.simulation_result import SimulationResult
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import Block
from rockstudy.model.control import Control
from rockstudy.model.excitation import GroundMotion

__all__ = ["simulate_reference", "OVERTURN_CRITERIA", "HISTORY_STEP", "METHOD", "MAX_EVENTS", "MAX_STALLED_EVENTS"]


def simulate_reference(block: Block, anchorage: Anchorage, control: Control, motion: GroundMotion, *,
                       overturn_criterion: str = "flat", free_time: float = FREE_TIME,
                       rest_velocity: float | None = None, record_history: bool = False,
                       rtol: float = REFERENCE_RTOL, atol: float = REFERENCE_ATOL,
                       initial_rotation: float = 0.0, initial_velocity: float = 0.0) -> SimulationResult:
    """Simulate the rocking block with the event-driven reference integrator.

    Integrates Eq. (1) with Eqs. (2)–(13) (:func:`rockstudy.model.equation_of_motion.angular_acceleration`),
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
    run = ReferenceRun(block, anchorage, control, motion, overturn_criterion, float(free_time),
                        float(rest_velocity), bool(record_history), float(rtol), float(atol),
                        float(initial_rotation), float(initial_velocity))
    return run.run()
