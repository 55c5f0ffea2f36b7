"""Oracles for the reference engine, rockstudy.engine.reference (paper Eqs. 1–17).

Each test compares the engine with something known independently of it: exact quadratures
of free rocking, Housner's restitution and amplitude decay, energy conservation, the uplift
threshold, mirror symmetry, limiting cases of the control laws, the Filippov conditions of the
sliding mode, and the timing rules of sampled control.
"""
import math

import numpy as np
import pytest

import oracles
from rockstudy.engine.reference import simulate_reference
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import BLOCK_PRESETS, GRAVITY
from rockstudy.model.control import Control
from rockstudy.model.equation_of_motion import angular_acceleration
from rockstudy.model.excitation import GroundMotion, modulated_duration

BLC06 = BLOCK_PRESETS["BLC06"]
P, ALPHA = BLC06.p, BLC06.alpha
UPLIFT = GRAVITY * math.tan(ALPHA)
STILL = GroundMotion("rectangular", 0.0, 0.0, duration=1e-3)  # no excitation at all


def modulated(frequency_ratio, amplitude_ratio, block=BLC06):
    omega = frequency_ratio * block.p
    return GroundMotion("modulated", amplitude_ratio * block.uplift_acceleration, omega,
                        duration=modulated_duration(omega))


def one_sine(frequency_ratio, amplitude_ratio, block=BLC06):
    omega = frequency_ratio * block.p
    return GroundMotion("one-sine", amplitude_ratio * block.uplift_acceleration, omega,
                        duration=2 * math.pi / omega)



def quarter_period(theta0, p=P, alpha=ALPHA):
    """Exact time from θ0 (at rest) to θ = 0 in free rocking of BLC06 (see ``oracles.quarter_period``). [s]"""
    return oracles.quarter_period(theta0, p, alpha)


def jumps(history):
    """Indices i where history[i], history[i+1] share a time (the state jumps there)."""
    return np.nonzero(np.diff(history["t"]) == 0)[0]


# ----------------------------------------------------------------------------- arguments
def test_unknown_overturn_criterion_is_rejected():
    with pytest.raises(ValueError, match="overturn_criterion"):
        simulate_reference(BLC06, Anchorage(), Control("FS"), STILL, overturn_criterion="upright")


def test_engine_name_and_quiet_ground():
    r = simulate_reference(BLC06, Anchorage(), Control("CS01"), STILL)
    assert r.engine == "reference"
    assert r.status == "rest" and not r.overturned
    assert r.max_rotation_ratio == 0.0 and r.n_impacts == 0


# ----------------------------------------------------------------------------- free rocking
@pytest.mark.parametrize("strategy, motion", [
    ("PASSIVE", one_sine(4.0, 3.0)),
    # small rocks near the uplift threshold: an apex and the next impact can fall within one
    # solver step, which the engine must notice (it did not at first: 0.7 % error)
    ("CS01", one_sine(2.0, 1.05)),
], ids=["PASSIVE", "CS01-small-rocks"])
def test_tighter_tolerance_converges(strategy, motion):
    loose = simulate_reference(BLC06, Anchorage(), Control(strategy), motion, free_time=5.0)
    tight = simulate_reference(BLC06, Anchorage(), Control(strategy), motion, free_time=5.0, rtol=1e-12, atol=1e-15)
    assert loose.n_impacts == tight.n_impacts >= 3
    np.testing.assert_allclose(loose.impact_times, tight.impact_times, rtol=0, atol=1e-7)
    assert loose.max_rotation_ratio == pytest.approx(tight.max_rotation_ratio, rel=1e-6)


# ----------------------------------------------------------------------------- uplift
def test_uplift_instant_and_side():
    """a_p = 2 g tanα: uplift where a_p sin(ω t) = g tanα, onto θ < 0 for a positive pulse."""
    motion = one_sine(3.0, 2.0)
    r = simulate_reference(BLC06, Anchorage(), Control("FS"), motion, record_history=True)
    t_up = math.asin(0.5) / motion.omega
    assert r.uplift_times[0] == pytest.approx(t_up, abs=1e-12)
    h = r.history
    after = (h["t"] > t_up + 1e-6) & (h["t"] < t_up + 0.05)
    assert np.all(h["theta"][after] < 0)


