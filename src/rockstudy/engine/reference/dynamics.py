"""The block's equation of motion on one corner, and the restrainers that can break (Eqs. 1–13).

The formula itself is :func:`rockstudy.model.equation_of_motion.angular_acceleration` (Eqs. 1–7), shared with the
fast engine; this module only supplies its arguments: the working side, the acting stiffness
κ·f_K and damping 2ξp·f_D of the intact elements on that side (Eqs. 4–5 with the fracture
functions of Eqs. 8–11), and the ground motion at t.
"""
from __future__ import annotations

import math

import numpy as np

from rockstudy.engine.reference.ground import Excitation
from rockstudy.engine.simulation_result import FRACTURE_ELEMENTS
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import Block
from rockstudy.model.equation_of_motion import angular_acceleration
from rockstudy.model.excitation import GroundMotion

ELEMENTS = FRACTURE_ELEMENTS
"""Restrainer elements; the "left" ones work while the block rocks on θ > 0 (side +1)."""


class Dynamics:
    """θ̈ of Eq. (1) for a block on a given corner under an :class:`Excitation`.

    Parameters
    ----------
    block : Block
        Frequency parameter p [rad/s], slenderness α [rad], gravity g [m/s^2].
    damping : float
        Damper term 2ξp of the anchorage (0 without one). [1/s]
    excitation : Excitation
        Scalar Ẍg(t), Ÿg(t). [m/s^2]
    """

    def __init__(self, block: Block, damping: float, excitation: Excitation):
        self.p = block.p
        self.gravity = block.gravity
        self.tan_alpha = block.b / block.h
        self.sin_alpha, self.cos_alpha = math.sin(block.alpha), math.cos(block.alpha)
        self.damping = damping
        self.excitation = excitation

    def acceleration(self, t: float, theta: float, theta_dot: float, side: int, kappa: float,
                     spring_ok: bool, damper_ok: bool) -> float:
        """θ̈ of Eqs. (1)–(7) on corner ``side`` with stiffness ``kappa`` if the spring is intact. [rad/s^2]

        Parameters
        ----------
        t : float
            Time. [s]
        theta, theta_dot : float
            Rotation [rad] and angular velocity [rad/s].
        side : {1, -1}
            Pivoting corner: +1 for θ > 0.
        kappa : float
            Dimensionless stiffness the device applies (κ_max or κ_min). [-]
        spring_ok, damper_ok : bool
            The working side's spring and damper are intact (Eqs. 8–11).
        """
        ex = self.excitation
        return angular_acceleration(theta, theta_dot, float(side), float(kappa * spring_ok),
                                    self.damping * damper_ok, ex.horizontal(t), ex.vertical(t), self.p,
                                    self.gravity, self.sin_alpha, self.cos_alpha)

    def uplift_margin(self, t: float) -> float:
        """|Ẍg| − (g + Ÿg)·tanα: positive when the ground lifts a block at rest (Eq. 15). [m/s^2]

        Parameters
        ----------
        t : float
            Time at which the ground motion is evaluated. [s]
        """
        ex = self.excitation
        return abs(ex.horizontal(t)) - (self.gravity + ex.vertical(t)) * self.tan_alpha

    def uplift_window(self, t: float, motion: GroundMotion):
        """For records and pulses: the knot interval in which uplift can first happen after t.

        Between knots Ẍg and Ÿg are linear, so the margin |Ẍg| − (g + Ÿg)·tanα is convex there
        and can only become positive in the interval that ends at the first knot where it is.

        Parameters
        ----------
        t : float
            Time at rest. [s]
        motion : GroundMotion
            The motion (its array form evaluates the margin at every knot). [m/s^2]

        Returns
        -------
        (float, float) or None
            (start, end) of that interval [s], or None if there is no uplift before the end.
        """
        knots = self.excitation.knots
        ahead = knots[knots > t]
        margin = (np.abs(motion.horizontal(ahead))
                  - (self.gravity + motion.vertical_acceleration(ahead)) * self.tan_alpha)
        positive = np.nonzero(margin > 0.0)[0]
        if len(positive) == 0:
            return None
        j = positive[0]
        return (ahead[j - 1] if j > 0 else t), float(ahead[j])


