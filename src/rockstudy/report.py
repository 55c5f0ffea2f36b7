"""HTML pages of the study's tables for the workflow report (the front door of the tables, as
:mod:`rockstudy.plotting` is of the figures).

The tables are written as netCDF, CSV and Markdown; a Snakemake report shows an HTML result in the
page, a CSV only as a download. These functions turn a table's Markdown (or the claims and Table 1
comparison datasets) into small self-contained HTML pages, and make the fragment of the report's
overview page that states the headline results: Table 1 beside the paper and the claims checklist.

Verdicts keep their words (PASS, FAIL, n/a) and add a marker and a colour from a colour-blind-safe
pair (blue and orange), so that nothing is read from colour alone.
"""
from __future__ import annotations

import html
import math
import re
from typing import TYPE_CHECKING

import numpy as np

from rockstudy._version import __version__
from rockstudy.analysis.fragility_fit import ALWAYS_OVERTURNS, NEVER_OVERTURNS

if TYPE_CHECKING:
    import xarray as xr

STYLE = """
body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; margin: 1.2em; color: #1a1a1a;
       line-height: 1.45; max-width: 75em; }
table { border-collapse: collapse; margin: 0.8em 0; font-size: 0.92em; }
th, td { border: 1px solid #c8c8c8; padding: 0.25em 0.6em; text-align: left; vertical-align: top; }
th { background: #eef2f7; }
td.num, th.num { text-align: right; font-variant-numeric: tabular-nums; }
.pass { color: #0b5394; font-weight: 600; }
.fail { color: #b45309; font-weight: 600; }
.na { color: #595959; }
caption { caption-side: top; text-align: left; font-weight: 600; padding-bottom: 0.3em; }
div.scroll { overflow-x: auto; max-width: 100%; }
"""
"""CSS of the pages: plain tables, right-aligned numbers, blue PASS and orange FAIL (Okabe–Ito-like hues);
a table wider than the page scrolls inside its own box (:func:`scrolling`) instead of being cut off."""

VERDICT_CLASS = {"PASS": "pass", "FAIL": "fail", "n/a": "na"}
VERDICT_MARK = {"PASS": "✓ PASS", "FAIL": "✗ FAIL", "n/a": "n/a"}


def verdict_html(word: str) -> str:
    """A verdict (PASS, FAIL or n/a) as marked, coloured text.

    Parameters
    ----------
    word : str
        ``"PASS"``, ``"FAIL"`` or ``"n/a"``; another word is shown as it is, in the n/a style.
    """
    return f'<span class="{VERDICT_CLASS.get(word, "na")}">{html.escape(VERDICT_MARK.get(word, word))}</span>'


def scrolling(fragment: str, style: str = "") -> str:
    """``fragment`` with every table wrapped in a box that scrolls sideways when the table is wider
    than the column it sits in.

    Parameters
    ----------
    fragment : str
        An HTML fragment.
    style : str, default ""
        Inline style of the boxes, for a page where no style sheet applies; empty: the ``scroll`` class
        of :data:`STYLE`.
    """
    box = f'<div class="scroll" style="{style}">' if style else '<div class="scroll">'
    return re.sub(r"<table\b", lambda m: box + m[0], fragment).replace("</table>", "</table></div>")


def document(title: str, body: str) -> str:
    """A complete HTML page: ``title`` as its title and first heading, ``body`` (HTML) below, its
    tables in boxes that scroll sideways (:func:`scrolling`).

    Parameters
    ----------
    title : str
        The page's title and first heading (escaped).
    body : str
        The page's content, HTML.
    """
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<title>{html.escape(title)}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n"
            f"{scrolling(body)}\n</body>\n</html>\n")


def markdown_html(text: str) -> str:
    """Markdown (CommonMark with pipe tables) as an HTML fragment; verdicts marked as in :func:`verdict_html`.

    Parameters
    ----------
    text : str
        The Markdown; raw HTML in it is escaped.
    """
    from markdown_it import MarkdownIt

    out = MarkdownIt("commonmark", {"html": False}).enable("table").render(text)
    for word in ("PASS", "FAIL"):
        out = out.replace(f"<strong>{word}</strong>", f"<strong>{verdict_html(word)}</strong>")
    return out


WIDE_TABLE_COLUMNS = 8
"""A Markdown table with more columns than this is shown transposed on its HTML page (its columns as rows):
a report page beside the sidebar shows about 900 px, too few for a dozen labelled columns side by side."""


def transposed_wide_tables(text: str, max_columns: int = WIDE_TABLE_COLUMNS) -> str:
    """``text`` with every pipe table of more than ``max_columns`` columns transposed (its first header cell
    stays in the corner, marked "→": its values now run across); other lines as they are.

    Parameters
    ----------
    text : str
        Markdown.
    max_columns : int, default :data:`WIDE_TABLE_COLUMNS`
        The widest table kept as it is.
    """
    def cells(line):
        return [c.strip() for c in line.strip().strip("|").split("|")]

    lines, out, i = text.splitlines(), [], 0
    while i < len(lines):
        is_table = (lines[i].lstrip().startswith("|") and i + 1 < len(lines)
                    and re.fullmatch(r"\s*\|?(\s*:?-+:?\s*\|)+\s*:?-*:?\s*\|?\s*", lines[i + 1]))
        if not is_table:
            out.append(lines[i])
            i += 1
            continue
        j = i + 2
        while j < len(lines) and lines[j].lstrip().startswith("|"):
            j += 1
        rows = [cells(lines[i])] + [cells(line) for line in lines[i + 2:j]]
        if len(rows[0]) > max_columns and all(len(r) == len(rows[0]) for r in rows):
            columns = list(zip(*rows))
            out.append("| " + " | ".join((f"{columns[0][0]} →",) + columns[0][1:]) + " |")
            out.append("|---" * len(columns[0]) + "|")
            out += ["| " + " | ".join(column) + " |" for column in columns[1:]]
        else:
            out += lines[i:j]
        i = j
    return "\n".join(out) + ("\n" if text.endswith("\n") else "")


