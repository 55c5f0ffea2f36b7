import math

import pytest

from rockstudy import BLOCK_PRESETS, Anchorage, Block, Control


def test_blc06_geometry():
    b = BLOCK_PRESETS["BLC06"]
    assert b.R == pytest.approx(math.hypot(0.2, 0.8), rel=1e-12)
    assert b.R == pytest.approx(0.82, abs=0.005)  # paper: R = 0.82 m
    assert math.tan(b.alpha) == pytest.approx(0.25, rel=1e-12)  # H/B = 4
    assert b.p == pytest.approx(math.sqrt(3 * 9.81 / (4 * b.R)), rel=1e-12)
    assert b.p == pytest.approx(3.0, abs=0.02)  # paper: p = 3 rad/s
    assert b.e == pytest.approx(31 / 34, rel=1e-12)  # 1 - 1.5 sin^2 alpha with sin^2 = 1/17
    assert b.inertia == pytest.approx(4 / 3 * b.mass * b.R**2)
    assert b.uplift_acceleration == pytest.approx(9.81 * 0.25)


def test_restitution_vanishes_at_h_over_b_inverse_sqrt2():
    b = Block(width=2.0, height=2.0 / math.sqrt(2), depth=1.0)  # h/b = 1/sqrt(2)
    assert b.e == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize("field,value", [("width", -0.4), ("height", 0.0), ("density", float("nan"))])
def test_block_rejects_bad_sizes(field, value):
    kw = dict(width=0.4, height=1.6, depth=0.47)
    kw[field] = value
    with pytest.raises(ValueError, match=field):
        Block(**kw)


def test_anchorage_validation_and_physical_values():
    with pytest.raises(ValueError, match="kappa_min"):
        Anchorage(kappa_max=0.5, kappa_min=1.0)
    with pytest.raises(ValueError, match="damping_ratio"):
        Anchorage(damping_ratio=-0.1)
    b = BLOCK_PRESETS["BLC06"]
    a = Anchorage()
    # kappa = 4 K b^2 / (m g R) and 3 D b^2 / (m R^2) = 2 xi p, inverted
    assert 4 * a.K_max(b) * b.b**2 / (b.mass * b.gravity * b.R) == pytest.approx(1.0)
    assert 3 * a.D(b) * b.b**2 / (b.mass * b.R**2) == pytest.approx(2 * 0.05 * b.p)
    assert a.theta_spring(b) == b.alpha and a.theta_damper(b) == b.alpha


def test_control_validation():
    with pytest.raises(ValueError, match="strategy"):
        Control("CS03")
    with pytest.raises(ValueError, match="sampling_time"):
        Control("CS01", sampling_time=-0.1)
    with pytest.raises(ValueError, match="delay"):
        Control("CS01", sampling_time=0.0, delay=0.06)
