#!/usr/bin/env bash
# The layers only look down (README, Layout): no source of a layer includes a header of a layer
# above it. Lowest first: elements, integrators, structure, rope, solvers, drives, loads,
# simulation, analysis, twin; io (scene and crane files) sits beside the physics and may be read
# by structure, rope, loads, drives and what is above them, never by elements or integrators
# (they take plain parameters). cli and ros are the front ends and nothing includes them.
# Usage: layering_test.sh SOURCE_DIR
set -uo pipefail
ROOT="${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
declare -A FORBIDDEN=(
  [elements]="io integrators structure rope solvers drives loads simulation analysis twin"
  [integrators]="io structure solvers drives loads simulation analysis twin"
  [structure]="solvers drives simulation analysis twin"
  [rope]="solvers drives simulation analysis twin"
  [solvers]="drives loads simulation analysis twin"
  [drives]="solvers loads simulation analysis twin"
  [loads]="solvers drives simulation analysis twin"
  [io]="integrators solvers drives simulation analysis twin"
  [simulation]="analysis twin"
  [analysis]="twin"
  [twin]=""
)
bad=0
for layer in "${!FORBIDDEN[@]}"; do
  for file in "$ROOT"/src/"$layer"/*.cpp "$ROOT"/include/crane_twin/"$layer"/*.hpp; do
    [ -f "$file" ] || continue
    for up in ${FORBIDDEN[$layer]} cli ros; do
      if grep -q "#include \"crane_twin/$up/" "$file"; then
        echo "layering: ${file#"$ROOT"/} ($layer) includes $up: $(grep -m1 "#include \"crane_twin/$up/" "$file")"
        bad=1
      fi
    done
  done
done
[ "$bad" -eq 0 ] && echo "layering_test: passed" || { echo "layering_test: FAILED"; exit 1; }
