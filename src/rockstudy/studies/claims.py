"""The paper's checkable statements (§5 and the Conclusions), evaluated on a run's results.

Each claim is a plain function of the run's tables and spectra that returns a
:class:`ClaimResult`: the paper's words, our explicit definition of them (what "smooths",
"appreciably", "enough" mean here), the numbers behind the verdict, and PASS / FAIL (or
``None``, "not evaluated", when the run lacks the data, e.g. a tiny study without R010).
Where a claim can also be checked on the paper's own Table 1 it is, so a FAIL of ours can be
told apart from a statement the paper's numbers do not support either.

Inputs are the datasets of :mod:`rockstudy.studies.study`: Table 1 (``j_os`` over ``reference`` ×
``strategy`` × ``noise_level``), the timing tables (``j_os`` over ``reference`` ×
``strategy`` × ``sampling_time`` or ``delay``), the convergence dataset of Fig. 6a, and the
gathered spectra. J_OS values are in percent; thresholds are ratios a_p/(g·tanα).
"""
from __future__ import annotations

import math

import numpy as np
import xarray as xr

from rockstudy._version import __version__
from rockstudy.core.constants import PAPER
from rockstudy.studies.claim_checks import (  # noqa: F401 -- the claims and their data, read here by name
    APPRECIABLE,
    CONVERGED,
    CONVERGENCE_FROM,
    PAPER_LEVELS,
    PAPER_TABLE1,
    RANGE_SLACK,
    ClaimResult,
    _range_claim,
    _row,
    claim_both_beat_fs,
    claim_controlled_less_sensitive,
    claim_controlled_rises,
    claim_cs01_beats_cs02,
    claim_cs01_less_affected,
    claim_cs01_sampling,
    claim_cs01_stable_sampled,
    claim_cs02_sampling,
    claim_delay,
    claim_forty_enough,
    claim_fs_falls,
    claim_fs_negative,
    claim_gap_shrinks,
    claim_noise_smooths,
    total_variation,
)


def evaluate_claims(table1: xr.Dataset | None, *, convergence: xr.Dataset | None = None,
                    sampling: xr.Dataset | None = None, delay: xr.Dataset | None = None,
                    spectra: dict | None = None, levels: dict | None = None,
                    a_max0_ratio: float = 4.0, cap: float | None = None) -> list[ClaimResult]:
    """Every checkable statement of §5 and the Conclusions, in the paper's order.

    Parameters
    ----------
    table1 : xarray.Dataset or None
        Table 1 as built by :func:`rockstudy.studies.tables.table1`.
    convergence : xarray.Dataset, optional
        Fig. 6a data (:func:`rockstudy.studies.datasets.convergence_dataset`).
    sampling, delay : xarray.Dataset, optional
        The timing tables (:func:`rockstudy.studies.tables.timing_table`).
    spectra : dict, optional
        {(strategy, level name): aggregate thresholds over the frequency grid} [-].
    levels : dict, optional
        {level name: noise level} [-].
    a_max0_ratio : float, default 4.0
        a_max,0 as an amplitude ratio (4 = g for BLC06). [-]
    cap : float, optional
        Threshold cap for the total variation (default ``a_max0_ratio``). [-]

    Returns
    -------
    list of ClaimResult
    """
    cap = a_max0_ratio if cap is None else cap
    return [
        claim_fs_negative(table1),
        claim_fs_falls(table1),
        claim_controlled_rises(table1),
        claim_controlled_less_sensitive(table1),
        claim_noise_smooths(spectra or {}, levels or {}, cap),
        claim_forty_enough(convergence, a_max0_ratio),
        claim_both_beat_fs(table1),
        claim_cs01_beats_cs02(table1),
        claim_gap_shrinks(table1),
        claim_cs01_stable_sampled(sampling),
        claim_cs01_sampling(sampling),
        claim_cs02_sampling(sampling),
        claim_cs01_less_affected(sampling),
        claim_delay(delay),
        _range_claim(table1, "CS01", 28, 32),
        _range_claim(table1, "CS02", 16, 23),
    ]


def _verdict(value) -> str:
    return "n/a" if value is None else ("PASS" if value else "FAIL")


