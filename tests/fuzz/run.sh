#!/bin/sh
# Fuzzes the scene parser with libFuzzer (clang, ASan + UBSan) for MINUTES minutes [5].
# Seeds: every shipped scene; dictionary: the keys and names of the scene format (scene.dict).
# Findings (crash-*, leak-*, timeout-*) land in build-fuzz/findings; the corpus grows in build-fuzz/corpus.
# Usage: tests/fuzz/run.sh [MINUTES]   (needs: apt-get install clang)
set -eu
minutes=${1:-5}
src=$(cd "$(dirname "$0")/../.." && pwd)
build="$src/build-fuzz"
CC=clang CXX=clang++ cmake -S "$src" -B "$build" -DFATHOM_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null
cmake --build "$build" -j 2 --target fuzz_scene >/dev/null
mkdir -p "$build/corpus" "$build/findings"
cp "$src"/scenes/*.json "$build/corpus/"
cd "$build/findings"
"$build/fuzz_scene" "$build/corpus" -dict="$src/tests/fuzz/scene.dict" -max_total_time=$((minutes * 60)) \
    -max_len=16384 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 2>&1 | tail -n 25
