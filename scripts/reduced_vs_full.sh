#!/usr/bin/env bash
# The default reduced rope against full order on the shipped scenes (docs/accuracy-vs-time.md,
# "Operation"): for each line of the list (name scene duration [--set k=v ...]) both models at
# the scene's own step, their wall times (crane_sim's summary), the speed-up, the reduced run's
# hand-overs and the payload / rope RMS errors (crane_sim compare). One table row per scene.
#   scripts/reduced_vs_full.sh [LIST] [JOBS]     (defaults: config/operation_scenes.txt, 2)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
LIST="${1:-$ROOT/config/operation_scenes.txt}"
JOBS="${2:-2}"
SIM="${CRANE_SIM:-$ROOT/build/core/crane_sim}"
OUT="$(mktemp -d)"
one() {
  local name=$1 scene=$2 dur=$3
  shift 3
  for m in full reduced; do
    "$SIM" run "$ROOT/config/scenes/$scene.yaml" --set duration="$dur" --set rope.model="$m" "$@" \
      --out "$OUT/${name}_$m.csv" --nodes "$OUT/${name}_${m}_nodes.csv" --quiet \
      > "$OUT/${name}_$m.log" 2>&1 || echo "exit=$?" >> "$OUT/${name}_$m.log"
  done
  local wf wr ho cmp
  wf=$(sed -n 's/^summary: wall_s=\([^ ]*\).*/\1/p' "$OUT/${name}_full.log")
  wr=$(sed -n 's/^summary: wall_s=\([^ ]*\).*/\1/p' "$OUT/${name}_reduced.log")
  ho=$(sed -n 's/.*hand_overs=\([^ ]*\) full_order_steps=\(.*\)/\1 | \2/p' "$OUT/${name}_reduced.log")
  cmp=$("$SIM" compare "$OUT/${name}_reduced.csv" "$OUT/${name}_full.csv" \
        --nodes-a "$OUT/${name}_reduced_nodes.csv" --nodes-b "$OUT/${name}_full_nodes.csv" |
        awk -F, '/payload_error_max|rope_rms_max/ {printf "%.2g | ", $2}')
  echo "| $name | $dur | $wf | $wr | $(awk -v a="$wf" -v b="$wr" 'BEGIN{if (b>0) printf "%.1f", a/b}') | $ho | $cmp"
}
export -f one
export ROOT SIM OUT
echo "| scene | sim s | full wall s | reduced wall s | speed-up | hand-overs | full-order steps | payload error m | rope RMS error m |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
grep -v '^#' "$LIST" | grep . | xargs -P "$JOBS" -L1 bash -c 'one "$@"' _
