#!/usr/bin/env bash
# The package's own checks of its form: the C++ sources follow .clang-format (clang-format
# --dry-run), and catkin_lint -W2 (the ROS ecosystem's checker; Debian package catkin-lint) with
# every dependency resolved offline: a rosdep database in a temporary ROS_HOME from Debian's
# listing of the ROS packages and rosdep/crane_twin.yaml (the system libraries). catkin_lint
# checks the package under its own name, so it reads the workspace's mirror of the repository
# (scripts/build.sh makes it). Prints the findings; exits 1 on any.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PYENV_VERSION=system
export PATH="/usr/bin:$PATH"
PKG="${1:-$ROOT/build/ws/src/crane_twin}"
[ -f "$PKG/package.xml" ] || { echo "lint: no package at $PKG (run scripts/build.sh first)" >&2; exit 2; }
FORMAT="$(cd "$PKG" && find -L bench include src test -name '*.cpp' -o -name '*.hpp' -o -name '*.h' |
  sort | xargs clang-format --dry-run 2>&1 | grep 'warning:' || true)"
if [ -n "$FORMAT" ]; then
  echo "$FORMAT" | head -20
  echo "lint: $(echo "$FORMAT" | wc -l) lines differ from .clang-format (clang-format -i FILE fixes them)"
  exit 1
fi
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$TMP/sources.list.d" "$TMP/home"
echo "yaml file:///usr/share/python3-rosdep2/debian.yaml debian" >"$TMP/sources.list.d/10-debian.list"
echo "yaml file://$ROOT/rosdep/crane_twin.yaml debian" >"$TMP/sources.list.d/20-crane_twin.list"
# rosdep update reads a rosdistro index: an empty one (no ROS distribution, only the listings).
printf '%%YAML 1.1\n---\ndistributions: {}\ntype: index\nversion: 4\n' >"$TMP/index-v4.yaml"
export ROS_HOME="$TMP/home" ROSDEP_SOURCE_PATH="$TMP/sources.list.d"
export ROSDISTRO_INDEX_URL="file://$TMP/index-v4.yaml"
rosdep update >"$TMP/rosdep.log" 2>&1 || { cat "$TMP/rosdep.log" >&2; exit 2; }
OUT="$(catkin_lint -W2 --quiet --rosdistro debian "$PKG" 2>&1)" || true
if [ -n "$OUT" ]; then
  echo "$OUT"
  echo "lint: catkin_lint -W2 found problems"
  exit 1
fi
echo "lint: the sources follow .clang-format; catkin_lint -W2 clean"
