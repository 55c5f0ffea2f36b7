"""The threshold scans' compile in two parts (``rockstudy.engine._kernel.parts``): the lists name what the
scans compile, with the argument types they compile it for."""
import json

import pytest

from fresh_python import run
from rockstudy.engine._kernel import parts

# In a fresh interpreter with an empty numba cache: what compiling the step loop compiles, then what the
# threshold scans compile on top of it (as the workflow's rule compile_engine), each function's argument
# types by the codes of parts.TYPE_CODES.
_COMPILED = """
import json, dataclasses, importlib
from numba.core.registry import CPUDispatcher
from rockstudy.engine._kernel import parts
from rockstudy.analysis.scenario import Scenario
from rockstudy.analysis.spectra import AmplitudeGrid, spectrum
from rockstudy.model.control import Control
from rockstudy import BLOCK_PRESETS
codes = {repr(t): c for c, t in parts.TYPE_CODES.items()}

def compiled():
    out = {}
    for short, name in parts.MODULES.items():
        for attr, fn in vars(importlib.import_module(name)).items():
            if isinstance(fn, CPUDispatcher) and fn.py_func.__module__ == name:
                for sig in fn.signatures:
                    out[f"{short}.{attr}"] = " ".join(codes.get(repr(t), repr(t)) for t in sig)
    return out

parts.compile_step_loop()
loop = compiled()
noisy = Scenario(BLOCK_PRESETS["BLC06"], control=Control("CS01"), noise_level=0.05)
grid = AmplitudeGrid(start=1.0, stop=1.2, step=0.1, resolution=0.05)
spectrum(noisy, [1.0], realisations=[0], grid=grid)
spectrum(dataclasses.replace(noisy, noise_level=0.0), [1.0], grid=grid)
print(json.dumps({"loop": loop, "scans": compiled()}))
"""


@pytest.fixture(scope="module")
def compiled(tmp_path_factory):
    return json.loads(run(_COMPILED, NUMBA_CACHE_DIR=str(tmp_path_factory.mktemp("numba")), NUMBA_NUM_THREADS="1"))


@pytest.mark.slow
def test_the_parts_are_compiled_by_the_scans_with_those_types_and_not_by_the_step_loop(compiled):
    """Each of ``DRIVER_PARTS`` is compiled by the scans for the argument types listed (other types would
    compile it twice) and not by the step loop (the two processes would compile it both)."""
    loop, scans = compiled["loop"], compiled["scans"]
    listed = {f"{module}.{name}": codes for module, name, codes in parts.DRIVER_PARTS}
    wrong = {name: (codes, scans.get(name)) for name, codes in listed.items() if scans.get(name) != codes}
    assert not wrong, f"listed types, then the scans' (None: not compiled by the scans): {wrong}"
    assert not set(listed) & set(loop)
    assert {"engine.setup", "engine.initial_state", "engine.driven_bound_data", "events.scan_exit"} <= set(listed)


@pytest.mark.slow
def test_the_step_loop_is_compiled_for_the_types_the_scans_call_it_with(compiled):
    module, name, codes = parts.STEP_LOOP
    assert compiled["loop"][f"{module}.{name}"] == codes == compiled["scans"][f"{module}.{name}"]
    assert "engine.drive" not in compiled["loop"]  # the driver's parts are not compiled with the step loop


def test_every_part_names_a_compiled_function_and_known_types():
    for module, name, codes in (parts.STEP_LOOP, *parts.DRIVER_PARTS):
        fn = parts.function(module, name)
        assert hasattr(fn, "compile"), (module, name)
        assert len(parts.signature(codes)) == fn.py_func.__code__.co_argcount, (module, name, codes)
