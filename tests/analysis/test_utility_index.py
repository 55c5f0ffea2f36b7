"""Tests for rockstudy.analysis.utility_index: the utility index J_OS, Eqs. 18-22 (hand-worked cases)."""
import numpy as np
import pytest

from rockstudy.analysis.utility_index import capped_threshold, utility_index, utility_terms

G = 9.81  # a_max,0 = g as the paper suggests [m/s^2]


def test_capped_threshold_eqs_19_20():
    assert capped_threshold(3.0, G) == 3.0
    assert capped_threshold(G, G) == G  # ">= a_max0" branch
    assert capped_threshold(12.0, G) == G
    assert capped_threshold(np.nan, G) == G  # no overturning below the scan bound
    np.testing.assert_array_equal(capped_threshold([1.0, np.nan, 20.0, np.inf], G), [1.0, G, G, G])


def test_identical_systems_give_zero():
    a = np.array([2.0, 4.0, 6.0, np.nan, 15.0])
    j, n_star = utility_index(a, a, G)
    assert j == 0.0
    assert n_star == 3  # the NaN and the 15 m/s^2 frequencies are capped for both


def test_system_never_overturning_gives_plus_100():
    # Δa_SYS = a_max0 − a*_REF = Δa_REF at every frequency -> each term 1
    ref = np.array([2.0, 4.0, 6.0])
    j, n_star = utility_index(np.full(3, np.nan), ref, G)
    assert j == pytest.approx(100.0, abs=1e-12) and n_star == 3
    j, _ = utility_index(np.full(3, 50.0), ref, G)  # above a_max0: capped, same thing
    assert j == pytest.approx(100.0, abs=1e-12)


def test_half_threshold_gives_minus_50():
    # a*_SYS = a*_REF / 2 < a*_REF: (a/2 − a) / a = −1/2
    ref = np.array([2.0, 4.0, 6.0])
    j, n_star = utility_index(ref / 2, ref, G)
    assert j == pytest.approx(-50.0, abs=1e-12) and n_star == 3


def test_mixed_hand_worked_case():
    a_max0 = 1.0
    a_sys = np.array([0.6, 0.3, np.nan, 0.5, 1.5])
    a_ref = np.array([0.4, 0.5, 1.2, np.nan, 1.0])
    # f1: sys above ref  -> (0.6 − 0.4) / (1 − 0.4) = 1/3
    # f2: sys below ref  -> (0.3 − 0.5) / 0.5       = −2/5
    # f3: both capped    -> excluded
    # f4: ref capped (1) -> (0.5 − 1) / 1           = −1/2
    # f5: both capped    -> excluded
    terms = utility_terms(a_sys, a_ref, a_max0)
    np.testing.assert_allclose(terms[[0, 1, 3]], [1 / 3, -2 / 5, -1 / 2], rtol=1e-14)
    assert np.isnan(terms[2]) and np.isnan(terms[4])
    j, n_star = utility_index(a_sys, a_ref, a_max0)
    assert n_star == 3
    assert j == pytest.approx(100 * (1 / 3 - 2 / 5 - 1 / 2) / 3, abs=1e-12)  # = −1700/90 %
    assert j == pytest.approx(-18.888888888888889, abs=1e-12)


def test_three_frequency_case_in_g():
    a_sys = np.array([0.5 * G, 0.2 * G, 0.9 * G])
    a_ref = np.array([0.25 * G, 0.4 * G, 0.3 * G])
    # (0.25/0.75) + (−0.2/0.4) + (0.6/0.7) = 1/3 − 1/2 + 6/7
    j, n_star = utility_index(a_sys, a_ref, G)
    assert n_star == 3
    assert j == pytest.approx(100 * (1 / 3 - 1 / 2 + 6 / 7) / 3, rel=1e-12)


def test_terms_in_unit_interval_random():
    rng = np.random.default_rng(12345)
    a_sys = rng.uniform(0.0, 2.0 * G, 2000)
    a_ref = rng.uniform(0.0, 2.0 * G, 2000)
    a_sys[rng.random(2000) < 0.1] = np.nan
    a_ref[rng.random(2000) < 0.1] = np.nan
    a_ref[:5] = 0.0  # edge: reference overturns at once
    terms = utility_terms(a_sys, a_ref, G)
    finite = terms[~np.isnan(terms)]
    assert finite.size > 0
    assert np.all((finite >= -1.0) & (finite <= 1.0))
    # NaN exactly where both capped
    both_capped = ~(a_sys < G) & ~(a_ref < G)
    np.testing.assert_array_equal(np.isnan(terms), both_capped)
    j, n_star = utility_index(a_sys, a_ref, G)
    assert -100.0 <= j <= 100.0 and n_star == finite.size


def test_both_capped_frequencies_are_excluded():
    base_sys, base_ref = np.array([3.0]), np.array([6.0])
    j1, n1 = utility_index(base_sys, base_ref, G)
    j2, n2 = utility_index(np.r_[base_sys, np.nan, 20.0], np.r_[base_ref, 11.0, np.nan], G)
    assert (j1, n1) == (j2, n2) == (pytest.approx(-50.0), 1)


def test_n_star_zero_raises():
    with pytest.raises(ValueError, match="no frequency has a threshold below a_max0"):
        utility_index([np.nan, 12.0], [10.0, np.nan], G)


def test_nan_handling():
    # NaN on one side only counts as a_max0 on that side
    terms = utility_terms([np.nan, 2.0], [3.0, np.nan], G)
    np.testing.assert_allclose(terms, [1.0, (2.0 - G) / G])


def test_input_errors():
    with pytest.raises(ValueError, match="shape"):
        utility_index([1.0, 2.0], [1.0, 2.0, 3.0], G)
    with pytest.raises(ValueError, match="a_max0"):
        utility_index([1.0], [2.0], 0.0)
    with pytest.raises(ValueError, match="a_sys"):
        utility_terms([-1.0], [2.0], G)
    with pytest.raises(ValueError, match="a_min"):
        capped_threshold(-0.5, G)
