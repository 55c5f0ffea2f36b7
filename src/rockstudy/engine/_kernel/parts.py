"""The threshold scans' compile in two parts that run side by side.

numba compiles a function's callees before the function itself, one after the other, in one process. The
step loop (:func:`rockstudy.engine._kernel.engine.integrate` and what it calls) and the other parts of the
driver and of the scan (:data:`DRIVER_PARTS`) call nothing of each other, so two processes can compile them
at once into numba's on-disk cache: one the step loop first (:func:`compile_step_loop`) and then the scans,
which find the parts the other compiled meanwhile (:func:`compile_driver_parts`) in the cache and load them
(the scans wait 6 s less for their compile; the parts take 5 s beside the step loop's 9 s).
The workflow's rules ``compile_engine`` and ``compile_engine_parts`` do so (docs/engine.md).

Each part is named with the argument types the scans call it with (:data:`TYPE_CODES`); a part listed with
other types is compiled once more by the scans, which costs time, never a result.
``tests/engine/test_parts.py`` compiles the scans on an empty cache and checks both lists against what they
compile.
"""
from __future__ import annotations

import importlib

from numba import types

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

DRIVER_PARTS = (
    ("engine", "_log_full", "f1 i"),
    ("engine", "_grow_log", "f1 i"),
    ("engine", "_write_log", "f1 i f"),
    ("engine", "_grow_hist", "f2 i"),
    ("engine", "takes_taylor_steps", "f1 i"),
    ("engine", "setup", "f1 f1 b b"),
    ("engine", "driven_bound_data", "f1 f1 f1"),
    ("engine", "initial_state", "f1 f1 f1"),
    ("engine", "_history_row", "f1 f1 f1 f1 f2 i1"),
    ("events", "scan_exit", "i f f f f f f b f1 f1 f1"),
    ("maps", "queue_new", "f f"),
    ("scan", "scan_start", ""),
    ("scan", "scan_amplitude", "f1 f1"),
    ("scan", "bracket_closed", "f f f"),
    ("scan", "scan_update", "f1 f1 f f b"),
    ("scan", "is_overturned", "i"),
    ("scan", "uplift_floor", "f1 f"),
)
"""What the threshold scans compile besides the step loop that runs once per run (the run's set-up, the early
stops' data, the scan's state machine), never in a scan (the history and log writers), or seldom and at
length (the search of the ground phase for its exit): (module, function, argument types). The parts called
at every pass of the driver (the bounds' tests, the maps at impact and uplift) stay with the driver, in one
process: compiled apart, they made the runs 2–3 % slower (numba links a part loaded from the cache as
machine code, so LLVM no longer inlines it into the driver)."""


def signature(codes: str) -> tuple:
    """The numba argument types of ``codes`` (:data:`TYPE_CODES`, separated by spaces)."""
    return tuple(TYPE_CODES[code] for code in codes.split())


def function(module: str, name: str):
    """The compiled function ``name`` of the module named ``module`` in :data:`MODULES`."""
    return getattr(importlib.import_module(MODULES[module]), name)


def compile_parts(parts) -> None:
    """Compile each (module, function, argument types) of ``parts`` into numba's cache, or load it from there."""
    for module, name, codes in parts:
        function(module, name).compile(signature(codes))


def compile_step_loop() -> None:
    """Compile the step loop (:data:`STEP_LOOP`) and everything it calls."""
    compile_parts((STEP_LOOP,))


def compile_driver_parts() -> None:
    """Compile the driver's and the scan's other parts (:data:`DRIVER_PARTS`)."""
    compile_parts(DRIVER_PARTS)
