"""Tests for rockstudy.noise: noise-contaminated excitations (paper §5)."""
import math

import numpy as np
import pytest

from rockstudy.excitation import GroundMotion, excitation_duration, modulated
from rockstudy.noise import (
    NOISE_DT,
    NOISE_LEVELS,
    NoisyRecord,
    baseline_samples,
    contaminate,
    energy,
    level_key,
    noise_generator,
    noisy_motion,
    noisy_record,
    scaled_white_noise,
)

OMEGA = 2.0 * 3.0  # ω_p/p = 2 for the benchmark block (p = 3 rad/s) [rad/s]
SEED = 20240611


def _energy(x, dt):
    return float(np.sum(np.asarray(x) ** 2) * dt)


def test_levels_and_keys():
    assert NOISE_DT == 0.0025
    assert NOISE_LEVELS == {"R000": 0.0, "R001": 0.01, "R005": 0.05, "R010": 0.10}
    assert [level_key(v) for v in NOISE_LEVELS.values()] == [0, 100, 500, 1000]


@pytest.mark.parametrize("kind", ["one-sine", "modulated"])
def test_baseline_samples_grid_and_values(kind):
    values, dt = baseline_samples(kind, OMEGA)
    duration = excitation_duration(kind, OMEGA)
    n = math.ceil(duration / NOISE_DT)
    assert dt == NOISE_DT
    assert values.shape == (n + 1,)
    assert (n - 1) * dt < duration <= n * dt + 1e-12
    if kind == "modulated":
        t = np.arange(n + 1) * dt
        np.testing.assert_allclose(values, modulated(t, 1.0, OMEGA), rtol=0, atol=0)
    else:
        np.testing.assert_allclose(values[:5], np.sin(OMEGA * np.arange(5) * dt), rtol=0, atol=1e-15)


def test_baseline_exact_multiple_adds_no_trailing_sample():
    # one-sine at ω = 2π lasts 1 s = 400 dt exactly; rounding must not make it 401
    values, dt = baseline_samples("one-sine", 2.0 * math.pi)
    assert len(values) == 401


@pytest.mark.parametrize("level", [0.01, 0.05, 0.10, 0.5])
@pytest.mark.parametrize("kind", ["one-sine", "modulated"])
def test_energy_match_exact(kind, level):
    base, dt = baseline_samples(kind, OMEGA)
    rec, energy_ratio, pga_ratio = contaminate(base, dt, level, noise_generator(SEED, level, 3), "energy")
    assert abs(_energy(rec, dt) / _energy(base, dt) - 1.0) < 1e-12
    assert abs(energy_ratio - 1.0) < 1e-12
    assert pga_ratio == pytest.approx(np.max(np.abs(rec)) / np.max(np.abs(base)), rel=1e-15)
    assert not np.allclose(rec, base)


@pytest.mark.parametrize("level", [0.01, 0.05, 0.10])
def test_pga_match_exact(level):
    base, dt = baseline_samples("modulated", OMEGA)
    rec, energy_ratio, pga_ratio = contaminate(base, dt, level, noise_generator(SEED, level, 0), "pga")
    assert abs(np.max(np.abs(rec)) / np.max(np.abs(base)) - 1.0) < 1e-12
    assert abs(pga_ratio - 1.0) < 1e-12
    assert energy_ratio == pytest.approx(_energy(rec, dt) / _energy(base, dt), rel=1e-12)


@pytest.mark.parametrize("level", [0.01, 0.05, 0.10])
def test_noise_energy_fraction_before_rescaling_is_level(level):
    base, dt = baseline_samples("modulated", OMEGA)
    # The same generator state gives the noise contaminate() adds.
    noise = scaled_white_noise(base.size, dt, level * _energy(base, dt), noise_generator(SEED, level, 7))
    assert _energy(noise, dt) / _energy(base, dt) == pytest.approx(level, rel=1e-12)
    assert abs(np.mean(noise)) < 4.0 * np.std(noise) / math.sqrt(noise.size)  # zero mean, 4 sigma
    # contaminate() = (baseline + that noise) rescaled to the baseline energy
    rec, _, _ = contaminate(base, dt, level, noise_generator(SEED, level, 7), "energy")
    summed = base + noise
    np.testing.assert_allclose(rec, summed * math.sqrt(_energy(base, dt) / _energy(summed, dt)),
                               rtol=1e-12, atol=1e-15)


def test_scaled_white_noise_zero_energy():
    assert np.array_equal(scaled_white_noise(10, 0.01, 0.0, np.random.default_rng(0)), np.zeros(10))


def test_energy_helper():
    assert energy([1.0, 2.0], 0.5) == 2.5


