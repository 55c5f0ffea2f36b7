"""Eqs. (1)–(7): the one right-hand side both engines integrate, against the paper's moments."""
import math

import pytest

from rockstudy import BLOCK_PRESETS, Anchorage
from rockstudy.model.anchorage import damper_moment, spring_moment
from rockstudy.model.equation_of_motion import angular_acceleration, normalised_energy

BLOCK = BLOCK_PRESETS["BLC06"]
ANCHORAGE = Anchorage(kappa_max=1.3, kappa_min=0.2, damping_ratio=0.07)


def physical_acceleration(theta, theta_dot, side, kappa, spring, damper, xg, yg):
    """Eq. (1) in physical units: I0·θ̈ = −m(g + Ÿg)R sin(sα − θ) − m Ẍg R cos(sα − θ) − M_K − M_D."""
    b, m, R, g, alpha = BLOCK.b, BLOCK.mass, BLOCK.R, BLOCK.gravity, BLOCK.alpha
    inertia = 4.0 / 3.0 * m * R**2
    K = ANCHORAGE.stiffness(BLOCK, kappa)
    moment = (-m * (g + yg) * R * math.sin(side * alpha - theta) - m * xg * R * math.cos(side * alpha - theta)
              - spring * spring_moment(theta, K, b) - damper * damper_moment(theta, theta_dot, ANCHORAGE.D(BLOCK), b))
    return moment / inertia


CASES = [  # θ, θ̇, s, κ, f_K, f_D, Ẍg, Ÿg
    (0.05, 0.3, 1.0, 1.3, 1, 1, 2.0, 0.0),
    (-0.1, -0.2, -1.0, 0.2, 1, 1, -3.0, 1.5),
    (0.2, -0.4, 1.0, 1.3, 0, 1, 0.0, -2.0),
    (-0.25, 0.1, -1.0, 1.3, 1, 0, 4.0, 0.0),
    (0.0, 0.5, 1.0, 0.0, 0, 0, -1.0, 0.0),
    (0.0, -0.5, -1.0, 1.3, 1, 1, 1.0, 0.5),
]


@pytest.mark.parametrize("theta,theta_dot,side,kappa,f_k,f_d,xg,yg", CASES)
def test_normalised_right_hand_side_equals_eq_1_in_physical_units(theta, theta_dot, side, kappa, f_k, f_d, xg, yg):
    got = angular_acceleration(theta, theta_dot, side, kappa * f_k, 2 * ANCHORAGE.damping_ratio * BLOCK.p * f_d,
                               xg, yg, BLOCK.p, BLOCK.gravity, math.sin(BLOCK.alpha), math.cos(BLOCK.alpha))
    assert got == pytest.approx(physical_acceleration(theta, theta_dot, side, kappa, f_k, f_d, xg, yg),
                                rel=1e-12, abs=1e-12)


def test_makris_sign_convention_and_uplift_acceleration():
    # at θ = 0 on side s, θ̈ = −p²(s·sinα + Ẍg/g·cosα): a positive Ẍg above g·tanα drives θ negative
    args = (0.0, 0.0, BLOCK.p, BLOCK.gravity, math.sin(BLOCK.alpha), math.cos(BLOCK.alpha))
    xg = BLOCK.gravity * math.tan(BLOCK.alpha)
    assert angular_acceleration(0.0, 0.0, -1.0, 0.0, 0.0, 1.001 * xg, *args[1:]) < 0
    assert angular_acceleration(0.0, 0.0, -1.0, 0.0, 0.0, 0.999 * xg, *args[1:]) > 0
    assert angular_acceleration(0.0, 0.0, -1.0, 0.0, 0.0, xg, *args[1:]) == pytest.approx(0.0, abs=1e-12)


def test_energy_is_one_at_rest_on_the_corner_and_grows_with_the_spring():
    assert normalised_energy(BLOCK.alpha, 0.0, BLOCK.p, BLOCK.alpha, 0.0) == 1.0
    assert normalised_energy(0.0, 0.0, BLOCK.p, BLOCK.alpha, 2.0) == pytest.approx(math.cos(BLOCK.alpha))
    e = normalised_energy(0.1, 0.2, BLOCK.p, BLOCK.alpha, 0.5)
    assert e == pytest.approx(0.04 / (2 * BLOCK.p**2) + math.cos(BLOCK.alpha - 0.1) + math.sin(0.05) ** 2)
