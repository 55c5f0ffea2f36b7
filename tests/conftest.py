import pytest

from rockstudy import BLOCK_PRESETS, Anchorage


@pytest.fixture(scope="session")
def blc06():
    return BLOCK_PRESETS["BLC06"]


@pytest.fixture(scope="session")
def anchorage():
    return Anchorage()