class RockingRHS:
    """Right-hand side y' = (θ̇, θ̈) of one rocking piece for ``solve_ivp`` (Eq. 1).

    The corner, the stiffness and the intact elements do not change within a piece, so they
    are fixed here once.

    Parameters
    ----------
    dynamics : Dynamics
        The block and its excitation.
    side : {1, -1}
        Pivoting corner.
    kappa_acting : float
        κ·f_K of the working side. [-]
    damping : float
        2ξp·f_D of the working side. [1/s]
    """

    def __init__(self, dynamics: Dynamics, side: int, kappa_acting: float, damping: float):
        self.dynamics = dynamics
        self.excitation = dynamics.excitation
        self.side = float(side)
        self.kappa_acting = float(kappa_acting)
        self.damping = float(damping)

    def __call__(self, t: float, y) -> tuple:
        """(θ̇, θ̈) at t for y = (θ, θ̇). [rad/s], [rad/s^2]"""
        d, ex = self.dynamics, self.excitation
        return (y[1], angular_acceleration(float(y[0]), float(y[1]), self.side, self.kappa_acting, self.damping,
                                           ex.horizontal(t), ex.vertical(t), d.p, d.gravity, d.sin_alpha,
                                           d.cos_alpha))


class Restrainers:
    """Which springs and dampers are still intact, and when the others broke (Eqs. 8–13).

    An element breaks for good when the block reaches its ultimate rotation on the element's
    working side; Eqs. (8)–(11) then give f = 0 for the rest of the run.

    Parameters
    ----------
    anchorage : Anchorage
        Ultimate rotations θ_K,u and θ_D,u.
    block : Block
        Geometry (the ultimate rotations default to α).
    anchored : bool
        False for FS or an inert anchorage: no elements at all.
    """

    def __init__(self, anchorage: Anchorage, block: Block, anchored: bool):
        spring, damper = anchorage.theta_spring(block), anchorage.theta_damper(block)
        self.theta_ultimate = {"spring_left": spring, "spring_right": spring,
                               "damper_left": damper, "damper_right": damper}
        self.intact = {name: anchored for name in ELEMENTS}
        self.fracture_times: dict[str, float] = {}

    def spring_ok(self, side: int) -> bool:
        """The spring working on corner ``side`` is intact.

        Parameters
        ----------
        side : {1, -1}
            Pivoting corner: +1 for θ > 0 (the left elements), -1 for θ < 0 (the right ones).
        """
        return self.intact["spring_left" if side > 0 else "spring_right"]

    def damper_ok(self, side: int) -> bool:
        """The damper working on corner ``side`` is intact.

        Parameters
        ----------
        side : {1, -1}
            Pivoting corner: +1 for θ > 0 (the left elements), -1 for θ < 0 (the right ones).
        """
        return self.intact["damper_left" if side > 0 else "damper_right"]

    def working(self, side: int) -> list[str]:
        """Intact elements that work while the block pivots on corner ``side``.

        Parameters
        ----------
        side : {1, -1}
            Pivoting corner: +1 for θ > 0 (the left elements), -1 for θ < 0 (the right ones).
        """
        suffix = "left" if side > 0 else "right"
        return [name for name in ELEMENTS if name.endswith(suffix) and self.intact[name]]

    def fracture(self, name: str, t: float) -> None:
        """Break element ``name`` at time ``t``; it stays broken for the rest of the run.

        Parameters
        ----------
        name : str
            One of :data:`ELEMENTS`.
        t : float
            Time of the fracture, kept in ``fracture_times``. [s]
        """
        self.intact[name] = False
        self.fracture_times[name] = t
