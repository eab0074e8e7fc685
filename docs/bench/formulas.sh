#!/bin/sh
# What each shipped fractal formula costs: ms per frame (one sample per pixel) at each preset, its own
# view (scenes/fractals/ or scenes/), median of RUNS frames after a warm-up (bench --frame-times).
# Usage: sh docs/bench/formulas.sh [FATHOM] [SIZE] [RUNS] > docs/bench/formulas.md
fathom=${1:-build/fathom}
size=${2:-640x360}
runs=${3:-7}
echo "# Fractal formulas: ms per frame"
echo
echo "\`sh docs/bench/formulas.sh $fathom $size $runs\` on $("$fathom" --scene menger --print-variant >/dev/null 2>&1 && \
    "$fathom" bench --frame-times --scene menger --runs 1 --size 32x18 --quiet | head -n 1 | sed 's/^[^,]*, [^,]*, //; s/: ms per frame.*//')."
echo "One sample per pixel at $size, median of $runs frames after a warm-up; each formula at its own view."
echo
echo "| formula | draft | interactive | final | reference | steps a pixel (final) |"
echo "|---|---|---|---|---|---|"
for f in $("$fathom" --list-formulas); do
    "$fathom" bench --frame-times --scene "$f" --runs "$runs" --size "$size" --quiet >"${TMPDIR:-/tmp}/formula-bench.txt" || exit 1
    awk -v f="$f" '
        $1 == "draft" || $1 == "interactive" || $1 == "final" || $1 == "reference" { ms[$1] = $2; if ($1 == "final") st = $4 }
        END { printf "| %s | %s | %s | %s | %s | %s |\n", f, ms["draft"], ms["interactive"], ms["final"], ms["reference"], st }
    ' "${TMPDIR:-/tmp}/formula-bench.txt"
done
rm -f "${TMPDIR:-/tmp}/formula-bench.txt"
