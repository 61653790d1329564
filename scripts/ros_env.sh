# Sourced by the scripts that talk to ROS (demo.sh, record_reference_bag.sh,
# rviz_screenshot.sh): the system python with the ROS modules, the workspace's setup, and a
# ROS master started when none runs (stopped again when the calling script exits).
# Usage: ROOT=<repository root>; source "$ROOT/scripts/ros_env.sh"; ensure_ros_master LOG
export PYENV_VERSION=system           # pyenv's python3 lacks the ROS modules
export PATH="/usr/bin:$PATH"
set +u  # ROS's setup scripts read unset variables
# shellcheck disable=SC1091
source "$ROOT/build/ws/devel/setup.bash"
set -u

OWN_MASTER=0
# Start roscore (output to LOG) unless a master answers; wait up to 20 s for it.
ensure_ros_master() {
  rosnode list >/dev/null 2>&1 && return 0
  echo "$(basename "$0"): starting a ROS master"
  roscore >"$1" 2>&1 &
  OWN_MASTER=$!
  trap '[ "$OWN_MASTER" != 0 ] && kill "$OWN_MASTER" 2>/dev/null || true' EXIT
  for _ in $(seq 100); do rosnode list >/dev/null 2>&1 && return 0; sleep 0.2; done
  echo "$(basename "$0"): the ROS master did not answer within 20 s (log $1)" >&2
  return 1
}
