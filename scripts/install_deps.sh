#!/usr/bin/env bash
# Install what crane_twin needs from Debian 12's own packages (run as root). Installs only the
# packages that are missing, so a second run costs a few dpkg queries.
# Usage: scripts/install_deps.sh [--core]   (--core: only what the ROS-free core, crane_sim, the
# unit tests and the benchmarks need: no ROS, no rviz)
set -euo pipefail
CORE_PKGS=(
  build-essential cmake pkg-config
  libeigen3-dev libsuitesparse-dev libarpack2-dev liblapack-dev libyaml-cpp-dev libcli11-dev
  libgtest-dev libgmock-dev googletest libbenchmark-dev libboost-dev
  parallel python3-yaml python3-numpy clang-format
)
ROS_PKGS=(
  catkin ros-core-dev ros-message-generation ros-std-msgs ros-sensor-msgs
  ros-geometry-msgs ros-visualization-msgs libtf2-ros-dev librostest-dev python3-rostest
  ros-trajectory-msgs libtrajectory-msgs-dev python3-trajectory-msgs
  ros-std-srvs ros-diagnostic-msgs ros-rosgraph-msgs ros-tf2-msgs librosbag-dev python3-rosbag
  libtopic-tools-dev catkin-lint python3-rosdep2 liburdfdom-tools
  python3-rospy python3-roslaunch python3-rostopic rviz tf2-tools
  ros-nav-msgs libnav-msgs-dev python3-nav-msgs python3-sensor-msgs python3-geometry-msgs
  python3-tf2-ros python3-std-srvs python3-std-msgs python3-diagnostic-msgs rosbash
  xvfb x11-utils imagemagick
  python3-matplotlib
)
case "${1:-}" in
  --core) PKGS=("${CORE_PKGS[@]}") ;;
  "") PKGS=("${CORE_PKGS[@]}" "${ROS_PKGS[@]}") ;;
  *) echo "install_deps: unknown option '$1' (usage: install_deps.sh [--core])" >&2; exit 2 ;;
esac
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#PKGS[@]} packages present"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
