"""Physics oracles for the compiled fast engine: closed forms, symmetry, energy, reductions."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from rockstudy import Anchorage, Block, Control
from rockstudy.engine.simulate import simulate
from rockstudy.model.excitation import GroundMotion, modulated_duration

NO_MOTION = GroundMotion("one-sine", 0.0, 1.0, 1.0)


def quarter_period(block, theta0):
    """Exact quarter period of free rocking from rest at theta0 (energy quadrature). [s]"""
    p, a = block.p, block.alpha
    return quad(lambda th: 1.0 / math.sqrt(2 * p * p * (math.cos(a - theta0) - math.cos(a - th))), 0, theta0,
                limit=200)[0]


def impact_pairs(result):
    """(t, theta_dot before, theta_dot after) at each impact, read from the history."""
    h = result.history
    t, v = h["t"], h["theta_dot"]
    pairs = []
    for ti in result.impact_times:
        idx = np.flatnonzero(t == ti)
        if len(idx) >= 2:
            pairs.append((ti, v[idx[0]], v[idx[-1]]))
    return pairs


def test_cs01_release_loses_the_spring_energy(blc06):
    """CS01, kappa_min = 0, no damper: out with the spring, back without it."""
    kappa = 1.0
    anch = Anchorage(kappa_max=kappa, kappa_min=0.0, damping_ratio=0.0)
    p, a = blc06.p, blc06.alpha
    r = simulate(blc06, anch, Control("CS01"), NO_MOTION, initial_rotation=0.5 * a, record_history=True)
    pairs = impact_pairs(r)
    for (_, _, after), (_, before_next, _) in zip(pairs[:5], pairs[1:6]):
        # outward with the spring on: theta_dot^2/2p^2 + cos a = cos(a - th_a) + 2 kappa sin^2(th_a/2)
        c = after**2 / (2 * p * p) + math.cos(a)
        th_a = __import__("scipy.optimize", fromlist=["brentq"]).brentq(
            lambda th, c=c: math.cos(a - th) + 2 * kappa * math.sin(th / 2) ** 2 - c, 0.0, a)
        # back with the spring released: the spring energy is gone
        v_back = math.sqrt(2 * p * p * (math.cos(a - th_a) - math.cos(a)))
        assert abs(before_next) == pytest.approx(v_back, rel=1e-7)


@pytest.mark.parametrize("pt1", [0.5, 1.0, 2.0])
def test_rectangular_pulse_closed_form_on_slender_block(pt1):
    alpha = 0.02
    block = Block.slender(alpha, R=1.0)
    t1 = pt1 / block.p
    predicted = 1.0 / (1.0 - math.exp(-pt1))  # a/(g alpha), linearised

    def overturns(beta):
        m = GroundMotion("rectangular", beta * block.gravity * alpha, 0.0, t1)
        return simulate(block, Anchorage(), Control("FS"), m, free_time=5.0).overturned

    lo, hi = 1.0, 10.0
    while hi - lo > 1e-4:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if overturns(mid) else (mid, hi)
    assert hi == pytest.approx(predicted, rel=0.005)


def test_reductions(blc06):
    om = 2 * blc06.p
    m = GroundMotion("modulated", 1.8 * blc06.uplift_acceleration, om, modulated_duration(om))
    fs = simulate(blc06, Anchorage(), Control("FS"), m, record_history=True)
    inert = simulate(blc06, Anchorage(kappa_max=0.0, damping_ratio=0.0), Control("PASSIVE"), m, record_history=True)
    np.testing.assert_array_equal(fs.history["theta"], inert.history["theta"])  # K = D = 0 is FS exactly
    equal = Anchorage(kappa_max=0.7, kappa_min=0.7)
    passive = simulate(blc06, equal, Control("PASSIVE"), m, record_history=True)
    for s in ("CS01", "CS02"):
        r = simulate(blc06, equal, Control(s), m, record_history=True)
        np.testing.assert_array_equal(r.history["theta"], passive.history["theta"])


def test_cs01_sliding_is_held_and_sampled_control_converges_to_it(blc06, anchorage):
    """MODEL-NOTES §1: BLC06, Eq. 23, omega_p/p = 1, a_p/(g tan a) = 1.2 slides on theta_dot = 0."""
    om = blc06.p
    m = GroundMotion("modulated", 1.2 * blc06.uplift_acceleration, om, modulated_duration(om))
    cont = simulate(blc06, anchorage, Control("CS01"), m, record_history=True)
    assert cont.status == "rest"
    h = cont.history
    held = (h["theta_dot"] == 0.0) & (np.abs(h["theta"]) > 1e-3)
    assert held.sum() >= 2  # the block is held still away from upright
    errors = [abs(simulate(blc06, anchorage, Control("CS01", sampling_time=ts), m).max_rotation_ratio
                  - cont.max_rotation_ratio) for ts in (1e-2, 1e-3, 3e-4)]
    assert errors[-1] < 0.01 * cont.max_rotation_ratio
    assert errors[0] > errors[-1]


def test_fracture_is_permanent_and_located(blc06):
    om = 1.0 * blc06.p
    m = GroundMotion("modulated", 3.0 * blc06.uplift_acceleration, om, modulated_duration(om))
    r = simulate(blc06, Anchorage(), Control("PASSIVE"), m, record_history=True)
    assert r.fracture_times, "a large excitation should break an element"
    h = r.history
    for name, tf in r.fracture_times.items():
        i = np.flatnonzero(h["t"] == tf)[0]
        side = 1 if name.endswith("left") else -1
        assert side * h["theta"][i] == pytest.approx(blc06.alpha, abs=1e-9)  # theta_u = alpha


def test_tighter_tolerance_changes_nothing_that_matters(blc06, anchorage):
    om = 2 * blc06.p
    m = GroundMotion("modulated", 1.5 * blc06.uplift_acceleration, om, modulated_duration(om))
    a = simulate(blc06, anchorage, Control("CS02"), m)
    b = simulate(blc06, anchorage, Control("CS02"), m, rtol=1e-11, atol=1e-13)
    assert a.status == b.status
    assert a.max_rotation_ratio == pytest.approx(b.max_rotation_ratio, rel=1e-5)


def test_bad_arguments_raise_clear_errors(blc06, anchorage):
    with pytest.raises(ValueError, match="engine"):
        simulate(blc06, anchorage, Control("FS"), NO_MOTION, engine="turbo")
    with pytest.raises(ValueError, match="overturn_criterion"):
        simulate(blc06, anchorage, Control("FS"), NO_MOTION, overturn_criterion="tipped")


@pytest.mark.parametrize("strategy", ["FS", "PASSIVE", "CS01"])
@pytest.mark.parametrize("excess", [1e-6, 1e-8, 1e-10])
def test_uplift_shorter_than_a_step_is_resolved_not_looped(blc06, anchorage, strategy, excess):
    """A one-sine pulse whose peak exceeds g·tanα by a factor 1 + ε lifts the block for a
    window shorter than the integrator's step. The engine must resolve that excursion and come
    back to rest, not re-uplift at the same instant until the event cap (the Zeno loop found at
    5 % noise, PASSIVE, omega_p/p = 3.15, realisation 22).

    Oracle: near the peak the net outward acceleration is A·(w² − τ²), with w the half-width of
    the window where |Ẍg| > g·tanα. From θ = θ̇ = 0 at τ = −w, θ(τ) ∝ w·u³/3 − u⁴/12 with
    u = τ + w, so the block lands at u = 4w (FS, and PASSIVE whose spring moment is negligible
    at these rotations)."""
    w_p = blc06.p
    motion = GroundMotion("one-sine", blc06.uplift_acceleration * (1.0 + excess), w_p, 2 * math.pi / w_p)
    r = simulate(blc06, anchorage, Control(strategy), motion, free_time=1.0)
    t_up = math.asin(1.0 / (1.0 + excess)) / w_p
    w = 0.5 * math.pi / w_p - t_up
    assert r.status == "rest"
    assert len(r.uplift_times) == 1
    assert r.uplift_times[0] == pytest.approx(t_up, abs=1e-3 * w)
    if strategy == "CS01":  # its apex switch may end an excursion below atol earlier
        assert t_up + 2 * w < r.rest_times[-1] <= t_up + 4.1 * w
    else:
        assert r.rest_times[-1] - t_up == pytest.approx(4 * w, rel=1e-2)


def test_first_half_cycle_of_eq23_uplifts_only_above_4_337(blc06, anchorage):
    """Eq. 23 spans five periods, so its first half-cycle peaks at a fixed fraction of the
    largest peak (about 1/4.34, computed here from the formula). Above that amplitude ratio the block
    uplifts in the first half-cycle at any frequency, which is the horizontal edge of the
    overturning maps."""
    s = np.linspace(0.0, 0.1, 200001)  # the first half-cycle, in units of T_d
    env = 90 * s**2 * (s - 1) ** 6 * np.abs(np.sin(2 * np.pi * 5 * (s - 1)))
    edge = 1.0 / env.max()  # a_p/(g·tanα) at which the first half-cycle reaches g·tanα
    assert 4.3 < edge < 4.4
    for ratio in (0.5, 1.7):
        omega = ratio * blc06.p
        half = np.pi / omega
        for a, first_half in ((0.99 * edge, False), (1.01 * edge, True)):
            motion = GroundMotion("modulated", a * blc06.uplift_acceleration, omega, modulated_duration(omega))
            r = simulate(blc06, anchorage, Control("CS01"), motion)
            assert (r.uplift_times[0] < half) == first_half


def test_energy_bound_never_changes_an_outcome(blc06):
    """The early stop below the overturning energy (docs/model.md) gives the same outcome as
    integrating on, on random runs of every strategy, T_s, Δτ, criterion and anchorage, noisy or not."""
    from rockstudy.engine import _kernel as kn
    from rockstudy.engine.simulate import pack_parameters
    from rockstudy.model.noise import noisy_record, record_motion

    rng = np.random.default_rng(2026)
    records = [(noisy_record("modulated", fr * blc06.p, 0.05, k, 7), fr * blc06.p)
               for k, fr in enumerate((1.5, 3.0, 4.5))]
    n_cases, n_stopped, n_stopped_sampled, strategies = 2000, 0, 0, ("FS", "PASSIVE", "CS01", "CS02")
    for i in range(n_cases):
        strategy = strategies[i % 4]
        sampling = (0.0, 0.0, 0.01, 0.05)[(i // 4) % 4]
        delay = 0.0 if sampling == 0 else float(rng.choice([0, 0.02, 0.2]))
        control = Control(strategy, sampling_time=sampling, delay=delay)
        kmax = float(rng.uniform(0.1, 3.0 if i % 7 else 10.0))
        anchorage = Anchorage(kappa_max=kmax, kappa_min=float(rng.uniform(0, kmax)),
                              damping_ratio=float(rng.uniform(0, 0.1)),
                              spring_ultimate_rotation=float(rng.uniform(0.3, 1.2) * blc06.alpha),
                              damper_ultimate_rotation=float(rng.uniform(0.3, 1.2) * blc06.alpha))
        amplitude = float(rng.uniform(1.0, 5.0)) * blc06.uplift_acceleration
        if i % 3 == 0:
            rec, om = records[int(rng.integers(len(records)))]
            motion = record_motion(rec, amplitude, om)
        else:
            om = float(rng.uniform(0.5, 5.0)) * blc06.p
            kind = "modulated" if i % 3 == 1 else "one-sine"
            end = modulated_duration(om) if kind == "modulated" else 2 * math.pi / om
            motion = GroundMotion(kind, amplitude, om, end)
        criterion = "alpha" if i % 5 == 0 else "flat"
        results = []
        for bound in (False, True):
            P = pack_parameters(blc06, anchorage, control, motion, overturn_criterion=criterion, free_time=10.0,
                                energy_bound=bound)
            results.append(kn.simulate_kernel(P, motion.record, motion.vertical, False, False))
        full, cut = results
        assert (cut.status == kn.ST_OVER) == (full.status == kn.ST_OVER), (i, strategy, sampling, full.status)
        assert (cut.n_impacts > 0) == (full.n_impacts > 0) or cut.status != kn.ST_OVER
        if cut.status == kn.ST_BOUND:
            n_stopped += 1
            n_stopped_sampled += sampling > 0
            assert full.status in (kn.ST_REST, kn.ST_TLIM) and cut.end_time <= full.end_time
        else:  # not stopped early: the very same run
            assert (cut.status, cut.end_time, cut.n_impacts) == (full.status, full.end_time, full.n_impacts)
    assert n_stopped > n_cases // 8  # the bound does act
    assert n_stopped_sampled > n_cases // 40  # ... under sampled control too


def _random_noisy_case(rng, block, i):
    """(anchorage, motion) of a random run on a noisy record (realisation ``i``) of random frequency, noise
    level, device and amplitude, drawn from ``rng``."""
    from rockstudy.model.noise import noisy_record, record_motion

    fr = float(rng.uniform(0.5, 5.0))
    rec = noisy_record("modulated", fr * block.p, float(rng.choice([0.01, 0.05, 0.1])), i, 7)
    kmax = float(rng.uniform(0.1, 3.0))
    anchorage = Anchorage(kappa_max=kmax, kappa_min=float(rng.uniform(0, kmax)),
                          damping_ratio=float(rng.uniform(0, 0.1)))
    return anchorage, record_motion(rec, float(rng.uniform(1.0, 4.0)) * block.uplift_acceleration, fr * block.p)


def test_quiet_knots_at_rest_pass_as_the_driver_would(blc06):
    """At rest under a record the knots pass in one tight loop (outcome runs only); a run with its
    history on takes every knot through the driver's loop. Both must be the very same run, to the
    bit: ending, end time, impacts, largest rotation, fracture times."""
    from rockstudy.engine import _kernel as kn
    from rockstudy.engine.simulate import pack_parameters

    rng = np.random.default_rng(11)
    n_rest_knots = 0
    for i in range(120):
        strategy = ("FS", "PASSIVE", "CS01", "CS02")[i % 4]
        anchorage, motion = _random_noisy_case(rng, blc06, i)
        P = pack_parameters(blc06, anchorage, Control(strategy), motion, free_time=5.0, energy_bound=False)
        quiet = kn.simulate_kernel(P, motion.record, motion.vertical, False, False)
        driver = kn.simulate_kernel(P, motion.record, motion.vertical, True, False)
        assert (quiet.status, quiet.end_time, quiet.n_impacts, quiet.max_abs_theta) == \
            (driver.status, driver.end_time, driver.n_impacts, driver.max_abs_theta), (i, strategy)
        np.testing.assert_array_equal(quiet.fracture_times, driver.fracture_times)
        hist = driver.history
        n_rest_knots += int(np.sum((hist[:, 1] == 0.0) & (hist[:, 2] == 0.0)))
    assert n_rest_knots > 1000  # the runs do rest between knots, so the loop is exercised


def test_controller_samples_in_the_step_loop_as_the_driver_would(blc06):
    """Under sampled control an outcome run takes the controller's samples inside its loops — at rest in
    the loop over known times, rocking in the step loop when a sample leaves the device as it is — where
    a run with its history on takes every sample through the driver's loop. Both must be the very same
    run, to the bit, for every strategy, sampling times from the record step up (one no multiple of it)
    and delays from none to several samples."""
    from rockstudy.engine import _kernel as kn
    from rockstudy.engine.simulate import pack_parameters

    rng = np.random.default_rng(12)
    samples_rocking = 0
    for i in range(96):
        strategy = ("FS", "PASSIVE", "CS01", "CS02")[i % 4]
        ts = (0.0025, 0.003, 0.01, 0.1)[(i // 4) % 4]
        delay = float(rng.choice([0.0, 0.0025, 0.06]))
        anchorage, motion = _random_noisy_case(rng, blc06, i)
        control = Control(strategy, sampling_time=ts, delay=delay)
        P = pack_parameters(blc06, anchorage, control, motion, free_time=5.0, energy_bound=False)
        quiet = kn.simulate_kernel(P, motion.record, motion.vertical, False, True)
        driver = kn.simulate_kernel(P, motion.record, motion.vertical, True, True)
        assert (quiet.status, quiet.end_time, quiet.n_impacts, quiet.max_abs_theta) == \
            (driver.status, driver.end_time, driver.n_impacts, driver.max_abs_theta), (i, strategy, ts, delay)
        for field in ("fracture_times", "impact_times", "uplift_times", "rest_times"):
            np.testing.assert_array_equal(getattr(quiet, field), getattr(driver, field), err_msg=f"{i} {field}")
        hist = driver.history
        rocking = (hist[:, 1] != 0.0) & (hist[:, 0] < motion.duration)
        on_sample = np.abs(hist[:, 0] / ts - np.round(hist[:, 0] / ts)) < 1e-9
        samples_rocking += int(np.sum(rocking & on_sample))
    assert samples_rocking > 1000  # the runs do rock across samples, so the step loop takes them


def _pumping_device_peak(block, kappa_high, theta, theta_dot, n_half_cycles=40):
    """Largest |θ| of free rocking under the worst device: K = κ_hi exactly while the block returns
    (sin θ·θ̇ < 0), 0 while it moves out; undamped; impacts by Eq. (14). Independent of the engine:
    scipy's DOP853 on Eq. (1) written out here, one half-excursion at a time."""
    from scipy.integrate import solve_ivp

    p, a, e = block.p, block.alpha, block.e

    def half(y, side, kappa, events):
        def rhs(t, z):
            return [z[1], -p * p * (side * math.sin(a - side * z[0]) + kappa * math.sin(z[0]))]
        for ev in events:
            ev.terminal = True
        return solve_ivp(rhs, (0, 100), y, method="DOP853", rtol=1e-11, atol=1e-13, events=events).y[:, -1]

    side = math.copysign(1.0, theta if theta != 0 else theta_dot)
    peak = abs(theta)
    y = [theta, theta_dot]
    for _ in range(n_half_cycles):
        if side * y[1] > 0:  # outward, spring off, until the apex or |θ| = α
            y = list(half(y, side, 0.0, [lambda t, z, s=side: s * z[1], lambda t, z, s=side: s * z[0] - a]))
            peak = max(peak, abs(y[0]))
            if side * y[0] >= a - 1e-12:
                return peak
        # inward (or at the apex), spring on, until θ = 0
        y = half(y, side, kappa_high, [lambda t, z: z[0]])
        side, y = -side, [0.0, y[1] * e]
        if abs(y[1]) < 1e-9:
            break
    return peak


