"""The threshold scans' compile in two processes (``rockstudy.engine._kernel.parts``): the lists name what the
scans compile, with the argument types they compile it for, and the split compile gives the scans the same
machine code as one process compiling everything."""
import json

import pytest

from fresh_python import run
from rockstudy.engine._kernel import parts

# In a fresh interpreter: what compiling the step loop compiles, then what the threshold scans compile on
# top of it (as the workflow's rule compile_engine), each function's argument types by the codes of
# parts.TYPE_CODES; and the machine code of the threshold scan, function by function, with the names numba
# makes unique per compile (a counter and the flags' tag after each function's name) and the local labels
# taken out.
_COMPILED = """
import json, dataclasses, importlib, re, sys
from numba.core.registry import CPUDispatcher
from rockstudy.engine._kernel import parts, scan
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

if sys.argv[1] == "parts":
    parts.compile_driver_parts()
    raise SystemExit
parts.compile_step_loop()
loop = compiled()
noisy = Scenario(BLOCK_PRESETS["BLC06"], control=Control("CS01"), noise_level=0.05)
grid = AmplitudeGrid(start=1.0, stop=1.2, step=0.1, resolution=0.05)
spectrum(noisy, [1.0], realisations=[0], grid=grid)
spectrum(dataclasses.replace(noisy, noise_level=0.0), [1.0], grid=grid)
(asm,) = scan.threshold_kernel.inspect_asm().values()
asm = re.sub(r"B[0-9]+v[0-9]+B[0-9]+c8tJTI[A-Za-z0-9_]*", "", asm)
asm = re.sub(r"[.]L[A-Za-z_]*[0-9]+(_[0-9]+)*", ".L", asm)
functions, name = {}, None
for line in asm.splitlines():
    if re.match(r"^_Z[A-Za-z0-9_]+:$", line):
        name = line[:-1]
        functions[name] = []
    elif name and line.lstrip().startswith(".size"):
        name = None
    elif name:
        functions[name].append(line)
print(json.dumps({"loop": loop, "scans": compiled(), "functions": functions}))
"""


def _compile(cache, split: bool) -> dict:
    env = dict(NUMBA_CACHE_DIR=str(cache), NUMBA_NUM_THREADS="1")
    if split:  # the parts first, into the cache the scans then load them from
        run("import sys; sys.argv = ['-', 'parts']\n" + _COMPILED, **env)
    return json.loads(run("import sys; sys.argv = ['-', 'scans']\n" + _COMPILED, **env))


@pytest.fixture(scope="module")
def compiled(tmp_path_factory):
    return _compile(tmp_path_factory.mktemp("numba"), split=False)


@pytest.fixture(scope="module")
def split(tmp_path_factory):
    return _compile(tmp_path_factory.mktemp("numba-split"), split=True)


@pytest.mark.slow
def test_the_split_compile_gives_the_scans_the_machine_code_of_one_process(compiled, split):
    """Each part compiled by the other process, with its caller's flags, and loaded from the cache, is linked
    and inlined as if compiled in place: the threshold scan's machine code is the same, function by function."""
    names = sorted(compiled["functions"])
    assert sorted(split["functions"]) == names
    assert any("6engine5drive" in name for name in names) and any("9integrate" in name for name in names)
    differ = [name for name in names if split["functions"][name] != compiled["functions"][name]]
    assert not differ, f"machine code differs in {differ}"


@pytest.mark.slow
def test_the_loop_parts_are_compiled_by_the_step_loop_with_those_types(compiled):
    listed = {f"{module}.{name}": codes for module, name, codes in parts.LOOP_PARTS}
    wrong = {name: (codes, compiled["loop"].get(name)) for name, codes in listed.items()
             if compiled["loop"].get(name) != codes}
    assert not wrong, f"listed types, then the step loop's (None: not compiled by it): {wrong}"
    assert {"dopri.step", "dopri.rhs", "engine.next_known_time"} <= set(listed)


@pytest.mark.slow
def test_the_other_parts_are_compiled_by_the_scans_with_those_types_and_not_by_the_step_loop(compiled):
    """Each of ``DRIVE_PARTS`` and ``DRIVER_PARTS`` is compiled by the scans for the argument types listed
    (other types would compile it twice) and not by the step loop (the two processes would compile it both)."""
    loop, scans = compiled["loop"], compiled["scans"]
    listed = {f"{module}.{name}": codes for module, name, codes in parts.DRIVE_PARTS + parts.DRIVER_PARTS}
    wrong = {name: (codes, scans.get(name)) for name, codes in listed.items() if scans.get(name) != codes}
    assert not wrong, f"listed types, then the scans' (None: not compiled by the scans): {wrong}"
    assert not set(listed) & set(loop)
    assert {"engine.setup", "engine.initial_state", "engine.driven_bound_data", "events.scan_exit",
            "engine.ground_phase"} <= set(listed)


@pytest.mark.slow
def test_the_step_loop_is_compiled_for_the_types_the_scans_call_it_with(compiled):
    module, name, codes = parts.STEP_LOOP
    assert compiled["loop"][f"{module}.{name}"] == codes == compiled["scans"][f"{module}.{name}"]
    assert "engine.drive" not in compiled["loop"]  # the driver's parts are not compiled with the step loop


def test_every_part_names_a_compiled_function_and_known_types():
    lists = (parts.LOOP_PARTS, parts.DRIVE_PARTS, parts.DRIVER_PARTS)
    for module, name, codes in (parts.STEP_LOOP, *(part for listed in lists for part in listed)):
        fn = parts.function(module, name)
        assert hasattr(fn, "compile"), (module, name)
        assert len(parts.signature(codes)) == fn.py_func.__code__.co_argcount, (module, name, codes)
    names = [(module, name) for listed in lists for module, name, _ in listed]
    assert len(names) == len(set(names))  # each part in one list, once
    assert parts.function(*parts.DRIVER).py_func.__name__ == "drive"


def test_a_part_is_compiled_with_the_flags_its_caller_gives_it():
    """numba's callees inherit the caller's reference counting: the step loop and the driver count none."""
    for caller in (parts.STEP_LOOP[:2], parts.DRIVER):
        assert parts.caller_flags(*caller).nrt is False
    assert parts.caller_flags("scan", "threshold_kernel").nrt is True