def test_rectangular_pulse_uplifts_at_once():
    """A step of 1.5 g tanα lifts the block at t = 0 onto θ < 0; 0.9 g tanα never does."""
    strong = GroundMotion("rectangular", 1.5 * UPLIFT, 0.0, duration=0.2)
    r = simulate_reference(BLC06, Anchorage(), Control("FS"), strong, free_time=3.0, record_history=True)
    assert r.uplift_times[0] == 0.0
    assert np.all(r.history["theta"][(r.history["t"] > 0) & (r.history["t"] <= 0.2)] < 0)
    weak = GroundMotion("rectangular", 0.9 * UPLIFT, 0.0, duration=0.2)
    r = simulate_reference(BLC06, Anchorage(), Control("FS"), weak)
    assert r.status == "rest" and len(r.uplift_times) == 0 and r.end_time == 0.2


def test_uplift_with_vertical_record():
    """|Ẍg| > (g + Ÿg)·tanα with Ÿg = −g/2: uplift where a_p sin(ωt) = (g/2)·tanα."""
    omega = 2.0 * P
    n = int(2 * math.pi / omega / 0.01) + 2
    motion = GroundMotion("one-sine", 0.6 * UPLIFT, omega, duration=2 * math.pi / omega,
                          vertical_dt=0.01, vertical=np.full(n, -0.5 * GRAVITY))
    r = simulate_reference(BLC06, Anchorage(), Control("FS"), motion, free_time=2.0)
    assert r.uplift_times[0] == pytest.approx(math.asin(0.5 / 0.6) / omega, abs=1e-12)


def test_record_matches_analytic_pulse():
    """A one-sine pulse given as a 1 ms record (linear between knots) rocks like the pulse."""
    analytic = one_sine(2.0, 2.5)
    dt = 1e-3
    t = np.arange(int(analytic.duration / dt) + 2) * dt
    record = GroundMotion("record", analytic.amplitude, analytic.omega, duration=t[-1], record_dt=dt,
                          record=np.asarray(analytic.horizontal(t)) / analytic.amplitude)
    a = simulate_reference(BLC06, Anchorage(), Control("CS01"), analytic, free_time=3.0)
    b = simulate_reference(BLC06, Anchorage(), Control("CS01"), record, free_time=3.0)
    # interpolation error of the record: a_p (ω dt)²/8 ≈ 4e-6 a_p
    assert b.uplift_times[0] == pytest.approx(a.uplift_times[0], abs=1e-5)
    assert b.max_rotation_ratio == pytest.approx(a.max_rotation_ratio, rel=1e-4)
    np.testing.assert_allclose(b.impact_times[:3], a.impact_times[:3], atol=1e-4)


# ----------------------------------------------------------------------------- fracture
def test_fracture_at_ultimate_rotation():
    """Left elements break when θ reaches θ_u (> 0 side), each at its own rotation."""
    anchorage = Anchorage(kappa_max=0.5, spring_ultimate_rotation=0.5 * ALPHA,
                          damper_ultimate_rotation=0.7 * ALPHA)
    r = simulate_reference(BLC06, anchorage, Control("PASSIVE"), STILL, initial_rotation=0.3 * ALPHA,
                           initial_velocity=0.8 * P * ALPHA, free_time=3.0, record_history=True)
    h = r.history
    assert set(r.fracture_times) >= {"spring_left", "damper_left"}
    for name, theta_u in (("spring_left", 0.5 * ALPHA), ("damper_left", 0.7 * ALPHA)):
        at = h["t"] == r.fracture_times[name]
        np.testing.assert_allclose(h["theta"][at], theta_u, rtol=1e-10)
    assert r.fracture_times["spring_left"] < r.fracture_times["damper_left"]
    # the right elements can only break on the other side
    for name in ("spring_right", "damper_right"):
        if name in r.fracture_times:
            at = h["t"] == r.fracture_times[name]
            assert np.all(h["theta"][at] < 0)