def claims_dataset(results: list[ClaimResult], attrs: dict | None = None) -> xr.Dataset:
    """The claims as a labelled dataset: ``passed`` (1 PASS, 0 FAIL, -1 not evaluated) and the texts.

    Parameters
    ----------
    results : list of ClaimResult
        The evaluated claims (:func:`evaluate_claims`), in order.
    attrs : dict, optional
        Further global attributes of the dataset.
    """
    def code(v):
        return -1 if v is None else int(v)
    keys = [r.key for r in results]
    return xr.Dataset(
        {"passed": ("claim", np.array([code(r.passed) for r in results], dtype=np.int8),
                    {"long_name": "verdict on this run", "flag_values": np.array([-1, 0, 1], dtype=np.int8),
                     "flag_meanings": "not_evaluated fail pass"}),
         "paper_passed": ("claim", np.array([code(r.paper_passed) for r in results], dtype=np.int8),
                          {"long_name": "verdict of the same check on the paper's own Table 1",
                           "flag_values": np.array([-1, 0, 1], dtype=np.int8),
                           "flag_meanings": "not_applicable fail pass"}),
         "section": ("claim", [r.section for r in results]),
         "statement": ("claim", [r.statement for r in results]),
         "definition": ("claim", [r.definition for r in results]),
         "evidence": ("claim", [r.evidence for r in results])},
        coords={"claim": ("claim", keys)},
        attrs={"title": "Claims of the paper (§5, Conclusions) checked on this run", "paper": PAPER,
               "rockstudy_version": __version__, "appreciable_jos_percent": APPRECIABLE,
               "converged_jos_percent": CONVERGED, "convergence_from_n": CONVERGENCE_FROM,
               "range_slack_percent": RANGE_SLACK, **(attrs or {})})


COMPARISON_TITLE = "Table 1: paper vs this run"
"""The title of :func:`table1_comparison`'s dataset."""


def table1_comparison(table1: xr.Dataset) -> xr.Dataset:
    """Table 1 side by side: the paper's J_OS, ours and ours − paper per cell [%] (NaN where absent).

    Parameters
    ----------
    table1 : xarray.Dataset
        Table 1 of this run (:func:`rockstudy.studies.tables.table1`); it may lack cells (a tiny study).
    """
    keys = list(PAPER_TABLE1)
    paper = np.array([PAPER_TABLE1[k] for k in keys])
    ours = np.full(paper.shape, np.nan)
    for i, (ref, s) in enumerate(keys):
        row = _row(table1, ref, s, PAPER_LEVELS)
        if row is None:  # a partial row (e.g. a tiny study): fill what exists
            for j, lv in enumerate(PAPER_LEVELS):
                try:
                    ours[i, j] = float(table1["j_os"].sel(reference=ref, strategy=s, noise_level=lv))
                except KeyError:
                    pass
        else:
            ours[i] = row
    dims = ("row", "noise_level")
    pct = {"units": "percent"}
    return xr.Dataset(
        {"paper": (dims, paper, {**pct, "long_name": "J_OS in the paper's Table 1"}),
         "ours": (dims, ours, {**pct, "long_name": "J_OS of this run"}),
         "difference": (dims, ours - paper, {**pct, "long_name": "ours minus paper (points)"})},
        coords={"row": ("row", [f"{s} vs {ref}" for ref, s in keys]),
                "reference": ("row", [ref for ref, _ in keys]), "strategy": ("row", [s for _, s in keys]),
                "noise_level": ("noise_level", list(PAPER_LEVELS))},
        attrs={"title": COMPARISON_TITLE, "paper": PAPER, "rockstudy_version": __version__})


