"""Truth tables for the fracture and working functions (Eqs. 8-13) and control laws (16-17)."""
import pytest

from rockstudy import _kernel as kn
from rockstudy.anchorage import (damper_left_intact, damper_right_intact, left_working, right_working,
                                 spring_left_intact, spring_right_intact)
from rockstudy.control import cs01_is_on, cs02_is_on

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
    assert bool(kn.control_on(kn.CS01, theta, theta_dot, 5.0)) is on  # CS01 ignores the ground motion


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
    assert bool(kn.control_on(kn.CS02, theta, theta_dot, xg)) is on


def test_passive_and_fs_always_on():
    for th, thd, xg in [(0.1, -0.1, 1.0), (-0.1, 0.1, -1.0)]:
        assert kn.control_on(kn.PASSIVE, th, thd, xg)
        assert kn.control_on(kn.FS, th, thd, xg)
