"""The early stop during the excitation (docs/engine.md, "Early stops"): its input bound is an upper
bound, it never changes an outcome or a threshold, and it acts."""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from rockstudy import Anchorage, Control
from rockstudy.engine import _kernel as kn
from rockstudy.engine._kernel import maps
from rockstudy.engine._kernel.engine import cannot_uplift_any_more, driven_bound_data, remaining_input, run_kernel
from rockstudy.engine._kernel.layout import B_LEVEL
from rockstudy.engine._kernel.scan import case_outcome, is_overturned, scan_amplitude, scan_start, scan_update
from rockstudy.engine.simulate import kernel_record, pack_parameters
from rockstudy.model.excitation import GroundMotion, interpolate_record, modulated_acceleration, modulated_duration
from rockstudy.model.noise import noisy_record, record_motion

STRATEGIES = ("FS", "PASSIVE", "CS01", "CS02")


def _case(blc06, rng, i, records):
    """(P, rec) of a random run: every strategy, continuous or sampled with delay, noisy records and Eq. 23."""
    strategy = STRATEGIES[i % 4]
    sampling = (0.0, 0.0, 0.0025, 0.05)[(i // 4) % 4]
    delay = 0.0 if sampling == 0 else float(rng.choice([0.0, 0.02, 0.1]))
    control = Control(strategy, sampling_time=sampling, delay=delay)
    kmax = float(rng.uniform(0.05, 3.0))
    anchorage = Anchorage(kappa_max=kmax, kappa_min=float(rng.choice([0.0, rng.uniform(0, kmax)])),
                          damping_ratio=float(rng.uniform(0, 0.1)),
                          spring_ultimate_rotation=float(rng.uniform(0.3, 1.2) * blc06.alpha),
                          damper_ultimate_rotation=float(rng.uniform(0.3, 1.2) * blc06.alpha))
    amplitude = float(rng.uniform(1.0, 4.0)) * blc06.uplift_acceleration
    if i % 3:
        rec, om = records[int(rng.integers(len(records)))]
        motion = record_motion(rec, amplitude, om)
    else:
        om = float(rng.uniform(0.5, 5.0)) * blc06.p
        motion = GroundMotion("modulated", amplitude, om, modulated_duration(om))
    P = pack_parameters(blc06, anchorage, control, motion, overturn_criterion="alpha" if i % 5 == 0 else "flat",
                        free_time=10.0, energy_bound=True)
    return P, kn.writable(kernel_record(control, motion))


@pytest.fixture(scope="module")
def records(blc06):
    return [(noisy_record("modulated", fr * blc06.p, 0.05, k, 7), fr * blc06.p) for k, fr in enumerate((1.5, 3.0, 4.5))]


def _without_stop(B):
    B = B.copy()
    B[B_LEVEL] = 0.0  # nothing is below 0: the stop never fires
    return B


def test_remaining_input_bounds_the_input_still_to_come(blc06, records):
    """∫_t^T |Ẍg|/a_p dt by quadrature never exceeds the bound, for a record and for Eq. 23."""
    vert = np.zeros(0)
    rec, om = records[0]
    motion = record_motion(rec, 1.0, om)
    P = pack_parameters(blc06, Anchorage(), Control("CS01"), motion, energy_bound=True)
    samples = kn.writable(motion.record)
    B = driven_bound_data(P, samples, vert)
    dt, dur = P[kn.I_RDT], P[kn.I_DUR]
    fine = np.linspace(0.0, dur, 200001)
    mag = np.abs([interpolate_record(t, dt, samples) for t in fine])
    tail = np.concatenate([np.cumsum((0.5 * (mag[1:] + mag[:-1]) * np.diff(fine))[::-1])[::-1], [0.0]])
    for j in range(0, len(fine), 997):
        assert remaining_input(fine[j], P, B) >= tail[j] * (1 - 1e-9)
    om = 2.0 * blc06.p
    motion = GroundMotion("modulated", 1.0, om, modulated_duration(om))
    P = pack_parameters(blc06, Anchorage(), Control("CS01"), motion, energy_bound=True)
    B = driven_bound_data(P, np.zeros(0), vert)
    for t in np.linspace(0.0, motion.duration, 23):
        exact = quad(lambda s: abs(modulated_acceleration(s, 1.0, om, motion.duration)), t, motion.duration,
                     limit=400)[0]
        assert remaining_input(t, P, B) >= exact * (1 - 1e-9)


def test_no_uplift_any_more_means_no_uplift_ahead(blc06, records):
    """Where the engine says a resting block can no longer uplift, |Ẍg| stays at or below g·tanα on a fine
    grid to the end of the excitation; where it says it can, a knot ahead exceeds it."""
    vert = np.zeros(0)
    rec, om = records[1]
    motion = record_motion(rec, 1.0, om)
    samples = kn.writable(motion.record)
    uplift = blc06.gravity * math.tan(blc06.alpha)
    for ratio in (1.2, 2.0, 4.0):
        P = pack_parameters(blc06, Anchorage(), Control("CS01"), motion, energy_bound=True)
        P[kn.I_AMP] = ratio * uplift / float(np.max(np.abs(samples)))
        B = driven_bound_data(P, samples, vert)
        dt, dur = P[kn.I_RDT], P[kn.I_DUR]
        fine = np.linspace(0.0, dur, 100001)
        mag = P[kn.I_AMP] * np.abs([interpolate_record(t, dt, samples) for t in fine])
        ahead = np.maximum.accumulate(mag[::-1])[::-1]
        said = [cannot_uplift_any_more(t, P, B) for t in fine[::211]]
        assert any(said) and not all(said)
        for t, quiet, peak in zip(fine[::211], said, ahead[::211]):
            if quiet:
                assert peak <= uplift
            else:
                assert np.max(np.abs(samples[max(int(t / dt) - 1, 0):])) * P[kn.I_AMP] > uplift * (1 - 1e-8)


def test_switching_level_is_safe_after_the_excitation():
    """Below the switching level, the half-cycle bound of sampled control holds (maps.cannot_overturn_switching
    at the level's peak rotation); just above the level it does not hold for the level's own test."""
    for alpha, e, kmax in ((0.25, 0.9, 0.5), (0.1, 0.985, 0.2), (0.3, 0.7, 3.0)):
        level = maps.switching_level(alpha, e, kmax, 0.0, True)
        assert 0.0 < level < 1.0 - math.cos(alpha)
        theta = maps.peak_rotation(0.999 * level, alpha)
        assert maps.cannot_overturn_switching(theta, 0.0, 1.0, 1.0, alpha, e, kmax)
        assert not maps._free_level_holds(level * 1.001 + 1e-15, alpha, e, kmax, 0.0, True)
    assert maps.switching_level(0.25, 1.0, 0.5, 0.0, True) == 0.0  # no loss at impacts: no level is safe


def test_driven_stop_never_changes_an_outcome(blc06, records):
    """Random runs of every strategy, continuous and sampled with delay, on noisy records and Eq. 23: the
    run with the stop overturns exactly when the run without it does, at the same time, and is otherwise
    the same run up to the stop; the stop acts, for sampled switching control too, and the switching
    device's bound without the time left (the ``B_RATCHET`` levels) ends some runs sooner."""
    rng = np.random.default_rng(45)
    vert = np.zeros(0)
    n_cases, n_stopped, n_stopped_pumping, n_ratchet = 480, 0, 0, 0
    for i in range(n_cases):
        P, rec = _case(blc06, rng, i, records)
        B = driven_bound_data(P, rec, vert)
        cut = run_kernel(P, rec, vert, B, False, False)
        without_ratchet = B.copy()
        without_ratchet[kn.B_RATCHET:kn.B_TAIL] = 0.0
        n_ratchet += cut.end_time < run_kernel(P, rec, vert, without_ratchet, False, False).end_time
        full = run_kernel(P, rec, vert, _without_stop(B), False, False)
        assert (cut.status == kn.ST_OVER) == (full.status == kn.ST_OVER), i
        if cut.status == kn.ST_OVER:
            assert (cut.overturn_time, cut.end_time, cut.n_impacts) == (full.overturn_time, full.end_time,
                                                                       full.n_impacts)
        elif cut.end_time < full.end_time:
            assert cut.status == kn.ST_BOUND and cut.end_time < P[kn.I_DUR] and full.status != kn.ST_ELIMIT
            n_stopped += 1
            n_stopped_pumping += P[kn.I_TS] > 0 and STRATEGIES[i % 4] in ("CS01", "CS02")
        else:
            assert (cut.status, cut.end_time, cut.n_impacts) == (full.status, full.end_time, full.n_impacts)
    assert n_stopped > n_cases // 6
    assert n_stopped_pumping > 5 and n_ratchet > 20


def test_driven_stop_keeps_every_threshold(blc06, records):
    """Threshold scans (grazing runs near each threshold included) with and without the stop find the same
    threshold and the same highest safe amplitude."""
    rng = np.random.default_rng(7)
    vert = np.zeros(0)
    grid = np.round(np.arange(1.0, 6.0 + 1e-9, 0.25), 10)
    for i in range(40):
        P, rec = _case(blc06, rng, i, records)
        peak = float(np.max(np.abs(rec))) if rec.size else 1.0
        B = driven_bound_data(P, rec, vert)
        found = []
        for data in (B, _without_stop(B)):
            state = scan_start()
            done = False
            while not done:
                o = case_outcome(P, rec, vert, data, scan_amplitude(state, grid), peak)
                done = scan_update(state, grid, 1e-3, 1.0 / peak, is_overturned(o))
            found.append((state[kn.S_HI], state[kn.S_LO]))
        assert np.array_equal(found[0], found[1], equal_nan=True), (i, found)


def test_ratchet_levels_hold_their_claims():
    """Every impact lowers Q on [0, Q̄] (Ψ(e²q) <= q) and not just above the largest level; c bounds
    Ψ'(v) = 1 + κ_hi·sin θ_a/sin(α − θ_a) for every V₀ = v with Ψ(v) <= Q̄ (finite differences)."""
    for alpha, e, kmax in ((0.245, 0.912, 1.0), (0.1, 0.985, 0.2), (0.3, 0.7, 3.0), (0.245, 0.912, 0.05)):
        assert maps.RATCHET_FRACTIONS.size * 2 == kn.B_TAIL - kn.B_RATCHET
        pairs = np.full(kn.B_TAIL + 1, np.nan)
        maps.ratchet_levels(alpha, e, kmax, pairs, kn.B_RATCHET)
        assert np.isnan(pairs[kn.B_RATCHET - 1]) and np.isnan(pairs[kn.B_TAIL])
        pairs = pairs[kn.B_RATCHET:kn.B_TAIL].reshape(-1, 2)
        top = pairs[-1, 0]
        assert 0.0 < top < 1.0 - math.cos(alpha) and np.all(np.diff(pairs[:, 0]) > 0)

        def psi(v, alpha=alpha, kmax=kmax):
            return v + kmax * (1.0 - np.cos(alpha - np.arccos(np.minimum(1.0, np.cos(alpha) + v))))

        q = np.linspace(0.0, top, 2001)
        assert np.all(psi(e * e * q) <= q)
        assert psi(e * e * top * 1.001) > top * 1.001 * (1 - maps.DRIVEN_MARGIN) or top * 1.001 > (
            1 - math.cos(alpha)) * (1 - maps.DRIVEN_MARGIN)
        for level, c in pairs:
            v = np.linspace(0.0, level, 4001)
            v = v[psi(v) <= level]
            slope = np.diff(psi(v)) / np.diff(v)
            assert np.all(slope <= c * (1 + 1e-9)) and slope[-1] > c * (1 - 1e-2)


def _input_so_far(t, P, rec):
    """p/√2·∫₀ᵗ |Ẍg/g| dτ exactly, Ẍg linear between the record's knots (the kernel's input)."""
    dt, n = P[kn.I_RDT], int(P[kn.I_SOFF]) if P[kn.I_SENSE] != 0.0 else rec.shape[0]
    r = np.append(rec[:n], 0.0) * abs(P[kn.I_AMP])
    knots = np.arange(r.size) * dt

    def piece(a, b, h):  # ∫ over h of |a + (b − a)·s/h| ds
        if a * b >= 0.0:
            return 0.5 * h * (abs(a) + abs(b))
        return 0.5 * h * (a * a + b * b) / (abs(a) + abs(b))

    cum = np.concatenate([[0.0], np.cumsum([piece(r[k], r[k + 1], dt) for k in range(r.size - 1)])])
    out = np.empty_like(t)
    for j, tj in enumerate(np.minimum(t, P[kn.I_DUR])):
        k = min(int(tj / dt), r.size - 2)
        x = tj - knots[k]
        out[j] = cum[k] + piece(r[k], r[k] + (r[k + 1] - r[k]) * x / dt, x)
    return P[kn.I_P] / math.sqrt(2.0) * out / P[kn.I_G]


def test_ratchet_quantity_rises_only_by_the_input(blc06, records):
    """The claim behind the switching device's bound without the time left: along a run (sampled or delayed
    CS01/CS02 and continuous CS02, any κ_max, e, ξ, fracture), √Q − c·∫p/√2·|Ẍg/g| dt never rises while
    Q <= Q̄, through every impact, uplift and rest; Q = V₀ + κ_max·S(θ) returning, Ψ(V₀) otherwise."""
    rng = np.random.default_rng(17)
    vert = np.zeros(0)
    checked = 0
    for i in range(400):
        P, rec = _case(blc06, rng, i, records)
        strategy = STRATEGIES[i % 4]
        if i % 3 == 0 or strategy not in ("CS01", "CS02") or (P[kn.I_TS] == 0.0 and strategy == "CS01"):
            continue
        B = driven_bound_data(P, rec, vert)
        kmax = float(P[kn.I_KMAX])
        level, c = B[kn.B_RATCHET + 10], B[kn.B_RATCHET + 11]
        H = kn.simulate_kernel(P, rec, vert, True, False).history
        t, th, thd = H[:, 0], H[:, 1], H[:, 2]
        alpha, p = P[kn.I_ALPHA], P[kn.I_P]
        assert np.allclose(np.abs(H[t < P[kn.I_DUR], 4]), np.abs(np.interp(
            t[t < P[kn.I_DUR]], np.arange(int(P[kn.I_SOFF]) if P[kn.I_SENSE] else rec.size) * P[kn.I_RDT],
            rec[:int(P[kn.I_SOFF]) if P[kn.I_SENSE] else rec.size] * P[kn.I_AMP])), rtol=1e-9, atol=1e-9)
        v = thd ** 2 / (2 * p * p) + np.cos(alpha - np.abs(th)) - np.cos(alpha)
        peak = alpha - np.arccos(np.minimum(1.0, np.cos(alpha) + v))
        q = v + kmax * (1.0 - np.cos(np.where(th * thd < 0.0, th, peak)))
        keep = np.abs(th) > 1e-12  # at θ = 0 the row before an impact is returning, the row after outward
        d = np.sqrt(np.maximum(q, 0.0)) - c * _input_so_far(t, P, rec)
        d, below = d[keep], ((q <= level) & (np.abs(th) <= alpha))[keep]
        pair = below[1:] & below[:-1]
        assert np.all(np.diff(d)[pair] <= 1e-7), (i, np.max(np.diff(d)[pair]))
        checked += int(pair.sum() > 100)
    assert checked > 30
