#!/bin/sh
# What each shipped fractal formula costs: ms per frame (one sample per pixel) at each preset, its own
# view (scenes/fractals/ or scenes/), median of RUNS frames after a warm-up (bench --frame-times); the
# Julia set and hybrid views; and what double precision (a deep zoom) costs against float.
# Usage: sh docs/bench/formulas.sh [FATHOM] [SIZE] [RUNS] > docs/bench/formulas.md
fathom=${1:-build/fathom}
size=${2:-640x360}
runs=${3:-7}
tmp="${TMPDIR:-/tmp}/formula-bench.$$.txt"
trap 'rm -f "$tmp"' EXIT
# bench SCENE [--set ...]: the frame times of a scene's view, into $tmp
bench() {
    scene=$1
    shift
    "$fathom" bench --frame-times --scene "$scene" --runs "$runs" --size "$size" --quiet "$@" >"$tmp" || exit 1
}
echo "# Fractal formulas: ms per frame"
echo
echo "\`sh docs/bench/formulas.sh $fathom $size $runs\` on $("$fathom" bench --frame-times --scene menger --runs 1 \
    --size 32x18 --quiet | head -n 1 | sed 's/^[^,]*, [^,]*, //; s/: ms per frame.*//')."
echo "One sample per pixel at $size, median of $runs frames after a warm-up; each formula at its own view."
echo
echo "| formula | draft | interactive | final | reference | steps a pixel (final) |"
echo "|---|---|---|---|---|---|"
for f in $("$fathom" --list-formulas) julia_bulb hybrid_box_bulb; do
    bench "$f"
    awk -v f="$f" '
        $1 == "draft" || $1 == "interactive" || $1 == "final" || $1 == "reference" { ms[$1] = $2; if ($1 == "final") st = $4 }
        END { printf "| %s | %s | %s | %s | %s | %s |\n", f, ms["draft"], ms["interactive"], ms["final"], ms["reference"], st }
    ' "$tmp"
done
echo
echo "julia_bulb is the Mandelbulb's Julia set (\`fractal.julia\`), hybrid_box_bulb the Mandelbox with"
echo "Mandelbulb steps (\`fractal.hybrid\`): scenes, not formulas."
echo
echo "## Double precision against float"
echo
echo "The same view, the formula computed in float and in double (\`fractal.precision\`), final preset."
echo "The formulas' own views need no double: this is what a deep zoom's precision costs. deep_zoom is a"
echo "view 3e-11 wide, where only double draws the right place (in float the camera itself rounds away)."
echo
echo "| view | float ms | double ms | double / float |"
echo "|---|---|---|---|"
for f in mandelbulb mandelbox menger quaternion_julia sierpinski julia_bulb deep_zoom; do
    line="| $f |"
    for p in float double; do
        if [ "$f" = deep_zoom ] && [ $p = float ]; then
            line="$line (another place) |"
            continue
        fi
        bench "$f" --set fractal.precision=$p
        ms=$(awk '$1 == "final" { print $2 }' "$tmp")
        line="$line $ms |"
        eval "ms_$p=$ms"
    done
    if [ "$f" = deep_zoom ]; then
        echo "$line |"
    else
        echo "$line $(awk -v a="$ms_float" -v b="$ms_double" 'BEGIN { printf "%.2f", b / a }') |"
    fi
done
