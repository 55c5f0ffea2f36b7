"""The library's entry points (simulate, GroundMotion, Scenario, threshold, spectrum) apply the one
validation layer: any argument gives a result or an InputError naming the parameter, quickly, never
another exception, a hang or an unbounded allocation (hypothesis)."""
import math
import os
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, spectrum, threshold
from rockstudy.core import validation as v
from rockstudy.engine import simulate as simulate_module
from rockstudy.engine.simulate import simulate
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import BLOCK_PRESETS
from rockstudy.model.control import Control
from rockstudy.model.excitation import GroundMotion
from rockstudy.model.noise import NoiseReading

BLC06 = BLOCK_PRESETS["BLC06"]
EXAMPLES = int(os.environ.get("ROCKSTUDY_HYPOTHESIS_EXAMPLES", "60"))
PROPERTY = settings(max_examples=EXAMPLES, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
PULSE = GroundMotion("one-sine", 3.0, 5.0, 2 * math.pi / 5.0)
ANY = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-2**70, 2**70),
                st.sampled_from([0, 1, -1, 0.5, 1e-300, 1e300, 1e-9, 10.0, "1", None, True, [1.0], "BLC06"]))


def named(exc: Exception, *names: str) -> bool:
    return isinstance(exc, v.InputError) and any(n in str(exc) for n in names)


# --- simulate ------------------------------------------------------------------------------------
SIMULATE_ARGS = {"free_time": ANY, "initial_rotation": ANY, "initial_velocity": ANY, "rest_velocity": ANY,
                 "rtol": ANY, "atol": ANY, "overturn_criterion": st.sampled_from(["flat", "alpha", "x", None, 1])}


@PROPERTY
@given(kwargs=st.fixed_dictionaries({}, optional=SIMULATE_ARGS))
def test_property_simulate_gives_a_result_or_names_the_argument(kwargs):
    try:
        res = simulate(BLC06, Anchorage(), Control("CS01"), PULSE, **kwargs)
    except ValueError as exc:
        assert named(exc, *kwargs), (kwargs, exc)
    else:
        assert res.status in ("rest", "overturned", "time limit", "cannot overturn", "undetermined")
        for key in ("free_time", "initial_rotation", "initial_velocity", "rtol", "atol"):
            if key in kwargs:
                assert math.isfinite(float(kwargs[key]))
        if "rtol" in kwargs:
            assert simulate_module.RTOL_RANGE[0] <= kwargs["rtol"] <= simulate_module.RTOL_RANGE[1]


@pytest.mark.parametrize("args, name", [
    (("BLC06", Anchorage(), Control("FS"), PULSE), "block"),
    ((BLC06, None, Control("FS"), PULSE), "anchorage"),
    ((BLC06, Anchorage(), "CS01", PULSE), "control"),
    ((BLC06, Anchorage(), Control("FS"), [1.0, 2.0]), "motion"),
])
def test_simulate_names_a_wrong_type(args, name):
    with pytest.raises(v.InputError, match=f"^{name} must be a rockstudy"):
        simulate(*args)


def test_the_event_cap_is_an_undetermined_result_not_an_exception(monkeypatch):
    kn = simulate_module._kernel
    real = kn.simulate_kernel

    def capped(*args):  # the kernel's result (a KernelResult named tuple) as if it had reached the cap
        return real(*args)._replace(status=kn.ST_ELIMIT)
    monkeypatch.setattr(kn, "simulate_kernel", capped)
    res = simulate(BLC06, Anchorage(), Control("CS01"), PULSE)
    assert res.status == "undetermined" and res.overturned is False
    assert "cap" in res.message and "reference" in res.message
    assert res.summary()["overturned"] is None and res.summary()["status"] == "undetermined"


# --- GroundMotion and Scenario ---------------------------------------------------------------------
@PROPERTY
@given(kind=st.sampled_from(["one-sine", "modulated", "record", "rectangular", "x", None]),
       amplitude=ANY, omega=ANY, duration=ANY, dt=ANY,
       samples=st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=5))
