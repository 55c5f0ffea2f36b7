"""Compiled fast engine: event-accurate Dormand–Prince 5(4) integration of the controlled rocking
block (paper Eqs. 1–17), in numba, in small parts:

* :mod:`.layout`  — the named parameter vector, status codes, the :class:`KernelResult` tuple;
* :mod:`.ground`  — Ẍg(t), Ÿg(t) (Eq. 23 and records via :mod:`rockstudy.model.excitation`);
* :mod:`.dopri`   — one Dormand–Prince step, its continuous extension, the right-hand side
  (:func:`rockstudy.model.equation_of_motion.angular_acceleration`, Eqs. 1–7);
* :mod:`.events`  — event detection/location on the interpolant, REST and HOLD exits;
* :mod:`.maps`    — impact (Eqs. 14–15), uplift, CS01 apex decision, fracture (Eqs. 8–13),
  the sampled controller's queue;
* :mod:`.engine`  — the driving loop (paper §3) over one state record (``R_*`` slots) and the
  run's constants (``C_*``): ``next_known_time``, ``ground_phase`` (REST/HOLD), ``known_time_events``,
  ``apex``, ``integrate`` (the step loop), ``search_events`` (the event search of one step),
  ``state_event`` (the maps);
* :mod:`.scan`    — outcomes, the one threshold scan, parallel batches.

Integration: Dormand–Prince 5(4) with error control (rtol, atol), first-same-as-last, and the
4th-order continuous extension to locate state events: impacts (θ = 0), overturning, fractures,
the CS01 switch (θ̇ = 0) and the CS02 switch (Ẍg = 0), by the Illinois method on the
interpolant (a quartic in the fraction of the step, its coefficients summed once per step).
Known-time events are never stepped over: the end of the excitation, record knots,
controller sample and actuation instants. Three modes: REST, ROCK and HOLD (the CS01 Filippov
sliding state, docs/model.md, "CS01 sliding"). See ``docs/model.md``.
"""
from rockstudy.core.constants import MAX_EVENTS, NEGLIGIBLE_STEP
from rockstudy.engine._kernel.engine import simulate_kernel
from rockstudy.engine._kernel.ground import ground_acceleration, vertical_acceleration
from rockstudy.engine._kernel.layout import *  # noqa: F401,F403  (the named parameter slots and codes)
from rockstudy.engine._kernel.scan import (
                   S_HI,
                   S_LO,
                   outcome_batch,
                   outcome_kernel,
                   outcome_serial,
                   scan_amplitude,
                   scan_start,
                   scan_update,
                   threshold_batch,
                   threshold_kernel,
                   threshold_serial,
                   uplift_floor,
)
from rockstudy.model.control import CS01, CS02, FS, PASSIVE, stiffness_on
from rockstudy.model.excitation import MODULATED as KIND_MODULATED
from rockstudy.model.excitation import ONE_SINE as KIND_ONE_SINE
from rockstudy.model.excitation import RECORD as KIND_RECORD
from rockstudy.model.excitation import RECTANGULAR as KIND_RECTANGULAR

__all__ = ["MAX_EVENTS", "NEGLIGIBLE_STEP", "CS01", "CS02", "FS", "PASSIVE", "stiffness_on", "KIND_MODULATED",
           "KIND_ONE_SINE", "KIND_RECORD", "KIND_RECTANGULAR", "ground_acceleration", "vertical_acceleration",
           "simulate_kernel", "outcome_batch", "outcome_kernel", "scan_amplitude", "scan_start", "scan_update",
           "S_HI", "S_LO",
           "threshold_batch", "threshold_kernel", "threshold_serial", "outcome_serial", "uplift_floor"]
