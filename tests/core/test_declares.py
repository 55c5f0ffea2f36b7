"""Each class and function declares its numeric arguments where it is defined (core.quantities.declares), so
core names nothing of the layers above it; the registry it fills is what check_arguments reads."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

import rockstudy
from rockstudy.analysis import fragility, jos, record_scan, spectra  # noqa: F401 -- their declarations
from rockstudy.core import quantities
from rockstudy.core.quantities import ARGUMENTS, SIZES, check_arguments, declare, declares
from rockstudy.core.validation import InputError
from rockstudy.engine import simulate  # noqa: F401
from rockstudy.model import records  # noqa: F401
from rockstudy.studies import design  # noqa: F401

CORE = Path(quantities.__file__).parent


def test_core_names_no_class_or_function_of_the_layers_above():
    owners = {owner.split(".")[0] for owner in ARGUMENTS}
    assert len(owners) >= 20
    for path in CORE.glob("*.py"):
        named = {node.value for node in ast.walk(ast.parse(path.read_text()))
                 if isinstance(node, ast.Constant) and isinstance(node.value, str)}
        assert not named & owners, f"{path.name} names {sorted(named & owners)} of the layers above"


def test_the_declaration_sits_on_the_definition():
    """Each declared class or function is the object the decorator returned (``__qualname__`` keyed)."""
    for owner in ARGUMENTS:
        head = owner.split(".")[0]
        if head in rockstudy.__all__:
            assert getattr(rockstudy, head).__qualname__ == head


@pytest.fixture
def registries():
    """The registries as they were before the test: what a test declares does not outlive it (a later test
    in the same process compares the registries with the library's own declarations)."""
    saved = [(registry, dict(registry)) for registry in (ARGUMENTS, SIZES)]
    yield
    for registry, items in saved:
        registry.clear()
        registry.update(items)


def test_declares_returns_the_object_and_fills_the_registry(registries):
    @declares(sizes={"xs": 3}, x="kappa", xs="frequency_ratio")
    def probe_function(x, xs=()):
        return x

    assert probe_function(2) == 2
    assert ARGUMENTS["test_declares_returns_the_object_and_fills_the_registry.<locals>.probe_function"] == {
        "x": "kappa", "xs": "frequency_ratio"}
    assert SIZES["test_declares_returns_the_object_and_fills_the_registry.<locals>.probe_function", "xs"] == 3


def test_an_unknown_quantity_or_a_second_different_declaration_is_refused(registries):
    with pytest.raises(KeyError, match="not a declared quantity"):
        declare("probe_unknown", x="no_such_quantity")
    declare("probe_twice", x="kappa")
    declare("probe_twice", x="kappa")  # the same again (a module reloaded) is fine
    with pytest.raises(KeyError, match="twice"):
        declare("probe_twice", x="seed")


def test_check_arguments_reads_the_registry_and_names_the_callers_option():
    """The CLI's call: the grid's options checked by AmplitudeGrid's declaration, named by option."""
    with pytest.raises(InputError, match="--max-amplitude-ratio"):
        check_arguments("AmplitudeGrid", {"stop": -1.0}, {"stop": "--max-amplitude-ratio"})
    assert check_arguments("AmplitudeGrid", {"start": 1, "stop": 2.0}) == {"start": 1.0, "stop": 2.0}
    with pytest.raises(KeyError, match="declares no arguments"):
        check_arguments("NoSuchOwner", {})
