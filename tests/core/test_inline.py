"""rockstudy.core._inline: the selective-inlining cost model inlines into the named callers only, and an
inlined call computes bitwise what the ordinary call computes."""
from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
from numba import njit

from rockstudy.core._inline import inline_into


def _ir(name):
    return SimpleNamespace(func_id=SimpleNamespace(func_name=name))


def test_cost_model_inlines_into_named_callers_only():
    model = inline_into("step", "locate")
    assert model(None, _ir("step"), _ir("rhs"))
    assert model(None, _ir("locate"), _ir("rhs"))
    assert not model(None, _ir("ground_phase"), _ir("rhs"))
    assert not model(None, _ir("steps"), _ir("rhs"))  # names, not prefixes


@njit(inline=inline_into("hot"))
def _term(x, a):
    return a[0] * math.sin(x) / a[1] + math.cos(x) * a[2]


@njit
def hot(xs, a):  # _term is inlined here
    out = np.empty_like(xs)
    for i in range(xs.shape[0]):
        out[i] = _term(xs[i], a)
    return out


@njit
def cold(xs, a):  # and called here
    out = np.empty_like(xs)
    for i in range(xs.shape[0]):
        out[i] = _term(xs[i], a)
    return out


def test_inlined_and_called_versions_agree_bitwise():
    xs = np.random.default_rng(3).uniform(-10, 10, 2000)
    a = np.array([1.7, 3.1, -0.3])
    np.testing.assert_array_equal(hot(xs, a), cold(xs, a))
    np.testing.assert_array_equal(hot(xs, a), np.array([_term.py_func(x, a) for x in xs]))
