"""Writes :mod:`rockstudy.engine._kernel.taylor`: the Taylor-series step between record knots, as
straight-line scalar code (every coefficient a local variable, so that the compiled step keeps them
in registers and allocates nothing).

Run ``python -m rockstudy.engine._kernel._generate_taylor`` after changing :data:`ORDER` or the
recurrences below; ``tests/engine/test_taylor.py`` checks that the module on disk is what this
writes.

The recurrences (automatic differentiation of Eq. 1 between two record knots, where Ẍg is linear in
τ = t − t₀ and Ÿg = 0): with θ = Σ a_k τ^k, sin θ = Σ s_k τ^k, cos θ = Σ c_k τ^k and b_k = k·a_k,

    s_0 = sin a_0,  c_0 = cos a_0,
    s_k = (1/k) Σ_{j=1..k} b_j·c_{k−j},   c_k = −(1/k) Σ_{j=1..k} b_j·s_{k−j}        (k >= 1)

and, with u = Ẍg/g = u_0 + u_1·τ, A = s·sinα + cosα·u and B = κ − cosα + s·sinα·u (s the pivoting side),
Eq. (1) θ̈ = −p²(A·cos θ + B·sin θ) − (c_d/2)(1 + cos θ)·θ̇ gives

    (k + 1)(k + 2)·a_{k+2} = −p²(A_0 c_k + A_1 c_{k−1} + B_0 s_k + B_1 s_{k−1})
                             − (c_d/2)(b_{k+1} + Σ_{j=0..k} c_j·b_{k+1−j}).
"""
from __future__ import annotations

from pathlib import Path

ORDER = 6
"""Degree of the θ polynomial of a step; its last term is the step's error estimate."""

HEADER = '''"""The Taylor-series step between record knots (written by
:mod:`rockstudy.engine._kernel._generate_taylor`; do not edit by hand).

Between two knots of a record Ẍg is linear and Ÿg = 0, so θ(t₀ + τ) is analytic on the step and its
Taylor coefficients follow from Eq. (1) by recurrences (automatic differentiation; the module that
writes this file states them). One step costs one sine and cosine and a few dozen multiply-adds,
where a Dormand–Prince step costs six evaluations of Eq. (1), each with its own sine and cosine,
one after the other. The step's polynomial is its own continuous extension: the events are located
on it as on Dormand–Prince's quartic (:mod:`rockstudy.engine._kernel.events`).
"""
from __future__ import annotations

import math

from rockstudy.core._inline import NO_REFCOUNT, inline_into, njit

ORDER = {order}
"""Degree of the θ polynomial (θ̇'s is one less); the last term is the error estimate."""


@njit(cache=True, inline=inline_into("integrate"), **NO_REFCOUNT)
def step(hh, y0, y1, side, kap, cd, u0, u1, p, sin_alpha, cos_alpha, Q, rtol, atol):
    """One Taylor step of size ``hh`` from (θ, θ̇) = (y0, y1), with Ẍg/g = u0 + u1·τ on the step.

    Writes the step's polynomials in the fraction sig of the step to ``Q`` (θ = Σ_j Q[0, j]·sig^j,
    j = 0 … ORDER; θ̇ = Σ_j Q[1, j]·sig^j, j = 0 … ORDER − 1; the columns beyond are set to 0) and
    returns (θ, θ̇) at the step's end, the scaled error norm of the last terms (accept when <= 1)
    and θ̈ at the step's end (from the polynomial). [rad, rad/s, -, rad/s^2]

    Inlined into the step loop (``engine.integrate``; measured 0–7 % faster per run than a call,
    2 s more compilation), elsewhere compiled without reference counting
    (``core._inline.NO_REFCOUNT``): it writes ``Q`` only.
    """
    pp = p * p
    sa = side * sin_alpha
    A0 = sa + cos_alpha * u0
    A1 = cos_alpha * u1
    B0 = kap - cos_alpha + sa * u0
    B1 = sa * u1
    hd = 0.5 * cd
    a0 = y0
    a1 = y1
    b1 = y1
    s0 = math.sin(a0)
    c0 = math.cos(a0)
'''


def _sum(terms: list[str]) -> str:
    return " + ".join(terms) if terms else "0.0"


