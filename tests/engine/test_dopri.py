"""The Dormand–Prince step of the fast engine (``rockstudy.engine._kernel.dopri``) against independent oracles:
scipy's RK45 Butcher tableau applied by hand, the method's order, and its continuous extension.

The step is written as a loop over a stage table (so that the right-hand side is compiled once);
these tests guard the table against a wrong coefficient, a skipped stage or a wrong stage time.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.integrate._ivp.rk import RK45

from rockstudy import BLOCK_PRESETS, Anchorage, Control
from rockstudy.engine._kernel import dopri
from rockstudy.engine._kernel.events import locate_poly, locate_sensed_poly
from rockstudy.engine._kernel.layout import I_ATOL, I_RTOL
from rockstudy.engine.simulate import pack_parameters
from rockstudy.model.excitation import GroundMotion, modulated_duration

BLC06 = BLOCK_PRESETS["BLC06"]
NONE = np.zeros(0)


def _problem(kappa: float = 0.0, damping: float = 0.0):
    """A rocking FS block under Eq. 23 at 3 × the uplift acceleration: θ̈(t, θ, θ̇) and its parameters."""
    omega = 2.0 * BLC06.p
    motion = GroundMotion("modulated", 3.0 * BLC06.uplift_acceleration, omega, modulated_duration(omega))
    P = pack_parameters(BLC06, Anchorage(), Control("FS"), motion)

    def f(t, y):
        return np.array([y[1], dopri.rhs(t, y[0], y[1], 1.0, kappa, damping, True, P, NONE, NONE)])

    return P, f


def _tableau_step(f, t, y, h):
    """One step with scipy's RK45 tableau (its A, B, C, E), stage by stage: an independent oracle."""
    K = np.zeros((7, 2))
    K[0] = f(t, y)
    for s in range(1, 6):
        K[s] = f(t + RK45.C[s] * h, y + h * (K[:s].T @ RK45.A[s, :s]))
    y_new = y + h * (K[:6].T @ RK45.B)
    K[6] = f(t + h, y_new)
    return y_new, h * (K.T @ RK45.E), K


def _step(P, f, t, y, h):
    K = np.zeros((7, 2))
    f0 = f(t, y)[1]
    n0, n1, err = dopri.step(t, h, y[0], y[1], f0, K, 1.0, 0.0, 0.0, True, P, NONE, NONE, P[I_RTOL], P[I_ATOL])
    return np.array([n0, n1]), err, K


@pytest.mark.parametrize("t, theta, theta_dot, h", [(0.5, 0.02, 0.1, 0.0025), (1.1, 0.15, -0.4, 0.01),
                                                    (0.3, 0.0, 0.3, 0.05)])
def test_step_matches_scipy_tableau(t, theta, theta_dot, h):
    P, f = _problem()
    y = np.array([theta, theta_dot])
    ours, err, K = _step(P, f, t, y, h)
    ref, ref_err, ref_K = _tableau_step(f, t, y, h)
    np.testing.assert_allclose(ours, ref, rtol=1e-14, atol=1e-16)
    np.testing.assert_allclose(K[:, 1], ref_K[:, 1], rtol=1e-12, atol=1e-14)  # every stage, the FSAL one too
    scale = P[I_ATOL] + P[I_RTOL] * np.maximum(np.abs(y), np.abs(ref))
    ref_norm = math.sqrt(0.5 * np.sum((ref_err / scale) ** 2))
    # The error estimate h·Σ E_i k_i cancels almost to nothing (it is ~1e-5 of the tolerance here), so the
    # two orders of summation may differ by the stages' own differences (<= 1e-12 relative, checked above)
    # and rounding, both amplified by the cancellation: bound the difference by 1e-11 · h·Σ|E_i k_i|.
    slack = 1e-11 * h * (np.abs(RK45.E) @ np.abs(ref_K)) / scale
    assert abs(err - ref_norm) <= math.sqrt(0.5 * np.sum(slack ** 2)) + 1e-10 * ref_norm
    assert abs(err - ref_norm) < 1e-3 * ref_norm  # and the estimate is still the same number


