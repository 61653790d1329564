#!/usr/bin/env bash
# The package works from its install space: `make install` of the catkin workspace, then, in a
# shell that sources only install/setup.bash (not the devel space, not the sources), roslaunch
# finds crane_twin there and sim.launch runs a few seconds to its end (rviz:=false,
# shutdown_at_end:=true) with exit status 0; the installed crane_sim, crane_recorder and a Python
# tool run too. Usage: install_space_test.sh CATKIN_BUILD_DIR (ctest passes it). Runs its own
# master on a free port.
set -uo pipefail
export PYENV_VERSION=system
export PATH="/usr/bin:$PATH"
BUILD="$1"
fail() { echo "install_space_test: FAILED: $*"; exit 1; }
cmake --build "$BUILD" --target install >"$BUILD/install_space_test.log" 2>&1 ||
  fail "make install: $(tail -20 "$BUILD/install_space_test.log")"
INSTALL="$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$BUILD/CMakeCache.txt")"
[ -f "$INSTALL/setup.bash" ] || fail "no $INSTALL/setup.bash"
T="$(mktemp -d)"
PORT=$((20000 + RANDOM % 20000))
cat >"$T/run.sh" <<SH
set -o pipefail  # not -u: setup.bash reads unset variables
unset ROS_PACKAGE_PATH CMAKE_PREFIX_PATH LD_LIBRARY_PATH PYTHONPATH ROSLISP_PACKAGE_DIRECTORIES
source "$INSTALL/setup.bash"
export ROS_MASTER_URI="http://localhost:$PORT"
cd "$T"
where="\$(rospack find crane_twin)"
[ "\$where" = "$INSTALL/share/crane_twin" ] || { echo "rospack finds crane_twin at \$where"; exit 1; }
"$INSTALL/lib/crane_twin/crane_sim" info "\$where/config/scenes/t8036_live.yaml" >/dev/null ||
  { echo "the installed crane_sim failed"; exit 1; }
rosrun crane_twin bag_to_series.py --help >/dev/null || { echo "bag_to_series.py not installed"; exit 1; }
roscore -p $PORT >"$T/core.log" 2>&1 &
CORE=\$!
trap 'kill \$CORE 2>/dev/null; wait \$CORE 2>/dev/null' EXIT
for _ in \$(seq 100); do rosparam list >/dev/null 2>&1 && break; sleep 0.2; done
timeout 120 roslaunch crane_twin sim.launch rviz:=false duration:=3 real_time_factor:=0 \
  shutdown_at_end:=true record:=true bag:="$T/run.bag" >"$T/launch.log" 2>&1 ||
  { echo "roslaunch exit status \$?"; tail -20 "$T/launch.log"; exit 1; }
grep -q "end of scene at t = 3" "$T/launch.log" || { echo "the run did not reach its end"; tail -20 "$T/launch.log"; exit 1; }
grep -q "holds every message we published" "$T/launch.log" || { echo "no complete recording"; tail -20 "$T/launch.log"; exit 1; }
SH
bash "$T/run.sh" >"$T/out.log" 2>&1 || { cat "$T/out.log"; rm -rf "$T"; fail "from the install space"; }
rm -rf "$T"
echo "install_space_test: passed"
