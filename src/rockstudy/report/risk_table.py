"""The Markdown table of a record set's risk (:func:`rockstudy.analysis.risk_sites.risk_dataset`), and the
one way every page writes a change over FS.

Every cell says what it means: a number, the words of a fit without a median ("never overturns on these
stripes"), or "—" with a numbered footnote saying why; never NaN.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from rockstudy.analysis.fragility_fit import ALWAYS_OVERTURNS, NEVER_OVERTURNS

if TYPE_CHECKING:
    import xarray as xr

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


def no_median_words(status: str) -> str:
    """What a cell says for a fit without a median: :data:`NO_FIT_WORDS` of its status, else "no median" and the
    status.

    Parameters
    ----------
    status : str
        The fit's status (:class:`rockstudy.analysis.fragility_fit.FragilityFit`); "" when the dataset has none.
    """
    return NO_FIT_WORDS.get(status, f"no median ({status})" if status else "no median")


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
