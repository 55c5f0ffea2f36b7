"""Dormand–Prince 5(4): one step with its error estimate, and the 4th-order continuous extension
(Shampine 1986, the one scipy's RK45 uses) that locates events inside a step."""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..motion import angular_acceleration
from .ground import ground_acceleration, vertical_acceleration
from .layout import I_COSA, I_G, I_P, I_SINA

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


@njit(cache=True)
def acceleration(th, thd, side, kap, cd, xg, yg, P):
    """θ̈ of Eqs. (1)–(7) with the block's constants from ``P``. [rad/s^2]"""
    return angular_acceleration(th, thd, side, kap, cd, xg, yg, P[I_P], P[I_G], P[I_SINA], P[I_COSA])


@njit(cache=True)
def rhs(t, th, thd, side, kap, cd, h_on, P, rec, vert):
    """θ̈ at time t (Ẍg only while the horizontal excitation is on). [rad/s^2]"""
    xg = ground_acceleration(t, P, rec) if h_on else 0.0
    yg = vertical_acceleration(t, P, vert)
    return acceleration(th, thd, side, kap, cd, xg, yg, P)


@njit(cache=True, inline="always")
def step(t, hh, y0, y1, f0, K, side, kap, cd, h_on, P, rec, vert, rtol, atol):
    """One Dormand–Prince step of size ``hh`` from (θ, θ̇) = (y0, y1) with θ̈ = f0 at t.

    Fills the stages ``K`` (7 × 2; row 6 is the derivative at the step's end, first same as last)
    and returns the 5th-order solution and the scaled error norm (accept when <= 1).
    """
    K[0, 0] = y1
    K[0, 1] = f0
    a0 = y0 + hh * A21 * K[0, 0]
    a1 = y1 + hh * A21 * K[0, 1]
    K[1, 0] = a1
    K[1, 1] = rhs(t + C2 * hh, a0, a1, side, kap, cd, h_on, P, rec, vert)
    a0 = y0 + hh * (A31 * K[0, 0] + A32 * K[1, 0])
    a1 = y1 + hh * (A31 * K[0, 1] + A32 * K[1, 1])
    K[2, 0] = a1
    K[2, 1] = rhs(t + C3 * hh, a0, a1, side, kap, cd, h_on, P, rec, vert)
    a0 = y0 + hh * (A41 * K[0, 0] + A42 * K[1, 0] + A43 * K[2, 0])
    a1 = y1 + hh * (A41 * K[0, 1] + A42 * K[1, 1] + A43 * K[2, 1])
    K[3, 0] = a1
    K[3, 1] = rhs(t + C4 * hh, a0, a1, side, kap, cd, h_on, P, rec, vert)
    a0 = y0 + hh * (A51 * K[0, 0] + A52 * K[1, 0] + A53 * K[2, 0] + A54 * K[3, 0])
    a1 = y1 + hh * (A51 * K[0, 1] + A52 * K[1, 1] + A53 * K[2, 1] + A54 * K[3, 1])
    K[4, 0] = a1
    K[4, 1] = rhs(t + C5 * hh, a0, a1, side, kap, cd, h_on, P, rec, vert)
    a0 = y0 + hh * (A61 * K[0, 0] + A62 * K[1, 0] + A63 * K[2, 0] + A64 * K[3, 0] + A65 * K[4, 0])
    a1 = y1 + hh * (A61 * K[0, 1] + A62 * K[1, 1] + A63 * K[2, 1] + A64 * K[3, 1] + A65 * K[4, 1])
    K[5, 0] = a1
    K[5, 1] = rhs(t + hh, a0, a1, side, kap, cd, h_on, P, rec, vert)
    n0 = y0 + hh * (B1 * K[0, 0] + B3 * K[2, 0] + B4 * K[3, 0] + B5 * K[4, 0] + B6 * K[5, 0])
    n1 = y1 + hh * (B1 * K[0, 1] + B3 * K[2, 1] + B4 * K[3, 1] + B5 * K[4, 1] + B6 * K[5, 1])
    K[6, 0] = n1
    K[6, 1] = rhs(t + hh, n0, n1, side, kap, cd, h_on, P, rec, vert)
    e0 = hh * (E1 * K[0, 0] + E3 * K[2, 0] + E4 * K[3, 0] + E5 * K[4, 0] + E6 * K[5, 0] + E7 * K[6, 0])
    e1 = hh * (E1 * K[0, 1] + E3 * K[2, 1] + E4 * K[3, 1] + E5 * K[4, 1] + E6 * K[5, 1] + E7 * K[6, 1])
    s0 = atol + rtol * max(abs(y0), abs(n0))
    s1 = atol + rtol * max(abs(y1), abs(n1))
    err = math.sqrt(0.5 * ((e0 / s0) ** 2 + (e1 / s1) ** 2))
    return n0, n1, err


@njit(cache=True)
def dense(sig, h, y0, y1, K):
    """State (θ, θ̇) at t0 + sig·h from the continuous extension of the step."""
    s1 = sig
    s2 = s1 * sig
    s3 = s2 * sig
    s4 = s3 * sig
    a = y0
    b = y1
    for i in range(7):
        w = DENSE[i, 0] * s1 + DENSE[i, 1] * s2 + DENSE[i, 2] * s3 + DENSE[i, 3] * s4
        a += h * w * K[i, 0]
        b += h * w * K[i, 1]
    return a, b
