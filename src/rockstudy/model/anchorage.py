"""Elastic-brittle semi-active anchorages at the two lower corners (paper Eqs. 4–13).

The device parameters are given in dimensionless form so that they scale with the
block (the paper does not publish its values):

* kappa = 4 K b^2 / (m g R): spring moment K·4b^2·sin(theta) over m g R;
* xi: damper ratio with 3 D b^2 / (m R^2) = 2 xi p;
* ultimate rotations theta_K,u and theta_D,u (default: alpha).
"""
from __future__ import annotations

import math
from dataclasses import InitVar, dataclass

from rockstudy.core._inline import njit
from rockstudy.core.quantities import check_arguments, declares
from rockstudy.core.validation import field_names
from rockstudy.model.block import Block


@declares(kappa_max="kappa", kappa_min="kappa", damping_ratio="damping_ratio",
          spring_ultimate_rotation="ultimate_rotation", damper_ultimate_rotation="ultimate_rotation")
@dataclass(frozen=True)
class Anchorage:
    """Dimensionless description of the restrainers.

    Parameters
    ----------
    kappa_max : float, default 1.0
        Dimensionless stiffness 4 K_max b^2 / (m g R) of the "on" state. [-]
    kappa_min : float, default 0.0
        Dimensionless stiffness 4 K_min b^2 / (m g R) of the "off" state. [-]
    damping_ratio : float, default 0.05
        xi with 3 D b^2 / (m R^2) = 2 xi p. [-]
    spring_ultimate_rotation : float or None
        theta_K,u, rotation at which a spring breaks; None means alpha. [rad]
    damper_ultimate_rotation : float or None
        theta_D,u, rotation at which a damper breaks; None means alpha. [rad]
    names : dict, optional
        The caller's name of each field in error messages (``{"kappa_max": "--kappa-max"}``); a field missing
        from it is named ``Anchorage.<field>``. Not stored.

    Raises
    ------
    ValueError
        (:class:`~rockstudy.core.validation.InputError` for a range) naming the field, its value and what is
        allowed: the one check of an anchorage, at construction (:meth:`check`).
    """

    kappa_max: float = 1.0
    kappa_min: float = 0.0
    damping_ratio: float = 0.05
    spring_ultimate_rotation: float | None = None
    damper_ultimate_rotation: float | None = None
    names: InitVar[dict | None] = None

    def __post_init__(self, names):
        self.check(names, **self.__dict__)

    @staticmethod
    def check(names=None, *, kappa_max=1.0, kappa_min=0.0, damping_ratio=0.05, spring_ultimate_rotation=None,
              damper_ultimate_rotation=None) -> None:
        """Refuse a bad field with a ``ValueError`` naming it ``names[field]`` (the caller's option or config
        key), else ``Anchorage.<field>``.

        Parameters
        ----------
        names : dict or None, default None
            Name of each field in the error message, e.g. ``{"kappa_max": "--kappa-max"}``; a field missing
            from it is named ``Anchorage.<field>``.
        kappa_max, kappa_min : float
            Dimensionless "on" and "off" stiffness, each in [0, 1e4], kappa_min <= kappa_max. [-]
        damping_ratio : float
            Damper ratio xi, in [0, 100]. [-]
        spring_ultimate_rotation, damper_ultimate_rotation : float or None
            theta_K,u and theta_D,u, each in (0, pi/2] or None (= alpha). [rad]
        """
        check_arguments("Anchorage", {  # each field's type and range (core.quantities), then their relation
            "kappa_max": kappa_max, "kappa_min": kappa_min, "damping_ratio": damping_ratio,
            "spring_ultimate_rotation": spring_ultimate_rotation, "damper_ultimate_rotation": damper_ultimate_rotation},
            names)
        if kappa_min > kappa_max:
            name = field_names("Anchorage", names)
            raise ValueError(f"{name('kappa_min')} ({kappa_min}) must not exceed {name('kappa_max')} ({kappa_max})")

    def theta_spring(self, block: Block) -> float:
        """Spring ultimate rotation theta_K,u. [rad]

        Parameters
        ----------
        block : rockstudy.Block
            The block, whose alpha is the default.
        """
        return block.alpha if self.spring_ultimate_rotation is None else float(self.spring_ultimate_rotation)

    def theta_damper(self, block: Block) -> float:
        """Damper ultimate rotation theta_D,u. [rad]

        Parameters
        ----------
        block : rockstudy.Block
            The block, whose alpha is the default.
        """
        return block.alpha if self.damper_ultimate_rotation is None else float(self.damper_ultimate_rotation)

    def stiffness(self, block: Block, kappa: float) -> float:
        """Physical spring stiffness K for a dimensionless kappa. [N/m]

        Parameters
        ----------
        block : rockstudy.Block
            The block, giving m, g, R and b.
        kappa : float
            Dimensionless stiffness 4 K b^2 / (m g R). [-]
        """
        return kappa * block.mass * block.gravity * block.R / (4.0 * block.b**2)

    @property
    def is_inert(self) -> bool:
        """True when the anchorage exerts no force at all (K = D = 0)."""
        return self.kappa_max == 0 and self.damping_ratio == 0

    def K_max(self, block: Block) -> float:
        """Physical "on" stiffness K_max. [N/m]

        Parameters
        ----------
        block : rockstudy.Block
            The block, giving m, g, R and b.
        """
        return self.stiffness(block, self.kappa_max)

    def K_min(self, block: Block) -> float:
        """Physical "off" stiffness K_min. [N/m]

        Parameters
        ----------
        block : rockstudy.Block
            The block, giving m, g, R and b.
        """
        return self.stiffness(block, self.kappa_min)

    def D(self, block: Block) -> float:
        """Physical damper coefficient D from 3 D b^2/(m R^2) = 2 xi p. [N s/m]

        Parameters
        ----------
        block : rockstudy.Block
            The block, giving m, R, b and p.
        """
        return 2.0 * self.damping_ratio * block.p * block.mass * block.R**2 / (3.0 * block.b**2)

    def to_attrs(self, block: Block) -> dict:
        """The anchorage as netCDF global attributes (``anchorage_*``), dimensionless and physical values.

        Parameters
        ----------
        block : rockstudy.Block
            The block that turns the dimensionless values into physical ones.
        """
        return {
            "anchorage_kappa_max": self.kappa_max,
            "anchorage_kappa_min": self.kappa_min,
            "anchorage_damping_ratio": self.damping_ratio,
            "anchorage_theta_K_u": self.theta_spring(block),
            "anchorage_theta_D_u": self.theta_damper(block),
            "anchorage_K_max_N_per_m": self.K_max(block),
            "anchorage_K_min_N_per_m": self.K_min(block),
            "anchorage_D_N_s_per_m": self.D(block),
        }


