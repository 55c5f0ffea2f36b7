"""Tests for rockstudy.model.noise: noise-contaminated excitations (paper §5)."""
import math

import numpy as np
import pytest

from fresh_python import run
from rockstudy.core.recent import Recent
from rockstudy.model.excitation import GroundMotion, excitation_duration, modulated
from rockstudy.model.noise import (
    NOISE_DT,
    NOISE_LEVELS,
    RECENT_RECORDS,
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
    rec, energy_ratio, pga_ratio = contaminate(base, dt, level, noise_generator(SEED, level, 3),
                                               NoiseReading(rescale="energy"))
    assert abs(_energy(rec, dt) / _energy(base, dt) - 1.0) < 1e-12
    assert abs(energy_ratio - 1.0) < 1e-12
    assert pga_ratio == pytest.approx(np.max(np.abs(rec)) / np.max(np.abs(base)), rel=1e-15)
    assert not np.allclose(rec, base)


@pytest.mark.parametrize("level", [0.01, 0.05, 0.10])
def test_pga_match_exact(level):
    base, dt = baseline_samples("modulated", OMEGA)
    rec, energy_ratio, pga_ratio = contaminate(base, dt, level, noise_generator(SEED, level, 0),
                                               NoiseReading(rescale="pga"))
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
    rec, _, _ = contaminate(base, dt, level, noise_generator(SEED, level, 7), NoiseReading(rescale="energy"))
    summed = base + noise
    np.testing.assert_allclose(rec, summed * math.sqrt(_energy(base, dt) / _energy(summed, dt)),
                               rtol=1e-12, atol=1e-15)


def test_scaled_white_noise_zero_energy():
    assert np.array_equal(scaled_white_noise(10, 0.01, 0.0, np.random.default_rng(0)), np.zeros(10))


def test_energy_helper():
    assert energy([1.0, 2.0], 0.5) == 2.5


def test_energy_is_accurate_and_depends_on_the_values_only():
    x = np.random.default_rng(3).standard_normal(20001) * np.linspace(0.0, 3.0, 20001)
    exact = math.fsum(v * v for v in x.tolist())  # exactly rounded sum of the (rounded) squares
    assert energy(x, 1.0) == pytest.approx(exact, rel=1e-14)
    # the same values at another address and stride give the same bits (pairwise summation's order
    # depends on the length alone)
    padded = np.empty(2 * x.size + 1)
    padded[1::2] = x
    assert energy(padded[1::2], 0.01) == energy(x.copy(), 0.01)


_RECORD_HASH = """
import hashlib
from rockstudy.model.noise import noisy_record
h = hashlib.sha256()
for ratio in (0.25, 0.5):  # long records (16,813 and 8,407 samples): a BLAS dot splits them over threads
    for k in range(3):
        h.update(noisy_record("modulated", ratio * 3.0, 0.05, k, 20190101).values.tobytes())
print(h.hexdigest())
"""


def test_noisy_records_are_the_same_bits_whatever_the_blas_threads():
    # the study's jobs run one BLAS thread (Snakemake sets OPENBLAS_NUM_THREADS to the job's
    # threads), the CLI and a user's script as many as the machine has cores
    digests = {run(_RECORD_HASH, OPENBLAS_NUM_THREADS=n, OMP_NUM_THREADS=n, MKL_NUM_THREADS=n) for n in ("1", "4")}
    assert len(digests) == 1


def test_same_key_same_record_different_realisation_differs():
    a = noisy_record("modulated", OMEGA, 0.05, 4, SEED)
    RECENT_RECORDS.clear()  # made again, not reused
    b = noisy_record("modulated", OMEGA, 0.05, 4, SEED)
    assert b is not a
    c = noisy_record("modulated", OMEGA, 0.05, 5, SEED)
    d = noisy_record("modulated", OMEGA, 0.10, 4, SEED)
    e = noisy_record("modulated", OMEGA, 0.05, 4, SEED + 1)
    assert np.array_equal(a.values, b.values)
    for other in (c, d, e):
        assert not np.allclose(a.values, other.values)


def test_realisation_independent_of_order():
    level = NOISE_LEVELS["R010"]
    alone = noisy_record("modulated", OMEGA, level, 3, SEED).values
    RECENT_RECORDS.clear()  # made again below, not reused
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


def test_recent_records_are_reused_the_same_bits_and_bounded():
    """A record asked for again is the one made before (same object), equal bit for bit to one made anew;
    the kept samples never exceed the limit, the oldest go first, and a record above it is not kept."""
    RECENT_RECORDS.clear()
    a = noisy_record("modulated", OMEGA, 0.05, 7, SEED)
    assert noisy_record("modulated", OMEGA, 0.05, 7, SEED) is a
    assert noisy_record("modulated", OMEGA, 0.05, 7, SEED, NoiseReading(span=1.0)) is not a  # another reading
    RECENT_RECORDS.clear()
    fresh = noisy_record("modulated", OMEGA, 0.05, 7, SEED)
    assert fresh is not a and np.array_equal(fresh.values, a.values) and fresh.energy_ratio == a.energy_ratio
    size = a.values.nbytes
    cache = Recent(2 * size, size=lambda record: record.values.nbytes)
    made = []

    def maker(k):
        def make():
            made.append(k)
            return noisy_record("modulated", OMEGA, 0.05, k, SEED)
        return make

    for k in (1, 2, 1, 3, 1):  # 3 pushes out 2 (1 was used since), then 1 is still there
        cache.get(k, maker(k))
        assert cache.nbytes <= cache.limit
    assert made == [1, 2, 3] and len(cache) == 2
    cache.get(2, maker(2))
    assert made == [1, 2, 3, 2]
    small = Recent(size - 1, size=lambda record: record.values.nbytes)
    small.get(1, maker(1))
    assert len(small) == 0 and small.nbytes == 0


def test_level_zero_is_baseline():
    base, dt = baseline_samples("modulated", OMEGA)
    rng = noise_generator(SEED, 0.0, 0)
    rec, energy_ratio, pga_ratio = contaminate(base, dt, 0.0, rng, NoiseReading(rescale="pga"))
    assert np.array_equal(rec, base) and rec is not base
    assert energy_ratio == 1.0 and pga_ratio == 1.0
    r = noisy_record("modulated", OMEGA, 0.0, 5, SEED)
    assert np.array_equal(r.values, base) and r.energy_ratio == 1.0 and r.pga_ratio == 1.0


def test_noisy_record_fields():
    r = noisy_record("one-sine", OMEGA, 0.05, 2, SEED, NoiseReading(rescale="pga"))
    assert isinstance(r, NoisyRecord)
    assert (r.dt, r.level, r.realisation, r.seed, r.reading.rescale) == (NOISE_DT, 0.05, 2, SEED, "pga")
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
    with pytest.raises(ValueError, match="NoiseReading.rescale"):
        NoiseReading(rescale="rms")
    with pytest.raises(ValueError, match="reading"):
        contaminate(base, dt, 0.05, rng, "energy")
    with pytest.raises(ValueError, match="reading"):
        noisy_record("one-sine", OMEGA, 0.05, 0, 0, "energy")
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


# --- the readings of the noise model ---------------------------------------------------
from rockstudy.core.validation import InputError  # noqa: E402
from rockstudy.model.noise import DEFAULT_READING, NoiseReading, reading_from_dict, rescale_both  # noqa: E402


def _old_contaminate(baseline, dt, level, rng, match):
    """rockstudy's contaminate() before the readings existed, verbatim in its arithmetic except for
    the energies, which are :func:`energy`'s (pairwise sums; they were BLAS dot products, whose bits
    depend on the BLAS threads)."""
    b = np.array(baseline, dtype=float)
    e_b = energy(b, dt)
    w = rng.standard_normal(b.size)
    noise = w * math.sqrt(level * e_b / energy(w, dt))
    summed = b + noise
    if match == "energy":
        return summed * math.sqrt(e_b / energy(summed, dt))
    return summed * (float(np.max(np.abs(b))) / float(np.max(np.abs(summed))))


# Records made before the readings existed: (kind, frequency ratio, level, realisation, rescale), their
# sample count, the MD5 of their samples then, and PGA ratio (omega = 3 * frequency ratio, seed 20190101).
# The samples are compared with the old arithmetic run here (_old_contaminate), not with the stored
# hashes: the energies' summation has since moved some samples by one unit in the last place.
OLD_RECORDS = [
    (("modulated", 2.0, 0.05, 3, "energy"), 2096, "813736a27098147cd07e68cc1844fa90", 1.1020634514183125),
    (("modulated", 0.25, 0.10, 39, "energy"), 16757, "21ec5842e275c7817769934ec776257a", 1.2569374358200789),
    (("one-sine", 4.9, 0.01, 0, "pga"), 172, "57e2e02d57da3d40064064de38479f07", 1.0),
    (("modulated", 1.0, 0.05, 0, "pga"), 4190, "d655103199c875268e1bdde49baabfe9", 1.0),
]


@pytest.mark.parametrize("case, n, digest, pga_ratio", OLD_RECORDS)
def test_default_reading_is_bit_for_bit_the_old_records(case, n, digest, pga_ratio):
    kind, f, level, k, match = case
    rec = noisy_record(kind, 3.0 * f, level, k, 20190101, NoiseReading(rescale=match))
    assert len(rec.values) == n
    assert rec.pga_ratio == pytest.approx(pga_ratio, rel=1e-12)
    base, dt = baseline_samples(kind, 3.0 * f)
    old = _old_contaminate(base, dt, level, noise_generator(20190101, level, k), match)
    assert np.array_equal(rec.values, old)
    if match == "energy":  # the default reading gives the same bits
        assert np.array_equal(noisy_record(kind, 3.0 * f, level, k, 20190101).values, old)


def test_reading_defaults_and_attrs():
    r = NoiseReading()
    assert r == DEFAULT_READING == reading_from_dict(None) == reading_from_dict({})
    assert (r.step, r.rescale, r.level_means, r.band, r.span) == (0.0025, "energy", "energy", None, 0.0)
    attrs = r.to_attrs()
    assert attrs["noise_rescale"] == "energy" and attrs["noise_step_s"] == 0.0025 and attrs["noise_band_hz"] == "none"
    assert "noise_match" not in attrs and "noise_dt_s" not in attrs
    assert NoiseReading(band=5.0).to_attrs()["noise_band_hz"] == 5.0


@pytest.mark.parametrize("step", [0.005, 0.010, 0.020])
def test_step_gives_samples_that_far_apart(step):
    rec = noisy_record("modulated", OMEGA, 0.05, 0, SEED, NoiseReading(step=step))
    assert rec.dt == step
    np.testing.assert_allclose(np.diff(rec.times), step, rtol=0, atol=1e-12)
    duration = excitation_duration("modulated", OMEGA)
    assert rec.duration >= duration - 1e-12 and rec.duration - step < duration
    # the baseline under the noise is Eq. 23 sampled at that step
    base, dt = baseline_samples("modulated", OMEGA, step)
    assert dt == step and len(base) == len(rec.values)
    m = noisy_motion("modulated", OMEGA, 1.0, 0.05, 0, SEED, NoiseReading(step=step))
    assert m.record_dt == step


def test_none_leaves_the_sum_unscaled():
    base, dt = baseline_samples("modulated", OMEGA)
    level = 0.05
    rec, energy_ratio, _ = contaminate(base, dt, level, noise_generator(SEED, level, 2),
                                      NoiseReading(rescale="none"))
    noise = scaled_white_noise(base.size, dt, level * _energy(base, dt), noise_generator(SEED, level, 2))
    np.testing.assert_array_equal(rec, base + noise)
    # energy of b + n = (1 + r) E_b + 2 Σ b n dt: close to 1 + r, not 1
    assert energy_ratio == pytest.approx(1 + level, abs=0.02)
    assert abs(energy_ratio - 1.0) > 0.02


@pytest.mark.parametrize("level", [0.01, 0.05, 0.10, 0.3])
def test_rms_meaning_is_energy_meaning_of_the_square(level):
    base, dt = baseline_samples("modulated", OMEGA)
    for rescale in ("energy", "none"):
        rms, _, _ = contaminate(base, dt, level, np.random.default_rng(11),
                                reading=NoiseReading(rescale=rescale, level_means="rms"))
        eng, _, _ = contaminate(base, dt, level ** 2, np.random.default_rng(11),
                                reading=NoiseReading(rescale=rescale, level_means="energy"))
        np.testing.assert_allclose(rms, eng, rtol=1e-13, atol=1e-15)
    # and the noise RMS over the baseline RMS is the level itself
    noisy, _, _ = contaminate(base, dt, level, np.random.default_rng(3), reading=NoiseReading(rescale="none",
                                                                                              level_means="rms"))
    noise = noisy - base
    assert math.sqrt(np.mean(noise ** 2) / np.mean(base ** 2)) == pytest.approx(level, rel=1e-12)
    assert NoiseReading(level_means="rms").energy_fraction(level) == pytest.approx(level ** 2, rel=1e-15)


@pytest.mark.parametrize("band", [2.0, 5.0, 20.0])
def test_band_limited_noise_has_no_power_above_its_band(band):
    base, dt = baseline_samples("modulated", OMEGA)
    level = 0.05
    rec, _, _ = contaminate(base, dt, level, noise_generator(SEED, level, 0),
                            reading=NoiseReading(rescale="none", band=band))
    noise = rec - base
    power = np.abs(np.fft.rfft(noise)) ** 2
    freqs = np.fft.rfftfreq(noise.size, dt)
    assert power[freqs > band].max() < 1e-20 * power.sum()
    assert _energy(noise, dt) / _energy(base, dt) == pytest.approx(level, rel=1e-12)
    # white noise, for contrast, has most of its power above a 5 Hz band (Nyquist 200 Hz)
    white = scaled_white_noise(noise.size, dt, 1.0, np.random.default_rng(0))
    wp = np.abs(np.fft.rfft(white)) ** 2
    assert wp[freqs > 5.0].sum() > 0.9 * wp.sum()


def test_span_adds_noise_after_the_intense_part_only_when_asked():
    level, span = 0.05, 1.0
    short = noisy_record("modulated", OMEGA, level, 1, SEED)
    long = noisy_record("modulated", OMEGA, level, 1, SEED, NoiseReading(span=span, rescale="none"))
    n_extra = int(round(span / NOISE_DT))
    assert len(long.values) == len(short.values) + n_extra
    assert long.duration == pytest.approx(short.duration + span)
    base, dt = baseline_samples("modulated", OMEGA)
    tail = long.values[len(base):]
    noise_in = long.values[:len(base)] - base
    # same noise RMS after T_d as during it (within sampling error of 400 samples), baseline zero there
    assert np.sqrt(np.mean(tail ** 2)) == pytest.approx(np.sqrt(np.mean(noise_in ** 2)), rel=0.15)
    # the level is measured on the intense part
    assert _energy(noise_in, dt) / _energy(base, dt) == pytest.approx(level, rel=1e-12)
    # default: nothing after the last sample of the intense part
    assert short.duration < excitation_duration("modulated", OMEGA) + NOISE_DT


@pytest.mark.parametrize("level", [0.01, 0.05, 0.10])
def test_both_keeps_energy_and_pga(level):
    base, dt = baseline_samples("modulated", OMEGA)
    rec, energy_ratio, pga_ratio = contaminate(base, dt, level, noise_generator(SEED, level, 4),
                                               NoiseReading(rescale="both"))
    assert energy_ratio == pytest.approx(1.0, abs=1e-12)
    assert pga_ratio == pytest.approx(1.0, abs=1e-12)
    # it is the energy-rescaled record with its peaks limited: same signs, order preserved
    summed = base + scaled_white_noise(base.size, dt, level * _energy(base, dt), noise_generator(SEED, level, 4))
    assert np.all(np.sign(rec) == np.sign(summed))
    unclipped = np.abs(rec) < np.max(np.abs(base)) - 1e-12
    ratio = rec[unclipped] / summed[unclipped]
    np.testing.assert_allclose(ratio, ratio[0], rtol=1e-12)


def test_rescale_both_hand_worked():
    # x = [2, 1, 1], dt = 1, target energy 3, peak 1.2: clip the 2 -> 1.2 (1.44), the rest s^2 * 2 = 1.56
    out = rescale_both(np.array([2.0, 1.0, -1.0]), 1.0, 3.0, 1.2)
    s = math.sqrt(1.56 / 2)
    np.testing.assert_allclose(out, [1.2, s, -s], rtol=1e-14)
    # below the peak already: plain energy rescaling
    np.testing.assert_allclose(rescale_both(np.array([1.0, 1.0]), 1.0, 0.5, 5.0), [0.5, 0.5])


@pytest.mark.parametrize("kwargs, message", [
    (dict(step=0.0), "NoiseReading.step = 0 s is not allowed"), (dict(step=math.nan), "NoiseReading.step"),
    (dict(step=True), "NoiseReading.step"), (dict(band=-1.0), "NoiseReading.band = -1 Hz is not allowed"),
    (dict(span=-1.0), "NoiseReading.span = -1 s is not allowed"), (dict(span=math.inf), "NoiseReading.span")])
def test_reading_numbers_go_through_the_validation_layer(kwargs, message):
    # the numeric fields are checked by rockstudy.core.validation (InputError, its message form), not a private copy
    with pytest.raises(InputError, match=message):
        NoiseReading(**kwargs)


@pytest.mark.parametrize("kwargs, name", [
    (dict(step=0.0), "NoiseReading.step"), (dict(rescale="rms"), "NoiseReading.rescale"),
    (dict(level_means="power"), "NoiseReading.level_means"), (dict(band=-1.0), "NoiseReading.band"),
    (dict(band=250.0), "Nyquist"), (dict(span=-1.0), "NoiseReading.span")])
def test_reading_errors_name_the_field(kwargs, name):
    with pytest.raises(ValueError, match=name):
        NoiseReading(**kwargs)
    with pytest.raises(ValueError, match="unknown"):
        reading_from_dict({"steps": 0.01})
