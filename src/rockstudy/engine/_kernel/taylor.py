"""The Taylor-series step between record knots (written by
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

ORDER = 6
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
    f0 = -pp * (A0 * c0 + B0 * s0) - hd * (b1 + c0 * b1)
    b2 = f0
    hd1 = hd * (1.0 + c0)
    ac = -pp * A0 - hd * b1
    bs = -pp * B0
    s1 = b1 * c0
    c1 = -(b1 * s0)
    e1 = -pp * (A1 * c0 + B1 * s0) - hd * (0.0)
    b3 = (e1 + bs * s1 + ac * c1) * 0.5 - (hd1 * 0.5) * b2
    s2 = (b1 * c1) * 0.5 + b2 * (c0 * 0.5)
    c2 = -((b1 * s1) * 0.5) - b2 * (s0 * 0.5)
    e2 = -pp * (A1 * c1 + B1 * s1) - hd * (c1 * b2)
    b4 = (e2 + bs * s2 + ac * c2) * 0.3333333333333333 - (hd1 * 0.3333333333333333) * b3
    s3 = (b1 * c2 + b2 * c1) * 0.3333333333333333 + b3 * (c0 * 0.3333333333333333)
    c3 = -((b1 * s2 + b2 * s1) * 0.3333333333333333) - b3 * (s0 * 0.3333333333333333)
    e3 = -pp * (A1 * c2 + B1 * s2) - hd * (c1 * b3 + c2 * b2)
    b5 = (e3 + bs * s3 + ac * c3) * 0.25 - (hd1 * 0.25) * b4
    s4 = (b1 * c3 + b2 * c2 + b3 * c1) * 0.25 + b4 * (c0 * 0.25)
    c4 = -((b1 * s3 + b2 * s2 + b3 * s1) * 0.25) - b4 * (s0 * 0.25)
    e4 = -pp * (A1 * c3 + B1 * s3) - hd * (c1 * b4 + c2 * b3 + c3 * b2)
    b6 = (e4 + bs * s4 + ac * c4) * 0.2 - (hd1 * 0.2) * b5
    a2 = b2 * 0.5
    a3 = b3 * 0.3333333333333333
    a4 = b4 * 0.25
    a5 = b5 * 0.2
    a6 = b6 * 0.16666666666666666
    h1 = hh
    h2 = h1 * hh
    h3 = h2 * hh
    h4 = h3 * hh
    h5 = h4 * hh
    h6 = h5 * hh
    Q[0, 0] = a0
    Q[1, 0] = b1
    Q[0, 1] = a1 * h1
    Q[1, 1] = b2 * h1
    Q[0, 2] = a2 * h2
    Q[1, 2] = b3 * h2
    Q[0, 3] = a3 * h3
    Q[1, 3] = b4 * h3
    Q[0, 4] = a4 * h4
    Q[1, 4] = b5 * h4
    Q[0, 5] = a5 * h5
    Q[1, 5] = b6 * h5
    Q[0, 6] = a6 * h6
    for j in range(6, Q.shape[1]):
        Q[1, j] = 0.0
    for j in range(7, Q.shape[1]):
        Q[0, j] = 0.0
    n0 = a6 * h6
    n0 = n0 + a5 * h5
    n0 = n0 + a4 * h4
    n0 = n0 + a3 * h3
    n0 = n0 + a2 * h2
    n0 = n0 + a1 * h1
    n0 = n0 + a0
    n1 = b6 * h5
    n1 = n1 + b5 * h4
    n1 = n1 + b4 * h3
    n1 = n1 + b3 * h2
    n1 = n1 + b2 * h1
    n1 = n1 + b1
    f_end = 5.0 * b6 * h4
    f_end = f_end + 4.0 * b5 * h3
    f_end = f_end + 3.0 * b4 * h2
    f_end = f_end + 2.0 * b3 * h1
    f_end = f_end + b2
    err0 = a6 * h6
    err1 = b6 * h5
    w0 = err0 / (atol + rtol * max(abs(y0), abs(n0)))
    w1 = err1 / (atol + rtol * max(abs(y1), abs(n1)))
    err = math.sqrt(0.5 * (w0 * w0 + w1 * w1))
    return n0, n1, err, f_end
