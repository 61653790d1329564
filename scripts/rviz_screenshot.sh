#!/usr/bin/env bash
# Headless rviz screenshot of the default scene through the ROS node (Xvfb + ImageMagick):
# scripts/rviz_screenshot.sh [out.png] [seconds to run before the shot]. Needs a build.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUT="${1:-$ROOT/docs/rviz_t8036.png}"
WAIT="${2:-30}"
export PYENV_VERSION=system
export PATH="/usr/bin:$PATH"
set +u  # ROS's setup scripts read unset variables
# shellcheck disable=SC1091
source "$ROOT/build/ws/devel/setup.bash"
set -u
LOG="$(mktemp)"
OWN_MASTER=0
if ! rosnode list >/dev/null 2>&1; then
  roscore >"$LOG.core" 2>&1 &
  OWN_MASTER=$!
  for _ in $(seq 50); do rosnode list >/dev/null 2>&1 && break; sleep 0.2; done
fi
xvfb-run -a -s "-screen 0 1280x800x24" bash -c "
  roslaunch crane_twin sim.launch rviz:=true >'$LOG' 2>&1 &
  LAUNCH=\$!
  sleep '$WAIT'
  import -window root '$OUT'
  kill -INT \$LAUNCH; wait \$LAUNCH || true"
[ "$OWN_MASTER" != 0 ] && kill "$OWN_MASTER" 2>/dev/null || true
echo "rviz_screenshot: wrote $OUT (launch log $LOG)"
