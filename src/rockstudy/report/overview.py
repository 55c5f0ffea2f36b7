"""Table 1 beside the paper's, the claims checklist, and the fragment of the report's overview page that
states the headline results (Table 1, the claims, and beyond the paper the fragility medians and the risk at
each site), styled inline for the Snakemake report's page.
"""
from __future__ import annotations

import html
import math
from typing import TYPE_CHECKING

import numpy as np

from rockstudy.report.pages import in_paper_words, scrolling, verdict_html
from rockstudy.report.risk_table import change_over_fs, no_median_words

if TYPE_CHECKING:
    import xarray as xr

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
        ``risk/<record set>.nc`` of the run (:func:`rockstudy.analysis.risk_sites.risk_dataset`); empty when
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
                text = no_median_words(str(ds["fit_status"].sel(strategy=s).values) if "fit_status" in ds else "")
            cells.append(f'<td class="num">{html.escape(text)}</td>')
        name = f"{ds.attrs.get('record_suite', '')} ({int(ds.attrs.get('n_records', 0))} records)"
        rows.append(f"<tr><th>{html.escape(name)}</th>{''.join(cells)}</tr>")
    table = ("<table>\n<caption>Fragility: the median PGA that overturns the block, each strategy "
             "(in brackets, the shift over FS)</caption>\n"
             f"<thead><tr><th>record set</th>{head}</tr></thead>\n<tbody>\n{chr(10).join(rows)}\n</tbody>\n</table>")
    return scrolling(_styled(table), style=INLINE["scroll"]) + "".join(_risk_overview(ds) for ds in risk)


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
                    text = no_median_words(str(ds["fit_status"].values[i]) if "fit_status" in ds else "")
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
