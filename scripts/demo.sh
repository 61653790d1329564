#!/usr/bin/env bash
# Install, build, and run the default T8036 scene's model set-up: size, structural modes and the
# static load check, written to build/demo/summary.txt.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SCENE="${1:-$ROOT/config/scenes/t8036_combination1.yaml}"
bash "$ROOT/scripts/install_deps.sh"
bash "$ROOT/scripts/build.sh"
SIM="$ROOT/build/ws/devel/lib/crane_twin/crane_sim"
OUT="$ROOT/build/demo"
mkdir -p "$OUT"
{
  echo "# crane_sim info $SCENE"
  "$SIM" info "$SCENE"
  echo "# crane_sim modes $SCENE --part structure --count 10"
  "$SIM" modes "$SCENE" --part structure --count 10
} | tee "$OUT/summary.txt"
echo "demo: summary written to $OUT/summary.txt"
