#!/usr/bin/env bash
# Every test: the Rust workspace's, then the Python package's
# (tests/python.sh, which skips saying why when python3 is missing).
set -euo pipefail
cd "$(dirname "$0")/.."
echo "== cargo test --workspace"
cargo test --workspace --locked
bash tests/python.sh
