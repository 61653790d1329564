#!/usr/bin/env bash
# Install, build, and run the default T8036 scene with crane_sim (no ROS yet: the ROS node is
# issue 6): the model's size and modes, a reduced run (10 rope modes) and a full-order run of
# the same scene, their SPEC 4 comparison, written to build/demo/summary.txt, and a plot of the
# payload, cab and jib-tip histories in build/demo/histories.png.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SCENE="${1:-$ROOT/config/scenes/t8036_combination1.yaml}"
bash "$ROOT/scripts/install_deps.sh"
bash "$ROOT/scripts/build.sh"
export PYENV_VERSION=system
SIM="$ROOT/build/ws/devel/lib/crane_twin/crane_sim"
OUT="$ROOT/build/demo"
mkdir -p "$OUT"
{
  echo "# crane_sim info $SCENE"
  "$SIM" info "$SCENE"
  echo "# crane_sim modes $SCENE --part structure --count 10"
  "$SIM" modes "$SCENE" --part structure --count 10
  echo "# reduced run (10 rope modes): crane_sim run $SCENE --set rope.mode_count=10"
  "$SIM" run "$SCENE" --set rope.mode_count=10 --out "$OUT/reduced.csv" --nodes "$OUT/reduced_nodes.csv" --quiet
  echo "# full-order run: crane_sim run $SCENE --set rope.model=full"
  "$SIM" run "$SCENE" --set rope.model=full --out "$OUT/full.csv" --nodes "$OUT/full_nodes.csv" --quiet
  echo "# crane_sim compare reduced.csv full.csv (SPEC 4 metrics)"
  "$SIM" compare "$OUT/reduced.csv" "$OUT/full.csv" --nodes-a "$OUT/reduced_nodes.csv" --nodes-b "$OUT/full_nodes.csv"
} | tee "$OUT/summary.txt"
/usr/bin/python3 "$ROOT/scripts/plot_series.py" "$OUT/histories.png" "$OUT/full.csv" "$OUT/reduced.csv"
echo "demo: summary in $OUT/summary.txt, plot in $OUT/histories.png"
