#!/usr/bin/env bash
# The main job: build in release, show the device (verified compute dispatch), then the default
# evaluation on the bundled Cornell box (report in out/eval/report.md).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh

cargo build --release --locked -p blueshift
"$CARGO_TARGET_DIR/release/blueshift" --validation info
"$CARGO_TARGET_DIR/release/blueshift" eval --out out/eval "$@"
