#!/usr/bin/env bash
# Re-runs the evaluations behind docs/results.md, rewrites its generated tables (the text
# between <!-- reproduce:NAME begin --> and <!-- reproduce:NAME end -->) and refreshes the
# curated figures in docs/figures/.
#
#   bash tools/reproduce.sh               all runs (about 10-25 minutes each on 2 CPU cores)
#   bash tools/reproduce.sh --only NAME   one run: motion, motion-textured, motion-speeds,
#                                         motion-edges, still-256, cornell or textured
#   bash tools/reproduce.sh --references  only fill the reference cache for the runs (or the
#                                         --only one): one `white` sequence each, docs untouched.
#                                         On a new machine the references are most of the time
#                                         of a run (a 64-frame strafe at 8 bounces: about 10 min)
#   bash tools/reproduce.sh --bin B       use the binary B instead of building a release one
#   bash tools/reproduce.sh --reuse       no eval: rewrite the tables from the reports already
#                                         in out/results/NAME/ (e.g. after editing the docs)
#   bash tools/reproduce.sh --quick       smoke run: 12 frames, one sequence; writes
#                                         out/results/results.md and out/results/figures/,
#                                         leaves docs/ untouched
#
# The motion run's headline table (per frame / accumulated along the motion) also replaces
# README.md's results table, and the best named method per configuration its "which method to
# pick". Eval outputs go to out/results/NAME/ (report.md, report.json, PNGs). Nothing is left
# half-written: each run goes to a staging directory that replaces the old one only when it
# succeeds, and docs files are written to a temporary file and then renamed.
# Needs only bash, coreutils and awk (besides what scripts/setup.sh installs).
set -euo pipefail
cd "$(dirname "$0")/.."

# name | arguments of `blueshift eval` besides the common ones below
RUNS=(
  "motion|--methods white,sobol,stbn,fast,mask-r2,mask-rot,mask-rot-follow,blocknet,sort-grid-adaptive,sort-cycle,sort-cycle:target=screen,sort-cycle:mask=none,sort-cycle:mask=motion,sort-cycle:grouping=surfaces,sort-cycle:without=sample-keys,sort-cycle:without=sobol-jitter,sort-cycle:without=still-volume,sort-cycle:without=motion-volume,sort-cycle:without=white-depth --camera static,strafe:2.5 --bounces 1,8 --sequences 8 --width 128 --height 128"
  "motion-textured|--scene textured --methods white,sobol,stbn,fast,mask-r2,mask-rot,mask-rot-follow,blocknet,sort-grid-adaptive,sort-cycle,sort-cycle:target=screen,sort-cycle:mask=motion,sort-cycle:without=sample-keys,sort-cycle:without=texture-jitter,sort-cycle:without=motion-volume --camera strafe:2.5 --bounces 1,8 --sequences 8 --width 128 --height 128"
  "motion-speeds|--methods white,sobol,stbn,fast,mask-r2,mask-rot,mask-rot-follow,blocknet,sort-grid-adaptive,sort-cycle,sort-cycle:target=screen,sort-cycle:without=motion-volume,sort-cycle:without=white-depth --camera strafe:1,strafe:5 --bounces 1,8 --sequences 8 --width 128 --height 128"
  "motion-edges|--scene edges --methods white,sobol,stbn,fast,mask-r2,mask-rot,mask-rot-follow,blocknet,sort-grid-adaptive,sort-cycle,sort-cycle:target=screen,sort-cycle:mask=none,sort-cycle:mask=motion,sort-cycle:without=sample-keys,sort-cycle:without=sobol-jitter,sort-cycle:without=still-volume,sort-cycle:without=motion-volume,sort-cycle:without=white-depth --camera static,strafe:2.5 --bounces 1,8 --sequences 8 --width 128 --height 128"
  "still-256|--methods white,sobol,stbn,mask-r2,mask-rot,blocknet,sort-cycle,sort-cycle:without=still-volume --camera static --bounces 1,8 --sequences 4 --width 256 --height 256"
  "cornell|--methods white,sobol,hbo19,stbn,fast,mask-r2,sort-retarget,sort-grid-adaptive,sort-cycle,sort-cycle:without=motion-volume,sort-cycle:without=white-depth --camera static,pan:1,orbit:1 --bounces 1,8 --sequences 4 --width 128 --height 128"
  "textured|--scene textured --methods white,sobol,hbo19,stbn,fast,sort-retarget,sort-grid-adaptive,sort-cycle,sort-cycle:without=sobol-jitter,sort-cycle:without=motion-volume --camera static,pan:1 --bounces 1,8 --sequences 4 --width 128 --height 128"
)
# name | file in the run's output | name under docs/figures/
FIGURES=(
  "cornell|static_b1_spp1_white_error.png|cornell-direct-static_white_error.png"
  "cornell|static_b1_spp1_sort-retarget_error.png|cornell-direct-static_sort-retarget_error.png"
  "cornell|static_b1_spp1_sort-cycle_error.png|cornell-direct-static_sort-cycle_error.png"
  "cornell|front.png|cornell-front.png"
  "cornell|static_b1_spp1_sort-grid-adaptive_error.png|cornell-direct-static_sort-grid-adaptive_error.png"
  "cornell|static_b1_spp1_radial.png|cornell-direct-static_radial.png"
  "cornell|pan-1_b1_spp1_p1.png|cornell-direct-pan1_p1.png"
  "textured|pan-1_b1_spp1_frames.png|textured-pan_frames.png"
)

