#!/usr/bin/env bash
# The default reduced rope and the pendulum rope against full order on the shipped scenes
# (docs/accuracy-vs-time.md, "Operation"): for each line of the list (name scene duration
# [--set k=v ...]) the three models at the scene's own step; per model its wall time (crane_sim's
# summary) and its payload, rope RMS and top-tension errors against full order (crane_sim
# compare); for the reduced run also the speed-up and its hand-overs. One Markdown table row per
# scene, in the list's order.
#   scripts/reduced_vs_full.sh [LIST] [JOBS]     (defaults: config/operation_scenes.txt, 2)
# A list line is split at blanks (xargs): quote a value with blanks,
#   --set "commands=[{t: 0, slew_rate: 0.05}]".
# CRANE_SIM overrides the binary (default build/core/crane_sim). REFERENCE_DT=DT [s] adds a last
# column, full order's own step error: full order at DT (e.g. half the scenes' step) against full
# order at the scene's step, payload / rope RMS [m] (a reduced error above 1 cm within it is the
# reference's, not the reduction's; docs/accuracy-vs-time.md "Load handling").
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
LIST="${1:-$ROOT/config/operation_scenes.txt}"
JOBS="${2:-2}"
SIM="${CRANE_SIM:-$ROOT/build/core/crane_sim}"
REFERENCE_DT="${REFERENCE_DT:-}"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
one() {
  local index=$1 name=$2 scene=$3 dur=$4
  shift 4
  local m
  for m in full reduced pendulum; do
    "$SIM" run "$ROOT/config/scenes/$scene.yaml" --set duration="$dur" --set rope.model="$m" "$@" \
      --out "$OUT/${name}_$m.csv" --nodes "$OUT/${name}_${m}_nodes.csv" --quiet \
      > "$OUT/${name}_$m.log" 2>&1 || echo "exit=$?" >> "$OUT/${name}_$m.log"
  done
  if [ -n "$REFERENCE_DT" ]; then
    "$SIM" run "$ROOT/config/scenes/$scene.yaml" --set duration="$dur" --set rope.model=full "$@" \
      --set time_step="$REFERENCE_DT" --out "$OUT/${name}_fine.csv" \
      --nodes "$OUT/${name}_fine_nodes.csv" --quiet > "$OUT/${name}_fine.log" 2>&1 ||
      echo "exit=$?" >> "$OUT/${name}_fine.log"
  fi
  # A run that exits non-zero (a scene refused with exit 2, a failure) gets a row that says so,
  # with the first such run's exit code and error line, instead of blank columns.
  local failed="" first=""
  for m in full reduced pendulum; do
    if grep -q '^exit=' "$OUT/${name}_$m.log"; then
      failed+="${failed:+, }$m"
      [ -n "$first" ] || first="exit $(sed -n 's/^exit=//p' "$OUT/${name}_$m.log" | head -n1): $(
        grep -m1 -i 'error' "$OUT/${name}_$m.log" | tr '|' '/')"
    fi
  done
  if [ -n "$failed" ]; then
    printf '%05d| %s | %s | not compared (%s): %s |\n' "$index" "$name" "$dur" "$failed" "$first"
    return 0
  fi
  wall() { sed -n 's/^summary: wall_s=\([^ ]*\).*/\1/p' "$OUT/${name}_$1.log"; }
  errs() {
    "$SIM" compare "$OUT/${name}_$1.csv" "$OUT/${name}_full.csv" \
      --nodes-a "$OUT/${name}_$1_nodes.csv" --nodes-b "$OUT/${name}_full_nodes.csv" |
      awk -F, '/^payload_error_max|^rope_rms_max|^tension_error_relative/ {printf "%.2g | ", $2}'
  }
  local wf wr wp ho
  wf=$(wall full); wr=$(wall reduced); wp=$(wall pendulum)
  # (hand-overs, with the speculative hand-backs taken back where any, and full-order steps)
  ho=$(sed -n 's/.*hand_overs=\([^ ]*\) taken_back=\([^ ]*\) full_order_steps=\([^ ]*\).*/\1 \2 \3/p' \
    "$OUT/${name}_reduced.log" |
    awk '{printf "%s%s | %s", $1, ($2 > 0 ? " (" $2 " taken back)" : ""), $3}')
  local spread=""
  if [ -n "$REFERENCE_DT" ]; then
    spread="$(errs fine | awk -F' [|] ' '{printf "%s / %s |", $1, $2}')"
  fi
  printf '%05d| %s | %s | %s | %s | %s | %s | %s%s | %s%s\n' "$index" "$name" "$dur" "$wf" "$wr" \
    "$(awk -v a="$wf" -v b="$wr" 'BEGIN{if (b > 0) printf "%.1f", a / b}')" "$ho" "$(errs reduced)" \
    "$wp" "$(errs pendulum)" "$spread"
}
export -f one
export ROOT SIM OUT REFERENCE_DT
if [ -n "$REFERENCE_DT" ]; then
  echo "| scene | sim s | full wall s | reduced wall s | speed-up | hand-overs | full-order steps | payload error m | rope RMS error m | tension error | pendulum wall s | pendulum payload error m | pendulum rope RMS m | pendulum tension error | full at ${REFERENCE_DT} s vs full: payload / rope RMS m |"
  echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
else
  echo "| scene | sim s | full wall s | reduced wall s | speed-up | hand-overs | full-order steps | payload error m | rope RMS error m | tension error | pendulum wall s | pendulum payload error m | pendulum rope RMS m | pendulum tension error |"
  echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
fi
grep -v '^#' "$LIST" | grep . | awk '{print NR, $0}' | xargs -P "$JOBS" -L1 bash -c 'one "$@"' _ |
  sort | cut -c6-
