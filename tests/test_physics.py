"""Physics oracles, one suite run on both engines (``engine`` = "fast", "reference").

Each test compares a run with something known independently of the code: exact quadratures of
free rocking, Housner's restitution and amplitude decay (Eq. 14), energy conservation between
impacts, the uplift threshold g·tanα, and mirror symmetry. Engine-specific behaviour (the
fast engine's event cap, the reference engine's sliding-mode bookkeeping) stays in
test_fast_engine.py and test_reference.py.
"""
import math

import numpy as np
import pytest

import oracles
from rockstudy import BLOCK_PRESETS, Anchorage, Block, Control
from rockstudy.engine.simulate import simulate
from rockstudy.model.equation_of_motion import normalised_energy
from rockstudy.model.excitation import GroundMotion, modulated_duration

BLC06 = BLOCK_PRESETS["BLC06"]
P, ALPHA = BLC06.p, BLC06.alpha
STILL = GroundMotion("rectangular", 0.0, 0.0, duration=1e-3)  # no excitation at all
RTOL = {"fast": 1e-7, "reference": 1e-8}
"""Agreement with the exact solutions expected of each engine (fast rtol 1e-8, reference 1e-10)."""

pytestmark = pytest.mark.parametrize("engine", ["fast", "reference"])



def quarter_period(theta0, p=P, alpha=ALPHA):
    """Exact time from θ0 (at rest) to θ = 0 in free rocking of BLC06 (see ``oracles.quarter_period``). [s]"""
    return oracles.quarter_period(theta0, p, alpha)


def jumps(history):
    """Indices i where history[i], history[i+1] share a time and θ̇ jumps (impacts).

    (The fast engine may also record an unchanged state twice at one instant.)"""
    return np.nonzero((np.diff(history["t"]) == 0) & (np.diff(history["theta_dot"]) != 0))[0]


@pytest.mark.parametrize("ratio", [0.1, 0.5, 0.9])
def test_free_rocking_period_matches_exact_quadrature(engine, ratio):
    """e = 1: first impact at T/4, then every T/2, T from the exact quadrature."""
    block = Block(BLC06.width, BLC06.height, BLC06.depth, restitution=1.0)
    theta0 = ratio * ALPHA
    r = simulate(block, Anchorage(), Control("FS"), STILL, initial_rotation=theta0, free_time=8.0, engine=engine)
    period = 4 * quarter_period(theta0)
    assert r.status == "time limit" and r.n_impacts >= 4
    assert r.impact_times[0] == pytest.approx(period / 4, rel=RTOL[engine])
    np.testing.assert_allclose(np.diff(r.impact_times), period / 2, rtol=RTOL[engine])
    assert r.max_rotation_ratio == pytest.approx(ratio, rel=RTOL[engine])
    # Housner's closed form 4/p·acosh(1/(1 − θ0/α)) (small α) is close: within 0.5 % for BLC06.
    assert 4 / P * math.acosh(1 / (1 - ratio)) == pytest.approx(period, rel=5e-3)


def test_free_rocking_amplitude_decay_and_restitution(engine):
    """Housner's e (Eq. 14): θ̇⁺/θ̇⁻ = e and cos(α−θ_n) = cos α + e^(2n)[cos(α−θ0) − cos α]."""
    e = BLC06.e
    assert e == pytest.approx(1 - 1.5 * math.sin(ALPHA) ** 2, rel=1e-15)
    theta0 = 0.6 * ALPHA
    r = simulate(BLC06, Anchorage(), Control("FS"), STILL, initial_rotation=theta0, free_time=6.0,
                 record_history=True, engine=engine)
    h = r.history
    idx = jumps(h)
    n_checked = 8
    assert len(idx) >= n_checked and r.n_impacts >= n_checked
    for n in range(n_checked):
        i = idx[n]
        before, after = h["theta_dot"][i], h["theta_dot"][i + 1]
        assert h["t"][i] == r.impact_times[n]
        assert after / before == pytest.approx(e, rel=1e-12)
        cos_theta_n = math.cos(ALPHA) + e ** (2 * n) * (math.cos(ALPHA - theta0) - math.cos(ALPHA))
        theta_n = ALPHA - math.acos(cos_theta_n)
        speed = math.sqrt(2 * P * P * (cos_theta_n - math.cos(ALPHA)))
        assert abs(before) == pytest.approx(speed, rel=RTOL[engine])
        if n >= 1:
            gap = r.impact_times[n] - r.impact_times[n - 1]
            assert gap == pytest.approx(2 * quarter_period(theta_n), rel=10 * RTOL[engine])


