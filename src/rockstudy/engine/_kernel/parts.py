"""The threshold scans' compile in two processes side by side.

numba compiles a function's callees before the function itself, one after the other, in one process, and
looks for each in its on-disk cache first. The workflow's rule ``compile_engine`` compiles the step loop
(:func:`rockstudy.engine._kernel.engine.integrate`, :func:`compile_step_loop`) and then the scans, and
``compile_engine_parts`` beside it compiles into the same cache what they call (:func:`compile_driver_parts`):
what the step loop calls (:data:`LOOP_PARTS`), what the driver calls (:data:`DRIVE_PARTS`) and the scan's other
parts (:data:`DRIVER_PARTS`), each before the first process asks for it, which then loads it. The first process
is left with the step loop, the driver and the scan themselves (docs/engine.md).

The machine code is the same as one process compiling everything: numba keeps each function's optimised
LLVM code in the cache beside its machine code and links that into its callers as it links a function it
has just compiled, and each part is compiled with the flags its caller's compile gives it
(:func:`compile_parts`' ``called_from``: numba's callees inherit their caller's reference counting, which
decides what LLVM inlines). ``tests/engine/test_parts.py`` compiles the scans both ways on empty caches and
compares their machine code, and checks each list against what the scans compile, with the argument types
the scans call each part with (:data:`TYPE_CODES`; a part listed with other types would be compiled once more
by the scans: time, never a result).
"""
from __future__ import annotations

import contextlib
import importlib

from numba import types
from numba.core import compiler
from numba.core.targetconfig import ConfigStack

TYPE_CODES = {"f": types.float64, "i": types.int64, "b": types.boolean, "f1": types.float64[::1],
              "f2": types.float64[:, ::1], "i1": types.int64[::1], "b1": types.boolean[::1]}
"""The argument types of the compiled parts, by code: float, int and bool scalars; C-contiguous arrays
of one or two dimensions."""

MODULES = {"dopri": "rockstudy.engine._kernel.dopri", "engine": "rockstudy.engine._kernel.engine",
           "events": "rockstudy.engine._kernel.events", "ground": "rockstudy.engine._kernel.ground",
           "maps": "rockstudy.engine._kernel.maps", "scan": "rockstudy.engine._kernel.scan",
           "anchorage": "rockstudy.model.anchorage", "control": "rockstudy.model.control",
           "equation_of_motion": "rockstudy.model.equation_of_motion", "excitation": "rockstudy.model.excitation"}
"""The modules of the compiled functions, by the short names the lists below use."""

STEP_LOOP = ("engine", "integrate", "f1 f1 f1 f1 f1 f2 f2 f f1 b1 f2 i1")
"""The step loop, (module, function, argument types): with it, numba compiles everything it calls."""

DRIVER = ("engine", "drive")
"""The driver's loop, (module, function), which the scans compile after the step loop."""

LOOP_PARTS = (
    ("dopri", "rhs", "f f f f f f b f1 f1 f1"),
    ("engine", "_ground_at", "f f1 f1"),
    ("dopri", "step", "f f f f f f2 f f f b f1 f1 f1 f f"),
    ("maps", "queue_push", "f1 b1 i i f b"),
    ("engine", "_sensed", "f1 f1 f1"),
    ("engine", "next_known_time", "f1 f1 f1 f1 f1"),
    ("engine", "_event_point", "f b f f f f f2"),
    ("engine", "_locate_sensed_on", "f f2 f f f f1 f1"),
    ("engine", "_locate_cold", "f f2 f f f"),
    ("events", "locate_poly", "f f f f f f f f"),
    ("dopri", "dense_coefficients", "f f f f2 f2"),
    ("engine", "_grown_step", "f f"),
    ("engine", "_grows_past", "f f f"),
    ("engine", "_hist_full", "f2 i"),
    ("engine", "_events_used", "f1 f1 f1"),
    ("engine", "_working", "f1"),
)
"""What the step loop calls and does not inline (the Dormand–Prince step and its right-hand side, the
event searches, the next known time, the small readers of the state), compiled as the step loop compiles
them: (module, function, argument types). The three the step loop asks for first and that take longest
come first, then the rest in the reverse of the order in which it asks for them, so that the two processes
meet halfway instead of compiling the same functions at the same time."""