usage() { sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; }

quick=0
reuse=0
references=0
only=""
bin=""
while (($#)); do
  case "$1" in
    --quick) quick=1 ;;
    --reuse) reuse=1 ;;
    --references) references=1 ;;
    --bin) [ $# -ge 2 ] || { echo "reproduce: --bin needs a path" >&2; exit 2; }; bin="$2"; shift ;;
    --only) [ $# -ge 2 ] || { echo "reproduce: --only needs a NAME" >&2; exit 2; }; only="$2"; shift ;;
    --only=*) only="${1#--only=}" ;;
    -h | --help) usage; exit 0 ;;
    *) echo "reproduce: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
  shift
done

if ((reuse && references)); then
  echo "reproduce: --reuse runs no eval, --references only evals: choose one" >&2
  exit 2
fi
if [ -n "$bin" ] && [ ! -x "$bin" ]; then
  echo "reproduce: --bin: '$bin' is not an executable file" >&2
  exit 2
fi

names=()
for r in "${RUNS[@]}"; do names+=("${r%%|*}"); done
if [ -n "$only" ]; then
  ok=0
  for n in "${names[@]}"; do [ "$n" = "$only" ] && ok=1; done
  if [ "$ok" -ne 1 ]; then
    echo "reproduce: unknown run '$only' (runs: ${names[*]})" >&2
    exit 2
  fi
fi

if ((quick)); then
  common="--spp 1 --frames 12"
  results_md=out/results/results.md
  figures_dir=out/results/figures
else
  common="--spp 1 --frames 64"
  results_md=docs/results.md
  figures_dir=docs/figures
fi

for m in begin end; do
  for n in "${names[@]}" motion-scenes; do
    if ! grep -qx "<!-- reproduce:$n $m -->" docs/results.md; then
      echo "reproduce: docs/results.md lacks the marker <!-- reproduce:$n $m -->" >&2
      exit 1
    fi
  done
  for n in motion pick motion-scenes; do
    if ! grep -qx "<!-- reproduce:$n $m -->" README.md; then
      echo "reproduce: README.md lacks the marker <!-- reproduce:$n $m -->" >&2
      exit 1
    fi
  done
done

if ((!reuse)) && [ -z "$bin" ]; then
  source scripts/setup.sh
  cargo build --release --locked -p blueshift
  bin="$CARGO_TARGET_DIR/release/blueshift"
fi
mkdir -p out/results "$figures_dir"

