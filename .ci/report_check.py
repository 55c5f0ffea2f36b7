"""Open the workflow report in headless Chromium and check what a reader sees.

Usage: python .ci/report_check.py REPORT.html RESULTS_DIR [--screenshot PNG]

Fails (exit 1, naming what is missing) unless the rendered page shows, as visible text (the page's
``innerText``, which leaves out scripts, embedded data and hidden elements):
* the overview page with the study's settings;
* every number of Table 1 of this run (``reproduction/table1_vs_paper.nc``: ours and the paper's) in the
  Table 1 beside the paper, each in its row;
* every claim's verdict (``reproduction/claims.nc``: PASS / FAIL / n/a, this run's and the paper's) in its
  row of the claims checklist, and the PASS / FAIL counts;
* the report's items listed by what they show (labels), not by file names: the Reproduction category
  lists "Table 1 of this run beside the paper's" and "Claims of §5 ...";
* no source hash among the job parameters the report shows for its items.

Chromium is Debian's (/usr/bin/chromium) driven by Playwright; a fresh profile folder every run.
"""
from __future__ import annotations

import argparse
import math
import re
import sys
import tempfile
from pathlib import Path

import xarray as xr
from playwright.sync_api import sync_playwright

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]
VERDICT = {1: "PASS", 0: "FAIL", -1: "n/a"}


def number(value: float) -> str | None:
    return None if not math.isfinite(value) else f"{value:+.2f}"


def expected_table1(results: Path) -> dict[str, list[str]]:
    """Row label -> the numbers (ours, paper) the page must show in that row."""
    ds = xr.open_dataset(results / "reproduction" / "table1_vs_paper.nc")
    rows = {}
    for row in ds["row"].values:
        cells = [number(float(ds[name].sel(row=row, noise_level=lv))) for lv in ds["noise_level"].values
                 for name in ("ours", "paper")]
        rows[str(row)] = [c for c in cells if c is not None]
    n_ours = int(ds["ours"].notnull().sum())
    if n_ours == 0:
        sys.exit("report_check: table1_vs_paper.nc has no number of this run: nothing to look for")
    return rows


def expected_claims(results: Path) -> list[tuple[str, str, str]]:
    """(statement, this run's verdict, the paper's) per claim."""
    ds = xr.open_dataset(results / "reproduction" / "claims.nc")
    return [(str(ds["statement"].sel(claim=c).item()), VERDICT[int(ds["passed"].sel(claim=c))],
             VERDICT[int(ds["paper_passed"].sel(claim=c))]) for c in ds["claim"].values]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("report")
    parser.add_argument("results")
    parser.add_argument("--screenshot")
    parser.add_argument("--chromium", default="/usr/bin/chromium")
    args = parser.parse_args()
    results = Path(args.results)
    table1, claims = expected_table1(results), expected_claims(results)
    problems = []
    with sync_playwright() as p, tempfile.TemporaryDirectory(prefix="report-check-profile-") as profile:
        browser = p.chromium.launch_persistent_context(profile, executable_path=args.chromium, args=FLAGS,
                                                       headless=True, viewport={"width": 1400, "height": 1000})
        page = browser.new_page()
        page.goto(Path(args.report).resolve().as_uri())
        page.wait_for_load_state("networkidle")
        page.get_by_text("Table 1: J_OS (Eq. 21) of this run", exact=False).first.wait_for(state="visible",
                                                                                            timeout=30_000)
        text = page.inner_text("body")
        seed = xr.open_dataset(results / "tables" / "table1.nc").attrs["noise_seed"]
        for phrase in ("What was computed", "With which settings", "Headline results", f"seed {seed}"):
            if phrase not in text:
                problems.append(f"overview: {phrase!r} is not visible")
        t1 = page.locator("table", has=page.locator("caption", has_text="Table 1: J_OS (Eq. 21) of this run")).first
        if not t1.is_visible():
            problems.append("Table 1 beside the paper is not visible")
        for row, numbers in table1.items():
            cells = t1.locator("tr", has=page.locator("th", has_text=row)).first.inner_text()
            problems += [f"Table 1, row {row!r}: {n} not visible (row reads {cells!r})" for n in numbers
                         if n not in cells]
        cl = page.locator("table", has=page.locator("caption", has_text="The paper's claims on this run")).first
        if not cl.is_visible():
            problems.append("the claims checklist is not visible")
        rows = cl.locator("tbody tr")
        if rows.count() != len(claims):
            problems.append(f"claims: {rows.count()} rows visible, {len(claims)} claims in claims.nc")
        for i, (statement, ours, paper) in enumerate(claims):
            if i >= rows.count():
                break
            cells = [c.strip() for c in rows.nth(i).inner_text().split("\t")]
            if statement[:40] not in cells[2] or not cells[3].endswith(ours) or not cells[4].endswith(paper):
                problems.append(f"claim {i + 1}: expected {ours} / {paper} for {statement[:50]!r}, row reads {cells}")
        counts = {w: sum(1 for _, o, _ in claims if o == w) for w in ("PASS", "FAIL")}
        if f"{counts['PASS']} PASS, {counts['FAIL']} FAIL" not in text:
            problems.append(f"claims: the count '{counts['PASS']} PASS, {counts['FAIL']} FAIL' is not visible")
        shown = page.evaluate("Object.values(results).map(r => [r.name, r.job_properties.params])")
        problems += [f"{name}: the parameters a reader sees show a source hash: {params[:120]!r}"
                     for name, params in shown if re.search(r"[0-9a-f]{40,}", params or "")]
        if args.screenshot:  # the landing page from its top (the report scrolls inside its main panel)
            page.evaluate("document.querySelectorAll('*').forEach(el => { el.scrollTop = 0; })")
            page.set_viewport_size({"width": 1400, "height": 2400})
            page.screenshot(path=args.screenshot)
            page.set_viewport_size({"width": 1400, "height": 1000})
        page.get_by_text("Reproduction", exact=True).first.click()
        page.wait_for_timeout(1000)
        subcategory = page.get_by_text("Claims and Table 1", exact=True)
        if subcategory.count():  # shown when the category has more than one subcategory
            subcategory.first.click()
            page.wait_for_timeout(1000)
        listing = page.inner_text("body")
        for label in ("Table 1 of this run beside the paper's", "Claims of §5 and the Conclusions"):
            if label not in listing:
                problems.append(f"Reproduction category: the item {label!r} is not listed by its label")
        if args.screenshot:
            page.screenshot(path=str(Path(args.screenshot).with_name(Path(args.screenshot).stem + "-reproduction.png")))
        browser.close()
    if problems:
        print("report_check: FAILED\n  " + "\n  ".join(problems))
        return 1
    n = sum(len(v) for v in table1.values())
    print(f"report_check: OK - Table 1 ({n} numbers in {len(table1)} rows) and {len(claims)} claim verdicts "
          f"({counts['PASS']} PASS, {counts['FAIL']} FAIL) visible in {args.report}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
