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
* no source hash among the job parameters the report shows for its items, and no parameter dump
  (more than :data:`MAX_PARAMS` characters, or a Python dict);
* at two window widths (:data:`WIDTHS`), nothing of the overview page under the rule graph, its top not
  cut off above the main panel, and no table cut off on the right, there or on any table page: a table
  wider than its column must sit in a box that scrolls sideways;
* at both widths, every figure, opened from its list and then with its caption beside it, drawn whole
  and as large as the window allows: as wide as the smallest of its natural width, the window's width
  less the sidebar's share (:data:`SIDEBAR_SHARE`) and the panel's padding, and the width at which it is
  as tall as the window less :data:`VERTICAL_MARGIN` (:data:`SLACK` px short at most); never wider than
  its natural width, not cut off on either side, its bottom within the window and reachable from its top;
* no docutils system message (an undefined substitution, a malformed caption) in the overview or in any
  item's caption;
* no two items of one category with the same label (the lists would open the same item twice);
* at both widths, every column of every table seen whole: a table that only fits by scrolling sideways
  hides its last columns (the overview's Table 1 in its column, and every table page at the width the
  report gives it);
* at both widths, the smallest text of every figure drawn at least :data:`MIN_TEXT_PX` high: the size
  the figure's PNG states (``rockstudy.plotting.save.SMALLEST_TEXT_KEY``) times the scale it is drawn at.

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

from rockstudy.report import in_paper_words

FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]
VERDICT = {1: "PASS", 0: "FAIL", -1: "n/a"}
WIDTHS = (1280, 1920)
"""Window widths [px] at which the layout is checked (a laptop, a desktop screen)."""
MAX_PARAMS = 400
"""Longest job-parameter text an item may show [characters]: a summary, not a dump."""
NESTED_DICT = re.compile(r"{'[^{}]*{")
"""A Python dict of dicts in the parameters shown: a dump, whatever its length."""
SIDEBAR_SHARE = {"list": 1 / 4, "caption": 1 / 3}
"""Most of the window the sidebar may take beside an open figure: a quarter while it lists the items
(Snakemake's own share for its lists), a third while it shows the item's caption and parameters."""
VERTICAL_MARGIN = 48
"""Height [px] of the window a figure leaves free (3 rem: the panel's margins), so that it is seen whole."""
SLACK = 4
"""How much narrower [px] than the width it could have a figure may be drawn (rounding, borders)."""
MIN_TEXT_PX = 7.0
"""Smallest legible height [CSS px] of a figure's text as drawn (the font size times the drawing scale)."""
SMALLEST_TEXT_KEY = "rockstudy smallest text px"
"""The PNG text chunk that states the figure's smallest text [px] (rockstudy.plotting.save)."""

# Boxes of the page as (what, left, right, top, bottom) in CSS pixels; "cut" lists tables whose right
# edge passes their column's (or the page's) with no box that scrolls sideways between them.
LAYOUT_JS = """() => {
  const box = el => { const r = el.getBoundingClientRect(); return [r.left, r.right, r.top, r.bottom]; };
  const scrolls = el => { for (let a = el.parentElement; a; a = a.parentElement) {
      const s = getComputedStyle(a).overflowX; if (s === 'auto' || s === 'scroll') return a; } return null; };
  const doc = document.querySelector('.document') || document.body;
  const graph = document.querySelector('.vega-embed');
  const column = doc.getBoundingClientRect();
  const edge = Math.min(column.right, document.documentElement.clientWidth);
  const cut = [], under = [], hidden = [];
  for (const t of doc.querySelectorAll('table')) {
    const r = t.getBoundingClientRect(), s = scrolls(t);
    const inner = s && s !== document.documentElement && s !== document.body;
    const right = inner ? s.getBoundingClientRect().right : r.right;
    const label = (t.caption ? t.caption.innerText : t.innerText).slice(0, 60);
    if (right > edge + 1) cut.push([label, Math.round(right), Math.round(edge)]);
    else if (inner && r.right > right + 1) hidden.push([label, Math.round(r.width), Math.round(right - r.left)]);
  }
  if (graph) {
    const g = graph.getBoundingClientRect();
    for (const el of doc.querySelectorAll(':scope > *, .scroll, table, p, ul')) {
      const r = el.getBoundingClientRect(), s = scrolls(el);
      const right = s && doc.contains(s) ? Math.min(r.right, s.getBoundingClientRect().right) : r.right;
      if (r.width > 0 && right > g.left + 1 && r.left < g.right && r.bottom > g.top && r.top < g.bottom)
        under.push([el.tagName + ': ' + el.innerText.slice(0, 50), Math.round(right - g.left)]);
    }
  }
  return {cut: cut, under: under, hidden: hidden};
}"""


