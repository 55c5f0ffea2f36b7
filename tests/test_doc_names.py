"""Every rockstudy name the documentation gives resolves: README.md and docs/**/*.md name no function,
class, constant or module that does not exist.

What counts as a rockstudy name (looked for in README.md and every ``docs/**/*.md``):

* **full names**, anywhere in the text, fenced code and ``{eval-rst}`` directives included:
  ``rockstudy.a.b`` (``rockstudy.engine.simulate``, ``rockstudy.model.noise.NoiseReading``);
* **short names**: every other dotted name in inline code (single backticks) outside fenced blocks.
  It is read as a rockstudy name when its first part(s) are the last part(s) of a rockstudy module's name
  (``_kernel.maps.fracture`` for ``rockstudy.engine._kernel.maps.fracture``, ``reference.events.Impact``,
  ``noise.energy``, ``engine.integrate``), or its first part is a class, function or constant defined at
  the top of a rockstudy module (``Excitation.sign_after``, ``NoiseReading.step``) or exported by the
  package (``Block.alpha``, ``Scenario.kernel_case``). Where a short name fits several of these
  (``events`` is the fast engine's and the reference engine's) it resolves if one reading resolves.
  A short name may instead be a key path of ``config.yaml`` (``beyond.fragility.records``,
  ``noise.step``): it resolves when ``config.yaml`` has that key.

Left alone: names without a dot (``integrate``), file names (the last part a file extension:
``config.yaml``, ``kernel_fingerprint.py``), paths (a ``/`` touching the dotted run:
``tests/engine/test_fast_engine.py``, ``Block.width/height/depth``), names of other packages (the first
part an importable module other than rockstudy: ``scipy.integrate.solve_ivp``, ``xarray.Dataset``) and
the usual aliases of ``OTHER_ALIASES`` (``np.dot``, ``xr.open_dataset``, ``ds.theta.sel``). Call
arguments and indexing end a name (``spectra.threshold(engine="reference")`` is ``spectra.threshold``).
Any other dotted name in inline code is reported: a stale module name (``motion.angular_acceleration``
after ``motion`` became ``equation_of_motion``) fails rather than passing unseen. An attribute of a
variable belongs in a fenced block, or is named by its class (``SimulationResult.overturned``).

A rockstudy name resolves when its module imports (:func:`importlib.import_module`) and each further part
is an attribute (:func:`getattr`) of what comes before it, or a field of a dataclass. An attribute set
only on an instance (in ``__init__``) does not resolve: write it as "the ``sensed`` attribute of
``reference.ground.Excitation``".

The failure lists every unresolved name with its file and line, so that a rename made elsewhere shows
every page to fix at once.
"""
from __future__ import annotations

import ast
import dataclasses
import importlib
import importlib.util
import re
from pathlib import Path

import pytest
import yaml

import rockstudy

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = Path(rockstudy.__file__).resolve().parent

FENCE = re.compile(r"^(```|~~~).*?^\1[ \t]*$", re.MULTILINE | re.DOTALL)
INLINE_CODE = re.compile(r"(?<!`)`([^`\n]+)`(?!`)")
# a dotted run of identifiers, not part of a path, a longer dotted run or a number
DOTTED = re.compile(r"(?<![\w./\\-])[A-Za-z_]\w*(?:\.[A-Za-z_]\w*)+(?![\w/])")
FULL = re.compile(r"(?<![\w./\\-])rockstudy(?:\.[A-Za-z_]\w*)+")
OTHER_ALIASES = {"np", "xr", "ds", "plt", "pd"}
FILE_EXTENSIONS = {"py", "md", "rst", "nc", "yaml", "yml", "smk", "png", "pdf", "svg", "csv", "html", "cff",
                   "toml", "txt", "npz", "json", "AT2", "log", "cfg", "ini", "sh", "ipynb", "zip", "gz"}


def documents() -> list[Path]:
    return [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]


def package_modules() -> list[str]:
    """Every module and package of rockstudy, from the source tree (nothing imported)."""
    names = []
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        names.append(".".join(parts[:-1] if parts[-1] == "__init__" else parts))
    return sorted(names)


MODULES = package_modules()


def module_file(module: str) -> Path:
    path = PACKAGE.parent.joinpath(*module.split("."))
    return path / "__init__.py" if path.is_dir() else path.with_suffix(".py")


def top_level_definitions() -> dict[str, list[str]]:
    """name -> the modules that define it at their top level (classes, functions, constants)."""
    found: dict[str, list[str]] = {}
    for module in MODULES:
        for node in ast.parse(module_file(module).read_text(encoding="utf-8")).body:
            if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
                names = [node.name]
            elif isinstance(node, (ast.Assign, ast.AnnAssign)):
                targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                names = [t.id for t in targets if isinstance(t, ast.Name)]
            else:
                names = []
            for name in names:
                found.setdefault(name, []).append(module)
    return found


DEFINITIONS = top_level_definitions()
CONFIG = yaml.safe_load((ROOT / "config.yaml").read_text(encoding="utf-8"))


def exports() -> set[str]:
    return set(getattr(rockstudy, "__all__", ())) | {n for n in dir(rockstudy) if not n.startswith("_")}


def line_of(text: str, offset: int) -> int:
    return text.count("\n", 0, offset) + 1


