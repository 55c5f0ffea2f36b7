"""The fragility medians the docs quote are the run's: every cell of the medians tables in
docs/records-and-design.md and docs/reproduction.md against docs/figures/run_numbers.csv, which
`snakemake -j2 docs` writes from the run's fragility files (with the README's pictures)."""
import csv
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NUMBERS = ROOT / "docs" / "figures" / "run_numbers.csv"
ROWS = {"far field": "p695-far-field", "near field, pulse": "p695-near-field-pulse",
        "near-field pulse": "p695-near-field-pulse"}
CELL = re.compile(r"^(\d\.\d{3}) \((\d\.\d{3})–(\d\.\d{3})\)(?:, ([+-]\d+) %)?$")


def run_numbers() -> dict:
    return {(r["suite"], r["strategy"]): r for r in csv.DictReader(NUMBERS.open(encoding="utf-8"))}


def quoted_tables(path: Path):
    """(suite, strategy, cell text) of every row of a medians table (header | suite | FS | ... |)."""
    strategies = None
    for line in path.read_text(encoding="utf-8").splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")] if line.startswith("|") else None
        if cells is None:
            strategies = None
        elif cells[0] == "suite" and "FS" in cells:
            strategies = cells[1:]
        elif strategies and not set(cells[0]) <= {"-"}:
            name = re.sub(r"\s*\(\d+\)$", "", cells[0])
            yield from ((ROWS[name], s, c) for s, c in zip(strategies, cells[1:]))


def check(quoted, numbers) -> list[str]:
    wrong = []
    for suite, strategy, text in quoted:
        r = numbers[(suite, strategy)]
        m = CELL.match(text)
        if m is None:
            wrong.append(f"{suite} {strategy}: {text!r} is not 'median (low–high)[, shift %]'")
            continue
        expect = [f"{float(r[k]):.3f}" for k in ("median_physical", "median_physical_low", "median_physical_high")]
        shift = round(float(r["median_shift_percent"]))
        if list(m.groups()[:3]) != expect or (m[4] is not None and int(m[4]) != shift):
            wrong.append(f"{suite} {strategy}: the docs say {text!r}, the run {expect} "
                         f"({float(r['median_shift_percent']):+.0f} %)")
    return wrong


@pytest.mark.parametrize("page", ["records-and-design.md", "reproduction.md"])
def test_quoted_fragility_medians_are_the_runs(page):
    quoted = list(quoted_tables(ROOT / "docs" / page))
    assert len(quoted) >= 8, f"docs/{page}: the fragility medians table is gone"
    assert check(quoted, run_numbers()) == []


def test_a_stale_median_is_caught():
    numbers = run_numbers()
    fs = numbers[("p695-far-field", "FS")]
    stale = f"{float(fs['median_physical']) + 0.001:.3f} (0.000–9.000)"
    assert len(check([("p695-far-field", "FS", stale)], numbers)) == 1


def test_the_readme_picture_is_made_by_the_docs_rule():
    rule = (ROOT / "workflow" / "rules" / "docs.smk").read_text()
    for picture in re.findall(r"\]\((docs/figures/[^)]+\.png)\)", (ROOT / "README.md").read_text()):
        assert Path(picture).name in rule and (ROOT / picture).is_file()