def markdown_page(text: str, title: str | None = None) -> str:
    """A Markdown table file (``tables/*.md``, ``claims.md``, ...) as a complete HTML page; a table of more
    than :data:`WIDE_TABLE_COLUMNS` columns is shown transposed (:func:`transposed_wide_tables`).

    Parameters
    ----------
    text : str
        The Markdown.
    title : str, optional
        Page title; default: the first line of ``text`` without its ``#`` marks.
    """
    first = next((line for line in text.splitlines() if line.strip()), "rockstudy table")
    return document(title or first.lstrip("# ").strip(), markdown_html(in_paper_words(transposed_wide_tables(text))))


def _number(value: float, signed: bool = True) -> str:
    if value is None or not math.isfinite(float(value)):
        return "–"
    return f"{float(value):+.2f}" if signed else f"{float(value):.2f}"


def table1_beside_paper_html(comparison: xr.Dataset) -> str:
    """Table 1 of this run beside the paper's: one row per (strategy, reference), per noise level
    the paper's J_OS, ours and the difference (ours − paper), in %.

    Parameters
    ----------
    comparison : xarray.Dataset
        ``reproduction/table1_vs_paper.nc``: ``paper``, ``ours``, ``difference`` over (row, noise_level).
    """
    levels = [str(v) for v in comparison["noise_level"].values]
    head = "".join(f'<th class="num" colspan="3">{html.escape(lv)}</th>' for lv in levels)
    sub = "".join('<th class="num">paper</th><th class="num">ours</th><th class="num">diff</th>' for _ in levels)
    rows = []
    for row in comparison["row"].values:
        cells = []
        for lv in levels:
            point = comparison.sel(row=row, noise_level=lv)
            cells += [f'<td class="num">{_number(point[name].item())}</td>' for name in ("paper", "ours", "difference")]
        rows.append(f"<tr><th>{html.escape(in_paper_words(str(row)))}</th>{''.join(cells)}</tr>")
    return ('<table class="table1">\n<caption>Table 1: J_OS (Eq. 21) of this run beside the paper [%]; '
            "diff = ours − paper; – where the run has no such noise level</caption>\n"
            f'<thead><tr><th rowspan="2">strategy vs reference</th>{head}</tr><tr>{sub}</tr></thead>\n'
            f"<tbody>\n{chr(10).join(rows)}\n</tbody>\n</table>")


VERDICT_OF_FLAG = {1: "PASS", 0: "FAIL", -1: "n/a"}
"""The claims dataset's flag values (``passed``, ``paper_passed``) as words."""


def claims_summary(claims: xr.Dataset) -> dict:
    """Counts of PASS, FAIL and n/a of this run's verdicts.

    Parameters
    ----------
    claims : xarray.Dataset
        ``reproduction/claims.nc`` (:func:`rockstudy.studies.claims.claims_dataset`): ``passed`` over ``claim``.
    """
    flags = np.asarray(claims["passed"].values, dtype=int)
    return {word: int(np.count_nonzero(flags == flag)) for flag, word in VERDICT_OF_FLAG.items()}


def claims_html(claims: xr.Dataset) -> str:
    """The claims checklist: section, statement, this run's verdict, the same check on the paper's
    own Table 1, and the numbers behind the verdict.

    Parameters
    ----------
    claims : xarray.Dataset
        ``reproduction/claims.nc``: ``passed`` and ``paper_passed`` (1 pass, 0 fail, −1 not
        evaluated), ``section``, ``statement``, ``evidence`` over ``claim``.
    """
    counts = claims_summary(claims)
    rows = []
    for i, name in enumerate(claims["claim"].values, start=1):
        c = claims.sel(claim=name)
        ours = VERDICT_OF_FLAG[int(c["passed"].item())]
        paper = VERDICT_OF_FLAG[int(c["paper_passed"].item())]
        rows.append(f"<tr><td class=\"num\">{i}</td><td>{html.escape(str(c['section'].item()))}</td>"
                    f"<td>{html.escape(str(c['statement'].item()))}</td><td>{verdict_html(ours)}</td>"
                    f"<td>{verdict_html(paper)}</td><td>{html.escape(str(c['evidence'].item()))}</td></tr>")
    summary = (f"{counts['PASS']} PASS, {counts['FAIL']} FAIL, {counts['n/a']} not evaluated "
               "(paper: the same check on the paper's own Table 1, where it applies)")
    return ('<table class="claims">\n'
            f"<caption>Claims of §5 and the Conclusions checked on this run: {html.escape(summary)}</caption>\n"
            "<thead><tr><th>#</th><th>§</th><th>claim</th><th>this run</th><th>paper's numbers</th>"
            "<th>evidence</th></tr></thead>\n"
            f"<tbody>\n{chr(10).join(rows)}\n</tbody>\n</table>")


