#!/usr/bin/env bash
# The Python package's tests (python/tests): a virtual environment under
# target/, the package built from this workspace by `pip install ./python`
# (maturin from PyPI), and pytest against the repository's fixtures, with
# the release `vstf` binary to compare arrays with its PNGs; the example
# notebooks (examples/) are run by nbclient as part of it, and the widget
# is driven in JupyterLab in chromium (skipped without chromium unless
# VSTF_REQUIRE_BROWSER=1, as .ci/run sets when it installed it).
#
# Without python3 (or its venv module) the tests are skipped, saying so;
# with VSTF_REQUIRE_PYTHON=1 (as .ci/run sets) that is a failure.
set -euo pipefail
cd "$(dirname "$0")/.."

skip() {
  echo "SKIPPED the Python tests: $1" >&2
  if [ "${VSTF_REQUIRE_PYTHON:-0}" = 1 ]; then exit 1; fi
  exit 0
}

command -v python3 >/dev/null 2>&1 || skip "python3 is not installed"
venv=target/python-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv" 2>/dev/null || skip "python3 -m venv failed (Debian: apt-get install python3-venv)"
fi
echo "== the vstf executable the tests compare with"
cargo build --release --locked -p vstf
echo "== pip install ./python (into $venv)"
"$venv/bin/python" -m pip install -q --upgrade pip
"$venv/bin/python" -m pip install -q "maturin>=1.9,<2" "pytest>=7" numpy \
  nbclient nbformat ipykernel matplotlib pandas tqdm anywidget jupyterlab selenium
"$venv/bin/python" -m pip install -q ./python
echo "== pytest python/tests"
VSTF_BIN="$PWD/target/release/vstf" "$venv/bin/pytest" -q python/tests
