"""The Markdown and HTML helpers of the report's pages: a complete page around a fragment, Markdown
tables as HTML (wide ones transposed), verdicts as marked, coloured words, and the code's names of the
references of J_OS in the paper's words.

Verdicts keep their words (PASS, FAIL, n/a) and add a marker and a colour from a colour-blind-safe
pair (blue and orange), so that nothing is read from colour alone.
"""
from __future__ import annotations

import html
import re

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
