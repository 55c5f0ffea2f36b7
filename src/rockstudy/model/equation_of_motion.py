"""Equation of motion of the anchored block, Eqs. (1)–(7), in normalised form.

Dividing Eq. (1) by I0 = m g R / p² gives, with s = sgn θ the pivoting side,

    θ̈ = −p² [ (1 + Ÿg/g)·sin(sα − θ) + (Ẍg/g)·cos(sα − θ) + κ·f_K·sin θ ]
         − 2ξp·f_D·cos²(θ/2)·θ̇

Makris sign convention: a positive Ẍg drives θ negative. κ is the current dimensionless
stiffness, f_K and f_D are 1 while the working-side spring / damper is intact.

:func:`angular_acceleration` is the one implementation: it is compiled with numba and called
by the fast engine (:mod:`rockstudy.engine._kernel`) and by the reference engine alike.
"""
from __future__ import annotations

import math

from rockstudy.core._inline import inline_into, njit


@njit(cache=True, inline=inline_into("acceleration"))
def angular_acceleration(theta, theta_dot, side, kappa, damping, ground_acceleration, vertical_acceleration,
                         p, gravity, sin_alpha, cos_alpha):
    """θ̈ of Eq. (1) with Eqs. (2)–(7). [rad/s^2]

    Parameters
    ----------
    theta : float
        Rotation θ. [rad]
    theta_dot : float
        Angular velocity θ̇. [rad/s]
    side : {+1.0, -1.0}
        Pivoting side s = sgn θ (needed at θ = 0). [-]
    kappa : float
        Dimensionless stiffness acting, κ·f_K: 4 K b²/(m g R) of the device state in use times
        the working-side spring's fracture function (Eqs. 6, 8–13). [-]
    damping : float
        2ξp·f_D: the damper coefficient 3 D b²/(m R²) times the working-side damper's fracture
        function (Eqs. 7, 8–13). [1/s]
    ground_acceleration, vertical_acceleration : float
        Ẍg and Ÿg. [m/s^2]
    p : float
        Frequency parameter √(3g/4R). [rad/s]
    gravity : float
        g. [m/s^2]
    sin_alpha, cos_alpha : float
        sin α and cos α of the slenderness angle (precomputed once per run). [-]
    """
    s = math.sin(theta)
    c = math.cos(theta)
    sa = side * sin_alpha
    sin_arg = sa * c - cos_alpha * s   # sin(s·α − θ)
    cos_arg = cos_alpha * c + sa * s   # cos(s·α − θ)
    # cos²(θ/2) = (1 + cos θ)/2
    return (-p * p * ((1.0 + vertical_acceleration / gravity) * sin_arg + (ground_acceleration / gravity) * cos_arg
                      + kappa * s) - damping * 0.5 * (1.0 + c) * theta_dot)


@njit(cache=True)
def normalised_energy(theta, theta_dot, p, alpha, kappa):
    """ε = θ̇²/(2p²) + cos(α − |θ|) + 2κ sin²(θ/2): mechanical energy over m g R. [-]

    Kinetic energy, the height of the centre of mass and the energy stored in a spring of
    dimensionless stiffness κ (Eq. 6), with ε = 1 when the block stands still at |θ| = α.
    """
    return theta_dot**2 / (2 * p * p) + math.cos(alpha - abs(theta)) + 2 * kappa * math.sin(0.5 * theta) ** 2