def comparison_markdown(comp: xr.Dataset) -> str:
    """Table 1 side by side as Markdown: per row and level, paper / ours / difference.

    Parameters
    ----------
    comp : xarray.Dataset
        The comparison of :func:`table1_comparison`.
    """
    levels = list(comp["noise_level"].values)
    head = ["Table 1 row"] + [f"{lv} paper / ours / diff" for lv in levels] + ["max abs diff"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for i, row in enumerate(comp["row"].values):
        cells = []
        for j in range(len(levels)):
            p, o, d = (float(comp[v].values[i, j]) for v in ("paper", "ours", "difference"))
            cells.append(f"{p:+.2f} / " + ("-" if math.isnan(o) else f"{o:+.2f} / {d:+.2f}"))
        diffs = np.abs(comp["difference"].values[i])
        worst = "-" if np.all(np.isnan(diffs)) else f"{np.nanmax(diffs):.2f}"
        lines.append("| " + " | ".join([str(row)] + cells + [worst]) + " |")
    return "\n".join(lines) + "\n"


def claims_markdown(results: list[ClaimResult], comp: xr.Dataset | None = None, header: str = "") -> str:
    """The checklist as Markdown (one line per claim, then details), with Table 1 side by side.

    Parameters
    ----------
    results : list of ClaimResult
        The evaluated claims (:func:`evaluate_claims`), in order.
    comp : xarray.Dataset, optional
        The comparison of :func:`table1_comparison`; None: no side-by-side table.
    header : str, default ""
        Markdown put under the title (e.g. the run's settings); empty: none.
    """
    n_pass = sum(r.passed is True for r in results)
    n_fail = sum(r.passed is False for r in results)
    out = ["# Claims of the paper checked on this run", ""]
    if header:
        out += [header, ""]
    out += [f"**{n_pass} PASS, {n_fail} FAIL, {len(results) - n_pass - n_fail} not evaluated** "
            f"(\"paper\": the same check on the paper's own Table 1, where it applies).", "",
            "| # | § | claim | ours | paper's own numbers | evidence |", "|---|---|---|---|---|---|"]
    for i, r in enumerate(results, 1):
        out.append(f"| {i} | {r.section} | {r.statement} | **{r.verdict}** | {_verdict(r.paper_passed)} | "
                   f"{r.evidence} |")
    out += ["", "## Definitions", ""]
    out += [f"{i}. `{r.key}`: {r.definition}" for i, r in enumerate(results, 1)]
    if comp is not None:
        out += ["", "## Table 1 side by side (J_OS, %)", "", comparison_markdown(comp)]
    return "\n".join(out) + "\n"


def claims_csv(results: list[ClaimResult]) -> str:
    """The checklist as CSV (one row per claim) for the HTML report.

    Parameters
    ----------
    results : list of ClaimResult
        The evaluated claims (:func:`evaluate_claims`), in order.
    """
    import csv
    import io as _io
    buf = _io.StringIO()
    writer = csv.writer(buf)
    writer.writerow(["claim", "section", "verdict", "paper_own_numbers", "statement", "definition", "evidence"])
    for r in results:
        writer.writerow([r.key, r.section, r.verdict, _verdict(r.paper_passed), r.statement, r.definition,
                         r.evidence])
    return buf.getvalue()


def evaluate_run(table1: xr.Dataset, spectra, levels: dict, a_max0_g: float, *, convergence=None, sampling=None,
                 delay=None) -> list[ClaimResult]:
    """:func:`evaluate_claims` on a run's datasets, a_max,0 given in g and converted with the block's α.

    Parameters
    ----------
    table1 : xarray.Dataset
        Table 1 (:func:`rockstudy.studies.tables.table1`).
    spectra : iterable of xarray.Dataset
        The gathered spectra (:func:`rockstudy.studies.datasets.gather_spectra`), with scalar ``strategy`` and
        ``noise_level`` coordinates; at least one. The first one's ``block_alpha`` converts a_max,0.
    levels : dict
        Level name -> noise level; spectra at other levels are left out. [-]
    a_max0_g : float
        Protection level a_max,0. [g]
    convergence : xarray.Dataset, optional
        The convergence dataset of Fig. 6a (:func:`rockstudy.studies.datasets.convergence_dataset`).
    sampling, delay : xarray.Dataset, optional
        The timing tables (:func:`rockstudy.studies.tables.timing_table`).
    """
    spectra = list(spectra)
    if not spectra:
        raise ValueError("spectra must hold at least one gathered spectrum dataset")
    ratio = float(a_max0_g) / math.tan(float(spectra[0].attrs["block_alpha"]))
    by_value = {float(v): name for name, v in levels.items()}
    curves = {}
    for ds in spectra:
        name = by_value.get(float(ds["noise_level"]))
        if name is not None:
            curves[(ds["strategy"].item(), name)] = ds["threshold"].values
    return evaluate_claims(table1, convergence=convergence, sampling=sampling, delay=delay, spectra=curves,
                           levels=levels, a_max0_ratio=ratio)
