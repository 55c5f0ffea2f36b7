"""The named slots of what crosses the compiled engine's parts (rockstudy.engine._kernel.layout): every
vector's slots are distinct and fit it, so no two quantities can share a slot."""
import pytest

from rockstudy.engine._kernel import layout

MULTI = {"R_SPRING": 2, "R_DAMPER": 2, "R_FRAC": 4}  # slots that hold a small array


@pytest.mark.parametrize("prefix, size", [("I_", "NPAR"), ("C_", "NCONST"), ("R_", "NSTATE"), ("N_", "NFILL")])
def test_slots_are_distinct_and_fit(prefix, size):
    names = [n for n in vars(layout) if n.startswith(prefix) and n.isupper()]
    assert names
    used = []
    for n in names:
        start = getattr(layout, n)
        used += range(start, start + MULTI.get(n, 1))
    assert len(used) == len(set(used)), f"{prefix}* slots overlap"
    assert min(used) == 0 and max(used) == getattr(layout, size) - 1
    assert len(used) == getattr(layout, size), f"{prefix}* leave a slot of {size} unused"


def test_state_record_is_what_the_engine_returns():
    """The engine's result is read from the state record: a fresh state is at rest at t = 0 with
    intact elements, and setup() takes the device of the strategy."""
    import numpy as np

    from rockstudy import BLOCK_PRESETS, Anchorage, Control
    from rockstudy.engine import _kernel as kn
    from rockstudy.engine._kernel import engine
    from rockstudy.engine.simulate import pack_parameters
    from rockstudy.model.excitation import GroundMotion

    b = BLOCK_PRESETS["BLC06"]
    motion = GroundMotion("one-sine", 1.0, 2 * b.p, np.pi / b.p)
    for strategy, kmax, kmin in (("FS", 0.0, 0.0), ("PASSIVE", 2.0, 2.0), ("CS01", 2.0, 0.5)):
        P = pack_parameters(b, Anchorage(kappa_max=2.0, kappa_min=0.5), Control(strategy), motion)
        C = engine.setup(P, np.zeros(0), False, False)
        S = engine.initial_state(P, C, kn.writable(motion.record))
        assert (C[kn.C_KMAX], C[kn.C_KMIN]) == (kmax, kmin)
        assert S[kn.R_T] == 0.0 and S[kn.R_MODE] == kn.MODE_REST and S[kn.R_H_ON] == 1.0
        assert list(S[kn.R_SPRING:kn.R_SPRING + 2]) == [1.0, 1.0] and np.isnan(S[kn.R_FRAC:kn.R_FRAC + 4]).all()