DRIVE_PARTS = (
    ("maps", "impact", "f f f f f f f f"),
    ("maps", "fracture", "f f f f1 f1 f1 f f"),
    ("maps", "cannot_overturn", "f f f f f"),
    ("maps", "cannot_overturn_switching", "f f f f f f f"),
    ("engine", "below_overturning_energy", "f1 f1 f1"),
    ("maps", "apex_decision", "f f f f f f f1"),
    ("engine", "_turn", "f1 i"),
    ("ground", "vertical_acceleration", "f f1 f1"),
    ("maps", "uplift_side", "f"),
    ("engine", "_write_log", "f1 i f"),
    ("events", "scan_exit", "i f f f f f f b f1 f1 f1"),
    ("engine", "ground_phase", "f1 f1 f1 f1 f1 f"),
    ("engine", "pass_quiet_knots", "f1 f1 f1 f1 f1 f1 f1 b1 f"),
    ("engine", "_knot_before", "f f1 f1"),
    ("engine", "_history_row", "f1 f1 f1 f1 f2 i1"),
    ("engine", "_room_full", "f1 f2 f1 f1 f1 i1"),
)
"""What the driver calls besides the step loop (the ground phase and its exit search, the rest under a
record, the maps at impact, uplift and fracture, the energy bound, the history and log writers), compiled as
the driver compiles them, in about the reverse of the order in which it asks for them. The parts of the
driver that run at every pass or state event (the state event's maps, the apex, the impulse bound) are
inlined into it (``core._inline.inline_into``): as calls they made the scans 2–5 % slower."""

DRIVER_PARTS = (
    ("engine", "setup", "f1 f1 b b"),
    ("engine", "driven_bound_data", "f1 f1 f1"),
    ("engine", "initial_state", "f1 f1 f1"),
    ("maps", "queue_new", "f f"),
    ("scan", "scan_start", ""),
    ("scan", "scan_amplitude", "f1 f1"),
    ("scan", "uplift_floor", "f1 f"),
    ("scan", "bracket_closed", "f f f"),
    ("scan", "scan_update", "f1 f1 f f b"),
    ("scan", "is_overturned", "i"),
    ("engine", "_log_full", "f1 i"),
    ("engine", "_grow_log", "f1 i"),
    ("engine", "_grow_hist", "f2 i"),
    ("engine", "takes_taylor_steps", "f1 i"),
)
"""What the scan calls besides the driver, once per run (the run's set-up, the early stops' data, the scan's
state machine) or never in a scan (growing the history and the logs)."""


def signature(codes: str) -> tuple:
    """The numba argument types of ``codes`` (:data:`TYPE_CODES`, separated by spaces)."""
    return tuple(TYPE_CODES[code] for code in codes.split())


def function(module: str, name: str):
    """The compiled function ``name`` of the module named ``module`` in :data:`MODULES`."""
    return getattr(importlib.import_module(MODULES[module]), name)


def caller_flags(module: str, name: str):
    """numba's compile flags of the function ``name``: those a function it calls is compiled with (numba's
    callees inherit their caller's reference counting, error model and fast-math where they set none)."""
    caller = function(module, name)
    flags = compiler.Flags()
    caller.targetdescr.options.parse_as_flags(flags, caller.targetoptions)
    return flags


def compile_parts(parts, called_from=None) -> None:
    """Compile each (module, function, argument types) of ``parts`` into numba's cache, or load it from there;
    as the compiled function ``called_from`` (module, name) would compile it, when given."""
    with ConfigStack().enter(caller_flags(*called_from)) if called_from else contextlib.nullcontext():
        for module, name, codes in parts:
            function(module, name).compile(signature(codes))


def compile_step_loop() -> None:
    """Compile the step loop (:data:`STEP_LOOP`) and everything it calls."""
    compile_parts((STEP_LOOP,))


def compile_driver_parts() -> None:
    """Compile what the step loop calls (:data:`LOOP_PARTS`), what the driver calls (:data:`DRIVE_PARTS`)
    and the scan's other parts (:data:`DRIVER_PARTS`), each as its caller compiles it."""
    compile_parts(LOOP_PARTS, called_from=STEP_LOOP[:2])
    compile_parts(DRIVE_PARTS, called_from=DRIVER)
    compile_parts(DRIVER_PARTS)
