"""One simulation of the controlled block: the public entry point for both engines.

``engine="fast"`` runs the compiled kernel (:mod:`rockstudy.engine._kernel`); ``engine="reference"``
runs :func:`rockstudy.engine.reference.simulate_reference` on scipy's ``solve_ivp``. Both implement
``docs/model.md`` and are tested against each other and against closed forms.
"""
from __future__ import annotations

import math

import numpy as np

from rockstudy.core import validation
from rockstudy.core.constants import FAST_ATOL, FAST_RTOL, FREE_TIME, MAX_STEP_FRACTION
from rockstudy.core.constants import rest_velocity as default_rest_velocity
from rockstudy.core.limits import OVERTURN_CRITERIA
from rockstudy.core.quantities import ATOL_RANGE, RTOL_RANGE, check_arguments, declares  # noqa: F401 -- named in docs
from rockstudy.engine import _kernel
from rockstudy.engine.simulation_result import (
    FRACTURE_ELEMENTS,
    STATUS_CANNOT_OVERTURN,
    STATUS_OVERTURNED,
    STATUS_REST,
    STATUS_TIME_LIMIT,
    STATUS_UNDETERMINED,
    SimulationResult,
)
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import Block
from rockstudy.model.control import Control
from rockstudy.model.excitation import GroundMotion
from rockstudy.model.sensor import sensed_samples, sensed_step

ENGINES = ("fast", "reference")
DEFAULT_FREE_TIME = FREE_TIME
"""Free rocking allowed after the excitation before a run stops as "time limit" (``constants.FREE_TIME``). [s]"""
__all__ = ["simulate", "pack_parameters", "kernel_record", "overturn_rotation", "ENGINES", "OVERTURN_CRITERIA",
           "DEFAULT_FREE_TIME", "FAST_RTOL", "FAST_ATOL"]


def overturn_rotation(block: Block, criterion: str) -> float:
    """Rotation at which the block counts as overturned: π/2 ("flat") or α ("alpha"). [rad]

    Parameters
    ----------
    block : rockstudy.Block
        The rocking block; its slenderness α is the "alpha" rotation.
    criterion : {"flat", "alpha"}
        Overturned when lying flat (|θ| ≥ π/2) or once past the uplift-free limit (|θ| ≥ α);
        anything else raises ``ValueError``.
    """
    if criterion == "flat":
        return math.pi / 2
    if criterion == "alpha":
        return block.alpha
    raise ValueError(f"overturn_criterion must be one of {', '.join(OVERTURN_CRITERIA)}, got {criterion!r}")


STEPPERS = ("taylor", "dopri")
"""How the fast engine steps between record knots (:func:`pack_parameters`)."""


def max_step(block: Block, motion: GroundMotion) -> float:
    """The engine's largest step: :data:`~rockstudy.core.constants.MAX_STEP_FRACTION` of the free-rocking
    period 2π/p and, for an analytic excitation, of its period 2π/ω_p. [s]

    Parameters
    ----------
    block : rockstudy.Block
        The block (its p).
    motion : rockstudy.GroundMotion
        The ground motion (its kind and ω_p).
    """
    hmax = MAX_STEP_FRACTION * 2 * math.pi / block.p
    if motion.kind in ("one-sine", "modulated"):
        hmax = min(hmax, MAX_STEP_FRACTION * 2 * math.pi / motion.omega)
    return hmax