def test_switching_bound_against_a_pumping_device(blc06):
    """From every state the sampled-control bound accepts, the worst device (full stiffness exactly
    while the block returns) never brings it to |θ| = α; and the bound is needed: from some states the
    continuous bound (W < 1) accepts, that device does overturn the block."""
    from rockstudy.engine._kernel import maps

    p, a, e = blc06.p, blc06.alpha, blc06.e
    rng = np.random.default_rng(11)
    accepted, pumped_over = 0, 0
    for _ in range(100):
        kappa_high = float(rng.choice([0.5, 1.0, 4.0, 10.0]))
        scale = float(rng.choice([0.3, 1.0]))  # small rocking, where the bound acts, and large
        theta = float(rng.uniform(-a, a)) * scale
        theta_dot = float(rng.uniform(-1, 1)) * scale * p * math.sqrt(2 * (1 - math.cos(a - abs(theta))))
        side = math.copysign(1.0, theta if theta != 0 else theta_dot)
        peak = _pumping_device_peak(blc06, kappa_high, theta, theta_dot)
        if maps.cannot_overturn_switching(theta, theta_dot, side, p, a, e, kappa_high):
            accepted += 1
            assert peak < a, (kappa_high, theta, theta_dot, peak)
        elif maps.cannot_overturn(theta, theta_dot, p, a, 0.0) and peak >= a:
            pumped_over += 1
    assert accepted >= 15
    assert pumped_over >= 5


