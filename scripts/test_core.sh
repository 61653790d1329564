#!/usr/bin/env bash
# The ROS-free part on its own: install what it needs, build the core library, crane_sim and the
# unit tests with plain CMake (no catkin, no ROS) in build/core, and run the unit tests. Exits
# non-zero when any test fails (or is skipped); the last lines are ctest's own summary.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$ROOT/scripts/install_deps.sh" --core
export PYENV_VERSION=system
export PATH="/usr/bin:$PATH"
cmake -S "$ROOT" -B "$ROOT/build/core" -DCRANE_TWIN_ROS=OFF -DCMAKE_BUILD_TYPE=Release
cmake --build "$ROOT/build/core" -j"$(nproc)"
cd "$ROOT/build/core"
ctest --output-on-failure -j"$(nproc)"
