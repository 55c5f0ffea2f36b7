"""The package's architecture as a test: imports only point down the layers, and no module imports
another in a circle (also not through an import inside a function).

Layers, bottom to top: ``_version`` < ``core/`` < ``model/`` < ``engine/`` < ``analysis/`` < ``studies/``
< ``cli/``, ``plotting/``, ``report/`` < the package face ``__init__.py``.
"""
from __future__ import annotations

import ast
from pathlib import Path

import fresh_python
import rockstudy

ROOT = Path(rockstudy.__file__).parent
LAYERS = {"_version": 0, "core": 1, "model": 2, "engine": 3, "analysis": 4, "studies": 5, "cli": 6, "plotting": 6,
          "report": 6, "__init__": 7}


def module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__" and len(parts) > 1:
        parts = parts[:-1]
    return ".".join(["rockstudy", *parts]) if parts != ["__init__"] else "rockstudy"


def layer(module: str) -> int:
    parts = module.split(".")
    return LAYERS["__init__"] if len(parts) == 1 else LAYERS[parts[1]]


def imports(path: Path, modules: set[str]) -> list[tuple[str, int]]:
    """(imported rockstudy module, line) of every import in ``path``, at any depth of the file."""
    found = []
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("rockstudy"):
            assert node.level == 0, f"{path}:{node.lineno}: relative import (the package uses absolute ones)"
            for alias in node.names:  # `from rockstudy.core import io` imports the module rockstudy.core.io
                sub = f"{node.module}.{alias.name}"
                found.append((sub if sub in modules else node.module, node.lineno))
        elif isinstance(node, ast.Import):
            found += [(a.name, node.lineno) for a in node.names if a.name.startswith("rockstudy")]
    return found


def graph() -> dict[str, list[tuple[str, int]]]:
    files = {module_name(p): p for p in ROOT.rglob("*.py")}
    return {name: imports(path, set(files)) for name, path in files.items()}


def test_every_module_belongs_to_a_layer():
    for name in graph():
        layer(name)  # KeyError names a module outside the layers


def test_imports_only_point_down_the_layers():
    upward = [f"{name} (layer {layer(name)}) imports {target} (layer {layer(target)}) at line {line}"
              for name, targets in graph().items() for target, line in targets
              if layer(target) > layer(name)]
    assert not upward, "\n".join(upward)


def test_no_import_cycle():
    edges = {name: {t for t, _ in targets if t != name} for name, targets in graph().items()}
    # a package imports its own children's names through __init__; that is not a cycle between modules
    for name in edges:
        edges[name] = {t for t in edges[name] if not t.startswith(name + ".")}
    state: dict[str, int] = {}
    cycles = []

    def visit(node, stack):
        state[node] = 1
        for nxt in sorted(edges.get(node, ())):
            if state.get(nxt) == 1:
                cycles.append(" -> ".join(stack[stack.index(nxt):] + [nxt]))
            elif nxt in edges and not state.get(nxt):
                visit(nxt, stack + [nxt])
        state[node] = 2

    for node in sorted(edges):
        if not state.get(node):
            visit(node, [node])
    assert not cycles, "\n".join(cycles)


def test_the_checker_sees_an_upward_import(tmp_path):
    """The oracle can fail: an import of the study layer from the model layer is caught."""
    bad = tmp_path / "bad.py"
    bad.write_text("def f():\n    from rockstudy.studies.study import check_study\n")
    (target, _), = imports(bad, {"rockstudy.studies.study"})
    assert layer(target) > LAYERS["model"]


def test_core_holds_no_config_model():
    """The config's models live with the study (``rockstudy.studies.config_model``): no module of ``core``
    defines a pydantic model or imports pydantic at its top, and importing every module of ``core`` in a fresh
    interpreter loads no module of a higher layer and not pydantic."""
    for path in sorted((ROOT / "core").rglob("*.py")):
        tree = ast.parse(path.read_text())
        top = [a.name for n in tree.body if isinstance(n, ast.Import) for a in n.names]
        top += [n.module for n in tree.body if isinstance(n, ast.ImportFrom) and n.module]
        assert not [m for m in top if m.split(".")[0] == "pydantic"], f"{path.name} imports pydantic"
        bases = [ast.unparse(b) for n in ast.walk(tree) if isinstance(n, ast.ClassDef) for b in n.bases]
        assert not {"BaseModel", "pydantic.BaseModel", "Section"} & set(bases), f"{path.name} defines a model"
    modules = sorted(name for name in graph() if layer(name) == LAYERS["core"] and name != "rockstudy.core")
    loaded = fresh_python.run(
        "import importlib, sys\n"
        f"for m in {modules!r}: importlib.import_module(m)\n"
        "print(' '.join(sorted(m for m in sys.modules if m.startswith(('rockstudy.', 'pydantic')))))").split()
    assert modules and set(modules) <= set(loaded)
    above = sorted({"pydantic" if m.startswith("pydantic") else m for m in loaded
                    if m.startswith("pydantic") or (m.startswith("rockstudy.") and layer(m) > LAYERS["core"])})
    assert not above, f"importing core loads {above}"


def test_the_checker_sees_core_importing_the_config_model(tmp_path):
    """The oracle can fail: core importing the config's models (at the top or inside a function) is caught."""
    bad = tmp_path / "bad.py"
    bad.write_text("from rockstudy.studies import config_model\n\ndef f():\n    import rockstudy.analysis.risk_sites\n")
    found = imports(bad, {"rockstudy.studies.config_model", "rockstudy.analysis.risk_sites"})
    assert [layer(t) for t, _ in found] == [LAYERS["studies"], LAYERS["analysis"]]
    assert all(layer(t) > LAYERS["core"] for t, _ in found)


MAX_MODULE_LINES = 600
"""Longest module outside the compiled kernel (``engine/_kernel``), in lines. [-]"""
MAX_FUNCTION_LINES = 120
"""Longest function or method outside the compiled kernel, decorators excluded, in lines. [-]"""


def test_modules_and_functions_stay_in_size():
    """Outside the compiled kernel no module passes 600 lines and no function 120: a module that grows
    past it holds two concerns, to be split (the kernel's driver and step loop stay whole for numba)."""
    too_long = []
    for path in sorted(ROOT.rglob("*.py")):
        if "_kernel" in path.relative_to(ROOT).parts:
            continue
        text = path.read_text(encoding="utf-8")
        if len(text.splitlines()) > MAX_MODULE_LINES:
            too_long.append(f"{module_name(path)}: {len(text.splitlines())} lines")
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                lines = node.end_lineno - node.lineno + 1
                if lines > MAX_FUNCTION_LINES:
                    too_long.append(f"{module_name(path)}.{node.name}: {lines} lines")
    assert not too_long, "over the size limits (module 600, function 120 lines):\n" + "\n".join(too_long)
