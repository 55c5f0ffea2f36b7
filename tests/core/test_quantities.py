"""The library's numeric arguments are checked from their one declaration (rockstudy.core.quantities).

* coverage: every numeric argument of the public classes and functions is declared in ``ARGUMENTS``, and
  every declared name is an argument;
* bad values generated from each declaration (past each end, at an open end, NaN, ±inf, a bool, a string,
  a fraction for an integer, None where not optional) are refused before any work, within 2 s, by an error
  naming the argument;
* values inside each declared range at its ends are accepted by the cheap constructors;
* a config key and the library argument of the same quantity accept the same values.
"""
from __future__ import annotations

import dataclasses
import inspect
import math
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import rockstudy
from rockstudy.analysis import fragility, record_scan
from rockstudy.core.quantities import ARGUMENTS, QUANTITIES, SIZES, Quantity, check_arguments
from rockstudy.core.validation import InputError
from rockstudy.model import noise, records
from rockstudy.studies import config_model, design

BLC06 = rockstudy.BLOCK_PRESETS["BLC06"]


def _motion(**kw):
    return rockstudy.GroundMotion(**{"kind": "record", "amplitude": 1.0, "omega": 1.0, "duration": 1.0,
                                     "record_dt": 0.01, "record": np.zeros(101), "vertical_dt": 0.01,
                                     "vertical": np.zeros(101), **kw})


def _record(**kw):
    return records.Record(**{"name": "r", "dt": 0.01, "acceleration": np.zeros(11), **kw})


def _file(tmp):
    path = tmp / "one.txt"
    path.write_text("0.0\n0.1\n0.0\n")
    return path


# owner -> (the object whose signature is declared, a call with valid values except those given)
OWNERS = {
    "Block": (rockstudy.Block, lambda **kw: rockstudy.Block(**{"width": 1.0, "height": 4.0, "depth": 1.0, **kw})),
    "Anchorage": (rockstudy.Anchorage, lambda **kw: rockstudy.Anchorage(**kw)),
    "Control": (rockstudy.Control, lambda **kw: rockstudy.Control(**{"strategy": "CS01", **kw})),
    "NoiseReading": (noise.NoiseReading, lambda **kw: noise.NoiseReading(**kw)),
    "GroundMotion": (rockstudy.GroundMotion, _motion),
    "Scenario": (rockstudy.Scenario, lambda **kw: rockstudy.Scenario(block=BLC06, **kw)),
    "AmplitudeGrid": (rockstudy.AmplitudeGrid, lambda **kw: rockstudy.AmplitudeGrid(**kw)),
    "frequency_grid": (rockstudy.frequency_grid, lambda **kw: rockstudy.frequency_grid(**kw)),
    "simulate": (rockstudy.simulate, lambda **kw: rockstudy.simulate(
        BLC06, rockstudy.Anchorage(), rockstudy.Control(), _motion(), **kw)),
    "threshold": (rockstudy.threshold, lambda **kw: rockstudy.threshold(
        rockstudy.Scenario(block=BLC06), **{"frequency_ratio": 1.0, **kw})),
    "spectrum": (rockstudy.spectrum, lambda **kw: rockstudy.spectrum(
        rockstudy.Scenario(block=BLC06), **{"frequency_ratios": [1.0], **kw})),
    "jos": (rockstudy.jos, lambda **kw: rockstudy.jos(None, None, **kw)),
    "Record": (records.Record, _record),
    "Record.motion": (records.Record.motion, lambda **kw: _record().motion(**kw)),
    "read_record": (records.read_record, lambda tmp, **kw: records.read_record(_file(tmp), **kw)),
    "read_one_column": (records.read_one_column, lambda tmp, **kw: records.read_one_column(
        _file(tmp), **{"dt": 0.01, **kw})),
    "noise_generator": (noise.noise_generator, lambda **kw: noise.noise_generator(
        **{"seed": 0, "level": 0.1, "realisation": 0, **kw})),
    "noisy_record": (noise.noisy_record, lambda **kw: noise.noisy_record(
        "modulated", **{"omega": 10.0, "level": 0.1, "realisation": 0, "seed": 0, **kw})),
    "record_threshold": (record_scan.record_threshold, lambda **kw: record_scan.record_threshold(None, [1.0], **kw)),
    "suite_fragility_dataset": (fragility.suite_fragility_dataset, lambda **kw: fragility.suite_fragility_dataset(
        None, None, [], [], [], suite="x", **kw)),
    "fragility_dataset": (fragility.fragility_dataset, lambda **kw: fragility.fragility_dataset(
        None, None, [], [], [], **kw)),
    "fragility_from_stripes": (fragility.fragility_from_stripes, lambda **kw: fragility.fragility_from_stripes(
        None, None, [], [], [], None, None, **kw)),
    "pga_levels": (design.pga_levels, lambda **kw: design.pga_levels(**kw)),
    "block_point": (design.block_point, lambda **kw: design.block_point(**{
        "R": 1.0, "alpha": 0.25, "anchorage": None, "strategies": ["FS"], "frequency_ratios": [1.0],
        "amplitude_start": 1.0, "amplitude_step": 0.1, "resolution": 0.01, "a_max0_g": 1.0, "records": [],
        "levels_g": [], "suite": "x", **kw})),
    "device_point": (design.device_point, lambda **kw: design.device_point(**{
        "block": None, "kappa_max": 1.0, "damping_ratio": 0.05, "strategies": ["FS"], "records": [],
        "levels_g": [], "suite": "x", **kw})),
}
SEQUENCE_ARGUMENTS = {("spectrum", "frequency_ratios"), ("spectrum", "realisations")}
"""Arguments declared item by item: a generated value is given as a one-item list."""
CHEAP = ("Block", "Anchorage", "Control", "NoiseReading", "GroundMotion", "Scenario", "AmplitudeGrid",
         "frequency_grid", "Record", "Record.motion", "noise_generator", "pga_levels")