def _speed_for_apex(theta0, apex, kappa):
    """Outward θ̇ at θ0 that reaches exactly ``apex`` (undamped, no excitation, ε conserved). [rad/s]"""
    def potential(theta):
        return math.cos(ALPHA - theta) + 2 * kappa * math.sin(theta / 2) ** 2
    return math.sqrt(2 * P * P * (potential(apex) - potential(theta0)))


@pytest.mark.parametrize("strategy", ["PASSIVE", "CS01"])
@pytest.mark.parametrize("excess", [1e-8, -1e-8])
def test_grazing_fracture_is_not_stepped_over(strategy, excess):
    """An apex 1e-8 above θ_K,u breaks the spring (at θ = θ_K,u); 1e-8 below does not.

    The rotation stays above θ_K,u for ~0.1 ms, far shorter than a solver step."""
    kappa, theta_u = 2.0, 0.8 * ALPHA
    anchorage = Anchorage(kappa_max=kappa, damping_ratio=0.0, spring_ultimate_rotation=theta_u)
    theta0 = 0.5 * theta_u
    speed = _speed_for_apex(theta0, theta_u * (1 + excess), kappa)
    r = simulate_reference(BLC06, anchorage, Control(strategy), STILL, initial_rotation=theta0,
                           initial_velocity=speed, free_time=1.0, record_history=True)
    if excess > 0:
        assert set(r.fracture_times) == {"spring_left"}
        at = r.history["t"] == r.fracture_times["spring_left"]
        np.testing.assert_allclose(r.history["theta"][at], theta_u, rtol=1e-10)
    else:
        assert r.fracture_times == {}
        assert r.max_rotation_ratio * ALPHA == pytest.approx(theta_u * (1 + excess), rel=1e-9)


@pytest.mark.parametrize("excess", [1e-8, -1e-8])
def test_grazing_overturn_alpha_criterion(excess):
    """With a spring intact past α, an apex 1e-8 above α overturns under the α criterion."""
    kappa = 2.0
    anchorage = Anchorage(kappa_max=kappa, damping_ratio=0.0, spring_ultimate_rotation=1.3 * ALPHA,
                          damper_ultimate_rotation=1.3 * ALPHA)
    theta0 = 0.5 * ALPHA
    speed = _speed_for_apex(theta0, ALPHA * (1 + excess), kappa)
    r = simulate_reference(BLC06, anchorage, Control("PASSIVE"), STILL, initial_rotation=theta0,
                           initial_velocity=speed, overturn_criterion="alpha", free_time=1.0)
    assert r.overturned == (excess > 0)
    if excess > 0:
        assert r.max_rotation_ratio == pytest.approx(1.0, rel=1e-12)


# ----------------------------------------------------------------------------- symmetry and limits
def test_cs01_with_equal_stiffnesses_is_passive():
    anchorage = Anchorage(kappa_max=0.8, kappa_min=0.8)
    motion = modulated(2.0, 1.8)
    passive = simulate_reference(BLC06, anchorage, Control("PASSIVE"), motion, free_time=5.0)
    cs01 = simulate_reference(BLC06, anchorage, Control("CS01"), motion, free_time=5.0)
    assert cs01.status == passive.status and cs01.n_impacts == passive.n_impacts > 0
    np.testing.assert_allclose(cs01.impact_times, passive.impact_times, rtol=0, atol=1e-8)
    assert cs01.max_rotation_ratio == pytest.approx(passive.max_rotation_ratio, rel=1e-8)


def test_inert_passive_anchorage_is_free_standing():
    motion = modulated(2.0, 1.8)
    inert = simulate_reference(BLC06, Anchorage(kappa_max=0.0, damping_ratio=0.0), Control("PASSIVE"), motion)
    free = simulate_reference(BLC06, Anchorage(), Control("FS"), motion)
    assert inert.summary() == free.summary()
    assert free.n_impacts > 0


# ----------------------------------------------------------------------------- control laws
def test_cs01_law_in_history():
    """Eq. (16): K_max while θ·θ̇ > 0, K_min while θ·θ̇ < 0 (held points excepted)."""
    a = Anchorage(kappa_max=1.0, kappa_min=0.2)
    r = simulate_reference(BLC06, a, Control("CS01"), modulated(2.0, 1.6), free_time=5.0, record_history=True)
    h = r.history
    product = h["theta"] * h["theta_dot"]
    moving = np.abs(product) > 1e-12
    assert moving.sum() > 1000
    expected = np.where(product[moving] > 0, a.kappa_max, a.kappa_min)
    np.testing.assert_array_equal(h["kappa"][moving], expected)


