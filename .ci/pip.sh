#!/usr/bin/env bash
# `pip install .` as a user outside Debian runs it (issue 36), here offline with Debian's setuptools
# and pybind11 (--no-build-isolation): into a fresh virtual environment that sees the system's
# NumPy and pytest, built in build-pip (ccache makes it mostly a link after the main build). Then
# the package's pytest suite runs against the installed package, from outside the source tree.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
venv="$(mktemp -d)/venv"
/usr/bin/python3 -m venv --system-site-packages "$venv"
CLASPPLAN_PIP_BUILD_DIR="$root/build-pip" CMAKE_BUILD_PARALLEL_LEVEL=2 \
  "$venv/bin/pip" install --no-build-isolation --quiet "$root"
cd "$(dirname "$venv")"
"$venv/bin/python" -c "import sys, claspplan; assert claspplan.__file__.startswith(sys.prefix), \
claspplan.__file__; print('pip: claspplan installed in', claspplan.__file__)"
CLASPPLAN_BIN="$root/build/claspplan" CLASPPLAN_SOURCE="$root" \
  "$venv/bin/python" -m pytest -q -p no:cacheprovider "$root/test/python"