def test_same_key_same_record_different_realisation_differs():
    a = noisy_record("modulated", OMEGA, 0.05, 4, SEED)
    b = noisy_record("modulated", OMEGA, 0.05, 4, SEED)
    c = noisy_record("modulated", OMEGA, 0.05, 5, SEED)
    d = noisy_record("modulated", OMEGA, 0.10, 4, SEED)
    e = noisy_record("modulated", OMEGA, 0.05, 4, SEED + 1)
    assert np.array_equal(a.values, b.values)
    for other in (c, d, e):
        assert not np.allclose(a.values, other.values)


def test_realisation_independent_of_order():
    level = NOISE_LEVELS["R010"]
    alone = noisy_record("modulated", OMEGA, level, 3, SEED).values
    # another job: other levels and realisations first, in reverse order
    loop = {}
    for lv in (0.05, level):
        for k in reversed(range(6)):
            loop[(lv, k)] = noisy_record("modulated", OMEGA, lv, k, SEED).values
    assert np.array_equal(loop[(level, 3)], alone)
    # and the generator itself is keyed, not stateful
    x = noise_generator(SEED, level, 3).standard_normal(5)
    noise_generator(SEED, level, 2).standard_normal(100)
    assert np.array_equal(noise_generator(SEED, level, 3).standard_normal(5), x)


def test_level_zero_is_baseline():
    base, dt = baseline_samples("modulated", OMEGA)
    rng = noise_generator(SEED, 0.0, 0)
    rec, energy_ratio, pga_ratio = contaminate(base, dt, 0.0, rng, "pga")
    assert np.array_equal(rec, base) and rec is not base
    assert energy_ratio == 1.0 and pga_ratio == 1.0
    r = noisy_record("modulated", OMEGA, 0.0, 5, SEED)
    assert np.array_equal(r.values, base) and r.energy_ratio == 1.0 and r.pga_ratio == 1.0


def test_noisy_record_fields():
    r = noisy_record("one-sine", OMEGA, 0.05, 2, SEED, match="pga")
    assert isinstance(r, NoisyRecord)
    assert (r.dt, r.level, r.realisation, r.seed, r.match) == (NOISE_DT, 0.05, 2, SEED, "pga")
    assert r.pga_ratio == pytest.approx(1.0, abs=1e-12)
    assert r.duration == pytest.approx((len(r.values) - 1) * NOISE_DT)
    assert r.to_attrs()["noise_level"] == 0.05
    with pytest.raises(ValueError):
        r.values[0] = 1.0  # read-only


def test_noisy_motion_record_and_analytic():
    amplitude = 2.5
    m = noisy_motion("modulated", OMEGA, amplitude, 0.05, 1, SEED)
    r = noisy_record("modulated", OMEGA, 0.05, 1, SEED)
    assert isinstance(m, GroundMotion) and m.kind == "record"
    assert m.amplitude == amplitude and m.omega == OMEGA and m.record_dt == NOISE_DT
    assert m.duration == pytest.approx((len(r.values) - 1) * NOISE_DT)
    assert np.array_equal(m.record, r.values)
    t = np.arange(len(r.values)) * NOISE_DT
    np.testing.assert_allclose(m.horizontal(t), amplitude * r.values, rtol=1e-12, atol=1e-12)

    m0 = noisy_motion("modulated", OMEGA, amplitude, 0.0, 1, SEED)
    assert m0.kind == "modulated" and m0.amplitude == amplitude
    assert m0.duration == excitation_duration("modulated", OMEGA)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(seed=-1, level=0.05, realisation=0), "seed"),
        (dict(seed=1.5, level=0.05, realisation=0), "seed"),
        (dict(seed=0, level=1.0, realisation=0), "level"),
        (dict(seed=0, level=-0.01, realisation=0), "level"),
        (dict(seed=0, level=0.05, realisation=-2), "realisation"),
        (dict(seed=0, level=0.05, realisation=True), "realisation"),
    ],
)
def test_generator_errors_name_argument(kwargs, name):
    with pytest.raises(ValueError, match=name):
        noise_generator(**kwargs)


def test_other_errors():
    base, dt = baseline_samples("one-sine", OMEGA)
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match="match"):
        contaminate(base, dt, 0.05, rng, match="rms")
    with pytest.raises(ValueError, match="match"):
        noisy_record("one-sine", OMEGA, 0.05, 0, 0, match="rms")
    with pytest.raises(ValueError, match="level"):
        contaminate(base, dt, 1.5, rng)
    with pytest.raises(ValueError, match="dt"):
        contaminate(base, 0.0, 0.05, rng)
    with pytest.raises(ValueError, match="baseline"):
        contaminate(np.zeros(10), dt, 0.05, rng)
    with pytest.raises(ValueError, match="excitation"):
        baseline_samples("square", OMEGA)
    with pytest.raises(ValueError, match="omega"):
        baseline_samples("one-sine", -1.0)
    with pytest.raises(ValueError, match="seed"):
        noisy_motion("one-sine", OMEGA, 1.0, 0.0, 0, -1)
