#!/usr/bin/env bash
# Regenerate docs/data/sweep_<scene>.csv for the four paper scenes (docs/accuracy-vs-time.md) and
# the chart docs/accuracy_vs_time.png. About 10 minutes on the 2-core machine; needs
# scripts/build.sh.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SIM="$ROOT/build/ws/devel/lib/crane_twin/crane_sim"
mkdir -p "$ROOT/docs/data"
for s in t8036_combination1 t8036_combination1_3deg t8036_combination2 t8036_combination2_3deg; do
  "$SIM" sweep "$ROOT/config/scenes/$s.yaml" --out "$ROOT/docs/data/sweep_$s.csv" "$@"
done
/usr/bin/python3 "$ROOT/scripts/plot_sweep.py" "$ROOT/docs/accuracy_vs_time.png" "$ROOT"/docs/data/sweep_*.csv
