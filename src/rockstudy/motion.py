"""Equation of motion of the anchored block, Eqs. (1)–(7), in normalised form.

Dividing Eq. (1) by I0 = m g R / p² gives, with s = sgn θ the pivoting side,

    θ̈ = −p² [ (1 + Ÿg/g)·sin(sα − θ) + (Ẍg/g)·cos(sα − θ) + κ·f_K·sin θ ]
         − 2ξp·f_D·cos²(θ/2)·θ̇

Makris sign convention: a positive Ẍg drives θ negative. κ is the current dimensionless
stiffness, f_K and f_D are 1 while the working-side spring / damper is intact.
"""
from __future__ import annotations

import math


def angular_acceleration(theta, theta_dot, side, kappa, spring_intact, damper_intact,
                         ground_acceleration, vertical_acceleration, p, alpha, gravity, damping_ratio):
    """θ̈ of Eq. (1) with Eqs. (2)–(7). [rad/s^2]

    Parameters
    ----------
    theta : float
        Rotation θ. [rad]
    theta_dot : float
        Angular velocity θ̇. [rad/s]
    side : {+1, -1}
        Pivoting side s = sgn θ (needed at θ = 0). [-]
    kappa : float
        Dimensionless stiffness in use, 4 K b²/(m g R). [-]
    spring_intact, damper_intact : bool
        Fracture functions f_K, f_D of the working side (Eqs. 8–13). [-]
    ground_acceleration, vertical_acceleration : float
        Ẍg and Ÿg. [m/s^2]
    p : float
        Frequency parameter. [rad/s]
    alpha : float
        Slenderness angle. [rad]
    gravity : float
        g. [m/s^2]
    damping_ratio : float
        ξ, with 3 D b²/(m R²) = 2 ξ p. [-]
    """
    arg = side * alpha - theta
    gravity_term = (1.0 + vertical_acceleration / gravity) * math.sin(arg)
    excitation_term = (ground_acceleration / gravity) * math.cos(arg)
    spring_term = kappa * math.sin(theta) if spring_intact else 0.0
    damper = 2.0 * damping_ratio * p * math.cos(0.5 * theta) ** 2 * theta_dot if damper_intact else 0.0
    return -p * p * (gravity_term + excitation_term + spring_term) - damper


def normalised_energy(theta, theta_dot, p, alpha, kappa):
    """ε = θ̇²/(2p²) + cos(α − |θ|) + 2κ sin²(θ/2): mechanical energy over m g R. [-]"""
    return theta_dot**2 / (2 * p * p) + math.cos(alpha - abs(theta)) + 2 * kappa * math.sin(0.5 * theta) ** 2
