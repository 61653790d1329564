#!/usr/bin/env bash
# Headless rviz screenshot of the default scene through the ROS node (Xvfb + ImageMagick):
# scripts/rviz_screenshot.sh [out.png] [seconds to run before the shot] [launch file, default
# sim.launch; site.launch shows the shipped site] [roslaunch arguments, e.g. scene:=FILE].
# Needs a build.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="${1:-$ROOT/docs/rviz_t8036.png}"
WAIT="${2:-30}"
LAUNCH_FILE="${3:-sim.launch}"   # site.launch: both cranes of the shipped site
EXTRA="${*:4}"
# shellcheck disable=SC1091
source "$ROOT/scripts/ros_env.sh"
LOG="$(mktemp)"
ensure_ros_master "$LOG.core"
xvfb-run -a -s "-screen 0 1280x800x24" bash -c "
  roslaunch crane_twin '$LAUNCH_FILE' rviz:=true $EXTRA >'$LOG' 2>&1 &
  LAUNCH=\$!
  sleep '$WAIT'
  import -window root '$OUT'
  kill -INT \$LAUNCH; wait \$LAUNCH || true"
echo "rviz_screenshot: wrote $OUT (launch log $LOG)"