# The figure open in the main panel: its natural and drawn size, its panel (the box that scrolls it,
# scrolled to its top first) and the padding around it, in CSS pixels; null while none is loaded.
FIGURE_JS = """() => {
  const img = [...document.querySelectorAll('img')].find(i => i.src.startsWith('data:image/') && !i.closest('nav'));
  if (!img || !img.complete || !img.naturalWidth) return null;
  let panel = img.parentElement;
  while (panel && !['auto', 'scroll'].includes(getComputedStyle(panel).overflowY)) panel = panel.parentElement;
  panel = panel || document.documentElement;
  panel.scrollTop = 0; panel.scrollLeft = 0;
  const r = img.getBoundingClientRect(), p = panel.getBoundingClientRect(), s = getComputedStyle(img.parentElement);
  const page = document.documentElement;
  return {head: img.src.slice(0, 4096), natural: img.naturalWidth, natural_height: img.naturalHeight,
          drawn: r.width, left: r.left,
          right: r.right, top: r.top, bottom: r.bottom, window_height: window.innerHeight,
          panel_left: p.left, panel_right: Math.min(p.right, page.clientWidth), panel_top: p.top,
          sideways: Math.max(panel.scrollWidth - panel.clientWidth, page.scrollWidth - page.clientWidth),
          padding: parseFloat(s.paddingLeft) + parseFloat(s.paddingRight)};
}"""

# An item is shown in the main panel: a loaded image, or a frame (HTML pages, PDF).
SHOWN_JS = """() => [...document.querySelectorAll('img')].some(i => !i.closest('nav') && i.src.startsWith('data:image/')
  && i.complete && i.naturalWidth > 0) || document.querySelector('#app iframe') !== null"""

# How far [px] the overview's top lies above the top of the panel that scrolls it, scrolled to its top.
OVERVIEW_TOP_JS = """() => {
  const doc = document.querySelector('.document');
  if (!doc) return null;
  let panel = doc.parentElement;
  while (panel && !['auto', 'scroll'].includes(getComputedStyle(panel).overflowY)) panel = panel.parentElement;
  panel = panel || document.documentElement;
  panel.scrollTop = 0;
  return panel.getBoundingClientRect().top - doc.getBoundingClientRect().top;
}"""


def open_report(page, url: str):
    page.goto(url)
    page.wait_for_load_state("networkidle")
    page.wait_for_timeout(1000)


def item_width(page) -> int | None:
    """Width [px] of the frame in which the report shows an HTML item at the current window width: the
    first page of the Tables category opened (through its first subcategory, if it has any)."""
    page.get_by_text("Tables", exact=True).first.click()
    page.wait_for_timeout(800)
    eye = page.locator("a[iconname=eye]")
    if not eye.count():  # the category lists subcategories first
        page.locator("div.p-3 li a").first.click()
        page.wait_for_timeout(800)
    if not eye.count():
        return None
    eye.first.click()
    page.wait_for_timeout(1000)
    frame = page.locator("iframe").first
    return round(frame.bounding_box()["width"]) if frame.count() else None


def layout_problems(page, url: str, width: int, tables: list[tuple[str, str]]) -> list[str]:
    """Overlap and clipping at window ``width``: the overview page, then each page of ``tables``
    ((label, data URL) of the report's HTML items) at the width the report gives an open item."""
    problems = []
    page.set_viewport_size({"width": width, "height": 1000})
    open_report(page, url)
    found = page.evaluate(LAYOUT_JS)
    problems += [f"{width} px, overview: {what!r} runs {px} px under the rule graph" for what, px in found["under"]]
    problems += [f"{width} px, overview: table {what!r} is cut off at {right} px (its column ends at {edge} px)"
                 for what, right, edge in found["cut"]]
    problems += [f"{width} px, overview: table {what!r} is {wide} px wide in a {seen} px column: its last columns "
                 "are seen only by scrolling sideways" for what, wide, seen in found["hidden"]]
    above = page.evaluate(OVERVIEW_TOP_JS)
    if above is None:
        problems.append(f"{width} px, overview: no overview page (.document) shown")
    elif above > 1:
        problems.append(f"{width} px, overview: its top {above:.0f} px lie above the main panel and cannot be "
                        "scrolled to")
    page_width = item_width(page)
    if page_width is None:
        return problems + [f"{width} px: no table page opens from the Tables category"]
    viewer = page.context.new_page()
    viewer.set_viewport_size({"width": page_width, "height": 1000})
    for label, data in tables:
        viewer.goto(data)
        found = viewer.evaluate(LAYOUT_JS)
        problems += [f"{width} px, {label!r}: table {what!r} is cut off at {right} px (the page is {edge} px wide)"
                     for what, right, edge in found["cut"]]
        problems += [f"{width} px, {label!r}: table {what!r} is {wide} px wide in a {seen} px page: its last "
                     "columns are seen only by scrolling sideways" for what, wide, seen in found["hidden"]]
    viewer.close()
    print(f"report_check: layout at {width} px: the overview and {len(tables)} pages")
    return problems


