#!/usr/bin/env bash
# sim.launch with record:=true as fast as possible (docs/ros.md "Recording"): the bag starts at
# t = 0 (the node holds its first step until the recorder listens), holds every state and rope
# marker the node published (it paces itself to crane_recorder), also with a busy core beside it
# and on a replay of a recorded run;
# roslaunch ends with the node at the scene's end, exit status 0 and no "REQUIRED process has
# died" (the node stops the launch as Ctrl-C would), and /use_sim_time is left false; a pendulum
# rope runs too, with its forecast. Runs its own master on
# a free port. Run in the workspace's environment (ctest: devel/env.sh).
set -uo pipefail
export PYENV_VERSION=system
export PATH="/usr/bin:$PATH"
T="$(mktemp -d)"
PORT=$((20000 + RANDOM % 20000))
export ROS_MASTER_URI="http://localhost:$PORT"
roscore -p "$PORT" >"$T/core.log" 2>&1 &
CORE=$!
trap 'kill $CORE 2>/dev/null; wait $CORE 2>/dev/null; rm -rf "$T"' EXIT
fail() { echo "record_from_start_test: FAILED: $*"; exit 1; }
for _ in $(seq 100); do rosparam list >/dev/null 2>&1 && break; sleep 0.2; done
timeout 300 roslaunch crane_twin sim.launch rviz:=false record:=true bag:="$T/run.bag" \
  real_time_factor:=0 duration:=5 shutdown_at_end:=true overrides:="[rope.elements=40]" \
  >"$T/launch.log" 2>&1
LAUNCH_STATUS=$?
[ "$LAUNCH_STATUS" -eq 0 ] || fail "roslaunch exit status $LAUNCH_STATUS: $(tail -20 "$T/launch.log")"
if grep -q "REQUIRED process" "$T/launch.log"; then fail "a normal end reported as a died process"; fi
grep -q "the scene ended (shutdown_at_end): stopping the launch" "$T/launch.log" ||
  fail "the node did not end the launch: $(tail -20 "$T/launch.log")"
for _ in $(seq 50); do [ -f "$T/run.bag" ] && break; sleep 0.2; done
[ -f "$T/run.bag" ] || fail "no bag: $(tail -20 "$T/launch.log")"
/usr/bin/python3 - "$T/run.bag" <<'PY' || fail "bag contents"
import sys, rosbag
bag = rosbag.Bag(sys.argv[1])
ts = [m.t for _, m, _ in bag.read_messages(topics=["/crane/state"])]
ropes = sum(1 for _ in bag.read_messages(topics=["/crane/rope"]))
print("states", len(ts), "first t", ts[0] if ts else None, "last t", ts[-1] if ts else None,
      "rope markers", ropes)
assert ts and ts[0] < 0.1, "the bag does not start at t = 0"
assert ts[-1] > 4.9, "the bag does not reach the end"
n = 5 * 30 + 1  # t = 0, 1/30, ..., 5 s
assert len(ts) == n, "states missing: %d of %d (30 Hz of simulated time)" % (len(ts), n)
gaps = [b - a for a, b in zip(ts, ts[1:])]
assert max(gaps) < 1.5 / 30 and min(gaps) > 0.5 / 30, "a hole or a repeat in the states"
assert ropes == n, "rope markers missing: %d of %d" % (ropes, n)
PY
grep -q "holds every message we published" "$T/launch.log" ||
  fail "the node did not confirm the bag holds every message: $(grep crane_record "$T/launch.log" | tail -3)"
# The same, replaying a recorded 20 s run with two busy processes beside it (a recorder that
# falls behind holds the run; rosbag record lost 1.27 s of 20 here in 1 of 2 runs).
busy() { while :; do :; done; }
busy & B1=$!
busy & B2=$!
timeout 300 roslaunch crane_twin replay.launch bag:="$(rospack find crane_twin)/test/data/full_order_run.bag" \
  real_time_factor:=0 rviz:=false duration:=20 shutdown_at_end:=true record:=true \
  record_bag:="$T/replay.bag" >"$T/replay.log" 2>&1
REPLAY_STATUS=$?
kill $B1 $B2; wait $B1 $B2 2>/dev/null
[ "$REPLAY_STATUS" -eq 0 ] || fail "replay exit status $REPLAY_STATUS: $(tail -20 "$T/replay.log")"
/usr/bin/python3 - "$T/replay.bag" <<'PY' || fail "replay bag contents"
import sys, rosbag
ts = [m.t for _, m, _ in rosbag.Bag(sys.argv[1]).read_messages(topics=["/crane/state"])]
print("replay states", len(ts), "first t", ts[0] if ts else None, "last t", ts[-1] if ts else None)
assert len(ts) == 20 * 30 + 1, "states missing: %d of %d" % (len(ts), 20 * 30 + 1)
PY
[ "$(rosparam get /use_sim_time 2>/dev/null)" = "false" ] || fail "/use_sim_time left $(rosparam get /use_sim_time)"
# The pendulum rope runs to its end too, and forecasts (every rope model continues its own state).
timeout 120 roslaunch crane_twin sim.launch rviz:=false real_time_factor:=0 duration:=2 \
  shutdown_at_end:=true overrides:="[rope.model=pendulum]" >"$T/pendulum.log" 2>&1 ||
  fail "pendulum run: $(tail -20 "$T/pendulum.log")"
if grep -q "no forecast" "$T/pendulum.log"; then fail "the pendulum run has no forecast"; fi
grep -q "end of scene at t = 2" "$T/pendulum.log" || fail "the pendulum run did not reach its end"
echo "record_from_start_test: passed"
