"""Selective inlining of compiled functions (numba's ``inline=`` cost model).

A call from one compiled function to another that takes arrays pays more than the call: numba's
callee increfs and decrefs each array argument, atomically. In the Dormand–Prince step the
right-hand side is evaluated six times per step and reads the parameter vector and the records, so
those calls cost a large share of the step. Inlining them everywhere (``inline="always"``) would
also inline them at a few dozen cold call sites and nearly double numba's compile time; this
inlines them only into the functions named.
"""
from __future__ import annotations

import numba
from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic, overload


def njit(*args, **options):
    """numba's ``njit`` with ``error_model="numpy"``, the decorator of every compiled function of the engine.

    numba's default error model (``"python"``) tests every floating-point division for a zero divisor, to
    raise ``ZeroDivisionError``; ``"numpy"`` divides as IEEE 754 does (±inf or NaN), with no test and no
    branch. No run of the engine divides by zero (every divisor is guarded where it can vanish), so the
    results are bitwise the same; the step loop runs about 1 % faster.
    """
    options.setdefault("error_model", "numpy")
    return numba.njit(*args, **options)


def inline_into(*callers: str):
    """A numba ``inline=`` cost model: inline the function only where it is called from a function
    named in ``callers`` (numba's untyped inlining; elsewhere it stays an ordinary call).

    Inlining changes no floating-point operation (numba compiles without fast-math), so the
    results are bitwise the same.
    """
    names = frozenset(callers)

    def cost_model(expr, caller_ir, callee_ir):
        return caller_ir.func_id.func_name in names

    cost_model.__name__ = f"inline_into_{'_'.join(sorted(names))}"
    return cost_model


NO_REFCOUNT = {"_nrt": False}
"""numba options of a compiled function that counts no references (numba's ``_nrt`` flag).

A compiled function increfs and decrefs every array it is handed, atomically, wherever numba's
pruning leaves the pair: in the engine's step loop that was about a tenth of a run. A function
compiled with these options does no counting; it must allocate no array and return none (it may
read and write the arrays it is given, which its caller keeps alive). The flag is numba's own,
though not in its documented options, so ``tests/engine/test_fast_engine.py`` checks that the
functions compiled with it still count nothing."""


def guarded_pow(x, y):
    """``x ** y`` for floats, as a call to C's ``pow`` that runs only where the code reaches it.

    numba compiles ``**`` on floats to LLVM's ``llvm.pow`` intrinsic, which LLVM treats as free of
    side effects: it may evaluate it ahead of the test that decides whether it is needed (in the
    step loop it did, on every step, about a tenth of a run). C's ``pow`` is the very function the
    intrinsic becomes on this target, so the bits are the same; declared as itself (it may set
    ``errno``), the call stays behind its test. Plain ``x ** y`` outside compiled code.
    """
    return x ** y


@intrinsic
def _c_pow(typingctx, x, y):
    """A call to C's ``pow`` (see :func:`guarded_pow`)."""
    sig = types.float64(types.float64, types.float64)

    def codegen(context, builder, signature, args):
        fnty = ir.FunctionType(ir.DoubleType(), [ir.DoubleType(), ir.DoubleType()])
        fn = cgutils.get_or_insert_function(builder.module, fnty, "pow")
        return builder.call(fn, args)

    return sig, codegen


@overload(guarded_pow)
def _guarded_pow_compiled(x, y):
    return lambda x, y: _c_pow(float(x), float(y))