"""Owners whose call with good values costs nothing (no simulation)."""


def _numeric_parameters(obj) -> set[str]:
    """Parameters annotated float or int (not bool) of a class (its dataclass fields) or a function."""
    if inspect.isclass(obj):
        items = [(f.name, str(f.type)) for f in dataclasses.fields(obj)]
    else:
        items = [(p.name, str(p.annotation)) for p in inspect.signature(obj).parameters.values()]
    return {name for name, kind in items
            if any(word in kind.replace("|", " ").replace("None", " ").split() for word in ("float", "int"))}


def test_every_public_callable_with_numbers_is_declared():
    results = ("SimulationResult", "ThresholdResult", "JosResult")  # what the library returns, not takes
    for name in set(rockstudy.__all__) - set(results):
        obj = getattr(rockstudy, name)
        if callable(obj) and (inspect.isclass(obj) and dataclasses.is_dataclass(obj) or inspect.isfunction(obj)):
            if _numeric_parameters(obj):
                assert name in ARGUMENTS, f"rockstudy.{name} takes numbers but core.quantities.ARGUMENTS has no entry"


@pytest.mark.parametrize("owner", sorted(OWNERS))
def test_declarations_cover_the_signature(owner):
    obj, _ = OWNERS[owner]
    params = set(inspect.signature(obj).parameters) if not inspect.isclass(obj) else {
        f.name for f in dataclasses.fields(obj)}
    declared = set(ARGUMENTS[owner])
    assert declared <= params, f"{owner}: declared but not an argument: {sorted(declared - params)}"
    missing = _numeric_parameters(obj) - declared - {"progress_chunks"}
    assert not missing, f"{owner}: numeric arguments without a declaration: {sorted(missing)}"


def test_the_coverage_check_can_fail():
    def f(x: float, n: int, flag: bool, name: str):
        pass
    assert _numeric_parameters(f) == {"x", "n"}


def bad_values(q: Quantity):
    """Values the declaration ``q`` refuses, generated from its ends, type and optionality."""
    fixed = [math.nan, math.inf, -math.inf, True, "1", [1.0]]
    if not q.optional:
        fixed.append(None)
    options = []
    if q.integer:  # integers past each end, and a fraction inside
        low = -2**63 if q.low is None else int(q.low) + (1 if q.low_open else 0)
        high = 2**63 if q.high is None else int(q.high) - (1 if q.high_open else 0)
        fixed += [low - 1, high + 1, low + 0.5]
        options += [st.integers(max_value=low - 1, min_value=low - 10**6),
                    st.integers(min_value=high + 1, max_value=high + 10**6)]
    else:
        if q.low is not None:
            fixed.append(q.low if q.low_open else float(np.nextafter(q.low, -math.inf)))
            options.append(st.floats(max_value=q.low, exclude_max=not q.low_open, allow_nan=False,
                                     allow_infinity=False, min_value=-1e300))
        if q.high is not None:
            fixed.append(q.high if q.high_open else float(np.nextafter(q.high, math.inf)))
            options.append(st.floats(min_value=q.high, exclude_min=not q.high_open, allow_nan=False,
                                     allow_infinity=False, max_value=1e300))
    options.append(st.sampled_from(fixed))
    return st.one_of(options)


CASES = [(owner, arg) for owner in sorted(OWNERS) for arg in ARGUMENTS[owner]]


@pytest.mark.parametrize("owner,arg", CASES, ids=[f"{o}.{a}" for o, a in CASES])
@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_bad_values_are_refused_naming_the_argument(owner, arg, data, tmp_path):
    q = QUANTITIES[ARGUMENTS[owner][arg]]
    value = data.draw(bad_values(q), label=f"{owner}.{arg}")
    call = OWNERS[owner][1]
    kwargs = {arg: [value] if (owner, arg) in SEQUENCE_ARGUMENTS else value}
    t0 = time.perf_counter()
    with pytest.raises(ValueError) as info:
        call(tmp_path, **kwargs) if owner in ("read_record", "read_one_column") else call(**kwargs)
    assert time.perf_counter() - t0 < 2.0
    assert isinstance(info.value, InputError), f"{owner}({arg}={value!r}): {type(info.value).__name__}: {info.value}"
    assert arg in str(info.value).split(" = ")[0], f"{owner}({arg}={value!r}): the error names {info.value}"
    assert len(str(info.value).splitlines()) <= 3


