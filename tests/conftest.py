import pytest

from rockstudy import BLOCK_PRESETS, Anchorage


@pytest.fixture(scope="session")
def blc06():
    return BLOCK_PRESETS["BLC06"]


@pytest.fixture(scope="session")
def anchorage():
    return Anchorage()


def pytest_collection_modifyitems(items):
    """The modules marked ``long_chain`` first, in their order: with several workers (pyproject's addopts,
    a module to a worker) such a chain (the tiny study, run once for the module's tests) starts at once
    while the other workers share the rest, instead of starting last and running alone."""
    items.sort(key=lambda item: item.get_closest_marker("long_chain") is None)
