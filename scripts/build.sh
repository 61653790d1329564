#!/usr/bin/env bash
# Build crane_twin in a catkin workspace outside the source tree proper: build/ws/src/crane_twin
# links back to the repository root (the package). Usage: scripts/build.sh [extra make targets]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PYENV_VERSION=system           # pyenv's python3 lacks the ROS modules catkin needs
export PATH="/usr/bin:$PATH"
WS="$ROOT/build/ws"
mkdir -p "$WS/src"
ln -sfn ../../.. "$WS/src/crane_twin"
cd "$WS"
catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release -j"$(nproc)" "$@"
