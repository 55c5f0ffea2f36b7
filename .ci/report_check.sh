#!/usr/bin/env bash
# .ci/report_check.sh -- build a study's report and check it in a real browser.
#
# Usage:  bash .ci/report_check.sh [tiny|default]   (from anywhere in the repository; as root where Chromium is missing)
#
#   tiny     the tiny study (.test/config.yaml), about two minutes [the default]
#   default  the default study (config.yaml): every section of the report, record sets and risk included
#            (a few minutes on 2 cores; .ci/run runs it with CI=true)
#
# Runs the study into a fresh folder, builds its Snakemake report, opens it in
# headless Chromium (Debian's package, installed here when missing; driven by Playwright) and fails
# unless Table 1's numbers and every claim's PASS / FAIL are visible text of the rendered page, the
# items are listed by what they show, no source hash and no dump is among the parameters shown, and,
# at 1280 and 1920 px, nothing of the overview runs under the rule graph or is cut off above it, every
# column of every table is seen without scrolling, every figure is drawn as wide as the window allows
# beside the sidebar, at most its natural width, with its smallest text at least 7 px high, no caption
# shows a docutils message and no two items share a label (.ci/report_check.py). The report is built as users build it, so
# with the stylesheet profiles/default/config.yaml sets (workflow/report/report.css). Leaves the report
# and screenshots in the folder it prints.
#
# Environment:
#   REPORT_CHECK_DIR   where results, report and screenshots go (wiped first) [a new temporary folder]
#   PYTHON             interpreter with rockstudy installed ("pip install -c constraints.txt -e .[all]") [python]
set -euo pipefail
cd "$(dirname "$0")/.."
STUDY="${1:-tiny}"
case "$STUDY" in
    tiny) CONFIG=(--configfile .test/config.yaml --replace-workflow-config) ;;
    default) CONFIG=() ;;
    *) echo "report_check: the study is 'tiny' or 'default', not '$STUDY'" >&2; exit 2 ;;
esac
PY="${PYTHON:-python}"
DIR="${REPORT_CHECK_DIR:-$(mktemp -d /tmp/rockstudy-report-check.XXXXXX)}"
T0=$(date +%s)
say() { printf '[report_check %4ss] %s\n' "$(( $(date +%s) - T0 ))" "$*"; }

if ! command -v chromium >/dev/null 2>&1; then
    say "installing Debian's chromium"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
fi
if ! "$PY" -c "import playwright" >/dev/null 2>&1; then   # the Python driver only: the browser is Debian's
    "$PY" -m pip install -q --disable-pip-version-check "playwright==1.65.2"
fi
say "$(chromium --version 2>/dev/null | head -1); playwright $("$PY" -c 'import importlib.metadata as m; print(m.version("playwright"))')"

rm -rf "$DIR" && mkdir -p "$DIR"
SMK=("$PY" -m snakemake "${CONFIG[@]}" --config "results_dir=$DIR/results")
"${SMK[@]}" -j2 --quiet rules > "$DIR/snakemake.log" 2>&1 || { tail -40 "$DIR/snakemake.log"; exit 1; }
say "$STUDY study done ($DIR/results)"
"${SMK[@]}" --report "$DIR/report.html" >> "$DIR/snakemake.log" 2>&1 || { tail -40 "$DIR/snakemake.log"; exit 1; }
if grep -E "\((ERROR|SEVERE|WARNING)/[0-9]\)" "$DIR/snakemake.log"; then
    echo "report_check: the report's text (captions, overview page) has reStructuredText errors" >&2; exit 1
fi
say "report built ($DIR/report.html, $(du -h "$DIR/report.html" | cut -f1))"
"$PY" .ci/report_check.py "$DIR/report.html" "$DIR/results" --screenshot "$DIR/report.png"
say "screenshots: $DIR/report.png, $DIR/report-reproduction.png, $DIR/report-figure-1280.png, $DIR/report-figure-1920.png"
