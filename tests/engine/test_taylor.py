"""The Taylor step between record knots (``rockstudy.engine._kernel.taylor``) against independent
oracles: scipy's DOP853 at a tight tolerance on the same equation, the order of its local error,
its polynomial inside the step, and whole runs against the Dormand–Prince stepper.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rockstudy import BLOCK_PRESETS, Anchorage, Control
from rockstudy.engine import _kernel as kn
from rockstudy.engine._kernel import _generate_taylor, dopri, taylor
from rockstudy.engine._kernel.engine import setup
from rockstudy.engine._kernel.layout import C_TAYLOR
from rockstudy.engine.simulate import kernel_record, pack_parameters
from rockstudy.model.excitation import GroundMotion, modulated_duration
from rockstudy.model.noise import noisy_record, record_motion

BLC06 = BLOCK_PRESETS["BLC06"]
RTOL, ATOL = 1e-8, 1e-10


def _eq1(side, kap, cd, u0, u1):
    """Eq. (1) written out independently of the kernel: θ̈ with Ẍg/g = u0 + u1·τ, Ÿg = 0."""
    p, s_a, c_a = BLC06.p, math.sin(BLC06.alpha), math.cos(BLC06.alpha)

    def f(tau, y):
        th, thd = y
        u = u0 + u1 * tau
        return [thd, -p * p * (math.sin(side * BLC06.alpha - th) + u * math.cos(side * BLC06.alpha - th)
                               + kap * math.sin(th)) - cd * math.cos(0.5 * th) ** 2 * thd]

    return f, p, s_a, c_a


def _taylor(h, y, side, kap, cd, u0, u1):
    _, p, s_a, c_a = _eq1(side, kap, cd, u0, u1)
    Q = np.zeros((2, dopri.NQ))
    n0, n1, err, f_end = taylor.step(h, y[0], y[1], side, kap, cd, u0, u1, p, s_a, c_a, Q, RTOL, ATOL)
    return np.array([n0, n1]), err, f_end, Q


CASES = [  # side, κ·f_K, 2ξp·f_D, u0, u1 [1/s], (θ, θ̇)
    (1.0, 0.0, 0.0, 0.1, 30.0, (0.02, 0.1)),
    (-1.0, 1.5, 0.6, -0.3, -80.0, (-0.15, 0.4)),
    (1.0, 3.9, 0.0, 0.25, 5.0, (0.0, 0.01)),
    (-1.0, 0.0, 0.3, 0.0, 0.0, (-0.2, -0.8)),
]


def test_the_module_is_what_its_generator_writes():
    """taylor.py is generated: a hand edit, or a generator change not written out, fails here."""
    on_disk = (_generate_taylor.Path(_generate_taylor.__file__).with_name("taylor.py")).read_text(encoding="utf-8")
    assert on_disk == _generate_taylor.source()
    assert taylor.ORDER == _generate_taylor.ORDER == dopri.NQ - 1


@pytest.mark.parametrize("side, kap, cd, u0, u1, y", CASES)
def test_first_coefficient_is_the_one_implementation_of_eq1(side, kap, cd, u0, u1, y):
    """θ̈ at the step's start (2·a_2, from Q) is Eq. (1) as the model writes it, the function both
    engines call elsewhere."""
    from rockstudy.model.equation_of_motion import angular_acceleration

    h = 0.0025
    _, _, _, Q = _taylor(h, y, side, kap, cd, u0, u1)
    expected = angular_acceleration(y[0], y[1], side, kap, cd, u0 * BLC06.gravity, 0.0, BLC06.p, BLC06.gravity,
                                    math.sin(BLC06.alpha), math.cos(BLC06.alpha))
    assert 2.0 * Q[0, 2] / h ** 2 == pytest.approx(expected, rel=1e-13, abs=1e-13)


@pytest.mark.parametrize("side, kap, cd, u0, u1, y", CASES)
def test_step_matches_dop853_at_a_knot_step(side, kap, cd, u0, u1, y):
    """A 2.5 ms step (a noisy record's knot spacing) agrees with DOP853 at rtol 1e-13 far inside the
    integration tolerance: its error estimate is under a tenth of it, and the true error under the
    estimate."""
    f, *_ = _eq1(side, kap, cd, u0, u1)
    h = 0.0025
    ours, err, f_end, _ = _taylor(h, y, side, kap, cd, u0, u1)
    ref = solve_ivp(f, (0.0, h), y, method="DOP853", rtol=1e-13, atol=1e-16).y[:, -1]
    np.testing.assert_allclose(ours, ref, rtol=1e-11, atol=1e-14)
    np.testing.assert_allclose(f_end, f(h, ref)[1], rtol=1e-9, atol=1e-9)
    scale = ATOL + RTOL * np.maximum(np.abs(y), np.abs(ref))
    true = math.sqrt(0.5 * np.sum(((ours - ref) / scale) ** 2))
    assert true <= max(err, 1e-5) and err < 0.1, (true, err)


def test_local_error_order_is_the_degree_in_the_rate_and_one_more_in_the_rotation():
    """Halving the step divides θ̇'s one-step error by about 2^n and θ's by about 2^(n+1), n the
    step's degree (taylor.ORDER: θ's polynomial has degree n, θ̇'s n - 1)."""
    n = taylor.ORDER
    side, kap, cd, u0, u1, y = 1.0, 1.5, 0.6, 0.3, 20.0, (0.05, 0.3)
    f, *_ = _eq1(side, kap, cd, u0, u1)
    errors = []
    for h in (0.02, 0.01, 0.005):  # close enough to the limit for the leading term to dominate
        ref = solve_ivp(f, (0.0, h), y, method="DOP853", rtol=1e-13, atol=1e-17).y[:, -1]
        errors.append(np.abs(_taylor(h, y, side, kap, cd, u0, u1)[0] - ref))
    for coarse, fine in zip(errors, errors[1:]):
        ratio = coarse / fine
        assert 0.7 * 2 ** n < ratio[1] < 1.25 * 2 ** n, errors
        assert 0.7 * 2 ** (n + 1) < ratio[0] < 1.25 * 2 ** (n + 1), errors


def test_error_estimate_is_above_the_error_it_estimates():
    """The scaled error norm (the last terms of the series) is at least the true error of the step
    at steps where it matters (err of order 1), so a step the control accepts is accurate."""
    side, kap, cd, u0, u1, y = -1.0, 0.5, 0.2, -0.2, 40.0, (-0.1, -0.5)
    f, *_ = _eq1(side, kap, cd, u0, u1)
    seen = []
    for h in np.geomspace(0.002, 0.05, 15):
        ours, err, _, _ = _taylor(h, y, side, kap, cd, u0, u1)
        if not 0.05 < err < 20.0:
            continue  # far from the acceptance limit (the true error is then round-off, or irrelevant)
        ref = solve_ivp(f, (0.0, h), y, method="DOP853", rtol=1e-13, atol=1e-17).y[:, -1]
        scale = ATOL + RTOL * np.maximum(np.abs(y), np.abs(ref))
        true = math.sqrt(0.5 * np.sum(((ours - ref) / scale) ** 2))
        seen.append((h, err, true))
        assert true <= err, seen
    assert len(seen) >= 3 and min(e for _, e, _ in seen) < 1.0 < max(e for _, e, _ in seen), seen


@pytest.mark.parametrize("side, kap, cd, u0, u1, y", CASES[:2])
def test_the_polynomial_is_the_solution_inside_the_step(side, kap, cd, u0, u1, y):
    """Q holds θ and θ̇ as polynomials in the fraction of the step: they meet the start exactly, the
    end exactly as returned, follow DOP853 inside, and θ̇'s is the derivative of θ's."""
    f, *_ = _eq1(side, kap, cd, u0, u1)
    h = 0.0025
    end, _, _, Q = _taylor(h, y, side, kap, cd, u0, u1)
    assert dopri.dense_at(0.0, Q) == tuple(y)
    assert dopri.dense_at(1.0, Q) == tuple(end)
    sol = solve_ivp(f, (0.0, h), y, method="DOP853", rtol=1e-13, atol=1e-16, dense_output=True)
    for sig in (0.1, 0.37, 0.8):
        np.testing.assert_allclose(dopri.dense_at(sig, Q), sol.sol(sig * h), rtol=1e-12, atol=1e-15)
    j = np.arange(1, dopri.NQ)
    np.testing.assert_allclose(Q[1, :-1], j * Q[0, 1:] / h, rtol=1e-14, atol=1e-300)


def _noisy_run(i, stepper, want_log=True):
    rng = np.random.default_rng(1000 + i)
    strategy = ("FS", "PASSIVE", "CS01", "CS02")[i % 4]
    fr = float(rng.uniform(0.5, 4.5))
    motion = record_motion(noisy_record("modulated", fr * BLC06.p, 0.05, i, 7),
                           float(rng.uniform(1.2, 4.0)) * BLC06.uplift_acceleration, fr * BLC06.p)
    kmax = float(rng.uniform(0.2, 3.0))
    anchorage = Anchorage(kappa_max=kmax, kappa_min=0.0, damping_ratio=float(rng.uniform(0, 0.1)))
    control = Control(strategy)
    P = pack_parameters(BLC06, anchorage, control, motion, stepper=stepper)
    return kn.simulate_kernel(P, kn.writable(kernel_record(control, motion)), np.zeros(0), False, want_log)


def test_taylor_and_dormand_prince_runs_agree():
    """The same noisy-record runs with either stepper between the knots: every run ends the same way
    at the same time (1e-6 relative) with the same largest rotation, and the first ten impacts agree
    to 1e-7 s. Only a chattering sequence of impacts (hundreds of them, ever closer) may end after
    another count of impacts or drift further, as it does under any change of round-off."""
    same_count = 0
    for i in range(24):
        a, b = _noisy_run(i, "taylor"), _noisy_run(i, "dopri")
        assert a.status == b.status, i
        np.testing.assert_allclose(a.end_time, b.end_time, rtol=1e-6)
        np.testing.assert_allclose(a.max_abs_theta, b.max_abs_theta, rtol=1e-6)
        np.testing.assert_allclose(a.impact_times[:10], b.impact_times[:10], rtol=0.0, atol=1e-7)
        same_count += a.n_impacts == b.n_impacts
    assert same_count >= 22


def test_taylor_steps_only_where_the_ground_motion_is_linear_between_knots():
    """Records without vertical motion step by Taylor; analytic excitations, vertical records and
    ``stepper="dopri"`` step by Dormand–Prince."""
    omega = 2.0 * BLC06.p
    rec = record_motion(noisy_record("modulated", omega, 0.05, 0, 7), BLC06.uplift_acceleration * 2, omega)
    analytic = GroundMotion("modulated", 2 * BLC06.uplift_acceleration, omega, modulated_duration(omega))
    args = (BLC06, Anchorage(), Control("FS"))
    none = np.zeros(0)
    assert setup(pack_parameters(*args, rec), none, False, False)[C_TAYLOR] == 1.0
    assert setup(pack_parameters(*args, rec, stepper="dopri"), none, False, False)[C_TAYLOR] == 0.0
    assert setup(pack_parameters(*args, analytic), none, False, False)[C_TAYLOR] == 0.0
    assert setup(pack_parameters(*args, rec), np.ones(4), False, False)[C_TAYLOR] == 0.0
    with pytest.raises(ValueError, match="stepper must be one of taylor, dopri"):
        pack_parameters(*args, rec, stepper="rk4")