def test_local_error_is_fifth_order():
    """Halving the step divides the one-step error by about 2⁶ (a 5th-order method)."""
    P, f = _problem()
    t, y = 0.6, np.array([0.05, 0.2])
    errors = []
    for h in (0.04, 0.02, 0.01):
        exact = solve_ivp(f, (t, t + h), y, method="DOP853", rtol=1e-13, atol=1e-15).y[:, -1]
        errors.append(np.max(np.abs(_step(P, f, t, y, h)[0] - exact)))
    for coarse, fine in zip(errors, errors[1:]):
        assert 40.0 < coarse / fine < 100.0, errors


def test_dense_output_meets_both_ends_and_tracks_the_solution():
    P, f = _problem()
    t, y, h = 0.6, np.array([0.05, 0.2]), 0.02
    end, _, K = _step(P, f, t, y, h)
    np.testing.assert_array_equal(dopri.dense(0.0, h, y[0], y[1], K), y)
    np.testing.assert_allclose(dopri.dense(1.0, h, y[0], y[1], K), end, rtol=1e-13, atol=1e-16)
    sol = solve_ivp(f, (t, t + h), y, method="DOP853", rtol=1e-13, atol=1e-15, dense_output=True)
    for sig in (0.25, 0.5, 0.8):
        np.testing.assert_allclose(dopri.dense(sig, h, y[0], y[1], K), sol.sol(t + sig * h), rtol=1e-7, atol=1e-10)


def test_dense_quartic_is_the_shampine_extension_summed_over_the_stages():
    """dense_coefficients/dense_at (Horner in sig) against the continuous extension written as in
    Shampine (1986): y0 + h·Σ_i b_i(sig)·k_i with b_i(sig) = Σ_j DENSE[i, j]·sig^(j+1)."""
    P, f = _problem()
    t, y, h = 0.6, np.array([0.05, 0.2]), 0.02
    _, _, K = _step(P, f, t, y, h)
    Q = np.zeros((2, dopri.NQ))
    dopri.dense_coefficients(h, y[0], y[1], K, Q)
    for sig in np.linspace(0.0, 1.0, 11):
        b = dopri.DENSE @ (sig ** np.arange(1, 5))
        expected = y + h * (b @ K)
        np.testing.assert_allclose(dopri.dense_at(sig, Q), expected, rtol=1e-14, atol=1e-17)


def _poly(*g):
    """The coefficients the event functions take (dopri.NQ): a quartic's five, zeros above."""
    return tuple(g) + (0.0,) * (dopri.NQ - len(g))


def _horner(g, s):
    v = 0.0
    for c in reversed(g):  # as the kernel evaluates g
        v = v * s + c
    return v


def locate(hi, g0, g1, g2, g3, g4):
    """The engine's locator on a Dormand–Prince step's quartic: ``locate_poly`` with g5 = g6 = 0."""
    return locate_poly(hi, g0, g1, g2, g3, g4, 0.0, 0.0)


def test_locate_finds_the_root_of_a_quartic_from_the_right():
    """locate (Newton in the bracket) returns a point within LOCATE_TOLERANCE at or after the root,
    where g <= 0, and -1 when g stays positive; so does locate_sensed_poly (Illinois) with a_x = 0."""
    from rockstudy.core.constants import LOCATE_TOLERANCE

    for root in (1e-6, 0.137, 0.5, 0.999):
        # g = (root - sig)·(1 + sig²)·0.3 = 0.3·(root - sig + root·sig² - sig³): positive before the root
        g = (0.3 * root, -0.3, 0.3 * root, -0.3, 0.0)
        for s in (locate(1.0, *g), locate_sensed_poly(1.0, *g, 0.0, 0.0, 0.0, 0.0, 0.01, _problem()[0], NONE)):
            assert _horner(g, s) <= 0.0 and root - 1e-15 <= s <= root + LOCATE_TOLERANCE + 1e-15, (root, s)
    assert locate(1.0, 1.0, 0.1, 0.0, 0.0, 0.0) == -1.0  # no crossing
    assert locate(0.5, 0.3 * 0.7, -0.3, 0.0, 0.0, 0.0) == -1.0  # the root (0.7) lies beyond hi