def names_in(text: str) -> list[tuple[int, str, bool]]:
    """(line, name, full) for every candidate name of one document."""
    found = [(line_of(text, m.start()), m.group(0), True) for m in FULL.finditer(text)]
    fenced = [(m.start(), m.end()) for m in FENCE.finditer(text)]
    for span in INLINE_CODE.finditer(text):
        if any(a <= span.start() < b for a, b in fenced):
            continue
        for m in DOTTED.finditer(span.group(1)):
            if not m.group(0).startswith("rockstudy."):  # full names were taken above
                found.append((line_of(text, span.start()), m.group(0), False))
    return [(line, name, full) for line, name, full in found if name.rsplit(".", 1)[1] not in FILE_EXTENSIONS]


def candidates(name: str) -> list[tuple[str, list[str]]]:
    """The (module, attribute path) readings of a name; empty when it is no rockstudy name."""
    parts = name.split(".")
    if parts[0] == "rockstudy":
        return [(".".join(parts[:k]), parts[k:]) for k in range(len(parts), 0, -1)
                if ".".join(parts[:k]) in MODULES or k == 1]
    readings = []
    for k in range(len(parts), 0, -1):
        suffix = "." + ".".join(parts[:k])
        readings += [(module, parts[k:]) for module in MODULES if module.endswith(suffix)]
    readings += [(module, parts) for module in DEFINITIONS.get(parts[0], [])]
    if parts[0] in exports():
        readings.append(("rockstudy", parts))
    return readings


def is_config_key(name: str) -> bool:
    node = CONFIG
    for part in name.split("."):
        if not isinstance(node, dict) or part not in node:
            return False
        node = node[part]
    return True


def is_other_package(name: str) -> bool:
    first = name.split(".")[0]
    if first in OTHER_ALIASES:
        return True
    try:
        return first != "rockstudy" and importlib.util.find_spec(first) is not None
    except (ImportError, ValueError):
        return False


def _attribute(obj, part: str):
    try:
        return getattr(obj, part)
    except AttributeError:
        if dataclasses.is_dataclass(obj) and part in {f.name for f in dataclasses.fields(obj)}:
            return dataclasses.MISSING  # a field without default: a name, though no class attribute
        raise


def resolves(module: str, attributes: list[str]) -> bool:
    try:
        obj = importlib.import_module(module)
        for part in attributes:
            obj = _attribute(obj, part)
    except (ImportError, AttributeError):
        return False
    return True


def unresolved(paths: list[Path]) -> list[str]:
    bad = []
    for path in paths:
        text = path.read_text(encoding="utf-8")
        for line, name, full in names_in(text):
            readings = candidates(name)
            if any(resolves(m, a) for m, a in readings) or (not full and is_config_key(name)):
                continue
            if readings or full or not is_other_package(name):
                bad.append(f"{path.relative_to(ROOT) if path.is_relative_to(ROOT) else path}:{line}: {name}")
    return bad


def test_every_rockstudy_name_in_the_documentation_resolves():
    bad = unresolved(documents())
    assert not bad, f"{len(bad)} names in README.md and docs/ do not resolve:\n" + "\n".join(bad)


def test_the_documents_name_rockstudy_functions_at_all():
    """The extraction finds the names it is meant to find (a broken pattern would pass everything)."""
    names = {name for path in documents() for _, name, _ in names_in(path.read_text(encoding="utf-8"))}
    resolved = {n for n in names if candidates(n)}
    assert len(resolved) >= 50
    assert any(n.startswith("rockstudy.") for n in resolved) and any(n.startswith("_kernel.") for n in resolved)


@pytest.mark.parametrize("page, expected", [
    ("`rockstudy.engine.simulate.simulate` and `_kernel.maps.fracture`", []),
    ("`rockstudy.engine.no_such_module`", ["rockstudy.engine.no_such_module"]),
    ("`motion.angular_acceleration`, `equation_of_motion.angular_acceleration`", ["motion.angular_acceleration"]),
    ("`_kernel.engine._integrate` and `Block.not_an_attribute`",
     ["_kernel.engine._integrate", "Block.not_an_attribute"]),
    ("`utility_index.capped_threshold(a, 1.0)`; `spectra.threshold(engine=\"reference\")`", []),
    ("`config.yaml`, `docs/model.md`, `tests/engine/test_scan.py`, `ds.theta.sel(t=2.0)`, `np.dot`", []),
    ("`scipy.integrate.solve_ivp`, `Excitation.sign_after`, `NoiseReading.step`", []),
    ("`noise.step`, `beyond.fragility.records`; `noise.no_such_key`", ["noise.no_such_key"]),
    ("`run.overturned`, `SimulationResult.overturned`", ["run.overturned"]),
    ("```python\nfrom rockstudy.no_such import x\nnoise.no_such_name\n```\n", ["rockstudy.no_such"]),
    ("`events.locate_poly` (fast engine) and `events.Impact` (reference engine)", []),
    ("`events.no_such_event`", ["events.no_such_event"]),
])
def test_the_check_can_fail(tmp_path, page, expected):
    """Made-up pages whose bad names are known: each is reported with its file and line, no good one is."""
    path = tmp_path / "page.md"
    path.write_text("# A page\n\n" + page + "\n", encoding="utf-8")
    assert unresolved([path]) == [f"{path}:{3 if '```' not in page else 4}: {name}" for name in expected]