def test_cs02_law_in_history():
    """Eq. (17): during the excitation K_max iff Ẍg·θ < 0; afterwards CS01."""
    a = Anchorage(kappa_max=1.0, kappa_min=0.2)
    motion = modulated(2.0, 1.6)
    r = simulate_reference(BLC06, a, Control("CS02"), motion, free_time=5.0, record_history=True)
    h = r.history
    ground = h["ground_acceleration"]
    during = (h["t"] < motion.duration) & (np.abs(h["theta"]) > 1e-10) & (np.abs(ground) > 1e-9 * motion.peak())
    assert during.sum() > 500
    expected = np.where(ground[during] * h["theta"][during] < 0, a.kappa_max, a.kappa_min)
    np.testing.assert_array_equal(h["kappa"][during], expected)
    after = (h["t"] > motion.duration) & (np.abs(h["theta"] * h["theta_dot"]) > 1e-12)
    assert after.sum() > 100
    expected = np.where(h["theta"][after] * h["theta_dot"][after] > 0, a.kappa_max, a.kappa_min)
    np.testing.assert_array_equal(h["kappa"][after], expected)


def _cs01_decision(t, theta, theta_dot, ground, duration):
    return theta * theta_dot >= 0


def _cs02_decision(t, theta, theta_dot, ground, duration):
    if t < duration and ground != 0:
        return ground * theta <= 0
    return theta * theta_dot >= 0


@pytest.mark.parametrize("strategy, sampling_time, delay", [
    ("CS01", 0.01, 0.004), ("CS01", 0.01, 0.025), ("CS02", 0.01, 0.006), ("CS02", 0.02, 0.0)])
def test_sampled_control_zero_order_hold(strategy, sampling_time, delay):
    """The stiffness only changes at t_k + Δτ, to the decision of Eq. (16)/(17) on θ(t_k),
    θ̇(t_k), Ẍg(t_k), held until the next decision acts; K_max before the first one acts."""
    a = Anchorage(kappa_max=1.0, kappa_min=0.0)
    motion = modulated(2.0, 1.6)
    decide = _cs01_decision if strategy == "CS01" else _cs02_decision
    r = simulate_reference(BLC06, a, Control(strategy, sampling_time, delay), motion, free_time=3.0,
                           record_history=True)
    h = r.history
    t, kappa = h["t"], h["kappa"]
    assert np.all(kappa[t < delay] == a.kappa_max)
    change = np.nonzero(np.diff(kappa) != 0)[0]
    assert len(change) > 20
    assert np.all(t[change] == t[change + 1])  # changes are jumps at a stop ...
    phase = (t[change] - delay) / sampling_time
    np.testing.assert_allclose(phase, np.round(phase), rtol=0, atol=1e-9)  # ... at actuation instants
    checked, peak = 0, motion.peak()
    for k in range(1, int(r.end_time / sampling_time) - 2):
        tk = k * sampling_time
        i = np.searchsorted(t, tk - 1e-12)
        if i + 1 >= len(t) or abs(t[i] - tk) > 1e-12 or abs(t[i + 1] - tk) <= 1e-12:
            continue  # t_k is not a (single) history point
        th, thd, ground = h["theta"][i], h["theta_dot"][i], h["ground_acceleration"][i]
        if th != 0 and abs(thd) < 1e-9 or 0 < abs(ground) < 1e-9 * peak:
            continue  # too close to a switching surface to tell
        on = decide(tk, th, thd, ground, motion.duration)
        lo, hi = np.searchsorted(t, tk + delay, side="right"), np.searchsorted(t, tk + sampling_time + delay)
        assert np.all(kappa[lo:hi] == (a.kappa_max if on else a.kappa_min)), k
        checked += 1
    assert checked > 100