INLINE = {"table": "border-collapse: collapse; margin: 0.6em 0 1.2em 0; font-size: 0.9em;",
          "cell": "border: 1px solid #c8c8c8; padding: 0.2em 0.5em; text-align: left; vertical-align: top;",
          "num": "border: 1px solid #c8c8c8; padding: 0.2em 0.5em; text-align: right; white-space: nowrap;",
          "caption": "caption-side: top; text-align: left; font-weight: 600; padding-bottom: 0.3em;",
          "pass": "color: #0b5394; font-weight: 600;", "fail": "color: #b45309; font-weight: 600;",
          "na": "color: #595959;", "scroll": "overflow-x: auto; max-width: 100%;"}
"""Inline styles of the overview fragment: it sits inside the Snakemake report's page, whose style sheet
would otherwise strip the tables of borders and the verdicts of their colour."""


def _styled(text: str) -> str:
    for name in ("table", "caption", "pass", "fail", "na"):
        text = text.replace(f'<{name}>', f'<{name} style="{INLINE[name]}">').replace(
            f'class="{name}"', f'class="{name}" style="{INLINE[name]}"')
    text = text.replace('<td class="num">', f'<td class="num" style="{INLINE["num"]}">')
    text = text.replace("<th>", f'<th style="{INLINE["cell"]}">').replace("<td>", f'<td style="{INLINE["cell"]}">')
    text = text.replace('<th class="num"', f'<th style="{INLINE["num"]}" class="num"')
    return text


def table1_compact_html(comparison: xr.Dataset) -> str:
    """Table 1 of this run beside the paper's in one cell per noise level: "ours (paper)" J_OS in %.

    Parameters
    ----------
    comparison : xarray.Dataset
        ``reproduction/table1_vs_paper.nc``: ``paper`` and ``ours`` over (row, noise_level).
    """
    levels = [str(v) for v in comparison["noise_level"].values]
    head = "".join(f'<th class="num">{html.escape(lv)}: ours (paper)</th>' for lv in levels)
    rows = []
    for row in comparison["row"].values:
        cells = "".join(
            f'<td class="num">{_number(comparison.sel(row=row, noise_level=lv)["ours"].item())} '
            f'({_number(comparison.sel(row=row, noise_level=lv)["paper"].item())})</td>' for lv in levels)
        rows.append(f"<tr><th>{html.escape(in_paper_words(str(row)))}</th>{cells}</tr>")
    return ("<table>\n<caption>Table 1: J_OS (Eq. 21) of this run and, in brackets, the paper's [%]</caption>\n"
            f"<thead><tr><th>strategy vs reference</th>{head}</tr></thead>\n<tbody>\n{chr(10).join(rows)}\n"
            "</tbody>\n</table>")


def claims_compact_html(claims: xr.Dataset) -> str:
    """The claims checklist without the evidence column: claim, this run's verdict, the paper's.

    Parameters
    ----------
    claims : xarray.Dataset
        ``reproduction/claims.nc``: ``passed``, ``paper_passed``, ``section`` and ``statement`` over ``claim``.
    """
    counts = claims_summary(claims)
    rows = []
    for i, name in enumerate(claims["claim"].values, start=1):
        c = claims.sel(claim=name)
        rows.append(f'<tr><td class="num">{i}</td><td>{html.escape(str(c["section"].item()))}</td>'
                    f'<td>{html.escape(str(c["statement"].item()))}</td>'
                    f'<td>{verdict_html(VERDICT_OF_FLAG[int(c["passed"].item())])}</td>'
                    f'<td>{verdict_html(VERDICT_OF_FLAG[int(c["paper_passed"].item())])}</td></tr>')
    return ("<table>\n<caption>The paper's claims on this run: "
            f"{counts['PASS']} PASS, {counts['FAIL']} FAIL, {counts['n/a']} not evaluated</caption>\n"
            "<thead><tr><th>#</th><th>§</th><th>claim</th><th>this run</th><th>on the paper's own Table 1</th></tr>"
            f"</thead>\n<tbody>\n{chr(10).join(rows)}\n</tbody>\n</table>")


def overview_html(comparison: xr.Dataset, claims: xr.Dataset) -> str:
    """The headline results for the report's overview page: Table 1 beside the paper, then the claims
    (compact forms of :func:`table1_beside_paper_html` and :func:`claims_html`, styled inline).

    Parameters
    ----------
    comparison : xarray.Dataset
        ``reproduction/table1_vs_paper.nc`` (:func:`rockstudy.studies.claims.table1_comparison`).
    claims : xarray.Dataset
        ``reproduction/claims.nc`` (:func:`rockstudy.studies.claims.claims_dataset`).
    """
    return scrolling(_styled(table1_compact_html(comparison) + "\n" + claims_compact_html(claims)),
                     style=INLINE["scroll"])