def show_list(page, category: str, subcategory: str | None):
    """The sidebar listing the items of ``category`` (of its ``subcategory``, when it has several), by
    the names a reader clicks: in the menu or in the breadcrumbs above an open item."""
    nav = page.locator("#app > div > nav")
    nav.get_by_text(category, exact=True).first.click()
    page.wait_for_timeout(600)
    if subcategory is not None:
        nav.get_by_text(subcategory, exact=True).first.click()
        page.wait_for_timeout(600)


def figure_problems(page, url: str, width: int, categories: dict[str, dict[str, list[str]]],
                    shot: Path | None = None) -> list[str]:
    """How each figure is drawn at window ``width``, opened as a reader opens it: its category (and
    subcategory) in the sidebar, its eye button (the sidebar lists the items), then its information
    button (the sidebar shows its caption and parameters beside it). ``categories``: category ->
    subcategory -> result paths holding at least one figure. ``shot``: where to save a screenshot of the
    widest figure beside the list."""
    problems, drawn, widest = [], {mode: [] for mode in SIDEBAR_SHARE}, 0
    page.set_viewport_size({"width": width, "height": 1000})
    open_report(page, url)
    nav = page.locator("#app > div > nav")
    for category, subcategories in categories.items():
        for subcategory in subcategories:
            show_list(page, category, subcategory if len(subcategories) > 1 else None)
            for k in range(nav.locator("a[iconname=eye]").count()):
                label = nav.locator("tbody tr").nth(k).inner_text().strip()
                nav.locator("a[iconname=eye]").nth(k).click()
                page.wait_for_timeout(600)
                page.wait_for_function(SHOWN_JS, timeout=10_000)
                if page.evaluate(FIGURE_JS) is None:  # an item that is no figure
                    continue
                for mode in SIDEBAR_SHARE:
                    if mode == "caption":
                        nav.locator("a[iconname=information-circle]").nth(k).click()
                        page.wait_for_timeout(600)
                    f = page.evaluate(FIGURE_JS)
                    if shot is not None and mode == "list" and f["natural"] > widest:
                        page.screenshot(path=str(shot))
                        widest = f["natural"]
                    where = f"{width} px, {label[:50]!r} beside the {mode}"
                    could = min(f["natural"], width * (1 - SIDEBAR_SHARE[mode]) - f["padding"],
                                (f["window_height"] - VERTICAL_MARGIN) * f["natural"] / f["natural_height"])
                    drawn[mode].append(round(f["drawn"]))
                    text = smallest_text(f["head"])
                    if text is None:
                        problems.append(f"{where}: the PNG does not state its smallest text ({SMALLEST_TEXT_KEY!r})")
                    elif text * f["drawn"] / f["natural"] < MIN_TEXT_PX:
                        scale = f["drawn"] / f["natural"]
                        problems.append(f"{where}: its smallest text is drawn {text * scale:.1f} px high "
                                        f"({text:.1f} px at {scale:.0%}), below {MIN_TEXT_PX:g} px")
                    if f["drawn"] < could - SLACK:
                        problems.append(f"{where}: drawn {f['drawn']:.0f} px wide, could be {could:.0f} px "
                                        f"(natural {f['natural']} px)")
                    if f["drawn"] > f["natural"] + 1:
                        problems.append(f"{where}: drawn {f['drawn']:.0f} px wide, wider than its natural "
                                        f"{f['natural']} px")
                    if f["left"] < f["panel_left"] - 1 or f["right"] > f["panel_right"] + 1 or f["sideways"] > 1:
                        problems.append(f"{where}: cut off sideways (drawn {f['left']:.0f}-{f['right']:.0f} px in a "
                                        f"panel {f['panel_left']:.0f}-{f['panel_right']:.0f} px, "
                                        f"{f['sideways']:.0f} px to scroll sideways)")
                    if f["bottom"] > f["window_height"] + 1:
                        problems.append(f"{where}: its bottom {f['bottom'] - f['window_height']:.0f} px lie below the "
                                        "window: the figure is not seen whole")
                    if f["top"] < f["panel_top"] - 1:
                        problems.append(f"{where}: its top {f['panel_top'] - f['top']:.0f} px lie above the panel and "
                                        "cannot be scrolled to")
                show_list(page, category, subcategory if len(subcategories) > 1 else None)
    n = len(drawn["list"])
    if n == 0:
        return problems + [f"{width} px: no figure opens from the report's categories"]
    print(f"report_check: figures at {width} px: {n} drawn "
          + ", ".join(f"{min(v)}-{max(v)} px wide beside the {mode}" for mode, v in drawn.items()))
    return problems