def pack_parameters(block: Block, anchorage: Anchorage, control: Control, motion: GroundMotion, *,
                    overturn_criterion: str = "flat", free_time: float = DEFAULT_FREE_TIME,
                    initial_rotation: float = 0.0, initial_velocity: float = 0.0,
                    rest_velocity: float | None = None, rtol: float = FAST_RTOL,
                    atol: float = FAST_ATOL, energy_bound: bool = False,
                    stepper: str = "taylor") -> np.ndarray:
    """The kernel's parameter vector (its named slots: :mod:`rockstudy.engine._kernel.layout`).

    ``energy_bound`` lets the engine end a run once it provably can no longer overturn (outcome
    runs only: the history and event log after that point are not computed). ``stepper`` is how the
    engine steps between the knots of a record: ``"taylor"`` (Taylor series of degree 6, one sine
    and cosine a step) or ``"dopri"`` (Dormand–Prince 5(4), as everywhere else; docs/model.md).

    Parameters
    ----------
    block : rockstudy.Block
        The rocking block (p, α, g, coefficient of restitution).
    anchorage : rockstudy.Anchorage
        The restrainers: κ_max, κ_min, damping ratio and the rotations at which spring and damper break.
    control : rockstudy.Control
        The control strategy, its sampling time, delay and sensor.
    motion : rockstudy.GroundMotion
        The ground motion: its kind, amplitude, frequency, duration and record steps.
    overturn_criterion : {"flat", "alpha"}, default "flat"
        The overturning rotation, :func:`overturn_rotation`.
    free_time : float, default DEFAULT_FREE_TIME
        Time allowed after the excitation ends, finite and >= 0 (else ``ValueError``). [s]
    initial_rotation, initial_velocity : float, default 0
        Initial θ [rad] and θ̇ [rad/s].
    rest_velocity : float, optional
        |θ̇⁺| below which an impact ends the motion (Eq. 15); None for
        :func:`rockstudy.core.constants.rest_velocity`. [rad/s]
    rtol, atol : float, default FAST_RTOL, FAST_ATOL
        Relative and absolute tolerances of the step-size control. [-]
    energy_bound : bool, default False
        End the run once it provably can no longer overturn (for outcome-only runs).
    stepper : {"taylor", "dopri"}, default "taylor"
        How the engine steps between record knots (see above); anything else raises ``ValueError``.
    """
    if stepper not in STEPPERS:
        raise ValueError(f"stepper must be one of {', '.join(STEPPERS)}, got {stepper!r}")
    if not (free_time >= 0 and math.isfinite(free_time)):
        raise ValueError(f"free_time must be a finite number >= 0 [s], got {free_time!r}")
    P = np.zeros(_kernel.NPAR)
    P[_kernel.I_P] = block.p
    P[_kernel.I_ALPHA] = block.alpha
    P[_kernel.I_SINA] = math.sin(block.alpha)
    P[_kernel.I_COSA] = math.cos(block.alpha)
    P[_kernel.I_G] = block.gravity
    P[_kernel.I_E] = block.e
    P[_kernel.I_KMAX] = anchorage.kappa_max
    P[_kernel.I_KMIN] = anchorage.kappa_min
    P[_kernel.I_CD] = 2.0 * anchorage.damping_ratio * block.p
    P[_kernel.I_TKU] = anchorage.theta_spring(block)
    P[_kernel.I_TDU] = anchorage.theta_damper(block)
    P[_kernel.I_TOVER] = overturn_rotation(block, overturn_criterion)
    P[_kernel.I_STRAT] = control.code
    P[_kernel.I_TS] = control.sampling_time
    P[_kernel.I_DELAY] = control.delay
    P[_kernel.I_VREST] = default_rest_velocity(block.p, block.alpha) if rest_velocity is None else rest_velocity
    P[_kernel.I_RTOL] = rtol
    P[_kernel.I_ATOL] = atol
    P[_kernel.I_FREE] = free_time
    P[_kernel.I_KIND] = motion.code
    P[_kernel.I_AMP] = motion.amplitude
    P[_kernel.I_OMEGA] = motion.omega if motion.omega > 0 else 1.0
    P[_kernel.I_DUR] = motion.duration
    P[_kernel.I_RDT] = motion.record_dt if motion.record_dt > 0 else 1.0
    P[_kernel.I_VDT] = motion.vertical_dt if motion.vertical_dt > 0 else 1.0
    P[_kernel.I_TH0] = initial_rotation
    P[_kernel.I_THD0] = initial_velocity
    P[_kernel.I_HMAX] = max_step(block, motion)  # a fraction of the free-rocking and excitation time scales
    P[_kernel.I_BOUND] = 1.0 if energy_bound else 0.0
    P[_kernel.I_TAYLOR] = 1.0 if stepper == "taylor" else 0.0
    P[_kernel.I_SDT] = 1.0
    if control.sensor_band is not None:  # the sensed samples follow the driving ones (kernel_record)
        P[_kernel.I_SENSE] = 1.0
        P[_kernel.I_SOFF] = len(motion.record)
        P[_kernel.I_SDT] = sensed_step(motion)
    return P