def beyond_overview_html(fragility: list, risk: list = ()) -> str:
    """The headline of the studies beyond the paper for the report's overview page: per record set, the
    fragility median of every strategy as PGA [g] and its shift over the free-standing block; with a
    risk study, the probability of overturning of every strategy at each site.

    Parameters
    ----------
    fragility : list of xarray.Dataset
        ``fragility/<record set>.nc`` of the run (``fragility_median_physical`` [g] and
        ``median_shift_percent`` over ``strategy``); empty when the run has no fragility study.
    risk : list of xarray.Dataset
        ``risk/<record set>.nc`` of the run (:func:`rockstudy.analysis.risk.risk_dataset`); empty when
        the run has no risk study.
    """
    if not fragility:
        return "<!-- this run has no study beyond the paper in its default target -->\n"
    strategies = list(dict.fromkeys(str(s) for ds in fragility for s in ds["strategy"].values))
    head = "".join(f'<th class="num">{html.escape(s)}</th>' for s in strategies)
    rows = []
    for ds in fragility:
        cells = []
        for s in strategies:
            if s not in ds["strategy"].values:
                cells.append('<td class="num">–</td>')
                continue
            median = float(ds["fragility_median_physical"].sel(strategy=s))
            shift = float(ds["median_shift_percent"].sel(strategy=s))
            text = f"{median:.3f} g" + ("" if s == "FS" or not math.isfinite(shift) else f" ({shift:+.0f} %)")
            if not math.isfinite(median):
                status = str(ds["fit_status"].sel(strategy=s).values) if "fit_status" in ds else ""
                text = NO_FIT_WORDS.get(status, f"no median ({status})" if status else "no median")
            cells.append(f'<td class="num">{html.escape(text)}</td>')
        name = f"{ds.attrs.get('record_suite', '')} ({int(ds.attrs.get('n_records', 0))} records)"
        rows.append(f"<tr><th>{html.escape(name)}</th>{''.join(cells)}</tr>")
    table = ("<table>\n<caption>Fragility: the median PGA that overturns the block, each strategy "
             "(in brackets, the shift over FS)</caption>\n"
             f"<thead><tr><th>record set</th>{head}</tr></thead>\n<tbody>\n{chr(10).join(rows)}\n</tbody>\n</table>")
    return scrolling(_styled(table), style=INLINE["scroll"]) + "".join(_risk_overview(ds) for ds in risk)


def change_over_fs(reduction_percent: float, reference: bool = False) -> str:
    """The change of a probability (or rate) over FS's, as every page of the report writes it: signed, a drop
    negative ("−51 %", a typographic minus), a rise positive ("+3 %"); "—" on FS's own row.

    Parameters
    ----------
    reduction_percent : float
        100 (1 − p / p_FS): the risk's ``reduction_percent`` and ``scenario_reduction_percent``. [%]
    reference : bool, default False
        The row is FS itself.
    """
    if reference or not math.isfinite(reduction_percent):
        return "—"
    change = -reduction_percent
    return "0 %" if round(change) == 0 else f"{'+' if change > 0 else '−'}{abs(change):.0f} %"


def _risk_overview(ds) -> str:
    """One record set's risk for the overview: per site (scenario or hazard curve) and strategy, the
    probability of overturning, and in brackets its change over FS (:func:`change_over_fs`)."""
    strategies = [str(s) for s in ds["strategy"].values]
    rows = []
    sites = [("scenario", "scenario_probability", "scenario_reduction_percent", "P(overturn | {})"),
             ("hazard", "probability", "reduction_percent", "P(overturn in {years:g} years), {}")]
    for dim, prob, reduction, label in sites:
        for j, name in enumerate(ds[dim].values if dim in ds.coords else []):
            cells = []
            for i, s in enumerate(strategies):
                p, r = float(ds[prob].values[i, j]), float(ds[reduction].values[i, j])
                text = f"{p:.2%}" + ("" if s == "FS" or not math.isfinite(r) else f" ({change_over_fs(r)})")
                if not math.isfinite(p):
                    status = _fit_status(ds, i)
                    text = NO_FIT_WORDS.get(status, f"no median ({status})" if status else "no median")
                cells.append(f'<td class="num">{html.escape(text)}</td>')
            title = label.format(name, years=float(ds.attrs.get("years", 50.0)))
            rows.append(f"<tr><th>{html.escape(title)}</th>{''.join(cells)}</tr>")
    if not rows:
        return ""
    head = "".join(f'<th class="num">{html.escape(s)}</th>' for s in strategies)
    table = (f"<table>\n<caption>Risk on {html.escape(str(ds.attrs.get('record_suite', '')))}: the probability of "
             "overturning of each strategy (in brackets, the change over FS), from the stripes' fragility</caption>\n"
             f"<thead><tr><th>site</th>{head}</tr></thead>\n<tbody>\n{chr(10).join(rows)}\n</tbody>\n</table>")
    return scrolling(_styled(table), style=INLINE["scroll"])



RUN_NUMBERS = {"median": "fragility_median", "median_physical": "fragility_median_physical",
               "median_physical_low": "median_low_physical", "median_physical_high": "median_high_physical",
               "dispersion": "fragility_dispersion", "median_shift_percent": "median_shift_percent"}
"""Columns of ``docs/figures/run_numbers.csv`` (the fragility numbers the docs quote) and the variables
of a fragility dataset they come from."""


def run_numbers_csv(fragility: list) -> str:
    """The fragility numbers the docs quote, one row per (record set, strategy), at full precision,
    from the run's ``fragility/<record set>.nc`` datasets.

    Parameters
    ----------
    fragility : list of xarray.Dataset
        ``fragility/<record set>.nc`` of the run, each with the variables of :data:`RUN_NUMBERS` over
        ``strategy``.
    """
    lines = [",".join(["suite", "strategy", "n_records", *RUN_NUMBERS])]
    for ds in fragility:
        for s in ds["strategy"].values:
            values = [repr(float(ds[var].sel(strategy=s))) for var in RUN_NUMBERS.values()]
            lines.append(",".join([str(ds.attrs["record_suite"]), str(s), str(int(ds.attrs["n_records"])), *values]))
    return "\n".join(lines) + "\n"

