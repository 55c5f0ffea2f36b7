"""Every constant of constants.py is the one the code uses (no second copy anywhere)."""
import importlib
import inspect

import pytest

from rockstudy import BLOCK_PRESETS, Anchorage, Control
from rockstudy.analysis.spectra import Scenario
from rockstudy.core import constants
from rockstudy.engine import _kernel as kn
from rockstudy.engine import reference
from rockstudy.model import noise
from rockstudy.model.excitation import GroundMotion

BLC06 = BLOCK_PRESETS["BLC06"]
simulate = importlib.import_module("rockstudy.engine.simulate")  # the module, not the function


def test_free_time_default_is_the_constant_everywhere():
    assert constants.FREE_TIME == 30.0
    assert simulate.DEFAULT_FREE_TIME == constants.FREE_TIME
    assert Scenario(BLC06).free_time == constants.FREE_TIME
    assert inspect.signature(reference.simulate_reference).parameters["free_time"].default == constants.FREE_TIME
    assert inspect.signature(simulate.simulate).parameters["free_time"].default == constants.FREE_TIME


def test_rest_velocity_default_is_one_millionth_of_p_alpha_in_both_engines():
    assert constants.rest_velocity(BLC06.p, BLC06.alpha) == pytest.approx(1e-6 * BLC06.p * BLC06.alpha, rel=1e-15)
    motion = GroundMotion("one-sine", 0.0, 1.0, 1.0)
    P = simulate.pack_parameters(BLC06, Anchorage(), Control("FS"), motion)
    assert P[kn.I_VREST] == constants.rest_velocity(BLC06.p, BLC06.alpha)


def test_noise_step_and_tolerances():
    assert noise.NOISE_DT == constants.NOISE_DT == 0.0025
    motion = GroundMotion("one-sine", 0.0, 1.0, 1.0)
    P = simulate.pack_parameters(BLC06, Anchorage(), Control("FS"), motion)
    assert (P[kn.I_RTOL], P[kn.I_ATOL]) == (constants.FAST_RTOL, constants.FAST_ATOL)
    assert constants.REFERENCE_RTOL < constants.FAST_RTOL
    assert kn.MAX_EVENTS == constants.MAX_EVENTS and kn.NEGLIGIBLE_STEP == constants.NEGLIGIBLE_STEP


def test_every_constant_says_why():
    src = inspect.getsource(constants)
    for name in [n for n in vars(constants) if n.isupper()]:
        assert f'{name} = ' in src
        after = src.split(f"{name} = ", 1)[1].split("\n", 2)
        assert after[1].lstrip().startswith('"""'), f"{name} has no docstring line"