def test_functions_compiled_without_reference_counting_count_none():
    """The engine's hot functions are compiled with ``core._inline.NO_REFCOUNT`` (numba's private
    ``_nrt`` flag), and numba honours the flag: a function compiled with it that reads and writes
    arrays calls neither NRT_incref nor NRT_decref, the same function compiled without it does. A
    numba that drops or renames the flag fails here instead of silently slowing the engine down."""
    import re

    from numba import njit

    from rockstudy.core._inline import NO_REFCOUNT
    from rockstudy.engine._kernel import dopri, engine, events, ground, taylor

    for fn in (engine.integrate, engine.drive, taylor.step, dopri.step, dopri.rhs,
               dopri.dense_coefficients,
               ground.ground_acceleration, ground.sensed_acceleration, events.scan_exit,
               events.locate_sensed_poly):
        assert all(fn.targetoptions.get(k) == v for k, v in NO_REFCOUNT.items()), fn.__name__

    def body(a, b, n):
        s = 0.0
        for i in range(n):
            if a[i % a.shape[0]] > 0.0:
                b[i % b.shape[0]] = s
                s += a[(i + 1) % a.shape[0]]
        return s

    def counts(fn):
        fn(np.ones(3), np.zeros(2), 10)
        return len(re.findall(r"call \w+ @NRT_(?:incref|decref)", fn.inspect_llvm(fn.signatures[0])))

    assert counts(njit(**NO_REFCOUNT)(body)) == 0
    assert counts(njit(body)) > 0