class SourceFingerprint(tuple):
    """A source fingerprint as a workflow parameter: compared by its hash, shown by what it covers.

    Snakemake reruns a job when the ``repr`` of a parameter changes, and its report lists the
    parameters formatted (``f"{name}={value}"``). So ``repr`` and ``str`` are the plain hash string's
    (results recorded with the bare hash stay valid, and a script that stores the parameter in a
    dataset stores the hash), while formatting says which sources the result depends on instead of 64
    hex digits. A one-element tuple rather than a ``str``: Snakemake formats string parameters with the
    rule's wildcards, which would turn the value back into a plain string.

    Parameters
    ----------
    digest : str
        The fingerprint (:func:`rockstudy.studies.fingerprints.source_fingerprint`).
    covers : str
        What it covers, e.g. ``"core, model, engine, analysis"``.
    """

    covers: str

    def __new__(cls, digest: str, covers: str):
        obj = super().__new__(cls, (str(digest),))
        obj.covers = covers
        return obj

    @property
    def digest(self) -> str:
        """The SHA-256 hex digest."""
        return self[0]

    @property
    def description(self) -> str:
        """What the report shows: the package version and the sources covered."""
        return f"rockstudy {__version__} sources: {self.covers}"

    def __repr__(self) -> str:
        return repr(self[0])

    def __str__(self) -> str:
        return self[0]

    def __format__(self, spec: str) -> str:
        return format(self.description, spec)

    def __reduce__(self):
        return (SourceFingerprint, (self[0], self.covers))



REFERENCE_WORDS = {"no_noise": "no noise", "fs_same_noise": "FS at the same noise",
                   "continuous_same_noise": "continuous control", "sampled_without_delay_same_noise": "no delay"}
"""The references of J_OS (the code's keys) in the paper's words: Table 1's, and those of the timing
tables (§5.2), always at the same noise level."""

SWEEP_WORDS = {"J_OS against sampling_time": "J_OS against the sampling time T_s [s]",
               "J_OS against delay": "J_OS against the actuation delay Δτ [s]"}
"""The timing tables' titles in words."""


def in_paper_words(text: str) -> str:
    """Table headers and row names with the references of Table 1 in words: ``"no_noise: R005"``
    becomes ``"R005: J_OS vs. no noise"`` (the same strategy without noise) and ``"CS01 vs
    fs_same_noise"`` becomes ``"CS01 vs. FS at the same noise"``.

    Parameters
    ----------
    text : str
        Markdown or a row name of a J_OS table.
    """
    for code, words in SWEEP_WORDS.items():
        text = text.replace(code, words)
    keys = "|".join(sorted(REFERENCE_WORDS, key=len, reverse=True))
    text = re.sub(rf"\b({keys}): ([\w.%-]+)", lambda m: f"{m[2]}: J_OS vs. {REFERENCE_WORDS[m[1]]}", text)
    return re.sub(rf"\bvs\.? ({keys})\b", lambda m: f"vs. {REFERENCE_WORDS[m[1]]}", text)


def settings_text(settings) -> str:
    """A mapping of settings as plain words (``"step 0.0025, rescale energy, band none"``), for a
    page or a table's header; anything else as ``str``.

    Parameters
    ----------
    settings : dict or object
        Setting name -> value (None is shown as "none"); anything else is shown with ``str``.
    """
    if not isinstance(settings, dict):
        return str(settings)
    return ", ".join(f"{key.replace('_', ' ')} {'none' if value is None else value}" for key, value in settings.items())


class ExpectedAttributes(dict):
    """The ``expect`` parameter of a rule (each netCDF input's path -> the attributes it must carry)
    as the report shows it: which inputs are checked, not every attribute.

    A ``dict`` in every other way: ``repr`` (what Snakemake compares to decide a rerun) and what a
    script reads are the plain dictionary's, while formatting (``f"{name}={value}"``, how the report
    lists a job's parameters) gives :attr:`description`, a line instead of thousands of characters.
    """

    @property
    def description(self) -> str:
        """The checked inputs by file name (folder and name), at most three of them named."""
        names = ["/".join(str(path).replace("\\", "/").split("/")[-2:]) for path in self]
        shown = ", ".join(names[:3]) + (f" and {len(names) - 3} more" if len(names) > 3 else "")
        return f"attributes of {shown or 'no input'} checked against this job's settings"

    def __format__(self, spec: str) -> str:
        return format(self.description, spec)

    def __reduce__(self):
        return (ExpectedAttributes, (dict(self),))


def labels(result: str, paper: str = "") -> dict:
    """What a report item shows, for Snakemake's ``report(..., labels=...)``: the report then lists its
    items by this text instead of by file name.

    One label only: the report turns a second label with two values, each on half of a category's
    items, into a toggle between them, which would hide one of two different tables.

    Parameters
    ----------
    result : str
        What the item shows (may contain the rule's ``{wildcards}``).
    paper : str
        Where it is in the paper ("Fig. 6", "Table 1"); empty: beyond the paper.
    """
    return {"result": f"{result} ({paper or 'beyond the paper'})"}