def test_property_ground_motion_is_finite_or_refused_naming_the_field(kind, amplitude, omega, duration, dt, samples):
    try:
        m = GroundMotion(kind, amplitude, omega, duration, dt, np.asarray(samples, dtype=float))
    except ValueError as exc:
        assert "GroundMotion." in str(exc), exc
    else:
        assert math.isfinite(m.amplitude) and 0 < m.duration <= v.MAX_TIME_SPAN
        assert np.all(np.isfinite(m.record))


@PROPERTY
@given(field=st.sampled_from(["block", "anchorage", "control", "excitation", "noise_level", "seed", "noise",
                              "overturn_criterion", "free_time"]), value=ANY)
def test_property_scenario_names_the_field(field, value):
    try:
        sc = Scenario(value) if field == "block" else Scenario(BLC06, **{field: value})
    except ValueError as exc:
        assert field in str(exc), (field, value, exc)
    else:
        assert 0 <= sc.noise_level < 1 and 0 <= sc.free_time <= v.MAX_FREE_TIME


# --- spectrum and threshold: sizes before work --------------------------------------------------
class Reached(Exception):
    """The entry point got past its checks to the kernel."""


@pytest.fixture
def no_kernel(monkeypatch):
    from rockstudy.analysis import spectra

    def stub(*args, **kwargs):
        raise Reached
    monkeypatch.setattr(spectra, "_cases", stub)
    monkeypatch.setattr(spectra.kernel, "threshold_kernel", stub)


READINGS = st.builds(NoiseReading, step=st.sampled_from([1e-4, 1e-3, 0.0025, 0.01, 0.1]),
                     span=st.sampled_from([0.0, 1.0, 100.0, 3000.0]))


@PROPERTY
@given(level=st.sampled_from([0.0, 0.05]), reading=READINGS,
       n_real=st.sampled_from([1, 10, 1000, 10**5, 10**5 + 1, 10**7, 10**12]),
       freqs=st.sampled_from([[1.0], [0.25, 5.0], list(np.linspace(0.1, 5, 1000)), [0.0], [math.nan], [2e3]]),
       as_iterator=st.booleans())
def test_property_spectrum_refuses_what_exceeds_the_limits_before_any_work(level, reading, n_real, freqs, as_iterator,
                                                                          no_kernel):
    sc = Scenario(BLC06, noise_level=level, noise=reading)
    realisations = iter(range(n_real)) if as_iterator else range(n_real)
    t0 = time.perf_counter()
    try:
        spectrum(sc, freqs, realisations=realisations)
    except Reached:  # accepted: what it implies is within the limits
        n = 1 if level == 0 else n_real
        assert n <= v.MAX_REALISATIONS
        assert sc.record_bytes(freqs, n) <= v.memory_budget()
    except ValueError as exc:
        assert named(exc, "realisations", "frequency_ratios", "NoiseReading"), exc
    assert time.perf_counter() - t0 < 5


def test_spectrum_of_ten_million_realisations_is_refused_at_once():
    t0 = time.perf_counter()
    with pytest.raises(v.InputError, match="realisations"):
        spectrum(Scenario(BLC06, noise_level=0.05), [1.0], realisations=range(10**7))
    assert time.perf_counter() - t0 < 1


@pytest.mark.parametrize("kwargs, name", [
    ({"frequency_ratio": math.nan}, "frequency_ratio"), ({"frequency_ratio": "2"}, "frequency_ratio"),
    ({"frequency_ratio": 2.0, "realisation": -1}, "realisation"),
    ({"frequency_ratio": 2.0, "grid": (0.9, 6.0)}, "grid"),
])
def test_threshold_names_a_bad_argument(kwargs, name):
    with pytest.raises(v.InputError, match=name):
        threshold(Scenario(BLC06, noise_level=0.05), **kwargs)


def test_threshold_counts_the_reading_in_the_record_size(no_kernel):
    sc = Scenario(BLC06, noise_level=0.05, noise=NoiseReading(step=1e-5, span=3000.0))
    with pytest.raises(v.InputError, match="NoiseReading"):
        threshold(sc, 0.25, grid=AmplitudeGrid())
