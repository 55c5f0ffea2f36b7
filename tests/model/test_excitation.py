"""Ground motions: Eq. (23), the one-sine pulse and records, as both engines evaluate them."""
import math
from fractions import Fraction

import numpy as np
import pytest

from rockstudy import BLOCK_PRESETS, Anchorage, Control
from rockstudy.engine import _kernel as kn
from rockstudy.engine.simulate import pack_parameters
from rockstudy.model.excitation import (
    ENVELOPE_PEAK,
    KIND_CODE,
    MODULATED,
    ONE_SINE,
    RECORD,
    RECTANGULAR,
    GroundMotion,
    interpolate_record,
    modulated,
    modulated_acceleration,
    modulated_duration,
    modulated_peak,
    one_sine_acceleration,
)

OMEGA = 7.0
TD = modulated_duration(OMEGA)


def test_eq_23_duration_is_five_periods():
    assert TD == pytest.approx(5 * 2 * math.pi / OMEGA, rel=1e-15)


@pytest.mark.parametrize("fraction", [Fraction(1, 4), Fraction(1, 10), Fraction(3, 5), Fraction(9, 10)])
def test_eq_23_envelope_is_90_t2_t_minus_td_6_over_td_8(fraction):
    # at t = k·T_d the envelope is exactly 90 k² (k − 1)⁶; the carrier is evaluated independently
    t = float(fraction) * TD
    envelope = float(90 * fraction**2 * (fraction - 1) ** 6)
    expected = envelope * 2.5 * math.sin(OMEGA * (t - TD))
    assert modulated_acceleration(t, 2.5, OMEGA, TD) == pytest.approx(expected, rel=1e-12)


def test_eq_23_envelope_peak_at_quarter_duration():
    assert ENVELOPE_PEAK == pytest.approx(1.00113, abs=1e-5)
    s = np.linspace(0, 1, 100001)
    assert np.argmax(90 * s**2 * (s - 1) ** 6) == 25000
    assert 0.99 < modulated_peak() <= ENVELOPE_PEAK


def test_array_form_of_eq_23_used_for_records_agrees_with_the_engines_form():
    t = np.linspace(0, TD, 4001)
    scalar = np.array([modulated_acceleration(x, 1.3, OMEGA, TD) for x in t])
    np.testing.assert_allclose(modulated(t, 1.3, OMEGA), scalar, rtol=1e-13, atol=1e-15)
    assert modulated(np.array([-0.1, TD + 0.1]), 1.3, OMEGA).tolist() == [0.0, 0.0]


def test_one_sine_pulse():
    assert one_sine_acceleration(0.25 * 2 * math.pi / OMEGA, 3.0, OMEGA) == pytest.approx(3.0, rel=1e-15)
    assert one_sine_acceleration(0.0, 3.0, OMEGA) == 0.0


def test_record_interpolation_is_linear_and_holds_the_last_sample():
    samples = np.array([0.0, 2.0, -1.0])
    assert interpolate_record(0.5 * 0.01, 0.01, samples) == pytest.approx(1.0)
    assert interpolate_record(0.0175, 0.01, samples) == pytest.approx(2.0 - 0.75 * 3.0)
    assert interpolate_record(0.05, 0.01, samples) == -1.0


@pytest.mark.parametrize("kind", ["one-sine", "modulated", "record", "rectangular"])
def test_engine_ground_motion_matches_the_ground_motion_object(kind):
    rng = np.random.default_rng(1)
    if kind == "record":
        motion = GroundMotion("record", 2.0, OMEGA, 0.99, record_dt=0.01, record=rng.normal(size=100))
    elif kind == "rectangular":
        motion = GroundMotion("rectangular", 2.0, 0.0, 0.5)
    else:
        end = TD if kind == "modulated" else 2 * math.pi / OMEGA
        motion = GroundMotion(kind, 2.0, OMEGA, end)
    P = pack_parameters(BLOCK_PRESETS["BLC06"], Anchorage(), Control("FS"), motion)
    for t in np.linspace(0.0013, motion.duration * 1.1, 301):
        if kind == "rectangular" and t == motion.duration:
            continue
        assert kn.ground_acceleration(t, P, motion.record) == pytest.approx(float(motion.horizontal(t)), rel=1e-12,
                                                                            abs=1e-12)


def test_kind_codes_are_defined_once():
    assert [KIND_CODE[k] for k in ("one-sine", "modulated", "record", "rectangular")] == [
        ONE_SINE, MODULATED, RECORD, RECTANGULAR]
    assert (kn.KIND_ONE_SINE, kn.KIND_MODULATED, kn.KIND_RECORD, kn.KIND_RECTANGULAR) == (0, 1, 2, 3)
