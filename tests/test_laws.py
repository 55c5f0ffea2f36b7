"""Truth tables for the fracture and working functions (Eqs. 8-13) and control laws (16-17).

These are the functions both engines run (compiled once with numba), so each truth table tests
the fast and the reference engine at once.
"""
import math

import numpy as np
import pytest

from rockstudy.core.constants import ROTATION_TOLERANCE
from rockstudy.engine._kernel import maps
from rockstudy.model.anchorage import (
    damper_left_intact,
    damper_right_intact,
    left_working,
    right_working,
    spring_left_intact,
    spring_right_intact,
)
from rockstudy.model.control import (
    CS01,
    CS02,
    FS,
    PASSIVE,
    STRATEGIES,
    STRATEGY_CODE,
    cs01_is_on,
    cs02_is_on,
    stiffness_on,
)

TU = 0.2


@pytest.mark.parametrize("theta_min,expected", [(0.0, 1), (-0.1, 1), (-0.2, 0), (-0.3, 0)])
def test_right_fracture_functions(theta_min, expected):
    assert spring_right_intact(theta_min, TU) == expected  # Eq. 8
    assert damper_right_intact(theta_min, TU) == expected  # Eq. 10


@pytest.mark.parametrize("theta_max,expected", [(0.0, 1), (0.1, 1), (0.2, 0), (0.3, 0)])
def test_left_fracture_functions(theta_max, expected):
    assert spring_left_intact(theta_max, TU) == expected  # Eq. 9
    assert damper_left_intact(theta_max, TU) == expected  # Eq. 11


@pytest.mark.parametrize("theta,right,left", [(-0.1, 1.0, 0.0), (0.1, 0.0, 1.0), (0.0, 0.5, 0.5)])
def test_working_functions(theta, right, left):
    assert right_working(theta) == right  # Eq. 12
    assert left_working(theta) == left  # Eq. 13


CS01_TABLE = [  # theta, theta_dot, K_max?
    (0.1, 0.2, True), (0.1, -0.2, False), (-0.1, -0.2, True), (-0.1, 0.2, False),
    (0.1, 0.0, True), (0.0, 0.3, True), (0.0, 0.0, True),
]


@pytest.mark.parametrize("theta,theta_dot,on", CS01_TABLE)
def test_cs01_truth_table(theta, theta_dot, on):
    assert cs01_is_on(theta, theta_dot) is on
    assert bool(stiffness_on(CS01, theta, theta_dot, 5.0)) is on  # CS01 ignores the ground motion


CS02_TABLE = [  # theta, theta_dot, Xg_ddot, K_max?
    (0.1, 0.2, 1.0, False),   # ground drives theta negative while theta > 0: pulls it home, release
    (0.1, 0.2, -1.0, True),   # ground pushes the block outward: hold it
    (-0.1, -0.2, 1.0, True),
    (-0.1, 0.2, -1.0, False),
    (0.1, -0.2, -1.0, True),  # feed-forward ignores theta_dot
    (0.0, 0.1, 1.0, True),    # Xg*theta = 0 <= 0
    (0.1, -0.2, 0.0, False),  # Xg = 0: CS01
    (0.1, 0.2, 0.0, True),
]


@pytest.mark.parametrize("theta,theta_dot,xg,on", CS02_TABLE)
def test_cs02_truth_table(theta, theta_dot, xg, on):
    assert cs02_is_on(theta, theta_dot, xg) is on
    assert bool(stiffness_on(CS02, theta, theta_dot, xg)) is on


def test_passive_and_fs_always_on():
    for th, thd, xg in [(0.1, -0.1, 1.0), (-0.1, 0.1, -1.0)]:
        assert stiffness_on(PASSIVE, th, thd, xg)
        assert stiffness_on(FS, th, thd, xg)