# --- the fragility tables (Markdown) ---------------------------------------------------------------
def fragility_markdown(ds: xr.Dataset) -> str:
    """Markdown table of the fits: median (95 % interval), dispersion, median shift over FS (interval).

    Parameters
    ----------
    ds : xarray.Dataset
        A fragility dataset (``fragility/<record set>.nc``,
        :func:`rockstudy.analysis.fragility.suite_fragility_dataset`).
    """
    im = ds.attrs["intensity_measure_definition"]
    lines = [f"| strategy | median θ of {im} (95 % CI) | dispersion β (± se) | θ/θ_FS (bootstrap 95 % CI) "
             f"| median shift over FS | fit |", "|---|---|---|---|---|---|"]
    for s in ds.strategy.values:
        d = ds.sel(strategy=s)
        lines.append(f"| {s} | {float(d.fragility_median):.3f} ({float(d.median_low):.3f}–{float(d.median_high):.3f}) "
                     f"| {float(d.fragility_dispersion):.3f} ± {float(d.dispersion_se):.3f} "
                     f"| {float(d.median_ratio):.3f} ({float(d.median_ratio_low):.3f}–{float(d.median_ratio_high):.3f})"
                     f" | {float(d.median_shift_percent):+.1f} % | {str(d.fit_status.values)} |")
    lines.append("")
    lines.append(f"{ds.attrs['n_records']} records, {ds.sizes['intensity']} IM levels "
                 f"({float(ds.intensity.min()):g}–{float(ds.intensity.max()):g}); "
                 f"{ds.attrs['n_bootstrap']} bootstrap draws over records.")
    return "\n".join(lines + _two_fits(ds)) + "\n"


def _two_fits(ds: xr.Dataset) -> list:
    """The two lognormal fits of one object in PGA [g], side by side: the stripes' fit (P(overturn) at each
    level, the table above, which the risk uses) and the fit of the records' thresholds (their first
    overturning); empty for a fragility without per-record thresholds in PGA."""
    if not {"threshold_pga", "fragility_median_physical"} <= set(ds.data_vars) or "record_pga" not in ds.coords:
        return []
    if ds.attrs.get("intensity_measure") != "pga_ratio":
        return []
    from rockstudy.analysis.risk import threshold_fit
    rows = ["", "Two fits of the same object, PGA in g: the stripes' (P(overturn) at each level, above; the risk "
                "uses it) and the records' thresholds' (the first overturning the upward scan finds along each "
                "record's scale, a record without one censored at the last level). They differ because "
                "overturning is not monotone in the scale: a record can overturn the block at one scale and not "
                "at a higher one.", "",
            "| strategy | stripes' fit θ [g] (β) | records' thresholds' fit θ [g] (β) |", "|---|---|---|"]
    for s in ds.strategy.values:
        d, fit = ds.sel(strategy=s), threshold_fit(ds, str(s))
        rows.append(f"| {s} | {float(d.fragility_median_physical):.3f} ({float(d.fragility_dispersion):.2f}) "
                    f"| {fit.median:.3f} ({fit.dispersion:.2f}) |")
    return rows


def suite_summary_markdown(rows) -> str:
    """Markdown table of :func:`rockstudy.analysis.fragility.suite_summary`.

    Parameters
    ----------
    rows : list of dict
        The rows of :func:`rockstudy.analysis.fragility.suite_summary`; empty: an empty string.
    """
    from rockstudy.analysis.fragility import INTENSITY_MEASURES
    if not rows:
        return ""
    r0 = rows[0]
    lines = [f"| suite | strategy | median {INTENSITY_MEASURES[r0['intensity_measure']]} (95 % CI) | median "
             f"[{r0['physical_unit']}] (95 % CI) | β ± se | median {INTENSITY_MEASURES[r0['other_measure']]} (95 % CI) "
             "| θ/θ_FS (bootstrap 95 % CI) | shift over FS | fit |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['suite']} | {r['strategy']} | {r['median']:.3f} ({r['median_low']:.3f}–"
                     f"{r['median_high']:.3f}) | {r['median_physical']:.3f} ({r['median_physical_low']:.3f}–"
                     f"{r['median_physical_high']:.3f}) | {r['dispersion']:.3f} ± {r['dispersion_se']:.3f} | "
                     f"{r['median_other']:.3f} ({r['median_other_low']:.3f}–{r['median_other_high']:.3f}) | "
                     f"{r['median_ratio']:.3f} ({r['median_ratio_low']:.3f}–{r['median_ratio_high']:.3f}) | "
                     f"{r['median_shift_percent']:+.1f} % | {r['fit']} |")
    return "\n".join(lines) + "\n"


def threshold_markdown(ds: xr.Dataset) -> str:
    """Markdown table of every record's threshold: the smallest PGA [g] (and scale) that overturns the block,
    per strategy; "—" where nothing up to the last level overturns it.

    Parameters
    ----------
    ds : xarray.Dataset
        A fragility dataset with per-record thresholds (``threshold_pga``, ``threshold_scale``, the
        ``record_*`` coordinates; :func:`rockstudy.analysis.fragility.suite_fragility_dataset`).
    """
    strategies = [str(s) for s in ds.strategy.values]
    lines = ["| record | event | station | PGA [g] | " + " | ".join(f"{s}: PGA [g] (scale)" for s in strategies)
             + " |", "|---" * (4 + len(strategies)) + "|"]
    for k, name in enumerate(ds.record.values):
        cells = []
        for s in strategies:
            g = float(ds.threshold_pga.sel(strategy=s).values[k])
            sc = float(ds.threshold_scale.sel(strategy=s).values[k])
            cells.append("—" if not np.isfinite(g) else f"{g:.3f} ({sc:.2f}{' *' if sc <= 1 else ''})")
        lines.append(f"| {name} | {ds.record_event.values[k]} | {ds.record_station.values[k]} | "
                     f"{float(ds.record_pga.values[k]):.3f} | " + " | ".join(cells) + " |")
    lines.append("")
    lines.append(f"Threshold: smallest scale that overturns the block, every lower stripe level shown safe, bisected "
                 f"to {ds.attrs['threshold_resolution']:g} in {ds.attrs['intensity_measure_definition']}: the first "
                 "overturning the upward scan finds. Overturning is not monotone in the scale, so a record may "
                 "leave the block standing at a higher scale, and narrower overturning windows between the stripe "
                 "levels below it are not searched. "
                 "* : the record as recorded (scale <= 1) already overturns the block.")
    return "\n".join(lines) + "\n"


