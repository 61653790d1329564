#!/usr/bin/env bash
# The table of docs/accuracy-vs-time.md "Slack and snatch": every scene whose rope unloads, run at
# full order with the tension-only law (the default), at full order with the symmetric law and
# with the default reduced rope, one after the other (read ratios within a row). Per scene one
# Markdown row: tension-only wall s (energy-consistent steps, halved steps, energy rise), the
# symmetric law's wall s, their ratio, the reduced run's wall s (hand-overs, full-order steps,
# energy rise), its payload / rope RMS error against the tension-only full run (crane_sim
# compare), and the symmetric run's payload distance from the tension-only one.
#   scripts/slack_and_snatch.sh            (about 2 minutes on the 2-core machine)
#   REFINE=8 scripts/slack_and_snatch.sh   (one more column, about 8 minutes more: the tension-only
#                                           full run at an eighth of the scene's step, its payload /
#                                           rope RMS distance from the run at the scene's step)
#   SPREAD=1e-6 scripts/slack_and_snatch.sh (one more column, about 2 minutes more: the tension-only
#                                           full run with its start's swing turned SPREAD deg more
#                                           (1e-6 deg moves a payload on 60 m by 1 um), its payload /
#                                           rope RMS distance from the run as given: how far full
#                                           order parts from itself after a perturbation at round-off)
# CRANE_SIM overrides the binary (default build/core/crane_sim).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SIM="${CRANE_SIM:-$ROOT/build/core/crane_sim}"
C="$ROOT/config/scenes"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT

summary() { sed -n "s/^summary: .*\<$2=\([^ ]*\).*/\1/p" "$OUT/$1.log"; }
# The largest energy above the start [J] (none of these scenes has a drive).
rise() {
  /usr/bin/python3 - "$OUT/$1.csv" <<'EOF'
import csv, sys
e = [float(r["energy"]) for r in csv.DictReader(open(sys.argv[1]))]
print("%.2g J" % max(0.0, max(e) - e[0]))
EOF
}
taken_back() {  # hand-overs, with the speculative hand-backs taken back where any
  awk -v h="$(summary "$1" hand_overs)" -v k="$(summary "$1" taken_back)" \
    'BEGIN {printf "%s%s", h, (k > 0 ? " (" k " taken back)" : "")}'
}
REFINE="${REFINE:-}"
if [ -n "$REFINE" ] && ! [[ "$REFINE" =~ ^[1-9][0-9]*$ && "$REFINE" -gt 1 ]]; then
  echo "REFINE must be an integer above 1 (the step's divisor), got '$REFINE'" >&2
  exit 2
fi
SPREAD="${SPREAD:-}"
if [ -n "$SPREAD" ] && ! awk -v d="$SPREAD" 'BEGIN {exit !(d + 0 > 0 && d + 0 < 1)}'; then
  echo "SPREAD must be a swing angle in (0, 1) deg, got '$SPREAD'" >&2
  exit 2
fi
compare() {  # a b -> "payload / rope RMS"
  "$SIM" compare "$OUT/$1.csv" "$OUT/$2.csv" --nodes-a "$OUT/$1_n.csv" --nodes-b "$OUT/$2_n.csv" |
    awk -F, '/^payload_error_max/ {p = $2} /^rope_rms_max/ {r = $2} END {printf "%.2g / %.2g", p, r}'
}
run_as() {  # name scene [--set ...]: one run into $OUT/name.csv, name_n.csv and name.log
  local name="$1" scene="$2"
  shift 2
  "$SIM" run "$C/$scene.yaml" "$@" --out "$OUT/$name.csv" --nodes "$OUT/${name}_n.csv" \
    --quiet > "$OUT/$name.log" 2>&1 || echo "exit=$?" >> "$OUT/$name.log"
}
row() {  # label scene swing_deg [--set ...]
  local label="$1" scene="$2" swing="$3" v
  shift 3
  set -- --set initial.swing_deg="$swing" "$@"
  for v in full symmetric reduced; do
    local sets=(--set rope.model=full)
    [ "$v" = symmetric ] && sets+=(--set rope.tension_only=false)
    [ "$v" = reduced ] && sets=(--set rope.model=reduced)
    run_as "$v" "$scene" "$@" "${sets[@]}"
  done
  local refined=""
  if [ -n "$REFINE" ]; then
    local h
    # (the full run's own step: its simulated time over its steps)
    h=$(awk -v t="$(summary full sim_s)" -v k="$(summary full steps)" -v n="$REFINE" \
      'BEGIN {printf "%.10g", t / k / n}')
    run_as refined "$scene" "$@" --set rope.model=full --set time_step="$h"
    refined=" $(compare full refined) |"
  fi
  local spread=""
  if [ -n "$SPREAD" ]; then
    run_as spread "$scene" "$@" --set rope.model=full \
      --set initial.swing_deg="$(awk -v a="$swing" -v d="$SPREAD" 'BEGIN {printf "%.12g", a + d}')"
    spread=" $(compare spread full) |"
  fi
  local wf ws
  wf=$(summary full wall_s)
  ws=$(summary symmetric wall_s)
  printf '| %s | %s (%s, %s, %s) | %s | %s | %s (%s, %s, %s) | %s | %s |%s%s\n' "$label" "$wf" \
    "$(summary full energy_consistent_steps)" "$(summary full halved_steps)" "$(rise full)" "$ws" \
    "$(awk -v a="$wf" -v b="$ws" 'BEGIN{if (b > 0) printf "%.2f", a / b}')" \
    "$(summary reduced wall_s)" "$(taken_back reduced)" \
    "$(summary reduced full_order_steps)" "$(rise reduced)" "$(compare reduced full)" \
    "$(compare symmetric full | cut -d' ' -f1)" "$refined" "$spread"
}

head="| scene | tension-only full: wall s (e-c steps, halved, rise) | symmetric full wall s | ratio | default reduced: wall s (hand-overs, full-order steps, rise) | reduced payload / rope RMS error m | symmetric vs tension-only payload m |"
rule="| --- | --- | --- | --- | --- | --- | --- |"
if [ -n "$REFINE" ]; then
  head+=" tension-only full at 1/$REFINE of the step vs full: payload / rope RMS m |"
  rule+=" --- |"
fi
if [ -n "$SPREAD" ]; then
  head+=" tension-only full, start's swing $SPREAD deg more, vs full: payload / rope RMS m |"
  rule+=" --- |"
fi
echo "$head"
echo "$rule"
row '`rope_pendulum_chrono` (stress-free release, 60 m, 3.6 t, 120 el, 1 ms, 20 s)' \
  rope_pendulum_chrono 2.3
row '60 deg release, 3.6 t on 60 m from an anchor, 120 el, 1 ms, 20 s' rope_pendulum_chrono 60 \
  --set initial.mode=equilibrium
row '`hard_swing_60deg` (T8036, 60 deg release, 20 s)' hard_swing_60deg 60
row '40 deg release on the T8036 (`t8036_combination1`, 20 s)' t8036_combination1 40 \
  --set duration=20
row '12.5 t released stress-free from a rigid anchor (`hard_stress_free_heavy`, rigid structure, 20 s)' \
  hard_stress_free_heavy 0 --set structure.model=rigid --set duration=20
row '`hard_slack_throw` (combination 2, 12.5 t thrown up at 3 m/s, 10 s)' hard_slack_throw 0
row 'falling rope (60 m, no payload, released horizontal, 120 el, 0.5 ms, 5 s)' \
  hard_falling_rope 90 --set rope.elements=120 --set time_step=0.0005 --set duration=5