def _good_values(q: Quantity) -> list:
    low = q.low if q.low is not None else -1e6
    high = q.high if q.high is not None else 1e6
    if q.low_open:
        low = float(np.nextafter(low, math.inf)) if not q.integer else int(low) + 1
    if q.high_open:
        high = float(np.nextafter(high, -math.inf)) if not q.integer else int(high) - 1
    values = [low, high, (low + high) / 2 if not q.integer else int(low + (high - low) // 2)]
    return values + ([None] if q.optional else [])


GOOD = [(owner, arg) for owner in CHEAP for arg in ARGUMENTS[owner]]


@pytest.mark.parametrize("owner,arg", GOOD, ids=[f"{o}.{a}" for o, a in GOOD])
def test_values_inside_the_declared_range_pass_the_argument_check(owner, arg):
    """At each end of the range (and None where allowed) the argument itself is not refused; a relation with
    another argument (stop > start, a block's proportions) may still refuse the call, naming that relation."""
    q = QUANTITIES[ARGUMENTS[owner][arg]]
    for value in _good_values(q):
        assert check_arguments(owner, {arg: value}) == {arg: value if value is None else
                                                        (int(value) if q.integer else float(value))}


PAIRS = [("anchorage.kappa_max", "Anchorage", "kappa_max"), ("anchorage.damping_ratio", "Anchorage", "damping_ratio"),
         ("anchorage.spring_ultimate_rotation", "Anchorage", "spring_ultimate_rotation"),
         ("block.width", "Block", "width"), ("block.density", "Block", "density"),
         ("block.restitution", "Block", "restitution"), ("noise.step", "NoiseReading", "step"),
         ("noise.band", "NoiseReading", "band"), ("noise.span", "NoiseReading", "span"),
         ("control.sensor_band", "Control", "sensor_band"), ("free_time", "Scenario", "free_time"),
         ("frequency_grid.start", "frequency_grid", "start"), ("amplitude_grid.stop", "AmplitudeGrid", "stop"),
         ("amplitude_grid.resolution", "AmplitudeGrid", "resolution"), ("a_max0", "jos", "a_max0_g"),
         ("seed", "Scenario", "seed")]


@pytest.mark.parametrize("path,owner,arg", PAIRS, ids=[p for p, _, _ in PAIRS])
@settings(max_examples=40, deadline=None)
@given(value=st.one_of(st.floats(), st.integers(min_value=-10, max_value=10**20), st.none(), st.booleans()))
def test_a_config_key_and_its_library_argument_accept_the_same_values(path, owner, arg, value):
    q = QUANTITIES[ARGUMENTS[owner][arg]]
    if not q.integer and isinstance(value, int) and not isinstance(value, bool):
        value = float(value)  # the config's strict float takes no int; the library's does
    if q.integer and isinstance(value, float):
        return  # the library takes 3.0 as a seed, the strict config does not: a type, not a range
    try:
        config_model.check_value(path, value)
        config_ok = True
    except InputError:
        config_ok = False
    try:
        check_arguments(owner, {arg: value})
        library_ok = True
    except InputError:
        library_ok = False
    assert config_ok == library_ok, f"{path} and {owner}.{arg} disagree on {value!r}"


SIZE_CALLS = {
    ("spectrum", "frequency_ratios"): lambda n: OWNERS["spectrum"][1](frequency_ratios=np.full(n, 1.0)),
    ("spectrum", "realisations"): lambda n: OWNERS["spectrum"][1](realisations=range(n)),
    ("GroundMotion", "record"): lambda n: _motion(record=np.zeros(n)),
    ("GroundMotion", "vertical"): lambda n: _motion(vertical=np.zeros(n)),
    ("Record", "acceleration"): lambda n: _record(acceleration=np.zeros(n)),
}


def test_every_declared_size_is_tested():
    assert set(SIZE_CALLS) == set(SIZES)


@pytest.mark.parametrize("owner,arg", sorted(SIZES), ids=[f"{o}.{a}" for o, a in sorted(SIZES)])
def test_one_item_past_a_declared_size_is_refused_naming_the_argument(owner, arg):
    t0 = time.perf_counter()
    with pytest.raises(InputError, match=arg):
        SIZE_CALLS[owner, arg](SIZES[owner, arg] + 1)
    assert time.perf_counter() - t0 < 2.0
    if owner != "spectrum":  # at the limit itself the object is made (a spectrum would run)
        SIZE_CALLS[owner, arg](SIZES[owner, arg])