def _held_points(h):
    """Indices inside held stretches: θ̇ = 0 exactly with θ ≠ 0 unchanged over time."""
    still = (h["theta_dot"] == 0) & (h["theta"] != 0)
    same = np.zeros_like(still)
    same[1:-1] = still[1:-1] & still[:-2] & still[2:] & (h["theta"][1:-1] == h["theta"][:-2]) \
        & (h["theta"][1:-1] == h["theta"][2:])
    return np.nonzero(same)[0]


def test_cs01_sliding_case_finishes_and_sampled_control_converges():
    """MODEL-NOTES §1: BLC06, default anchorage, Eq. 23 at ω_p = p, a_p = 1.2 g tanα.

    Continuous CS01 finishes, holds the block on θ̇ = 0 where a_max ≤ 0 ≤ a_min (Filippov),
    and sampled CS01 with T_s = 1 ms gives nearly the same peak rotation.
    """
    motion = modulated(1.0, 1.2)
    anchorage = Anchorage()
    r = simulate_reference(BLC06, anchorage, Control("CS01"), motion, record_history=True)
    assert r.status in ("rest", "time limit")
    h = r.history
    held = _held_points(h)
    assert len(held) > 10
    for i in held:
        theta = h["theta"][i]
        s = 1 if theta > 0 else -1
        args = (h["ground_acceleration"][i], 0.0, BLC06.p, BLC06.gravity, math.sin(ALPHA), math.cos(ALPHA))
        spring = float(s * theta < anchorage.theta_spring(BLC06))
        a_max = angular_acceleration(theta, 0.0, float(s), anchorage.kappa_max * spring, 0.0, *args)
        a_min = angular_acceleration(theta, 0.0, float(s), anchorage.kappa_min * spring, 0.0, *args)
        a_eq = angular_acceleration(theta, 0.0, float(s), h["kappa"][i] * spring, 0.0, *args)
        assert s * a_max <= 1e-9 and s * a_min >= -1e-9
        assert anchorage.kappa_min <= h["kappa"][i] <= anchorage.kappa_max
        assert abs(a_eq) < 1e-9
    sampled = simulate_reference(BLC06, anchorage, Control("CS01", 1e-3), motion)
    assert sampled.status == r.status
    assert sampled.max_rotation_ratio == pytest.approx(r.max_rotation_ratio, rel=0.03)


@pytest.mark.parametrize("strategy", ["CS01", "CS02"])
def test_sampled_control_converges_to_continuous(strategy):
    """As T_s → 0 the sampled law approaches the continuous one (peak rotation)."""
    motion = modulated(2.0, 1.6)
    continuous = simulate_reference(BLC06, Anchorage(), Control(strategy), motion)
    gaps = []
    for sampling_time in (1e-2, 1e-3):
        sampled = simulate_reference(BLC06, Anchorage(), Control(strategy, sampling_time), motion)
        assert sampled.status == continuous.status
        gaps.append(abs(sampled.max_rotation_ratio / continuous.max_rotation_ratio - 1))
    assert gaps[1] < 0.01 and gaps[1] < gaps[0]


# ----------------------------------------------------------------------------- overturning
def test_overturn_criteria():
    """FS under a strong pulse overturns; the α criterion triggers first, at |θ| = α."""
    motion = one_sine(1.0, 3.0)
    flat = simulate_reference(BLC06, Anchorage(), Control("FS"), motion, record_history=True)
    alpha = simulate_reference(BLC06, Anchorage(), Control("FS"), motion, overturn_criterion="alpha",
                               record_history=True)
    assert flat.overturned and alpha.overturned and flat.status == "overturned"
    assert alpha.overturn_time < flat.overturn_time
    assert flat.max_rotation_ratio == pytest.approx(math.pi / 2 / ALPHA, rel=1e-12)
    assert alpha.max_rotation_ratio == pytest.approx(1.0, rel=1e-12)
    assert abs(alpha.history["theta"][-1]) == pytest.approx(ALPHA, rel=1e-12)
    # same trajectory up to then: the flat run crosses |θ| = α at the α run's overturn time
    h = flat.history
    i = np.nonzero(np.abs(h["theta"]) >= ALPHA)[0][0]
    crossing = np.interp(ALPHA, np.abs(h["theta"][i - 1:i + 1]), h["t"][i - 1:i + 1])
    assert crossing == pytest.approx(alpha.overturn_time, abs=1e-4)


