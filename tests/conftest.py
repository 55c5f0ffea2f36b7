import os

import pytest

from rockstudy import BLOCK_PRESETS, Anchorage
from rockstudy.core.frames import with_frame_room


@pytest.fixture(scope="session")
def blc06():
    return BLOCK_PRESETS["BLC06"]


@pytest.fixture(scope="session")
def anchorage():
    return Anchorage()


@pytest.fixture
def quantity_checks(monkeypatch):
    """The names under which every declared quantity is checked (each ``core.quantities.Quantity.check``
    call, in order), to count how often a value is checked and under which name."""
    from rockstudy.core import quantities
    calls = []
    real = quantities.Quantity.check

    def counted(self, name, value):
        calls.append(name)
        return real(self, name, value)
    monkeypatch.setattr(quantities.Quantity, "check", counted)
    return calls


SLOW = (
    "tests/test_tiny_study.py",
    "tests/test_workflow.py",
    "tests/test_doc_blocks.py",
    "tests/test_risk_workflow.py",
    "tests/test_beyond_workflow.py",
    "tests/test_overlays.py",
    "tests/test_docs.py::test_docs_build_without_warnings",
    "tests/test_docs.py::test_guide_examples_run",
    "tests/engine/test_termination.py::test_compiled_scans_and_the_suite_fragility_end_below_the_float_spacing",
)
"""Modules and tests marked ``slow`` here, besides those their own modules mark: the ones that run Snakemake
(each dry run builds the study's DAG; the tiny study runs it end to end), the documentation's Sphinx build
and examples, and a scan to the float spacing in a fresh process. pyproject's addopts leave the slow tests
out of a plain ``python -m pytest``; CI (``CI=true``) and ``-m slow`` or ``-m ""`` run them."""


def pytest_configure(config):
    """Under CI (``CI=true``, as ``.ci/run`` is run there) every test runs, the slow ones included."""
    if os.environ.get("CI") == "true":
        config.option.markexpr = ""


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(items):
    """Mark the :data:`SLOW` tests (before ``-m`` deselects by mark), then the modules marked ``long_chain``
    first, in their order: with several workers (pyproject's addopts, a module to a worker) such a chain
    (the tiny study, run once for the module's tests) starts at once while the other workers share the rest,
    instead of starting last and running alone."""
    for item in items:
        if item.nodeid.startswith(SLOW):
            item.add_marker(pytest.mark.slow)
    items.sort(key=lambda item: item.get_closest_marker("long_chain") is None)


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_protocol(item, nextitem):
    """Run each test (set-up, call, teardown) with room on Python's frame stack (``core.frames``), as the
    workflow's jobs run: numba compiles the engine on a cold cache tens of frames deep, and where that depth
    falls on the boundary of CPython's 16 KiB frame chunks, its compile maps and unmaps a chunk at every
    other call (seconds of system time per compile). Tests marked ``plain_frames`` run as pytest runs them."""
    from _pytest.runner import pytest_runtest_protocol as run
    if item.get_closest_marker("plain_frames"):
        return None
    return with_frame_room(run, item, nextitem)
