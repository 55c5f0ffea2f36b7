#!/usr/bin/env bash
# .ci/slurm/fresh.sh -- run the SLURM check as a machine that never ran it would.
#
# Usage:  bash .ci/slurm/fresh.sh            (as root, from anywhere in the repository)
#
# Creates a NEW virtual environment (a new folder under /tmp, removed at the end), installs
# the package with the README's command (pip install -c constraints.txt -e ".[all]"), checks that the SLURM
# executor plugin is NOT installed (so up.sh must install it, as on a new machine), then runs
# .ci/slurm/ci.sh inside that environment. A green run on a machine that has run the check
# before can hide a missing install step; this one cannot.
#
# Environment:
#   FRESH_VENV   where the virtual environment is created (wiped first, kept at the end)
#                [a new /tmp/venv-rockstudy-fresh.XXXXXX, removed at the end: two runs on one
#                machine do not share it]
#   PYTHON_BASE  interpreter the venv is made from                       [python3]
set -euo pipefail
cd "$(dirname "$0")/../.."
if [ -n "${FRESH_VENV:-}" ]; then
    VENV="$FRESH_VENV"
    rm -rf "$VENV"
else
    VENV="$(mktemp -d /tmp/venv-rockstudy-fresh.XXXXXX)"
    trap 'rm -rf "$VENV"' EXIT
fi
T0=$(date +%s)
say() { printf '[fresh %4ss] %s\n' "$(( $(date +%s) - T0 ))" "$*"; }

"${PYTHON_BASE:-python3}" -m venv "$VENV"
# shellcheck disable=SC1091
. "$VENV/bin/activate"
export PYTHON="$VENV/bin/python"
say "new venv $VENV ($(python --version))"
if [ -f constraints.txt ]; then   # the README's install command
    python -m pip install -q --disable-pip-version-check -c constraints.txt -e ".[all]"
else
    python -m pip install -q --disable-pip-version-check -e ".[all]"
fi
say "installed rockstudy from $(python -c 'import rockstudy, os; print(os.path.dirname(rockstudy.__file__))')"
if python -m pip show snakemake-executor-plugin-slurm >/dev/null 2>&1; then
    echo "fresh.sh: the SLURM executor plugin is already installed in a new venv?" >&2; exit 1
fi
say "snakemake-executor-plugin-slurm not installed (as on a new machine)"
CI=true bash .ci/slurm/ci.sh
say "SLURM check passed from a fresh venv"