def kernel_record(control: Control, motion: GroundMotion) -> np.ndarray:
    """The samples the kernel reads: the driving record, then (with a sensor) the sensed record. [-]

    Without a sensor (``control.sensor_band`` None) this is ``motion.record`` itself. With one, the
    unit-amplitude sensed samples of :func:`rockstudy.model.sensor.sensed_samples` follow the record's
    (slots ``I_SENSE``, ``I_SOFF``, ``I_SDT`` of :func:`pack_parameters`).

    Parameters
    ----------
    control : rockstudy.Control
        The control; only its ``sensor_band`` is read (None: the ideal sensor).
    motion : rockstudy.GroundMotion
        The ground motion whose ``record`` drives the block.
    """
    if control.sensor_band is None:
        return motion.record
    sensed, _ = sensed_samples(motion, control.sensor_band)
    return np.concatenate([motion.record, sensed])


def _result_from_kernel(out, block: Block, engine: str = "fast") -> SimulationResult:
    status, t_over, t_end, max_abs = out.status, out.overturn_time, out.end_time, out.max_abs_theta
    impacts, uplifts, rests, frac, H = out.impact_times, out.uplift_times, out.rest_times, out.fracture_times, \
        out.history
    if status == _kernel.ST_ELIMIT:  # no outcome: reported as such, never as "safe"
        return SimulationResult(
            status=STATUS_UNDETERMINED, overturned=False, overturn_time=math.nan, end_time=float(t_end),
            max_rotation_ratio=float(max_abs / block.alpha), impact_times=np.asarray(impacts).copy(),
            uplift_times=np.asarray(uplifts).copy(), rest_times=np.asarray(rests).copy(), engine=engine,
            message=f"the fast engine reached its cap of {_kernel.MAX_EVENTS} located events (impacts, uplifts, "
                    f"switches) or of {_kernel.MAX_STEPS} steps by t = {t_end:.6g} s, before the run ended: a long "
                    "run with many events, a chattering sequence it cannot resolve, or time scales far below the "
                    "run's length, so the outcome is undetermined; engine='reference' decides it (slowly)")
    name = {_kernel.ST_REST: STATUS_REST, _kernel.ST_OVER: STATUS_OVERTURNED, _kernel.ST_TLIM: STATUS_TIME_LIMIT,
            _kernel.ST_BOUND: STATUS_CANNOT_OVERTURN}[status]
    history = None
    if len(H):
        history = {"t": H[:, 0].copy(), "theta": H[:, 1].copy(), "theta_dot": H[:, 2].copy(),
                   "kappa": H[:, 3].copy(), "ground_acceleration": H[:, 4].copy()}
    return SimulationResult(
        status=name, overturned=status == _kernel.ST_OVER, overturn_time=float(t_over), end_time=float(t_end),
        max_rotation_ratio=float(max_abs / block.alpha), impact_times=np.asarray(impacts).copy(),
        uplift_times=np.asarray(uplifts).copy(), rest_times=np.asarray(rests).copy(),
        fracture_times={k: float(v) for k, v in zip(FRACTURE_ELEMENTS, frac) if np.isfinite(v)},
        history=history, engine=engine,
    )


