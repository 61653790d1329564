#!/usr/bin/env bash
# Build crane_twin in a catkin workspace under build/ (ignored by git): build/ws/src/crane_twin
# mirrors the repository root (the package). Usage: scripts/build.sh [extra make targets]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PYENV_VERSION=system           # pyenv's python3 lacks the ROS modules catkin needs
export PATH="/usr/bin:$PATH"
WS="$ROOT/build/ws"
# The package directory mirrors the repository root entry by entry (one symlink each) but
# leaves out build/ itself: a link to the whole root would put the workspace inside its own
# package, and roslaunch and rosrun, which walk the package, would loop through it.
PKG="$WS/src/crane_twin"
[ -L "$PKG" ] && rm "$PKG"
mkdir -p "$PKG"
for entry in "$ROOT"/* "$ROOT"/.ci; do
  name="$(basename "$entry")"
  [ "$name" = build ] && continue
  ln -sfn "$entry" "$PKG/$name"
done
for link in "$PKG"/* "$PKG"/.ci; do  # entries removed from the repository
  [ -L "$link" ] && [ ! -e "$link" ] && rm "$link"
done
# catkin caches the environment the test runners get (build/catkin_generated/setup_cached.sh)
# as what sourcing the devel space's setup adds, and that setup adds the python folder only if it
# exists when catkin configures: on a fresh clone it did not, and python rostest nodes could not
# import crane_twin.msg.
mkdir -p "$WS/devel/lib/python3/dist-packages"
cd "$WS"
catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release -j"$(nproc)" "$@"
