#!/usr/bin/env bash
# Fuzz the scene loader with libFuzzer (clang from Debian): scripts/fuzz_scene_loader.sh
# [seconds, default 300]. The seed corpus is the shipped scenes; new inputs go to
# build/fuzz/corpus, crashes to build/fuzz/. Exits non-zero if libFuzzer finds a crash, a
# timeout, a leak or an abort (a non-finite value or a foreign exception escaping).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SECONDS_TO_RUN="${1:-300}"
OUT="$ROOT/build/fuzz"
mkdir -p "$OUT/corpus"
# clang and its sanitizer/libFuzzer runtimes, from Debian (not needed by the build or the tests).
for p in clang libclang-rt-14-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="${missing:-} $p"
done
if [ -n "${missing:-}" ]; then
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $missing
fi
clang++ -std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -DCRANE_TWIN_SOURCE_DIR="\"$ROOT\"" -I"$ROOT/include" -I/usr/include/eigen3 \
  "$ROOT/test/fuzz/scene_loader_fuzz.cpp" "$ROOT/src/io/scene.cpp" \
  "$ROOT/src/io/config_reader.cpp" "$ROOT/src/io/crane_description.cpp" \
  "$ROOT/src/elements/timoshenko_beam_element.cpp" "$ROOT/src/elements/gauss_legendre.cpp" \
  -lyaml-cpp -o "$OUT/scene_loader_fuzz"
cp "$ROOT"/config/scenes/*.yaml "$OUT/corpus/"
cd "$OUT"
./scene_loader_fuzz -max_total_time="$SECONDS_TO_RUN" -timeout=10 -rss_limit_mb=4096 \
  -max_len=4096 -print_final_stats=1 corpus 2>&1 | tail -25