@pytest.mark.parametrize("g, root, close", [
    # a triple root: g' = 0 there and g is round-off noise within ~1e-5 of it; the bracket's
    # midpoint takes over from Newton
    ((0.4 ** 3, -3 * 0.4 ** 2, 3 * 0.4, -1.0, 0.0), 0.4, 1e-4),
    # g rises to a maximum inside before it falls (Newton from the secant point leaves the bracket)
    ((1e-3, 2.0, -2.5, 0.0, 0.0), (2.0 + math.sqrt(4.0 + 1e-2)) / 5.0, 1e-12),
    # nearly flat at the start, steep at the end
    ((1e-9, -1e-6, 0.0, 0.0, -1.0), 0.0009990039781390383, 2e-13),
])
def test_locate_keeps_to_the_bracket_on_hard_quartics(g, root, close):
    """Flat and non-monotone quartics with one crossing in (0, 1]: the point returned has g <= 0
    and lies at the root (the bracket [lo, hi] with g(lo) > 0 >= g(hi) is never lost)."""
    s = locate(1.0, *g)
    assert _horner(g, s) <= 0.0
    assert abs(s - root) <= close, (s, root)
    # the location of Taylor steps (degree NQ - 1), on the same quartic padded with zeros: the same point
    assert locate_poly(1.0, *_poly(*g)) == s


def test_locate_poly_finds_the_root_of_a_taylor_steps_polynomial():
    """locate_poly (Taylor steps) and locate_sensed_poly on g = (root - sig)·(1 + sig^(n-1)), n = NQ - 1
    the Taylor step's degree: one crossing, at the root, approached from the right within
    LOCATE_TOLERANCE; -1 when the root lies beyond hi."""
    from rockstudy.core.constants import LOCATE_TOLERANCE

    for root in (1e-6, 0.3, 0.77, 0.999):
        g = (root, -1.0) + (0.0,) * (dopri.NQ - 4) + (root, -1.0)
        for s in (locate_poly(1.0, *g), locate_sensed_poly(1.0, *g, 0.0, 0.0, 0.01, _problem()[0], NONE)):
            assert _horner(g, s) <= 0.0 and root - 1e-15 <= s <= root + LOCATE_TOLERANCE + 1e-15, (root, s)
        assert locate_poly(0.9 * root, *g) == -1.0


@pytest.mark.parametrize("root, curvature", [(0.3, -0.8), (0.3, 2.0), (1e-4, 50.0), (0.97, 0.5), (0.5, 0.0)])
def test_quadratic_start_is_the_root_of_the_parabola(root, curvature):
    """The Newton search's start: on a parabola g = (root - sig)·(1 + curvature·sig), positive at 0
    and non-positive at hi = 1, the start is the closed-form first root itself, and locate returns
    it within LOCATE_TOLERANCE from the right."""
    from rockstudy.core.constants import LOCATE_TOLERANCE
    from rockstudy.engine._kernel.events import _quadratic_start

    g = (root, curvature * root - 1.0, -curvature, 0.0, 0.0)
    assert _horner(g, 1.0) <= 0.0 < g[0]
    assert _quadratic_start(1.0, g[0], g[1], _horner(g, 1.0)) == pytest.approx(root, rel=1e-14, abs=1e-17)
    s = locate(1.0, *g)
    assert _horner(g, s) <= 0.0 and root - 1e-15 <= s <= root + LOCATE_TOLERANCE + 1e-15