# ----------------------------------------------------------------------------- the engine's parts
def test_every_reference_module_is_outside_the_simulation_fingerprint():
    """The workflow reruns the simulations when a module they run changes; the reference engine is not one."""
    from rockstudy.studies import fingerprints

    hashed = {p.as_posix() for p in fingerprints.fingerprint_files()}
    assert "engine/_kernel/engine.py" in hashed and "model/control.py" in hashed
    assert not {name for name in hashed if name.startswith("engine/reference/")}
    assert any(p.as_posix().startswith("engine/reference/") for p in fingerprints.fingerprint_files("engine"))


def test_filippov_stiffness_zeroes_the_acceleration():
    """θ̈ is affine in κ, so the equivalent stiffness gives θ̈ = 0 exactly (up to round-off)."""
    from rockstudy.engine.reference.controller import filippov_stiffness

    args = (0.3 * ALPHA, 0.0, 1.0)
    ground = (-1.0 * UPLIFT, 0.0, P, GRAVITY, math.sin(ALPHA), math.cos(ALPHA))
    a_max = angular_acceleration(*args, 2.0, 0.0, *ground)
    a_min = angular_acceleration(*args, 0.0, 0.0, *ground)
    assert a_max < 0 < a_min  # a held state: K_max pulls back, K_min lets it go out
    kappa = filippov_stiffness(a_max, a_min, 2.0, 0.0)
    assert 0.0 < kappa < 2.0
    assert abs(angular_acceleration(*args, kappa, 0.0, *ground)) < 1e-12 * abs(a_min)
    assert filippov_stiffness(1.0, 1.0, 2.0, 0.0) == 2.0


def test_armed_event_does_not_fire_at_its_start():
    """On its surface at t0 an event reads a tiny value on the approach side; later, its plain value."""
    from rockstudy.engine.reference.events import Apex, Impact, TurningPoint

    impact = Impact(side=-1, t0=0.5)  # s·θ falls through 0: approached from above
    assert impact(0.5, np.array([0.0, 1.0])) > 0.0
    assert impact(0.5, np.array([-0.2, 1.0])) == pytest.approx(0.2)  # already on the approach side
    assert impact(0.6, np.array([0.0, 1.0])) == 0.0
    apex = Apex(side=1, vel_sign=-1, t0=0.0)  # returning: s·θ̇ rises through 0
    assert apex.direction == 1 and apex(0.0, np.array([0.1, 0.0])) < 0.0
    turn = TurningPoint(side=1)
    assert not turn.terminal and turn.direction == 0 and turn(0.0, np.array([0.1, 0.0])) == 0.0


def test_sampled_queue_hand_worked():
    """T_s = 0.1 s, Δτ = 0.03 s: a change read at the next sample, overwritten within an interval."""
    from rockstudy.engine.reference.controller import Controller

    c = Controller("CS01", 1.0, 0.0, sampling_time=0.1, delay=0.03)
    c.push(0.0, True)  # read at t_0 = 0, acts at 0.03
    c.push(0.05, False)  # read at t_1 = 0.1 ...
    assert list(c.queue) == [(0, True), (1, False)]
    c.push(0.07, True)  # ... but back on before t_1: t_1 reads on, the same as t_0's decision
    assert list(c.queue) == [(0, True)]
    assert c.next_actuation() == pytest.approx(0.03)
    c.push(0.25, False)  # read at t_3 = 0.3, acts at 0.33
    assert c.kappa_at(np.array([0.02, 0.1, 0.34]), law_on=True) == [1.0, 1.0, 0.0]
    c.apply_due(0.2)
    assert c.active_on and list(c.queue) == [(3, False)]
    c.apply_due(0.34)
    assert not c.active_on and c.kappa(law_on=True) == 0.0 and c.next_actuation() == math.inf


def test_history_grid_is_strictly_inside():
    from rockstudy.engine.reference.recorder import HISTORY_STEP, history_grid

    assert history_grid(0.0, 3 * HISTORY_STEP) == pytest.approx([HISTORY_STEP, 2 * HISTORY_STEP])
    assert len(history_grid(HISTORY_STEP, 1.5 * HISTORY_STEP)) == 0
