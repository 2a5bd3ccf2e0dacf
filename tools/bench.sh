#!/usr/bin/env bash
# Measures what the permutation passes cost next to the trace pass (`blueshift bench`, GPU
# timestamps: on lavapipe the CPU time of each pass) and rewrites the table between
# <!-- bench:passes begin --> and <!-- bench:passes end --> in docs/results.md and README.md.
#
#   bash tools/bench.sh            all configurations (a few minutes on 2 quiet cores)
#   bash tools/bench.sh --bin B    use the binary B instead of building a release one
#   bash tools/bench.sh --rounds N passes over all configurations (default 3; the median counts)
#
# Times depend on the machine and its load; shares of the trace pass of the same run depend
# on them much less. Run it on a quiet machine. Nothing is written unless every run succeeds.
set -euo pipefail
cd "$(dirname "$0")/.."

bin=""
ROUNDS=3
while (($#)); do
  case "$1" in
    --bin) [ $# -ge 2 ] || { echo "bench.sh: --bin needs a path" >&2; exit 2; }; bin="$2"; shift ;;
    --rounds) [[ "${2:-}" =~ ^[1-9]$ ]] || { echo "bench.sh: --rounds needs 1-9" >&2; exit 2; }; ROUNDS="$2"; shift ;;
    -h | --help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bench.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
  shift
done
if [ -z "$bin" ]; then
  source scripts/setup.sh
  cargo build --release --locked -p blueshift
  bin="$CARGO_TARGET_DIR/release/blueshift"
fi

# method | camera path | width x height | bounces [| scene, default the Cornell box].
# `sort-cycle` sorts on the box only with a still view at depth (elsewhere its trace reads no
# seed there); on a scene with textures it sorts: the textured rows show what it costs there.
CONFIGS=(
  "sort-retarget|static|1920x1080|1"
  "sort-cycle|static|1920x1080|1"
  "sort-cycle|static|1920x1080|1|textured"
  "sort-cycle|strafe:2.5|1920x1080|1"
  "sort-cycle|strafe:2.5|1920x1080|1|textured"
  "sort-cycle:grouping=surfaces|strafe:2.5|1920x1080|1|textured"
  "mask-rot-follow|strafe:2.5|1920x1080|1"
  "sort-grid-adaptive|strafe:2.5|1920x1080|1"
  "sort-retarget|static|256x256|8"
  "sort-cycle|static|256x256|8"
  "sort-cycle|strafe:2.5|256x256|8"
  "sort-cycle|strafe:2.5|256x256|8|textured"
)

tmpfiles=()
cleanup() { ((${#tmpfiles[@]})) && rm -rf "${tmpfiles[@]}"; return 0; }
trap cleanup EXIT
table="$(mktemp)"
tmpfiles+=("$table")
{
  echo
  echo "| method | camera | size, bounces | trace | passes (largest first) | all permutation passes |"
  echo "|---|---|---|---|---|---|"
} > "$table"
# ROUNDS passes over all configurations, interleaved so that a slow spell of the machine hits
# every configuration alike; each configuration reports its round with the median share.
outs=()
for ((r = 0; r < ROUNDS; r++)); do
  for i in "${!CONFIGS[@]}"; do
    IFS='|' read -r method camera size bounces scene <<< "${CONFIGS[$i]}"
    out="$(mktemp)"
    tmpfiles+=("$out")
    outs[r * ${#CONFIGS[@]} + i]="$out"
    echo "== round $((r + 1))/$ROUNDS: bench --method $method --camera-path $camera ${size} --bounces $bounces ${scene:-cornell-box}" >&2
    "$bin" bench --method "$method" --camera-path "$camera" --width "${size%x*}" \
      --height "${size#*x}" --bounces "$bounces" --spp 1 --warmup 17 --frames 8 \
      --scene "${scene:-cornell-box}" > "$out"
    cat "$out" >&2
  done
done
# "  permutation passes MS ms NS ns/px: SHARE% of trace" (0 without permutation passes)
share() { awk '$1 == "permutation" { s = $7 + 0 } END { print s + 0 }' "$1"; }
for i in "${!CONFIGS[@]}"; do
  IFS='|' read -r method camera size bounces scene <<< "${CONFIGS[$i]}"
  [ -n "$scene" ] && camera="$camera, $scene"
  out="$(for ((r = 0; r < ROUNDS; r++)); do
    o="${outs[r * ${#CONFIGS[@]} + i]}"
    echo "$(share "$o") $o"
  done | sort -n | awk -v m=$(((ROUNDS + 1) / 2)) 'NR == m { print $2 }')"
  awk -v method="$method" -v camera="$camera" -v size="$size" -v bounces="$bounces" '
    # "  pass NAME median MS ms NS ns/px SHARE% of trace"
    $1 == "pass" && $2 == "trace" { trace = sprintf("%.1f ms, %.0f ns/px", $4, $6) }
    $1 == "pass" && $2 != "trace" && $2 != "accumulate" && $2 != "tonemap" && $2 != "taa" {
      n++; name[n] = $2; share[n] = $8 + 0
    }
    # "  permutation passes MS ms NS ns/px: SHARE% of trace"
    $1 == "permutation" { all = sprintf("%.1f ms, %.1f ns/px, **%s**", $3, $5, $7) }
    END {
      if (trace == "") { print "bench.sh: no trace pass in the output" > "/dev/stderr"; exit 1 }
      for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++)
        if (share[j] > share[i]) { t = share[i]; share[i] = share[j]; share[j] = t; t = name[i]; name[i] = name[j]; name[j] = t }
      list = ""
      for (i = 1; i <= n; i++) list = list (i > 1 ? ", " : "") sprintf("`%s` %.1f%%", name[i], share[i])
      if (all == "") all = "-"
      printf "| `%s` | %s | %s, %s | %s | %s | %s |\n", method, camera, size, bounces, trace, (list == "" ? "-" : list), all
    }' "$out" >> "$table"
done
cpu="$(awk -F': ' '/^model name/ { print $2; exit }' /proc/cpuinfo)"
{
  echo
  echo "Shares are of the trace pass of the same run; medians of 8 timed frames after 17 untimed ones (the steady state of a still view), the run with the median share of $ROUNDS interleaved rounds; $(nproc) cores ($cpu), load average $(cut -d' ' -f1-3 /proc/loadavg) at the end. Regenerate: \`bash tools/bench.sh\`."
  echo
} >> "$table"

source tools/splice.sh
# Both files are checked before either is written.
for f in docs/results.md README.md; do
  grep -qx "<!-- bench:passes begin -->" "$f" && grep -qx "<!-- bench:passes end -->" "$f" ||
    { echo "bench.sh: $f lacks the bench:passes markers" >&2; exit 1; }
done
for f in docs/results.md README.md; do splice bench:passes "$f" "$table"; done
echo "bench.sh: wrote the pass table into docs/results.md and README.md" >&2
