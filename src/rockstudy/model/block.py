"""Rigid rectangular block: geometry, inertia and Housner's restitution (paper §2).

Symbols follow the paper: B, H, By full width, height and depth; b = B/2 and
h = H/2 half sizes; R the half diagonal; alpha = atan(b/h) the slenderness angle;
p = sqrt(3 g / (4 R)) the frequency parameter; I0 = 4/3 m R^2 the polar moment of
inertia about a base corner; e = 1 - 3/2 sin^2(alpha) the coefficient of restitution
(Eq. 14).
"""
from __future__ import annotations

import math
from dataclasses import InitVar, asdict, dataclass

from rockstudy.core.quantities import check_arguments, declares
from rockstudy.core.validation import check_block

GRAVITY = 9.81
"""Acceleration of gravity used throughout. [m/s^2]"""


@declares(width="length", height="length", depth="length", density="density", gravity="gravity",
          restitution="restitution")
@dataclass(frozen=True)
class Block:
    """A rigid rectangular block standing on a rigid base.

    Parameters
    ----------
    width : float
        Full base width B. [m]
    height : float
        Full height H. [m]
    depth : float
        Out-of-plane depth By (enters the mass only). [m]
    density : float, default 2700
        Mass density. [kg/m^3]
    gravity : float, default 9.81
        Acceleration of gravity g. [m/s^2]
    restitution : float or None
        Coefficient of restitution e. ``None`` uses Housner's value, Eq. (14), which is >= 0 only
        for a slender block (height/width >= 1/sqrt(2)); a squatter block needs an explicit e. [-]
    names : dict, optional
        The caller's name of each field in error messages (``{"width": "--width"}``), and of the block itself
        under ``"block"``; one missing from it is named ``Block.<field>``. Not stored.

    Raises
    ------
    ValueError
        If a size is not a positive finite number, e is outside [0, 1], or the block is too squat
        for Eq. (14) and no restitution is given.
    """

    width: float
    height: float
    depth: float
    density: float = 2700.0
    gravity: float = GRAVITY
    restitution: float | None = None
    names: InitVar[dict | None] = None

    def __post_init__(self, names):
        names = names or {}
        check_arguments("Block", self.__dict__, names)  # each field's type and range (core.quantities)
        check_block(self, names.get("block", "Block"), names.get("restitution"))  # e < 0 from Eq. (14)?

    # --- derived geometry -------------------------------------------------------
    @property
    def b(self) -> float:
        """Half width. [m]"""
        return 0.5 * self.width

    @property
    def h(self) -> float:
        """Half height. [m]"""
        return 0.5 * self.height

    @property
    def R(self) -> float:
        """Half diagonal, distance from a base corner to the centre of mass. [m]"""
        return math.hypot(self.b, self.h)

    @property
    def alpha(self) -> float:
        """Slenderness angle atan(b/h). [rad]"""
        return math.atan2(self.b, self.h)

    @property
    def p(self) -> float:
        """Frequency parameter sqrt(3 g / (4 R)). [rad/s]"""
        return math.sqrt(3.0 * self.gravity / (4.0 * self.R))

    @property
    def mass(self) -> float:
        """Mass B·H·By·density. [kg]"""
        return self.width * self.height * self.depth * self.density

    @property
    def inertia(self) -> float:
        """Polar moment of inertia about a base corner, I0 = 4/3 m R^2. [kg m^2]"""
        return 4.0 / 3.0 * self.mass * self.R**2

    @property
    def housner_restitution(self) -> float:
        """Housner's coefficient of restitution 1 - 1.5 sin^2(alpha), Eq. (14). [-]"""
        return 1.0 - 1.5 * math.sin(self.alpha) ** 2

    @property
    def e(self) -> float:
        """Coefficient of restitution in use (override or Eq. 14). [-]"""
        return self.housner_restitution if self.restitution is None else float(self.restitution)

    @property
    def uplift_acceleration(self) -> float:
        """Horizontal ground acceleration that starts rocking from rest, g·tan(alpha). [m/s^2]"""
        return self.gravity * math.tan(self.alpha)

    def to_attrs(self) -> dict:
        """Flat dictionary of the defining and derived quantities (for dataset attributes)."""
        d = {f"block_{k}": v for k, v in asdict(self).items() if v is not None}
        d.update(block_R=self.R, block_alpha=self.alpha, block_p=self.p, block_mass=self.mass,
                 block_e=self.e)
        return d

    @classmethod
    def slender(cls, alpha: float, R: float = 1.0, **kwargs) -> "Block":
        """Block with a given slenderness angle alpha [rad] and half diagonal R [m].

        Parameters
        ----------
        alpha : float
            Slenderness angle, B = 2 R sin(alpha), H = 2 R cos(alpha). [rad]
        R : float, default 1.0
            Half diagonal. [m]
        **kwargs : dict
            Other fields of :class:`Block` (``density``, ``gravity``, ``restitution``); the depth is 1 m.
        """
        return cls(width=2 * R * math.sin(alpha), height=2 * R * math.cos(alpha), depth=1.0, **kwargs)


BLOCK_PRESETS: dict[str, Block] = {
    # The paper's benchmark block BLC06 (§5): B = 0.40 m, H = 1.60 m, By = 0.47 m,
    # giving R = 0.82 m, H/B = 4, p = 3.0 rad/s and e = 31/34.
    "BLC06": Block(width=0.40, height=1.60, depth=0.47),
}
"""Named blocks, by the name a configuration or the command line uses (``block: {preset: BLC06}``,
``--block BLC06``): ``"BLC06"`` is the paper's benchmark block (§5), B × H × B_y = 0.40 × 1.60 × 0.47 m
of density 2700 kg/m³, so that R = 0.82 m, α = 0.245 rad (H/B = 4), p = 3.0 rad/s and e = 31/34."""
