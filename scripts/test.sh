#!/usr/bin/env bash
# Install, build, run every unit test (and rostest) through ctest. Exits non-zero when any test
# fails; the last lines are ctest's own summary.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$ROOT/scripts/install_deps.sh"
bash "$ROOT/scripts/build.sh"
bash "$ROOT/scripts/build.sh" tests
export PYENV_VERSION=system
export PATH="/usr/bin:$PATH"
cd "$ROOT/build/ws/build"
ctest --output-on-failure -j1
