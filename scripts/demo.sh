#!/usr/bin/env bash
# The main demo: install, build, start a ROS master if none runs, and run the default
# T8036 scene (config/scenes/t8036_live.yaml: the default reduced rope, 5 ms steps) through crane_sim_node
# for 20 s of simulated time at real time, driven by scripts/operator_profile.py (trolley in,
# then slewing, then the command timeout), with rviz when a display exists. The run is recorded
# (build/demo/demo.bag); the applied commands are then replayed by crane_sim at full order and
# compared with the node's reduced run (the error metrics of docs/accuracy-vs-time.md). Writes
# build/demo/summary.txt and build/demo/histories.png (payload, cab and jib-tip histories of both
# runs).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SCENE="${1:-$ROOT/config/scenes/t8036_live.yaml}"
DURATION="${DEMO_DURATION:-20}"
bash "$ROOT/scripts/install_deps.sh"
bash "$ROOT/scripts/build.sh"
# shellcheck disable=SC1091
source "$ROOT/scripts/ros_env.sh"
SIM="$ROOT/build/ws/devel/lib/crane_twin/crane_sim"
OUT="$ROOT/build/demo"
mkdir -p "$OUT"
rm -f "$OUT/demo.bag"

ensure_ros_master "$OUT/roscore.log"

RVIZ=false
if [ -n "${DISPLAY:-}" ] && xdpyinfo >/dev/null 2>&1; then RVIZ=true; fi
echo "demo: crane_sim_node on $SCENE for $DURATION s (rviz: $RVIZ), recording $OUT/demo.bag"
roslaunch crane_twin sim.launch scene:="$SCENE" rviz:="$RVIZ" record:=true bag:="$OUT/demo.bag" \
  duration:="$DURATION" shutdown_at_end:=true start_paused:=true >"$OUT/launch.log" 2>&1 &
LAUNCH=$!
rosrun crane_twin operator_profile.py --end 15 >"$OUT/operator.log" 2>&1 &
OPERATOR=$!
wait "$LAUNCH" || true
kill "$OPERATOR" 2>/dev/null || true
for _ in $(seq 50); do [ -f "$OUT/demo.bag" ] && break; sleep 0.2; done
[ -f "$OUT/demo.bag" ] || { echo "demo: no bag recorded; see $OUT/launch.log" >&2; exit 1; }

/usr/bin/python3 "$ROOT/scripts/bag_to_series.py" "$OUT/demo.bag" --series "$OUT/node_reduced.csv" \
  --commands "$OUT/commands.yaml" --stats >"$OUT/node_stats.txt"
{
  echo "# crane_sim_node run, recorded: rosbag info $OUT/demo.bag"
  rosbag info "$OUT/demo.bag" | grep -E "duration|messages|topics|^ +/"
  echo "# node statistics (crane/state): scripts/bag_to_series.py demo.bag --stats"
  cat "$OUT/node_stats.txt"
  # A row every step, as the node's states fall on steps.
  STEP=$(/usr/bin/python3 -c "import sys, yaml; print(yaml.safe_load(open(sys.argv[1]))['time_step'])" "$SCENE")
  echo "# the node's applied commands replayed at full order by crane_sim:"
  echo "#   crane_sim run $SCENE --set duration=$DURATION --set rope.model=full --set output_interval=$STEP --set commands=<commands.yaml>"
  "$SIM" run "$SCENE" --set duration="$DURATION" --set rope.model=full --set output_interval="$STEP" \
    --set "commands=$(cat "$OUT/commands.yaml")" --out "$OUT/cli_full.csv" --quiet
  echo "# crane_sim compare node_reduced.csv cli_full.csv (error metrics of" \
    "docs/accuracy-vs-time.md at the node's output times)"
  "$SIM" compare "$OUT/node_reduced.csv" "$OUT/cli_full.csv"
  echo "# last state"
  tail -1 "$OUT/node_reduced.csv" | awk -F, '{printf "t=%s payload=(%.3f, %.3f, %.3f) slew_angle=%.4f trolley_radius=%.3f tension=%.0f N\n", $1, $2, $3, $4, $19, $20, $17}'
} | tee "$OUT/summary.txt"
/usr/bin/python3 "$ROOT/scripts/plot_series.py" "$OUT/histories.png" "$OUT/cli_full.csv" "$OUT/node_reduced.csv"
echo "demo: summary in $OUT/summary.txt, plot in $OUT/histories.png, bag $OUT/demo.bag"
