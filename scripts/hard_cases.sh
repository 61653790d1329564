#!/usr/bin/env bash
# Run every hard-case scene of docs/stability.md at full length (and the reduced model where it
# applies) and write build/hard_cases/<case>.csv, .log; then scripts/stability_report.py prints the
# table of docs/stability.md. About 10 minutes on the 2-core machine. Needs a build.
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SIM="${SIM:-$ROOT/build/ws/devel/lib/crane_twin/crane_sim}"  # SIM=... to run another build
OUT="$ROOT/build/hard_cases"
S="$ROOT/config/scenes"
mkdir -p "$OUT"
run() {  # name scene [--set ...]
  local name="$1" scene="$2"; shift 2
  echo "hard_cases: $name"
  "$SIM" run "$S/$scene" "$@" --quiet --out "$OUT/$name.csv" >"$OUT/$name.log" 2>&1
  echo "exit_status=$?" >>"$OUT/$name.log"
}
run swing_30deg hard_swing_30deg.yaml
run swing_30deg_reduced hard_swing_30deg.yaml --set rope.model=reduced
run swing_60deg hard_swing_60deg.yaml
run swing_60deg_reduced hard_swing_60deg.yaml --set rope.model=reduced
run short_rope_2m hard_short_rope_2m.yaml
run slack_throw hard_slack_throw.yaml
run stress_free_heavy hard_stress_free_heavy.yaml
run emergency_stop_slew hard_emergency_stop_slew.yaml
run emergency_stop_slew_reduced hard_emergency_stop_slew.yaml --set rope.model=reduced
run emergency_stop_trolley hard_emergency_stop_trolley.yaml
run hoist_60_3_60 hard_hoist_60_3_60.yaml
run hoist_60_3_60_reduced hard_hoist_60_3_60.yaml --set rope.model=reduced
run one_hour_undamped hard_one_hour_undamped.yaml
run large_step hard_large_step.yaml
run large_step_reduced hard_large_step.yaml --set rope.model=reduced
run random_commands hard_random_commands.yaml
run random_commands_reduced hard_random_commands.yaml --set rope.model=reduced
run falling_rope hard_falling_rope.yaml
run random_landed hard_random_landed.yaml
run random_landed_reduced hard_random_landed.yaml --set rope.model=reduced
# The paper's subdomains in the chord's frame (the paper scenes' setting) on the swings and the
# large step.
for c in swing_30deg swing_60deg large_step; do
  run "${c}_reduced_corotational" "hard_$c.yaml" --set rope.model=reduced --set rope.mode_count=10 \
    --set rope.reduction=subdomains --set rope.subdomain_frame=corotational
done
# The pendulum rope (the ladder's cheapest rung) on the cases where a straight bar makes sense.
for c in swing_60deg short_rope_2m slack_throw emergency_stop_slew emergency_stop_trolley \
         hoist_60_3_60 one_hour_undamped large_step random_commands random_landed; do
  run "${c}_pendulum" "hard_$c.yaml" --set rope.model=pendulum
done
run stress_free_heavy_rigid_pendulum hard_stress_free_heavy.yaml --set rope.model=pendulum --set structure.model=rigid
/usr/bin/python3 "$ROOT/scripts/stability_report.py" "$OUT"