def check_inputs(block, anchorage, control, motion, *, engine="fast", overturn_criterion="flat",
                 free_time=DEFAULT_FREE_TIME, initial_rotation=0.0, initial_velocity=0.0, rest_velocity=None,
                 rtol=None, atol=None) -> None:
    """The arguments of :func:`simulate` through the one validation layer: the types (named), finite
    numbers, tolerances in :data:`RTOL_RANGE`/:data:`ATOL_RANGE`, and a run within the limits of
    :mod:`rockstudy.core.validation` (time span, record samples).

    Parameters
    ----------
    block : rockstudy.Block
        Must be a :class:`~rockstudy.Block`.
    anchorage : rockstudy.Anchorage
        Must be a :class:`~rockstudy.Anchorage`.
    control : rockstudy.Control
        Must be a :class:`~rockstudy.Control`.
    motion : rockstudy.GroundMotion
        Must be a :class:`~rockstudy.GroundMotion`; its end time plus ``free_time`` is bounded by
        :data:`~rockstudy.core.validation.MAX_TIME_SPAN`.
    engine : {"fast", "reference"}, default "fast"
        One of :data:`ENGINES`.
    overturn_criterion : {"flat", "alpha"}, default "flat"
        One of :data:`OVERTURN_CRITERIA`.
    free_time : float, default DEFAULT_FREE_TIME
        Time after the excitation, >= 0 and at most :data:`~rockstudy.core.validation.MAX_FREE_TIME`. [s]
    initial_rotation : float, default 0
        Initial θ, within [-π/2, π/2]. [rad]
    initial_velocity : float, default 0
        Initial θ̇, any finite number. [rad/s]
    rest_velocity : float, optional
        Rest velocity of Eq. (15), >= 0 when given. [rad/s]
    rtol, atol : float, optional
        Tolerances, within :data:`RTOL_RANGE` and :data:`ATOL_RANGE` when given. [-]

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) naming the argument, the value and what is allowed.
    """
    for name, value, kind in (("block", block, Block), ("anchorage", anchorage, Anchorage),
                              ("control", control, Control), ("motion", motion, GroundMotion)):
        if not isinstance(value, kind):
            raise validation.InputError(
                f"{name} must be a rockstudy {kind.__name__}, got {type(value).__name__} {value!r}")
    if not isinstance(engine, str) or engine not in ENGINES:
        raise validation.InputError(f"engine must be one of {', '.join(ENGINES)}, got {engine!r}")
    if not isinstance(overturn_criterion, str) or overturn_criterion not in OVERTURN_CRITERIA:
        raise validation.InputError(f"overturn_criterion must be one of {', '.join(OVERTURN_CRITERIA)}, "
                           f"got {overturn_criterion!r}")
    free_time = check_arguments("simulate", {  # each number's type and range (core.quantities)
        "free_time": free_time, "initial_rotation": initial_rotation, "initial_velocity": initial_velocity,
        "rest_velocity": rest_velocity, "rtol": rtol, "atol": atol})["free_time"]
    span = motion.end_time + free_time
    if span > validation.MAX_TIME_SPAN:
        validation.fail("free_time", free_time,
                        f"the motion lasts {motion.end_time:.4g} s; with free_time a run lasts "
                        f"{span:.4g} s, the limit is {validation.MAX_TIME_SPAN:g} s", "s")
    hmax = max_step(block, motion)  # the run's work bounded before it starts, as check_time_span bounds a spectrum's
    if span / hmax > validation.MAX_STEPS:
        validation.fail("motion.omega", motion.omega, f"a run of {span:.4g} s at steps of at most {hmax:.3g} s needs "
                        f"{span / hmax:.3g} steps, the limit is {validation.MAX_STEPS:.0e} (a lower frequency, a "
                        "shorter free_time or a larger block)", "rad/s")
    if control.sampling_time > 0 and span / control.sampling_time > validation.MAX_CONTROLLER_SAMPLES:
        validation.fail("control.sampling_time", control.sampling_time,
                        f"a run of {span:.4g} s sampled every {control.sampling_time:g} s takes "
                        f"{span / control.sampling_time:.3g} controller samples, the limit is "
                        f"{validation.MAX_CONTROLLER_SAMPLES:.0e}", "s")


