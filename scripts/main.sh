#!/usr/bin/env bash
# The main job: build in release, show the device and verify a compute dispatch on it.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh

cargo build --release --locked -p blueshift
"$CARGO_TARGET_DIR/release/blueshift" --validation info "$@"
