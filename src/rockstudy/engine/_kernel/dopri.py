"""Dormand–Prince 5(4): one step with its error estimate, and the 4th-order continuous extension
(Shampine 1986, the one scipy's RK45 uses) that locates events inside a step."""
from __future__ import annotations

import math

import numpy as np

from rockstudy.core._inline import NO_REFCOUNT, inline_into, njit
from rockstudy.engine._kernel.ground import ground_acceleration, vertical_acceleration
from rockstudy.engine._kernel.layout import I_COSA, I_G, I_P, I_SINA
from rockstudy.model.equation_of_motion import angular_acceleration

C2, C3, C4, C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
A21 = 1 / 5
A31, A32 = 3 / 40, 9 / 40
A41, A42, A43 = 44 / 45, -56 / 15, 32 / 9
A51, A52, A53, A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
A61, A62, A63, A64, A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
B1, B3, B4, B5, B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
E1, E3, E4, E5, E6, E7 = -71 / 57600, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40
# continuous extension (scipy RK45.P), rows k1..k7, columns sigma^1..sigma^4
DENSE = np.array([
    [1, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0, 0, 0, 0],
    [0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
    [0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
    [0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
])


NQ = 7
"""Columns of a step's polynomial array ``Q``: degree 6, the Taylor step's
(:mod:`~rockstudy.engine._kernel.taylor`); Dormand–Prince's quartic leaves the columns above 4 zero."""


@njit(cache=True, inline=inline_into("rhs", "step", "exit_value"))
def acceleration(th, thd, side, kap, cd, xg, yg, P):
    """θ̈ of Eqs. (1)–(7) with the block's constants from ``P``. [rad/s^2]"""
    return angular_acceleration(th, thd, side, kap, cd, xg, yg, P[I_P], P[I_G], P[I_SINA], P[I_COSA])


@njit(cache=True, **NO_REFCOUNT)
def rhs(t, th, thd, side, kap, cd, h_on, P, rec, vert):
    """θ̈ at time t (Ẍg only while the horizontal excitation is on). [rad/s^2]"""
    xg = ground_acceleration(t, P, rec) if h_on else 0.0
    yg = vertical_acceleration(t, P, vert)
    return acceleration(th, thd, side, kap, cd, xg, yg, P)


# the stages 2-7 as a table: row s - 1 holds stage s's coefficients of k_1 ... k_(s-1) (zeros are
# skipped, as in the written-out sums), the last row being the 5th-order weights (FSAL)
STAGE_TIME = np.array([C2, C3, C4, C5, 1.0, 1.0])
STAGE = np.array([
    [A21, 0, 0, 0, 0, 0],
    [A31, A32, 0, 0, 0, 0],
    [A41, A42, A43, 0, 0, 0],
    [A51, A52, A53, A54, 0, 0],
    [A61, A62, A63, A64, A65, 0],
    [B1, 0, B3, B4, B5, B6],
])


@njit(cache=True, **NO_REFCOUNT)
def step(t, hh, y0, y1, f0, K, side, kap, cd, h_on, P, rec, vert, rtol, atol):
    """One Dormand–Prince step of size ``hh`` from (θ, θ̇) = (y0, y1) with θ̈ = f0 at t.

    Fills the stages ``K`` (7 × 2; row 6 is the derivative at the step's end, first same as last)
    and returns the 5th-order solution and the scaled error norm (accept when <= 1). The stages
    are one loop over the :data:`STAGE` table, so that the right-hand side is compiled once.
    Called, not inlined, from the step loop (``engine.integrate``): inlined, it made the loop's
    compilation a fifth slower and the runs no faster. It allocates nothing and counts no references
    (``core._inline.NO_REFCOUNT``).
    """
    K[0, 0] = y1
    K[0, 1] = f0
    a0 = y0
    a1 = y1
    xg = 0.0
    yg = 0.0
    for s in range(1, 7):
        if s == 1:  # written (h·a21)·k1, not h·(a21·k1): the grouping of the step's first form, for its bits
            a0 = y0 + hh * STAGE[0, 0] * K[0, 0]
            a1 = y1 + hh * STAGE[0, 0] * K[0, 1]
        else:
            c0 = STAGE[s - 1, 0] * K[0, 0]
            c1 = STAGE[s - 1, 0] * K[0, 1]
            for j in range(1, s):
                w = STAGE[s - 1, j]
                if w != 0.0:
                    c0 = c0 + w * K[j, 0]
                    c1 = c1 + w * K[j, 1]
            a0 = y0 + hh * c0
            a1 = y1 + hh * c1
        K[s, 0] = a1
        if s != 6:  # stages 6 and 7 are both at t + h: one reading of the ground motion serves both
            ts = t + STAGE_TIME[s - 1] * hh  # the reading of rhs, written out to stay inlined here
            xg = ground_acceleration(ts, P, rec) if h_on else 0.0
            yg = vertical_acceleration(ts, P, vert)
        K[s, 1] = acceleration(a0, a1, side, kap, cd, xg, yg, P)
    n0 = a0  # the last stage is the 5th-order solution (first same as last)
    n1 = a1
    e0 = hh * (E1 * K[0, 0] + E3 * K[2, 0] + E4 * K[3, 0] + E5 * K[4, 0] + E6 * K[5, 0] + E7 * K[6, 0])
    e1 = hh * (E1 * K[0, 1] + E3 * K[2, 1] + E4 * K[3, 1] + E5 * K[4, 1] + E6 * K[5, 1] + E7 * K[6, 1])
    s0 = atol + rtol * max(abs(y0), abs(n0))
    s1 = atol + rtol * max(abs(y1), abs(n1))
    err = math.sqrt(0.5 * ((e0 / s0) ** 2 + (e1 / s1) ** 2))
    return n0, n1, err


@njit(cache=True, **NO_REFCOUNT)
def dense_coefficients(h, y0, y1, K, Q):
    """The step's continuous extension as two quartics in sig, the fraction of the step:
    θ(t0 + sig·h) = Σ_j Q[0, j]·sig^j and θ̇ = Σ_j Q[1, j]·sig^j (j = 0 … 4; the columns above are
    set to 0), from the stages ``K``.

    Computed once for a step whose events are located: each point on the step is then a Horner
    evaluation (:func:`dense_at`) instead of a sum over the seven stages.
    """
    Q[0, 0] = y0
    Q[1, 0] = y1
    for j in range(4):
        c0 = DENSE[0, j] * K[0, 0]
        c1 = DENSE[0, j] * K[0, 1]
        for i in range(2, 7):  # the row of k2 is zero
            c0 += DENSE[i, j] * K[i, 0]
            c1 += DENSE[i, j] * K[i, 1]
        Q[0, j + 1] = h * c0
        Q[1, j + 1] = h * c1
    for j in range(5, Q.shape[1]):
        Q[0, j] = 0.0
        Q[1, j] = 0.0


@njit(cache=True, inline="always")
def dense_at(sig, Q):
    """State (θ, θ̇) at t0 + sig·h from the step's polynomials ``Q`` (:func:`dense_coefficients`, or the
    Taylor step's), by Horner over all :data:`NQ` columns (zero columns leave the bits of the quartic's)."""
    n = Q.shape[1] - 1
    a = Q[0, n]
    b = Q[1, n]
    for j in range(n - 1, -1, -1):
        a = a * sig + Q[0, j]
        b = b * sig + Q[1, j]
    return a, b


@njit(cache=True)
def dense(sig, h, y0, y1, K):
    """State (θ, θ̇) at t0 + sig·h from the continuous extension of the step (its stages ``K``)."""
    Q = np.empty((2, 5))
    dense_coefficients(h, y0, y1, K, Q)
    return dense_at(sig, Q)
