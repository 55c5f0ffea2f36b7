"""rockstudy.jos: J_OS of two spectrum datasets (Eq. 21), hand-worked, with its per-frequency terms."""
import math

import numpy as np
import pytest
import xarray as xr

import rockstudy as rs
from rockstudy.analysis.jos import JosResult, a_max0_ratio, jos

TAN_ALPHA = 0.25


def _spectrum(thresholds, stop=6.0):
    freqs = np.arange(1.0, len(thresholds) + 0.5)
    return xr.Dataset({"threshold": ("frequency_ratio", np.asarray(thresholds, dtype=float))},
                      coords={"frequency_ratio": freqs},
                      attrs={"grid_amplitude_start": 0.9, "grid_amplitude_stop": stop, "grid_amplitude_step": 0.1,
                             "block_alpha": math.atan(TAN_ALPHA)})


def test_jos_hand_worked():
    """BLC06-like tan(alpha) = 1/4: a_max,0 = 1 g is the amplitude ratio 4. Reference thresholds 2, 2, NaN, NaN;
    system 3, 1, NaN, 5: terms (3-2)/(4-2) = 0.5, (1-2)/2 = -0.5, both capped (not counted), 0 (5 capped at 4
    against the reference's NaN capped at 4 -- both capped, not counted). J_OS = 100 * (0.5 - 0.5) / 2 = 0."""
    ref, sys_ = _spectrum([2.0, 2.0, np.nan, np.nan]), _spectrum([3.0, 1.0, np.nan, 5.0])
    result = jos(sys_, ref)
    assert isinstance(result, JosResult) and result.defined
    assert result.a_max0_g == 1.0 and result.a_max0_ratio == pytest.approx(4.0, rel=1e-12)
    np.testing.assert_allclose(result.terms, [0.5, -0.5, np.nan, np.nan])
    assert (result.j_os, result.n_star) == (0.0, 2)
    np.testing.assert_array_equal(result.frequency_ratio, [1.0, 2.0, 3.0, 4.0])
    # a lower protection level: a_max,0 = 0.75 g is the ratio 3; terms (3-2)/(3-2) = 1, (1-2)/2 = -0.5
    assert jos(sys_, ref, 0.75).j_os == pytest.approx(25.0, rel=1e-12)
    assert rs.jos is jos and rs.JosResult is JosResult


def test_jos_undefined_and_refusals():
    never = _spectrum([np.nan, np.nan])
    result = jos(never, never)
    assert math.isnan(result.j_os) and result.n_star == 0 and not result.defined
    with pytest.raises(ValueError, match="same frequencies"):
        jos(_spectrum([1.0, 2.0]), _spectrum([1.0, 2.0, 3.0]))
    with pytest.raises(ValueError, match="--a-max0"):
        jos(never, never, 2.0, a_max0_name="--a-max0")  # 2 g is the ratio 8, above the scan's top 6
    assert a_max0_ratio(never, 1.5) == pytest.approx(6.0, rel=1e-12)