@declares(free_time="free_time", initial_rotation="initial_rotation", initial_velocity="initial_velocity",
          rest_velocity="rest_velocity", rtol="rtol", atol="atol")
def simulate(block: Block, anchorage: Anchorage, control: Control, motion: GroundMotion, *,
             engine: str = "fast", overturn_criterion: str = "flat", free_time: float = DEFAULT_FREE_TIME,
             initial_rotation: float = 0.0, initial_velocity: float = 0.0,
             rest_velocity: float | None = None, record_history: bool = False,
             rtol: float | None = None, atol: float | None = None) -> SimulationResult:
    """Simulate the block under a ground motion with the chosen anchorage control.

    Parameters
    ----------
    block : rockstudy.Block
        The rocking block.
    anchorage : rockstudy.Anchorage
        Its restrainers (springs and dampers, their stiffness and breaking rotations).
    control : rockstudy.Control
        The control law and its timing (sampling time, delay, sensor).
    motion : rockstudy.GroundMotion
        The ground motion.
    engine : {"fast", "reference"}
        Compiled event-accurate Dormand–Prince engine, or scipy ``solve_ivp`` reference.
    overturn_criterion : {"flat", "alpha"}
        Overturned at |θ| ≥ π/2 (default) or at |θ| ≥ α.
    free_time : float
        Time allowed after the excitation ends. [s]
    initial_rotation, initial_velocity : float
        Initial θ [rad] and θ̇ [rad/s] (free-rocking tests).
    rest_velocity : float, optional
        |θ̇⁺| below which an impact ends the motion (Eq. 15). Default 1e-6·p·α. [rad/s]
    record_history : bool
        Return time histories of θ, θ̇, κ and Ẍg.
    rtol, atol : float, optional
        Integration tolerances (engine defaults when None), within :data:`RTOL_RANGE` and :data:`ATOL_RANGE`.

    Returns
    -------
    SimulationResult
        Status "undetermined" (with a ``message``) when the fast engine reaches its cap on located events.

    Raises
    ------
    ValueError
        (:class:`rockstudy.core.validation.InputError`) for a wrong type, a non-finite number or a value
        beyond the limits (:func:`check_inputs`), naming the argument.
    """
    check_inputs(block, anchorage, control, motion, engine=engine, overturn_criterion=overturn_criterion,
                 free_time=free_time, initial_rotation=initial_rotation, initial_velocity=initial_velocity,
                 rest_velocity=rest_velocity, rtol=rtol, atol=atol)
    if engine == "reference":
        from rockstudy.engine.reference import simulate_reference
        kw = {}
        if rtol is not None:
            kw["rtol"] = rtol
        if atol is not None:
            kw["atol"] = atol
        return simulate_reference(block, anchorage, control, motion, overturn_criterion=overturn_criterion,
                                  free_time=free_time, rest_velocity=rest_velocity,
                                  record_history=record_history, initial_rotation=initial_rotation,
                                  initial_velocity=initial_velocity, **kw)
    P = pack_parameters(block, anchorage, control, motion, overturn_criterion=overturn_criterion,
                        free_time=free_time, initial_rotation=initial_rotation,
                        initial_velocity=initial_velocity, rest_velocity=rest_velocity,
                        rtol=FAST_RTOL if rtol is None else rtol, atol=FAST_ATOL if atol is None else atol)
    out = _kernel.simulate_kernel(P, _kernel.writable(kernel_record(control, motion)),
                                  _kernel.writable(motion.vertical), bool(record_history), True)
    return _result_from_kernel(out, block)