def test_strategy_codes_are_defined_once():
    assert [STRATEGY_CODE[name] for name in STRATEGIES] == [FS, PASSIVE, CS01, CS02] == [0, 1, 2, 3]


@pytest.mark.parametrize("side,theta,broken", [
    (1.0, 0.19, False), (1.0, 0.2, True), (1.0, 0.2 - 0.5 * ROTATION_TOLERANCE, True), (1.0, 0.25, True),
    (-1.0, -0.19, False), (-1.0, -0.2, True), (-1.0, -0.25, True),
])
def test_engine_fracture_map_uses_eqs_8_to_11_on_the_working_side(side, theta, broken):
    spring, damper, frac = np.ones(2), np.ones(2), np.full(4, np.nan)
    maps.fracture(side, theta, 1.5, spring, damper, frac, TU, 0.3)
    working = 0 if side > 0 else 1
    assert spring[working] == (0.0 if broken else 1.0)
    assert spring[1 - working] == 1.0 and damper.tolist() == [1.0, 1.0]  # the damper's θ_D,u = 0.3
    assert bool(frac[working] == 1.5) == broken and np.isnan(frac[2:]).all()


@pytest.mark.parametrize("thd,side,what,new_side", [
    (-2.0, 1.0, maps.REBOUND, -1.0), (2.0, -1.0, maps.REBOUND, 1.0),
    (-1e-9, 1.0, maps.REST, 1.0),
])
def test_engine_impact_map_eq_14(thd, side, what, new_side):
    e = 1.0 - 1.5 * math.sin(0.25) ** 2
    got = maps.impact(thd, side, e, 1e-6, 0.0, 0.0, 9.81, 0.25)
    assert got[0] == what and got[1] == new_side
    assert got[2] == (e * thd if what == maps.REBOUND else 0.0)


def test_engine_impact_map_uplifts_when_the_ground_can_lift_the_block():
    xg = 9.81 * math.tan(0.25) * 1.01
    what, side, thd = maps.impact(-1e-9, 1.0, 0.9, 1e-6, xg, 0.0, 9.81, 0.25)
    assert (what, side, thd) == (maps.UPLIFT, -1.0, 0.0)  # a positive Ẍg lifts it onto the θ < 0 corner


def _apex(theta, xg, kmax, kmin):
    from rockstudy import BLOCK_PRESETS
    from rockstudy.engine.simulate import pack_parameters
    from rockstudy.model.excitation import GroundMotion
    block = BLOCK_PRESETS["BLC06"]
    P = pack_parameters(block, __import__("rockstudy").Anchorage(), __import__("rockstudy").Control("CS01"),
                        GroundMotion("one-sine", 0.0, 1.0, 1.0))
    return maps.apex_decision(theta, math.copysign(1.0, theta), kmax, kmin, xg, 0.0, P), block


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_cs01_apex_decision_filippov_cases(sign):
    """MODEL-NOTES §1 at θ̇ = 0: out with K_max when gravity+K_max cannot hold the block, back with
    K_min when even K_min pulls it home, held in between (the three cases of the sliding surface)."""
    from rockstudy import BLOCK_PRESETS
    block = BLOCK_PRESETS["BLC06"]
    a, g = block.alpha, block.gravity
    theta = sign * (a - 0.01)  # near the corner: the gravity moment is small (≈ 0.01·cos α)
    # no excitation: both stiffnesses pull it back, however small the pull
    assert _apex(theta, 0.0, 1.0, 0.0)[0] == maps.TURN_BACK
    # the ground pushes outward (Makris: Ẍg of the opposite sign of θ) harder than gravity + K_max: out
    assert _apex(theta, -sign * 5 * g, 1.0, 0.0)[0] == maps.TURN_OUT
    # outward push between the two: held (s·a_max < 0 < s·a_min)
    push = -sign * g * math.sin(0.01) / math.cos(0.01) * 3.0
    assert _apex(theta, push, 1.0, 0.0)[0] == maps.HOLD