tmpfiles=()
cleanup() { ((${#tmpfiles[@]})) && rm -rf "${tmpfiles[@]}"; return 0; }
trap cleanup EXIT

# What each configuration's tables in one report.md add to the headline table, in a few lines
# (the headline's ratios are not repeated): the run's line; per configuration, the largest
# standard error over sequences of any method's two headline ratios (per frame: the first
# table's "P1 emitter-free"; accumulated: the second's "TAA P1"); the lowest per-frame P8 (a
# denoiser's scale); and the range of the RMSE ratios, a check (a permutation only moves
# error). Each method's own standard errors, FLIP, P2, LF, EMA and P4 stay in report.md.
tables() { # report.md
  awk '
    BEGIN { FS = " *[|] *"; ncol = split("1:P1 emitter-free|2:TAA P1|2:P8|1:RMSE", cols, "|") }
    # The standard error of a "ratio ± error" cell; "" for a bare ratio.
    function se(x) { return sub(/.*± */, "", x) ? x : "" }
    NR == 3 { info = $0; sub(/; commit [^;]*;/, ";", info) }
    /^## Per frame/ { skip = 1; next }
    /^## / { skip = 0; cfg = substr($0, 4); ncfg++; cfgs[ncfg] = cfg; tbl = 0; next }
    skip { next }
    /^[|] method [|]/ { tbl++; delete at; for (i = 2; i < NF; i++) at[tbl ":" $i] = i; next }
    /^[|]---/ { next }
    /^[|] / && ncfg > 0 {
      m = $2
      if (!(m in seen)) { seen[m] = 1; nm++; ms[nm] = m }
      for (c = 1; c <= ncol; c++) if (cols[c] in at) v[cols[c], m, cfg] = $(at[cols[c]])
    }
    END {
      if (nm == 0) { print "reproduce: no tables in the report" > "/dev/stderr"; exit 1 }
      print "Run: " info
      ses = ""; p8 = ""; lo = ""; hi = ""
      for (k = 1; k <= ncfg; k++) {
        c = cfgs[k]; f = ""; a = ""; b = ""
        for (i = 1; i <= nm; i++) {
          m = ms[i]
          if (m == "white") continue
          x = se(v["1:P1 emitter-free", m, c]); if (x != "" && (f == "" || x + 0 > f + 0)) f = x
          x = se(v["2:TAA P1", m, c]); if (x != "" && (a == "" || x + 0 > a + 0)) a = x
          x = v["2:P8", m, c]; if (x != "" && (b == "" || x + 0 < bx + 0)) { b = m; bx = x }
          x = v["1:RMSE", m, c]
          if (x == "") continue
          if (lo == "" || x + 0 < lo + 0) { lo = x; lo_at = "`" m "`, " c }
          if (hi == "" || x + 0 > hi + 0) { hi = x; hi_at = "`" m "`, " c }
        }
        if (f != "" || a != "") ses = ses (ses == "" ? "" : "; ") c " " (f == "" ? "-" : f) " / " (a == "" ? "-" : a)
        if (b != "") p8 = p8 (p8 == "" ? "" : "; ") c " `" b "` " bx
      }
      if (ses != "" || p8 != "" || lo != "") print ""
      if (ses != "") print "- Largest standard error over sequences of any ratio above (per frame / accumulated): " ses "."
      if (p8 != "") print "- Lowest P8 ratio to `white` per frame (sigma 8 px, a denoiser'"'"'s scale; pixels more than 24 px from a visible light): " p8 "."
      if (lo != "") print "- RMSE ratio to `white`, all pixels (a permutation only moves error: it should stay within 3%): " lo " (" lo_at ") to " hi " (" hi_at ")."
    }' "$1"
}

# The headline table of one report.md: per frame / accumulated (TAA along the motion, the
# EMA for a still camera) per configuration, with the motion of each.
headline() { # report.md
  awk '/^## Per frame \/ accumulated along the motion/ { on = 1; next } /^## / { on = 0 } on && /^[|]/' "$1"
}

# The same at equal frame time: the ratios times the square root of each method's frame time
# over white's, and that frame-time ratio.
equal_time() { # report.md
  awk '/^## Per frame \/ accumulated at equal frame time/ { on = 1; next } /^## / { on = 0 } on && /^[|]/' "$1"
}

# From a headline table (stdin): per configuration and for the geometric mean over them, the
# named method (preset or comparison baseline) with the lowest per-frame and the lowest
# accumulated ratio (spelled-out experiment forms and `white` left out), and the default's own
# figures.
picks() {
  awk -v default_method=sort-cycle '
    BEGIN { FS = " *[|] *" }
    /^[|] method [|]/ { for (i = 3; i < NF; i++) cfg[i] = $i; nc = NF - 1; next }
    /^[|]---/ || /^[|] [*]/ { next }
    /^[|] / {
      m = $2
      if (m == "white" || m ~ /:/) next
      lf = 0; la = 0
      for (i = 3; i <= nc; i++) {
        split($i, v, " / ")
        f[m, i] = v[1]; a[m, i] = v[2]
        lf += log(v[1]); la += log(v[2])
      }
      f[m, "mean"] = sprintf("%.3f", exp(lf / (nc - 2))); a[m, "mean"] = sprintf("%.3f", exp(la / (nc - 2)))
      ms[++nm] = m
    }
    END {
      cfg["mean"] = "geometric mean"
      for (i = 3; i <= nc; i++) cols[++ncol] = i
      cols[++ncol] = "mean"
      line = "| best |"; rule = "|---|"
      for (k = 1; k <= ncol; k++) { line = line " " cfg[cols[k]] " |"; rule = rule "---|" }
      print line; print rule
      lf = "| per frame |"; la = "| accumulated |"; ld = "| `" default_method "` (default) |"
      for (k = 1; k <= ncol; k++) {
        c = cols[k]; bf = ""; ba = ""
        for (j = 1; j <= nm; j++) {
          m = ms[j]
          if (bf == "" || f[m, c] + 0 < f[bf, c] + 0) bf = m
          if (ba == "" || a[m, c] + 0 < a[ba, c] + 0) ba = m
        }
        lf = lf " `" bf "` " f[bf, c] " |"; la = la " `" ba "` " a[ba, c] " |"
        ld = ld " " f[default_method, c] " / " a[default_method, c] " |"
      }
      print lf; print la; print ld
    }'
}

# From "SCENE=report.md" arguments: one row per configuration under motion (strafe columns of
# each headline table) with the best preset per frame and accumulated, and the default's and
# the free masks' own figures (per frame / TAA; standard errors left out).
motion_rows() {
  local a
  echo "| configuration | best per frame | best after TAA | \`sort-cycle\` (default) | \`stbn\` | \`mask-r2\` |"
  echo "|---|---|---|---|---|---|"
  {
    local n=0 scenes=" "
    for a in "$@"; do
      # a scene's rank: the position of its first argument
      [[ "$scenes" == *" ${a%%=*} "* ]] || { n=$((n + 1)); scenes+="${a%%=*} "; }
      headline "${a#*=}" | awk -v scene="${a%%=*}" -v order="$n" '
        BEGIN { FS = " *[|] *" }
        function num(x) { sub(/ *±.*/, "", x); return x }
        /^[|] method [|]/ { for (i = 3; i < NF; i++) cfg[i] = $i; nc = NF - 1; next }
        /^[|]---/ || /^[|] [*]/ { next }
        /^[|] / {
          m = $2
          if (m == "white" || m ~ /:/) next
          ms[++nm] = m
          for (i = 3; i <= nc; i++) { split($i, v, " / "); f[m, i] = num(v[1]); a[m, i] = num(v[2]) }
        }
        END {
          for (i = 3; i <= nc; i++) {
            if (cfg[i] !~ /^strafe/) continue
            bf = ""; ba = ""
            for (j = 1; j <= nm; j++) {
              m = ms[j]
              if (bf == "" || f[m, i] + 0 < f[bf, i] + 0) bf = m
              if (ba == "" || a[m, i] + 0 < a[ba, i] + 0) ba = m
            }
            c = cfg[i]; sub(/ spp1$/, "", c)
            # sort keys: scene (argument order), px/frame, bounces
            split(c, part, /[: ]b?/)
            line = order "\t" part[2] "\t" part[3] "\t"
            line = line "| " scene " " c " | `" bf "` " f[bf, i] " | `" ba "` " a[ba, i] " |"
            split("sort-cycle stbn mask-r2", show, " ")
            for (k = 1; k <= 3; k++) line = line " " f[show[k], i] " / " a[show[k], i] " |"
            print line
          }
        }'
    done | sort -t "$(printf '\t')" -k1,1n -k2,2n -k3,3n | cut -f4-
  }
}

source tools/splice.sh

# The runs to make: all, or the one --only names.
selected=()
for r in "${RUNS[@]}"; do
  if [ -z "$only" ] || [ "${r%%|*}" = "$only" ]; then selected+=("$r"); fi
done

# --references: each run's cameras, scenes and bounces with `white` alone and one sequence,
# which renders (and caches) every reference the full run will read.
if ((references)); then
  for r in "${selected[@]}"; do
    name="${r%%|*}"
    args="$(sed -E 's/--methods [^ ]+/--methods white/; s/--sequences [0-9]+/--sequences 1/' <<< "${r#*|}")"
    scratch="$(mktemp -d out/results/.$name.refs.XXXXXX)"
    tmpfiles+=("$scratch")
    echo "== $name (references): blueshift eval $args $common"
    # shellcheck disable=SC2086 # the argument lists are word-split on purpose
    "$bin" eval $args $common --out "$scratch"
  done
  echo "reproduce: references cached for: ${selected[*]%%|*}"
  exit 0
fi

# Every eval first: the docs are read only once they are done, so edits made to them during a
# long run are kept.
for r in "${selected[@]}"; do
  name="${r%%|*}"
  args="${r#*|}"
  out="out/results/$name"
  stage="out/results/.$name.new"
  if ((reuse)); then
    [ -f "$out/report.md" ] || { echo "reproduce: --reuse: no $out/report.md" >&2; exit 1; }
  else
    rm -rf "$stage"
    tmpfiles+=("$stage")
    echo "== $name: blueshift eval $args $common"
    # shellcheck disable=SC2086 # the argument lists are word-split on purpose
    "$bin" eval $args $common --out "$stage"
    rm -rf "$out"
    mv "$stage" "$out"
  fi
done

# The new results.md is assembled in a temporary file beside its destination.
work="$(mktemp "$results_md.XXXXXX.tmp")"
tmpfiles+=("$work")
cp docs/results.md "$work"
chmod 644 "$work"

for r in "${selected[@]}"; do
  name="${r%%|*}"
  args="${r#*|}"
  out="out/results/$name"

  body="$(mktemp "out/results/.$name.body.XXXXXX")"
  tmpfiles+=("$body")
  head_body="$(mktemp "out/results/.$name.head.XXXXXX")"
  tmpfiles+=("$head_body")
  {
    echo
    echo "Command: \`blueshift eval $args $common --out out/results/$name\`"
    echo
    echo "**Emitter-free P1 ratio to \`white\`: per frame / accumulated (TAA along the motion; the EMA for a still camera)**"
    echo
    headline "$out/report.md"
    echo
    echo "**At equal frame time: the same times the square root of the frame-time ratio to \`white\` (in parentheses)**"
    echo
    equal_time "$out/report.md"
    echo
    tables "$out/report.md"
    echo
  } > "$body"
  splice "reproduce:$name" "$work" "$body"
  if [ "$name" = motion ] && ((!quick)); then
    # README shows the named methods; the ablation rows (`PRESET:field=value`) stay in
    # docs/results.md.
    { echo; headline "$out/report.md" | awk -F'|' '$2 !~ /:/'; echo; } > "$head_body"
    splice "reproduce:$name" README.md "$head_body"
    { echo; headline "$out/report.md" | picks; echo; } > "$head_body"
    splice reproduce:pick README.md "$head_body"
  fi

  for f in "${FIGURES[@]}"; do
    IFS='|' read -r fname src dst <<< "$f"
    [ "$fname" = "$name" ] || continue
    if [ -f "$out/$src" ]; then
      cp "$out/$src" "$figures_dir/.$dst.tmp"
      mv "$figures_dir/.$dst.tmp" "$figures_dir/$dst"
    else
      echo "reproduce: warning: $out/$src not found, $figures_dir/$dst not updated" >&2
    fi
  done
done

# Under motion across scenes and speeds, from the four motion runs' reports; while any is
# missing (a machine that ran only some of them) the table is left as it was rather than
# written without that run's rows.
if ((!quick)); then
  scenes=()
  missing=()
  for s in cornell=motion cornell=motion-speeds textured=motion-textured edges=motion-edges; do
    if [ -f "out/results/${s#*=}/report.md" ]; then
      scenes+=("${s%%=*}=out/results/${s#*=}/report.md")
    else
      missing+=("${s#*=}")
    fi
  done
  if ((${#missing[@]})); then
    echo "reproduce: the motion-scenes table is left as it was: no report for ${missing[*]}" >&2
  else
    rows_body="$(mktemp out/results/.motion-scenes.XXXXXX)"
    tmpfiles+=("$rows_body")
    { echo; motion_rows "${scenes[@]}"; echo; } > "$rows_body"
    splice reproduce:motion-scenes "$work" "$rows_body"
    splice reproduce:motion-scenes README.md "$rows_body"
  fi
fi

mv "$work" "$results_md"
echo "reproduce: wrote $results_md and $figures_dir/"