# --- the risk table (Markdown) ------------------------------------------------------------------------
NO_FIT_WORDS = {NEVER_OVERTURNS: "never overturns on these stripes", ALWAYS_OVERTURNS: "overturns on every stripe"}
"""What a table cell says for a strategy whose stripes' fit has no median, by the fit's status
(:data:`~rockstudy.analysis.fragility_fit.NEVER_OVERTURNS`,
:data:`~rockstudy.analysis.fragility_fit.ALWAYS_OVERTURNS`)."""

NO_FIT_NOTES = {
    NEVER_OVERTURNS: "{s} never overturns on these stripes: no record overturns the block at any level, so its median "
                     "lies above the last stripe and its risk below what these stripes resolve; no number is given.",
    ALWAYS_OVERTURNS: "{s} overturns on every stripe: every record overturns the block at every level, so its median "
                      "lies below the first stripe and its risk above what these stripes resolve; no number is given."}
"""The footnote of a risk table for a strategy without a median, by its fit status."""

SUPERSCRIPTS = "¹²³⁴⁵⁶⁷⁸⁹"


class _Footnotes:
    """Numbered footnotes of a table: :meth:`mark` gives a cell its marker, :meth:`lines` the notes in order."""

    def __init__(self):
        self.texts: list[str] = []

    def mark(self, text: str) -> str:
        if text not in self.texts:
            self.texts.append(text)
        i = self.texts.index(text)
        return SUPERSCRIPTS[i] if i < len(SUPERSCRIPTS) else f"[{i + 1}]"

    def lines(self) -> list[str]:
        return [f"- {self.mark(text)} {text}" for text in self.texts]


def _percent(p: float) -> str:
    return "—" if not np.isfinite(p) else (f"{100 * p:.3g} %" if p >= 1e-4 else f"{p:.2e}")


def _fit_status(ds: xr.Dataset, i: int) -> str:
    return str(ds["fit_status"].values[i]) if "fit_status" in ds else ""


def _no_fit_note(strategy: str, status: str) -> str:
    """The footnote of a strategy whose stripes' fit has no median."""
    if status in NO_FIT_NOTES:
        return NO_FIT_NOTES[status].format(s=strategy)
    said = f' (fit status "{status}")' if status else ""
    return f"{strategy} has no fitted median{said}, so no risk is given."


def _with_range(value: str, low: float, high: float, notes: _Footnotes, fmt=_percent) -> str:
    """``value (low–high)``, or ``value`` with a footnote where the median has no 95 % interval."""
    if math.isfinite(low) and math.isfinite(high):
        return f"{value} ({fmt(low)}–{fmt(high)})"
    return value + notes.mark("No range in brackets: the median has no 95 % interval (its fit gives no standard "
                              "error).")


def _fragility_cells(ds: xr.Dataset, strategies: list, thresholds: bool, notes: _Footnotes) -> list:
    """Per strategy: its stripes' median with interval, β, and the thresholds' fit when the dataset has one."""
    rows = []
    for i, s in enumerate(strategies):
        median, beta = float(ds.fragility_median.values[i]), float(ds.fragility_dispersion.values[i])
        if math.isfinite(median) and math.isfinite(beta):
            low = float(ds["median_low"].values[i]) if "median_low" in ds else math.nan
            high = float(ds["median_high"].values[i]) if "median_high" in ds else math.nan
            row = [s, _with_range(f"{median:.3f}", low, high, notes, fmt=lambda v: f"{v:.3f}"), f"{beta:.2f}"]
        else:
            status = _fit_status(ds, i)
            mark = notes.mark(_no_fit_note(s, status))
            row = [s, NO_FIT_WORDS.get(status, "—") + mark, "—" + mark]
        if thresholds:
            t_median, t_beta = float(ds.threshold_fit_median.values[i]), float(ds.threshold_fit_dispersion.values[i])
            row.append(f"{t_median:.3f}, {t_beta:.2f}" if math.isfinite(t_median) and math.isfinite(t_beta) else
                       "—" + notes.mark(f"The records' thresholds of {s} give no lognormal fit (see the threshold "
                                        "table)."))
        rows.append(row)
    return rows


def _change_cell(ds: xr.Dataset, strategies: list, i: int, reduction: float, notes: _Footnotes) -> str:
    """The change over FS of strategy ``i``: "—" on FS's row, a footnote where FS or the strategy has no risk."""
    if strategies[i] == "FS":
        return "—"
    for k in (i, strategies.index("FS")):
        if not math.isfinite(float(ds.fragility_median.values[k])):
            return "—" + notes.mark(_no_fit_note(strategies[k], _fit_status(ds, k)))
    return change_over_fs(reduction) if math.isfinite(reduction) else "—"