def test_every_compiled_function_of_the_engine_divides_without_a_zero_test():
    """Every compiled function of the engine and the model is made by ``core._inline.njit``, with numba's
    ``error_model="numpy"``: a division tests no divisor for zero (the step loop's divisions, about 1 % of
    a run). A function decorated with ``numba.njit`` itself fails here. The error model decides only what a
    division by zero gives (±inf or NaN instead of ZeroDivisionError): shown on a compiled division."""
    import importlib
    import pkgutil

    import numba
    from numba.core.registry import CPUDispatcher

    from rockstudy.core._inline import njit
    from rockstudy.engine import _kernel

    modules = [importlib.import_module(f"rockstudy.engine._kernel.{m.name}")
               for m in pkgutil.iter_modules(_kernel.__path__)]
    modules += [importlib.import_module(f"rockstudy.model.{m}")
                for m in ("anchorage", "control", "equation_of_motion", "excitation")]
    found = {f"{mod.__name__}.{name}": fn for mod in modules for name, fn in vars(mod).items()
             if isinstance(fn, CPUDispatcher) and fn.py_func.__module__ == mod.__name__}
    assert len(found) > 40
    assert not [name for name, fn in found.items() if fn.targetoptions.get("error_model") != "numpy"]

    def ratio(a, b):
        return a / b

    assert njit(ratio)(1.0, 0.0) == math.inf
    assert math.isnan(njit(ratio)(0.0, 0.0))
    with pytest.raises(ZeroDivisionError):
        numba.njit(ratio)(1.0, 0.0)

def test_guarded_pow_is_cs_pow_bit_for_bit_and_not_llvms_intrinsic():
    """``core._inline.guarded_pow`` (the step-size power of the step loop) gives the bits of ``**`` in
    compiled code and in plain Python, and compiles to a call of C's ``pow``, not to the
    ``llvm.pow`` intrinsic that LLVM may evaluate ahead of the test guarding it."""
    from numba import njit

    from rockstudy.core._inline import guarded_pow

    @njit
    def guarded(x, y):
        return guarded_pow(x, y)

    @njit
    def plain(x, y):
        return x ** y

    rng = np.random.default_rng(5)
    for x in np.concatenate([rng.uniform(1e-12, 1.0, 200), rng.uniform(1.0, 1e6, 50)]):
        for y in (-0.2, 0.2, -0.125, 1.0 / 7.0):
            assert guarded(x, y) == plain(x, y) == guarded_pow(x, y) == x ** y
    ir = guarded.inspect_llvm(guarded.signatures[0])
    assert "@pow(" in ir and "llvm.pow" not in ir
    assert "llvm.pow" in plain.inspect_llvm(plain.signatures[0])
