#!/usr/bin/env bash
# Regenerate test/data/full_order_run.bag, the recorded full-order run the rostest
# replay_matches_full_order.test replays into the reduced simulator: the default live scene at
# full order (rope.model=full), driven for 20 s of simulated time by scripts/operator_profile.py
# (trolley in at 0.8 m/s, then slewing at 0.06 rad/s, then the command timeout), recorded by
# record.launch (crane/state, crane/command, crane/command_applied). /clock is published, so
# header stamps are simulated time, as in the replay. Needs a build.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="${1:-$ROOT/test/data/full_order_run.bag}"
# shellcheck disable=SC1091
source "$ROOT/scripts/ros_env.sh"
ensure_ros_master /dev/null
rm -f "$OUT"
roslaunch crane_twin sim.launch rviz:=false record:=true bag:="$OUT" \
  record_topics:="/crane/state /crane/command /crane/command_applied" record_markers:=false \
  overrides:="[rope.model=full]" duration:=20 shutdown_at_end:=true start_paused:=true \
  publish_clock:=true &
LAUNCH=$!
rosrun crane_twin operator_profile.py &
OPERATOR=$!
wait "$LAUNCH" || true
kill "$OPERATOR" 2>/dev/null || true
for _ in $(seq 50); do [ -f "$OUT" ] && break; sleep 0.2; done
rosbag info "$OUT"
