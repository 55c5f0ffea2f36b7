"""Count the limits written outside the registry (``rockstudy.core.limits``).

A limit is counted where it is written as a number, not where it is used:

* a module-level ``MAX_*`` / ``MIN_*`` / ``*_RANGE(S)`` / ``*_LIMIT(S)`` name bound to an expression that
  holds a number (an alias such as ``MAX_X = limits.MAX_X`` is not counted);
* a number other than 0 and 1 written as a range end: the first two arguments of ``Quantity(...)``, the
  ``low``/``high`` arguments of ``check_range``/``check_positive``/``check_nonnegative``/``check_int_range``
  and the ``gt``/``ge``/``lt``/``le`` of ``Field(...)`` and ``_number(...)``;
* a tuple of names (strings) written in two modules (a copied name list), counted once per extra copy.

The registry is ``core/limits.py``; ``core/constants.py`` (the engines' numerical constants) and the compiled
kernel are not counted. Usage: ``python .ci/count_limits.py [src/rockstudy]`` prints each hit and the total.
"""
from __future__ import annotations

import ast
import re
import sys
from collections import defaultdict
from pathlib import Path

NAME = re.compile(r"^(MAX|MIN)_|_RANGES?$|_LIMITS?$")
CHECKS = {"check_range": (2, 3), "check_positive": (3,), "check_nonnegative": (3,), "check_int_range": (2, 3)}
KEYWORDS = {"low", "high", "gt", "ge", "lt", "le"}
SKIP = ("core/limits.py", "core/constants.py", "engine/_kernel/")


def numbers(node) -> list[float]:
    return [n.value for n in ast.walk(node) if isinstance(n, ast.Constant)
            and isinstance(n.value, (int, float)) and not isinstance(n.value, bool)]


def bound(node) -> bool:
    """A range end written as a number (``50.0``, ``math.pi / 2``), not a relation to another input."""
    free = [n.id for n in ast.walk(node) if isinstance(n, ast.Name) and n.id != "math"]
    return not free and any(x not in (0, 1) for x in numbers(node))


def scan(path: Path, rel: str, names: dict) -> list[str]:
    tree = ast.parse(path.read_text())
    hits = []
    for node in tree.body:
        targets = node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(
            node, ast.AnnAssign) and node.value is not None else []
        for t in targets:
            if isinstance(t, ast.Name) and NAME.search(t.id) and numbers(node.value):
                hits.append(f"{rel}:{node.lineno}: {t.id}")
            if isinstance(t, ast.Name) and isinstance(node.value, ast.Tuple) and len(node.value.elts) >= 2 and all(
                    isinstance(e, ast.Constant) and isinstance(e.value, str) for e in node.value.elts):
                names[frozenset(e.value for e in node.value.elts)].append(f"{rel}:{node.lineno}: {t.id}")
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        func = node.func.id if isinstance(node.func, ast.Name) else node.func.attr if isinstance(
            node.func, ast.Attribute) else ""
        picked = range(2) if func == "Quantity" else CHECKS.get(func, ())
        args = [node.args[i] for i in picked if i < len(node.args)]
        kws = [k.value for k in node.keywords if k.arg in KEYWORDS and func in (*CHECKS, "Field", "_number",
                                                                                "Quantity")]
        for arg in (*args, *kws):
            if bound(arg):
                hits.append(f"{rel}:{node.lineno}: {func}(... {ast.unparse(arg)} ...)")
    return hits


def main(root: str = "src/rockstudy") -> int:
    base = Path(root)
    hits, names = [], defaultdict(list)
    for path in sorted(base.rglob("*.py")):
        rel = path.relative_to(base).as_posix()
        if not rel.startswith(SKIP):
            hits += scan(path, rel, names)
    for where in names.values():
        hits += [f"{w} (a copied name list)" for w in where[1:]]
    print("\n".join(hits))
    print(f"{len(hits)} limits written outside core/limits.py")
    return len(hits)


if __name__ == "__main__":
    main(*sys.argv[1:])