def smallest_text(head: str) -> float | None:
    """The smallest text [px] a PNG states (:data:`SMALLEST_TEXT_KEY`), from the start of its data URI."""
    import base64
    import struct
    data = head.split(",", 1)[-1]
    raw = base64.b64decode(data[:len(data) // 4 * 4])
    i = 8
    while i + 8 <= len(raw):
        n, kind = struct.unpack(">I", raw[i:i + 4])[0], raw[i + 4:i + 8]
        if kind == b"IDAT":
            break
        if kind == b"tEXt":
            key, _, value = raw[i + 8:i + 8 + n].partition(b"\0")
            if key.decode("latin-1") == SMALLEST_TEXT_KEY:
                return float(value)
        i += 12 + n
    return None


def caption_problems(page) -> list[str]:
    """Docutils system messages in the overview or a caption, and two items of a category with one label."""
    found = page.evaluate(r"""() => {
      const bad = [], seen = {}, twice = [];
      const overview = document.querySelector('.document');
      if (overview && /System Message|system-message/.test(overview.innerHTML)) bad.push(['the overview', '']);
      for (const [path, r] of Object.entries(results)) {
        const caption = r.caption || '';
        if (/System Message|system-message/.test(caption))
          bad.push([path, caption.replace(/<[^>]*>/g, ' ').replace(/\s+/g, ' ').slice(0, 160)]);
      }
      for (const [category, subs] of Object.entries(categories)) for (const [sub, paths] of Object.entries(subs))
        for (const path of paths) {
          const r = results[path];
          const label = r.labels ? Object.values(r.labels).join(' ') : r.name;
          const key = [category, sub, label].join(' / ');
          if (seen[key]) twice.push([key, seen[key], path]); else seen[key] = path;
        }
      return {bad: bad, twice: twice};
    }""")
    problems = [f"{where}: a docutils system message is shown ({text!r})" for where, text in found["bad"]]
    problems += [f"two items listed as {key!r}: {a} and {b}" for key, a, b in found["twice"]]
    return problems


def number(value: float) -> str | None:
    return None if not math.isfinite(value) else f"{value:+.2f}"


def expected_table1(results: Path) -> dict[str, list[str]]:
    """Row label -> the numbers (ours, paper) the page must show in that row."""
    ds = xr.open_dataset(results / "reproduction" / "table1_vs_paper.nc")
    rows = {}
    for row in ds["row"].values:
        cells = [number(float(ds[name].sel(row=row, noise_level=lv))) for lv in ds["noise_level"].values
                 for name in ("ours", "paper")]
        rows[in_paper_words(str(row))] = [c for c in cells if c is not None]
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
        problems += caption_problems(page)
        shown = page.evaluate("Object.values(results).map(r => [r.name, r.job_properties.params])")
        problems += [f"{name}: the parameters a reader sees show a source hash: {params[:120]!r}"
                     for name, params in shown if re.search(r"[0-9a-f]{40,}", params or "")]
        problems += [f"{name}: the parameters a reader sees are a dump of {len(params)} characters: {params[:120]!r}"
                     for name, params in shown if len(params or "") > MAX_PARAMS or NESTED_DICT.search(params or "")]
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
        tables = page.evaluate("Object.values(results).filter(r => (r.mime_type || r.mime) === 'text/html')"
                               ".map(r => [r.labels ? Object.values(r.labels).join(' ') : r.name, r.data_uri])")
        if not tables:
            problems.append("no HTML page among the report's items: nothing to check for clipping")
        figures = page.evaluate("""() => { const out = {};
            for (const [c, subs] of Object.entries(categories)) for (const [s, paths] of Object.entries(subs))
              if (paths.some(p => (results[p].mime_type || '').startsWith('image/')))
                (out[c] = out[c] || {})[s] = paths;
            return out; }""")
        if not figures:
            problems.append("no figure among the report's items: nothing to check for its width")
        for width in WIDTHS:
            problems += layout_problems(page, Path(args.report).resolve().as_uri(), width, tables)
            if figures:
                shot = Path(args.screenshot).with_name(f"{Path(args.screenshot).stem}-figure-{width}.png") \
                    if args.screenshot else None
                problems += figure_problems(page, Path(args.report).resolve().as_uri(), width, figures, shot)
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