def test_free_rocking_comes_to_rest(engine):
    r = simulate(BLC06, Anchorage(), Control("FS"), STILL, initial_rotation=0.5 * ALPHA, engine=engine)
    assert r.status == "rest" and len(r.rest_times) == 1
    assert r.end_time == r.rest_times[0] == r.impact_times[-1]


def test_energy_conserved_between_impacts_passive_undamped(engine):
    """PASSIVE, ξ = 0, no excitation: ε = θ̇²/(2p²) + cos(α−|θ|) + 2κ sin²(θ/2) is constant
    between impacts and loses the factor e² of its kinetic part at each impact."""
    kappa = 1.5
    anchorage = Anchorage(kappa_max=kappa, damping_ratio=0.0)
    r = simulate(BLC06, anchorage, Control("PASSIVE"), STILL, initial_rotation=0.8 * ALPHA, free_time=3.0,
                 record_history=True, engine=engine)
    h = r.history
    assert r.n_impacts >= 4 and not r.fracture_times
    energy = np.array([normalised_energy(th, thd, P, ALPHA, kappa) for th, thd in zip(h["theta"], h["theta_dot"])])
    idx = jumps(h)
    bounds = np.concatenate([[-1], idx, [len(h["t"]) - 1]])
    for lo, hi in zip(bounds[:-1] + 1, bounds[1:] + 1):
        stretch = energy[lo:hi]
        assert np.ptp(stretch) < 10 * RTOL[engine] * stretch.mean()
    for i in idx:
        assert energy[i + 1] - math.cos(ALPHA) == pytest.approx(BLC06.e**2 * (energy[i] - math.cos(ALPHA)), rel=1e-12)


@pytest.mark.parametrize("strategy", ["FS", "PASSIVE", "CS01", "CS02"])
def test_no_uplift_below_g_tan_alpha(engine, strategy):
    om = 2 * BLC06.p
    for ratio, uplifts in ((0.99, False), (1.01, True)):
        m = GroundMotion("one-sine", ratio * BLC06.uplift_acceleration, om, 2 * math.pi / om)
        r = simulate(BLC06, Anchorage(), Control(strategy), m, engine=engine, free_time=5.0)
        assert (len(r.uplift_times) > 0) is uplifts
        if not uplifts:
            assert r.max_rotation_ratio == 0.0 and r.status == "rest"


@pytest.mark.parametrize("control", [Control("FS"), Control("PASSIVE"), Control("CS01"), Control("CS02"),
                                     Control("CS01", 0.01, 0.004), Control("CS02", 0.005)],
                         ids=["FS", "PASSIVE", "CS01", "CS02", "CS01-sampled", "CS02-sampled"])
def test_mirror_symmetry(engine, control):
    """Ẍg → −Ẍg gives θ → −θ for every strategy (left and right elements swap)."""
    om = 2.0 * BLC06.p
    motion = GroundMotion("modulated", 1.6 * BLC06.uplift_acceleration, om, modulated_duration(om))
    plus = simulate(BLC06, Anchorage(), control, motion, free_time=5.0, record_history=True, engine=engine)
    minus = simulate(BLC06, Anchorage(), control, motion.scaled(-motion.amplitude), free_time=5.0,
                     record_history=True, engine=engine)
    assert plus.status == minus.status and plus.n_impacts == minus.n_impacts and plus.n_impacts > 0
    np.testing.assert_allclose(minus.impact_times, plus.impact_times, rtol=0, atol=1e-9)
    np.testing.assert_allclose(minus.uplift_times, plus.uplift_times, rtol=0, atol=1e-9)
    assert minus.max_rotation_ratio == pytest.approx(plus.max_rotation_ratio, rel=1e-9)
    swap = {"spring_left": "spring_right", "spring_right": "spring_left",
            "damper_left": "damper_right", "damper_right": "damper_left"}
    assert {swap[k]: v for k, v in minus.fracture_times.items()} == pytest.approx(plus.fracture_times, abs=1e-9)
    grid = np.linspace(0.0, min(plus.end_time, minus.end_time), 2001)
    np.testing.assert_allclose(np.interp(grid, minus.history["t"], minus.history["theta"]),
                               -np.interp(grid, plus.history["t"], plus.history["theta"]), rtol=0, atol=1e-8)