# --- Eqs. (8)–(13): fracture and working functions ---------------------------------
# Compiled: the fast engine breaks the working-side elements with these (rockstudy.engine._kernel.fracture);
# the reference engine calls them at its fracture events.
@njit(cache=True)
def spring_right_intact(theta_min: float, theta_K_u: float) -> int:
    """f_K,R, Eq. (8): 1 while the running minimum rotation stays above -theta_K,u."""
    return 1 if theta_min > -theta_K_u else 0


@njit(cache=True)
def spring_left_intact(theta_max: float, theta_K_u: float) -> int:
    """f_K,L, Eq. (9): 1 while the running maximum rotation stays below theta_K,u."""
    return 1 if theta_max < theta_K_u else 0


@njit(cache=True)
def damper_right_intact(theta_min: float, theta_D_u: float) -> int:
    """f_D,R, Eq. (10)."""
    return 1 if theta_min > -theta_D_u else 0


@njit(cache=True)
def damper_left_intact(theta_max: float, theta_D_u: float) -> int:
    """f_D,L, Eq. (11)."""
    return 1 if theta_max < theta_D_u else 0


@njit(cache=True)
def right_working(theta: float) -> float:
    """f_W,R, Eq. (12): (1 - sgn theta)/2; the right corner element works for theta < 0."""
    return (1.0 - math.copysign(1.0, theta) * (theta != 0)) / 2.0


@njit(cache=True)
def left_working(theta: float) -> float:
    """f_W,L, Eq. (13): (1 + sgn theta)/2; the left corner element works for theta > 0."""
    return (1.0 + math.copysign(1.0, theta) * (theta != 0)) / 2.0


def spring_moment(theta: float, K: float, b: float) -> float:
    """Restoring spring moment M_K = K·4b^2·sin(theta), Eq. (6) read as odd in theta. [N m]

    Parameters
    ----------
    theta : float
        Block rotation. [rad]
    K : float
        Spring stiffness of the working element. [N/m]
    b : float
        Half width of the block. [m]
    """
    return K * 4.0 * b * b * math.sin(theta)


def damper_moment(theta: float, theta_dot: float, D: float, b: float) -> float:
    """Damper moment M_D = D·4b^2·cos^2(theta/2)·theta_dot, Eq. (7). [N m]

    Parameters
    ----------
    theta : float
        Block rotation. [rad]
    theta_dot : float
        Block angular velocity. [rad/s]
    D : float
        Damper coefficient of the working element. [N s/m]
    b : float
        Half width of the block. [m]
    """
    return D * 4.0 * b * b * math.cos(0.5 * theta) ** 2 * theta_dot
