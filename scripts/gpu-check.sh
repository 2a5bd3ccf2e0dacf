#!/usr/bin/env bash
# A check on a machine with a GPU, run from a stripped release binary and the repository's
# assets (the GPU machine needs no Rust toolchain and no network, only a Vulkan loader and
# driver): `blueshift info`, `bench` at 1920x1080 of `white`, the paper and the default in
# direct light and at 8 bounces, and a short `eval`. Prints one table; logs go to OUT.
#
#   bash scripts/gpu-check.sh --bundle DIR   here (with cargo): build the release binary,
#                                            strip it, copy it with assets/ and this script
#                                            into DIR, to copy to the GPU machine
#   bash scripts/gpu-check.sh [--bin B] [--assets A] [--out OUT] [--quick]
#                                            on the GPU machine (from DIR: the bundled binary
#                                            and assets are found beside the script)
#
# The device is the binary's choice (a discrete GPU first; BLUESHIFT_DEVICE_INDEX=N picks
# another). --quick: 256x256 and fewer frames, to try the script itself on lavapipe.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"

usage() { sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; }
bin="" assets="" out="gpu-check" bundle="" quick=0
while (($#)); do
  case "$1" in
    --bin) bin="${2:?--bin needs a path}"; shift ;;
    --assets) assets="${2:?--assets needs a directory}"; shift ;;
    --out) out="${2:?--out needs a directory}"; shift ;;
    --bundle) bundle="${2:?--bundle needs a directory}"; shift ;;
    --quick) quick=1 ;;
    -h | --help) usage; exit 0 ;;
    *) echo "gpu-check: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
  shift
done

if [ -n "$bundle" ]; then
  cd "$here/.."
  source scripts/setup.sh
  cargo build --release --locked -p blueshift
  mkdir -p "$bundle/scripts"
  strip -o "$bundle/blueshift" "$CARGO_TARGET_DIR/release/blueshift"
  cp -r assets "$bundle/"
  cp scripts/gpu-check.sh "$bundle/scripts/"
  echo "gpu-check: bundle in $bundle ($(du -sh "$bundle" | cut -f1)); on the GPU machine: bash $bundle/scripts/gpu-check.sh"
  exit 0
fi

# The binary and assets: given, beside the script (a bundle), or this checkout's build.
if [ -z "$bin" ]; then
  for b in "$here/../blueshift" "${CARGO_TARGET_DIR:-$HOME/.cache/blueshift/target}/release/blueshift"; do
    [ -x "$b" ] && { bin="$b"; break; }
  done
fi
[ -n "$bin" ] && [ -x "$bin" ] || { echo "gpu-check: no blueshift binary (--bin, or --bundle first)" >&2; exit 1; }
assets="${assets:-$here/../assets}"
[ -f "$assets/MANIFEST" ] || { echo "gpu-check: no assets with a MANIFEST in '$assets' (--assets)" >&2; exit 1; }
if ! ldconfig -p 2>/dev/null | grep -q 'libvulkan\.so\.1'; then
  echo "gpu-check: warning: no libvulkan.so.1 in the linker cache; the binary will fail to load Vulkan" >&2
fi
export BLUESHIFT_ASSETS="$assets"
mkdir -p "$out"

if ((quick)); then size=(256 256) frames=3 eval_size=64 eval_frames=8; else size=(1920 1080) frames=8 eval_size=256 eval_frames=32; fi

echo "== info" | tee "$out/info.txt"
"$bin" info | tee -a "$out/info.txt"
device="$(sed -n 's/^selected: *//p' "$out/info.txt")"
case "$device" in
  *"(DISCRETE_GPU)"*) ;;
  *) echo "gpu-check: warning: the selected device is not a discrete GPU: $device" >&2 ;;
esac

# bench: one run per (method, bounces); the whole frame is the sum of its passes' medians.
rows=()
for bounces in 1 8; do
  white_ms=""
  for method in white sort-retarget sort-cycle; do
    log="$out/bench_${method}_b${bounces}.txt"
    "$bin" bench --method "$method" --width "${size[0]}" --height "${size[1]}" --spp 1 \
      --bounces "$bounces" --frames "$frames" > "$log" 2>&1 || { cat "$log" >&2; exit 1; }
    read -r trace frame msps perm < <(awk '
      /^  pass / { ms = $4; frame += ms; if ($2 == "trace") trace = ms }
      /^trace median/ { msps = $(NF - 1) }
      /^  permutation passes/ { perm = $3 }
      END { printf "%s %.3f %s %.3f\n", trace, frame, msps, (perm == "" ? 0 : perm + 0) + 0 }' "$log")
    [ -n "$white_ms" ] || white_ms="$frame"
    ratio="$(awk -v a="$frame" -v b="$white_ms" 'BEGIN { printf "%.3f", a / b }')"
    rows+=("| \`$method\` | ${size[0]}x${size[1]}, $bounces | $trace | $perm | $frame | $ratio | $msps |")
  done
done

echo "== eval (logs in $out/eval)"
"$bin" eval --methods white,mask-r2,sort-retarget,sort-cycle --camera static,strafe:2.5 \
  --bounces 1,8 --width "$eval_size" --height "$eval_size" --frames "$eval_frames" \
  --sequences 1 --cache "$out/references" --out "$out/eval" > "$out/eval.txt" 2>&1 \
  || { cat "$out/eval.txt" >&2; exit 1; }

{
  echo
  echo "Device: $device; $("$bin" --version)"
  echo
  echo "| method | size, bounces | trace ms | permutation passes ms | whole frame ms | frame / \`white\` | Msamples/s |"
  echo "|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
  echo
  awk '/^## Per frame \/ accumulated along the motion/ { on = 1; next } /^## / { on = 0 } on && /^[|]/' \
    "$out/eval/report.md"
} | tee "$out/table.md"
