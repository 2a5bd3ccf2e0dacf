#!/usr/bin/env bash
# The whole test suite: formatting, lints, then every test (GPU tests on lavapipe with the
# Khronos validation layer; any validation message fails the test that caused it).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh

echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy"
cargo clippy --workspace --all-targets --locked -q -- -D warnings
echo "== cargo test"
cargo test --workspace --locked
