# Sourced by tools/reproduce.sh and tools/bench.sh: generated text goes between marker lines.
#
#   splice MARKER FILE BODY   replaces the lines between "<!-- MARKER begin -->" and
#                             "<!-- MARKER end -->" in FILE by the file BODY (atomically)
splice() {
  local begin="<!-- $1 begin -->" end="<!-- $1 end -->" tmp
  grep -qxF "$begin" "$2" && grep -qxF "$end" "$2" ||
    { echo "splice: $2 lacks the $1 markers" >&2; return 1; }
  tmp="$(mktemp "$2.XXXXXX.tmp")"
  chmod --reference="$2" "$tmp"
  if awk -v begin="$begin" -v end="$end" -v body="$3" '
    $0 == begin { print; while ((getline line < body) > 0) print line; skip = 1; next }
    $0 == end { skip = 0 }
    !skip { print }' "$2" > "$tmp"; then
    mv "$tmp" "$2"
  else
    rm -f "$tmp"
    return 1
  fi
}