def source(order: int = ORDER) -> str:
    """The text of the generated module for a θ polynomial of degree ``order`` (>= 3)."""
    if order < 3:
        raise ValueError(f"order must be at least 3, got {order}")
    lines = [HEADER.format(order=order).rstrip("\n")]
    ind = "    "
    # level k gives b_{k+2} = (k + 2)·a_{k+2} = f_k/(k + 1), written so that the chain from one
    # level to the next is short: b_{k+1} enters by one multiply-add, b_k by five operations
    lines.append(f"{ind}f0 = -pp * (A0 * c0 + B0 * s0) - hd * (b1 + c0 * b1)")
    lines.append(f"{ind}b2 = f0")
    lines.append(f"{ind}hd1 = hd * (1.0 + c0)")
    lines.append(f"{ind}ac = -pp * A0 - hd * b1")
    lines.append(f"{ind}bs = -pp * B0")
    for k in range(1, order - 1):
        inv, inv1 = 1.0 / k, 1.0 / (k + 1)
        ps = _sum([f"b{j} * c{k - j}" for j in range(1, k)])
        pc = _sum([f"b{j} * s{k - j}" for j in range(1, k)])
        if k == 1:
            lines.append(f"{ind}s1 = b1 * c0")
            lines.append(f"{ind}c1 = -(b1 * s0)")
        else:
            lines.append(f"{ind}s{k} = ({ps}) * {inv!r} + b{k} * (c0 * {inv!r})")
            lines.append(f"{ind}c{k} = -(({pc}) * {inv!r}) - b{k} * (s0 * {inv!r})")
        damp = _sum([f"c{j} * b{k + 1 - j}" for j in range(1, k)])
        lines.append(f"{ind}e{k} = -pp * (A1 * c{k - 1} + B1 * s{k - 1}) - hd * ({damp})")
        lines.append(f"{ind}b{k + 2} = (e{k} + bs * s{k} + ac * c{k}) * {inv1!r} - (hd1 * {inv1!r}) * b{k + 1}")
    for k in range(2, order + 1):
        lines.append(f"{ind}a{k} = b{k} * {1.0 / k!r}")
    # scale to the fraction of the step: Q[0, j] = a_j·h^j, Q[1, j] = b_{j+1}·h^j
    lines.append(f"{ind}h1 = hh")
    for j in range(2, order + 1):
        lines.append(f"{ind}h{j} = h{j - 1} * hh")
    lines.append(f"{ind}Q[0, 0] = a0")
    lines.append(f"{ind}Q[1, 0] = b1")
    for j in range(1, order + 1):
        lines.append(f"{ind}Q[0, {j}] = a{j} * h{j}")
        if j < order:
            lines.append(f"{ind}Q[1, {j}] = b{j + 1} * h{j}")
    lines.append(f"{ind}for j in range({order}, Q.shape[1]):")
    lines.append(f"{ind}    Q[1, j] = 0.0")
    lines.append(f"{ind}for j in range({order + 1}, Q.shape[1]):")
    lines.append(f"{ind}    Q[0, j] = 0.0")
    # the end of the step, small terms first (n0 is exactly the θ polynomial at sig = 1 by Horner)
    lines.append(f"{ind}n0 = a{order} * h{order}")
    for j in range(order - 1, 0, -1):
        lines.append(f"{ind}n0 = n0 + a{j} * h{j}")
    lines.append(f"{ind}n0 = n0 + a0")
    lines.append(f"{ind}n1 = b{order} * h{order - 1}")
    for j in range(order - 1, 1, -1):
        lines.append(f"{ind}n1 = n1 + b{j} * h{j - 1}")
    lines.append(f"{ind}n1 = n1 + b1")
    lines.append(f"{ind}f_end = {float(order - 1)!r} * b{order} * h{order - 2}")
    for j in range(order - 1, 2, -1):
        lines.append(f"{ind}f_end = f_end + {float(j - 1)!r} * b{j} * h{j - 2}")
    lines.append(f"{ind}f_end = f_end + b2")
    lines.append(f"{ind}err0 = a{order} * h{order}")
    lines.append(f"{ind}err1 = b{order} * h{order - 1}")
    lines.append(f"{ind}w0 = err0 / (atol + rtol * max(abs(y0), abs(n0)))")
    lines.append(f"{ind}w1 = err1 / (atol + rtol * max(abs(y1), abs(n1)))")
    lines.append(f"{ind}err = math.sqrt(0.5 * (w0 * w0 + w1 * w1))")
    lines.append(f"{ind}return n0, n1, err, f_end")
    return "\n".join(lines) + "\n"


def write(path: Path | None = None) -> Path:
    """Write the generated module next to this one (or to ``path``)."""
    path = path or Path(__file__).with_name("taylor.py")
    path.write_text(source(), encoding="utf-8")
    return path


if __name__ == "__main__":
    print(write())