def _risk_cells(ds: xr.Dataset, i: int, n: int, cells, notes: _Footnotes) -> list:
    """``cells()`` (``n`` cells) of strategy ``i``, or ``n`` times "—" with its footnote where its fit has no
    median."""
    if math.isfinite(float(ds.fragility_median.values[i])):
        return cells()
    return ["—" + notes.mark(_no_fit_note(str(ds.strategy.values[i]), _fit_status(ds, i)))] * n


def _scenario_columns(ds: xr.Dataset, strategies: list, rows: list, notes: _Footnotes) -> tuple[list, list]:
    head, lines = [], []
    for j, name in enumerate(ds["scenario"].values if "scenario" in ds.coords else []):
        head += [f"P(overturn) in {name}", f"change over FS ({name})"]
        for i in range(len(strategies)):
            def p(i=i, j=j, notes=notes):
                return [_with_range(_percent(float(ds.scenario_probability.values[i, j])),
                                    float(ds.scenario_probability_low.values[i, j]),
                                    float(ds.scenario_probability_high.values[i, j]), notes)]
            change = _change_cell(ds, strategies, i, float(ds.scenario_reduction_percent.values[i, j]), notes)
            rows[i] += _risk_cells(ds, i, 1, p, notes) + [change]
        lines.append(f"{name}: {ds.attrs['gmm']} median PGA {float(ds.median_pga.values[j]):.3f} g, σ_ln "
                     f"{float(ds.ln_std_pga.values[j]):.2f}; scenario {ds.scenario_values.values[j]}.")
    return head, lines


def _tail_sentence(share) -> str:
    """What the hazard curve's note says of the share of the rates from outside its points."""
    share = np.asarray(share, dtype=float)
    share = share[np.isfinite(share)]
    if share.size == 0:
        return ""
    if share.max() == 0:
        return "; no part of a rate comes from outside the curve's points."
    return (f"; at most {100 * share.max():.2g} % of a rate comes from outside the curve's points (its end segments "
            "extended log-log)" + (" — more than 1 %: give the curve over a wider range of PGA." if share.max() > 0.01
                                   else "."))


def _hazard_columns(ds: xr.Dataset, strategies: list, rows: list, notes: _Footnotes) -> tuple[list, list]:
    head, lines, years = [], [], ds.attrs["years"]
    for j, name in enumerate(ds["hazard"].values if "hazard" in ds.coords else []):
        head += [f"λ [1/yr] ({name})", f"P in {years:g} yr ({name})", f"change over FS ({name})"]
        for i in range(len(strategies)):
            def cells(i=i, j=j, notes=notes):
                return [f"{float(ds.annual_rate.values[i, j]):.3g}",
                        _with_range(_percent(float(ds.probability.values[i, j])),
                                    float(ds.probability_low.values[i, j]), float(ds.probability_high.values[i, j]),
                                    notes)]
            change = _change_cell(ds, strategies, i, float(ds.reduction_percent.values[i, j]), notes)
            rows[i] += _risk_cells(ds, i, 2, cells, notes) + [change]
        sentence = _tail_sentence(ds.tail_share.values[:, j])
        lines.append(f"{name}: hazard curve {ds.hazard_source.values[j]}" + (sentence or "."))
    return head, lines


def risk_markdown(ds: xr.Dataset) -> str:
    """Markdown table of a record set's risk (:func:`rockstudy.analysis.risk_sites.risk_dataset`): per strategy
    the fragility used, P(overturn | scenario) for each scenario, and the annual rate and T-year probability
    for each hazard curve, each with its change over FS (:func:`change_over_fs`) and the range that the
    median's 95 % interval gives.

    A strategy whose stripes' fit has no median says why in its median cell ("never overturns on these
    stripes", :data:`NO_FIT_WORDS`) and has "—" with a footnote in its other cells: no cell shows NaN.

    Parameters
    ----------
    ds : xarray.Dataset
        A record set's risk (``risk/<record set>.nc``).
    """
    strategies = [str(s) for s in ds.strategy.values]
    notes = _Footnotes()
    thresholds = "threshold_fit_median" in ds
    head = ["strategy", "stripes' fit: median θ [g] (95 % CI)", "β"]
    head += ["thresholds' fit: θ [g], β (not used)"] if thresholds else []
    rows = _fragility_cells(ds, strategies, thresholds, notes)
    scenario_head, scenario_lines = _scenario_columns(ds, strategies, rows, notes)
    hazard_head, hazard_lines = _hazard_columns(ds, strategies, rows, notes)
    head += scenario_head + hazard_head
    lines = ["| " + " | ".join(head) + " |", "|---" * len(head) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    lines += ["", "The risk uses the stripes' lognormal fit in PGA: the probability of overturning at each PGA "
              "level, which is what the risk needs. The fit of the records' thresholds (each record's first "
              "overturning scale, found by the upward scan) describes another curve, since overturning is not "
              "monotone in the scale: a record may overturn the block at one scale and not at a higher one. "
              "In brackets: the probability with the median at the ends of its 95 % interval (how much the answer "
              "rests on the few records behind the median). The change over FS is "
              "\"—\" on FS's own row, FS being the reference.", ""]
    lines += notes.lines() + [f"- {n}" for n in scenario_lines + hazard_lines]
    return "\n".join(lines) + "\n"
