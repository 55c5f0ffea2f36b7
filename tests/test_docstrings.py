"""Every public function and method of every public module documents its parameters the numpydoc way.

The API reference (docs/api/*, autodoc + numpydoc, ``autodoc_typehints = "none"``) shows a function's
parameters only from its docstring's ``Parameters`` section, so each one must be there: every parameter of
the signature, by name, with a type (and the unit, where it has one, in the text) and a description, and
no name the signature does not have. Public means: a module whose dotted name has no part starting with
``_``, and a function or method defined in it whose name does not start with ``_``.
"""
from __future__ import annotations

import importlib
import inspect
import pkgutil
import warnings

import pytest

import rockstudy

docscrape = pytest.importorskip("numpydoc.docscrape")


def _public_modules() -> list[str]:
    names = ["rockstudy"]
    for info in pkgutil.walk_packages(rockstudy.__path__, "rockstudy."):
        if not any(part.startswith("_") for part in info.name.split(".")[1:]):
            names.append(info.name)
    return sorted(names)


def _public_functions(module):
    """(qualified name, function) of each public function and method defined in ``module``."""
    for name, obj in sorted(vars(module).items()):
        if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__:
            continue
        if inspect.isfunction(obj):
            yield name, obj
        elif inspect.isclass(obj):
            for member_name, member in sorted(vars(obj).items()):
                if member_name.startswith("_"):
                    continue
                func = member.__func__ if isinstance(member, (staticmethod, classmethod)) else member
                if inspect.isfunction(func):
                    yield f"{name}.{member_name}", func


def _signature_names(func) -> list[str]:
    names = []
    for p in inspect.signature(func).parameters.values():
        if p.name in ("self", "cls"):
            continue
        prefix = {p.VAR_POSITIONAL: "*", p.VAR_KEYWORD: "**"}.get(p.kind, "")
        names.append(prefix + p.name)
    return names


def _documented(func) -> list[tuple[str, str, str]]:
    """(name, type, description) of each entry of the docstring's Parameters section."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        doc = docscrape.FunctionDoc(func, config={})
    out = []
    for param in doc["Parameters"]:
        for name in param.name.split(","):
            out.append((name.strip(), param.type.strip(), " ".join(param.desc).strip()))
    return out


def problems(func) -> list[str]:
    """What ``func``'s docstring lacks, as short phrases (empty when it documents every parameter)."""
    wanted = _signature_names(func)
    if not wanted:
        return []
    documented = _documented(func)
    if not documented:
        return ["no numpydoc 'Parameters' section"]
    found = {name.lstrip("*"): (kind, desc) for name, kind, desc in documented}
    out = [f"'{name}' not documented" for name in wanted if name.lstrip("*") not in found]
    plain = {name.lstrip("*") for name in wanted}
    out += [f"'{name}' documented but not a parameter" for name in found if name not in plain]
    out += [f"'{name}' has no type" for name, (kind, _) in found.items() if name in plain and not kind]
    out += [f"'{name}' has no description" for name, (_, desc) in found.items() if name in plain and not desc]
    return out


@pytest.mark.parametrize("module_name", _public_modules())
def test_every_public_function_documents_its_parameters(module_name):
    module = importlib.import_module(module_name)
    missing = {qual: p for qual, func in _public_functions(module) if (p := problems(func))}
    assert not missing, f"{module_name}: " + "; ".join(f"{q}: {', '.join(p)}" for q, p in missing.items())


def test_the_check_can_fail():
    """A function without a Parameters section, and one with a stale entry, are found."""
    def bare(x, y=1):
        """Add."""

    def stale(x):
        """Add.

        Parameters
        ----------
        x : float
            A number. [m]
        z : int
            Gone.
        """

    def untyped(x):
        """Add.

        Parameters
        ----------
        x
            A number.
        """

    assert problems(bare) == ["no numpydoc 'Parameters' section"]
    assert problems(stale) == ["'z' documented but not a parameter"]
    assert problems(untyped) == ["'x' has no type"]
