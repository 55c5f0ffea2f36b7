"""Small dataset builders shared by several test folders (no simulation behind them)."""
import math

import numpy as np

from rockstudy.analysis.spectra import AmplitudeGrid, Scenario, spectrum_dataset
from rockstudy.model.anchorage import Anchorage
from rockstudy.model.block import BLOCK_PRESETS
from rockstudy.model.control import Control

BLC06 = BLOCK_PRESETS["BLC06"]
FREQS = np.array([0.5, 1.0, 2.0, 3.0])
A_MAX0 = 1.0 / math.tan(BLC06.alpha)  # a_max,0 = g as an amplitude ratio (= 4 for BLC06)


def fake_spectrum(strategy, level, thresholds, realisations=None, sampling_time=0.0, delay=0.0, *,
                  block=BLC06, anchorage=None, grid=None, freqs=FREQS, **settings):
    """A spectrum Dataset with given thresholds (realisation, frequency), no simulation; ``settings``: more
    :class:`Scenario` fields (excitation, seed, noise, overturn_criterion, free_time)."""
    thr = np.atleast_2d(np.asarray(thresholds, float))
    ks = list(range(thr.shape[0])) if realisations is None else realisations
    sc = Scenario(block, anchorage or Anchorage(), Control(strategy, sampling_time, delay), noise_level=level,
                  **settings)
    ones = np.ones_like(thr)
    return spectrum_dataset(sc, freqs, ks, thr, thr - 0.01, ones.astype(int), ones, ones, grid or AmplitudeGrid())


def two_fragilities():
    """The fitted fragilities of FS and CS01 (medians 0.5 and 0.8 g with their intervals, β = 0.4) as a
    fragility dataset holds them, for the risk's tests."""
    import xarray as xr
    return xr.Dataset({"fragility_median_physical": ("strategy", [0.5, 0.8], {"units": "g"}),
                       "median_low_physical": ("strategy", [0.4, 0.7], {"units": "g"}),
                       "median_high_physical": ("strategy", [0.6, 0.9], {"units": "g"}),
                       "fragility_median": ("strategy", [2.0, 3.2], {"units": "1"}),
                       "fragility_dispersion": ("strategy", [0.4, 0.4])},
                      coords={"strategy": ["FS", "CS01"]}, attrs={"record_suite": "test"})
