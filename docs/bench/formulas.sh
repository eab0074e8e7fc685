#!/bin/sh
# What each shipped fractal formula costs: ms per frame (one sample per pixel) at each preset, each at
# its own view (the scene of its name, scenes/fractals/ or scenes/; a formula without one: the fractal
# scene framed from its bound), median of RUNS frames after a warm-up (bench --frame-times, the backend
# fathom's auto takes); the Julia set and hybrid views; and what double precision (a deep zoom) costs
# against float. Your own formulas (~/.config/fathom/formulas/) are left out.
# Usage: sh docs/bench/formulas.sh [FATHOM] [SIZE] [RUNS] [OUT_DIR] [VIEWS]
#   writes OUT_DIR/formulas.md [the folder of this script: docs/bench], only once every view was
#   measured (a failed run leaves the old file as it was). VIEWS (e.g. "menger julia_bulb") measures
#   only those formulas and views, for a quick look [every one]. Defaults: build/fathom 640x360 7.
set -eu
fathom=${1:-build/fathom}
size=${2:-640x360}
runs=${3:-7}
out=${4:-$(dirname "$0")}
only=${5:-}
[ -d "$out" ] || { echo "formulas.sh: no folder '$out'" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp" "$out/.formulas.md.$$"' EXIT
trap 'exit 130' INT TERM
# wanted NAME: whether VIEWS (if given) names it
wanted() { [ -z "$only" ] || case " $only " in *" $1 "*) true ;; *) false ;; esac; }
# bench NAME [--set ...]: the frame times of NAME's view, into $tmp/bench; the scene of that name, or
# the fractal scene framed from the formula's bound
bench() {
    name=$1
    shift
    if grep -qxF "$name" "$tmp/scenes"; then view="--scene $name"; else view="--formula $name"; fi
    # shellcheck disable=SC2086 # $view is two words
    "$fathom" bench --frame-times $view --runs "$runs" --size "$size" --quiet "$@" >"$tmp/bench" 2>&1 ||
        { cat "$tmp/bench" >&2; echo "formulas.sh: fathom bench failed on $name" >&2; exit 1; }
    # the machine, from the first bench: "SCENE, WxH, MACHINE: ms per frame ..., auto takes BACKEND"
    [ -s "$tmp/device" ] || sed -n 's/^[^,]*, [^,]*, \(.*\): ms per frame.*auto takes \([a-z]*\).*/\1 (the \2 backend)/p' \
        "$tmp/bench" >"$tmp/device"
}
# ms PRESET: the median ms of PRESET in $tmp/bench on the backend auto takes (fragment ms is the 2nd
# field, compute ms the 4th: each cell is "MEDIAN [LO-HI]")
ms() {
    awk -v p="$1" '/: ms per frame/ { c = ($NF == "compute") ? 4 : 2 } $1 == p && c { print $c; found = 1 }
        END { if (!found) exit 1 }' "$tmp/bench" || { echo "formulas.sh: no $1 row in:" >&2; cat "$tmp/bench" >&2; exit 1; }
}
"$fathom" --list-scenes | awk '{ print $1 }' >"$tmp/scenes"
# the shipped formulas only: the user's folder pointed at nothing (its names, and its "note: ..." lines)
FATHOM_FORMULAS="$tmp/no-user-formulas" "$fathom" --list-formulas | grep -E '^[A-Za-z0-9_]+$' >"$tmp/formulas"
[ -s "$tmp/formulas" ] || { echo "formulas.sh: fathom --list-formulas listed no formula" >&2; exit 1; }

{
    echo "| formula | draft | interactive | final | reference | steps a pixel (final) |"
    echo "|---|---|---|---|---|---|"
    for f in $(cat "$tmp/formulas") julia_bulb hybrid_box_bulb; do
        wanted "$f" || continue
        bench "$f"
        # steps per pixel: the last field of a preset's row
        d=$(ms draft)
        i=$(ms interactive)
        fi=$(ms final)
        r=$(ms reference)
        steps=$(awk '$1 == "final" { print $NF }' "$tmp/bench")
        echo "| $f | $d | $i | $fi | $r | $steps |"
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
        wanted "$f" || continue
        if [ "$f" = deep_zoom ]; then
            bench "$f" --set fractal.precision=double
            ms_double=$(ms final)
            echo "| $f | (another place) | $ms_double | |"
            continue
        fi
        bench "$f" --set fractal.precision=float
        ms_float=$(ms final)
        bench "$f" --set fractal.precision=double
        ms_double=$(ms final)
        echo "| $f | $ms_float | $ms_double | $(awk -v a="$ms_float" -v b="$ms_double" 'BEGIN { printf "%.2f", b / a }') |"
    done
} >"$tmp/body"

[ -s "$tmp/device" ] || { echo "formulas.sh: no view measured (VIEWS '$only' names none)" >&2; exit 1; }
{
    echo "# Fractal formulas: ms per frame"
    echo
    cmd="sh docs/bench/formulas.sh $fathom $size $runs"
    [ -z "$only" ] || cmd="$cmd $out '$only'"
    echo "\`$cmd\` on $(cat "$tmp/device")."
    echo "One sample per pixel at $size, median of $runs frames after a warm-up; each formula at its own view."
    echo
    cat "$tmp/body"
} >"$tmp/formulas.md"
# into place in one rename (a copy beside it first: $tmp may be another file system)
cp "$tmp/formulas.md" "$out/.formulas.md.$$"
mv -f "$out/.formulas.md.$$" "$out/formulas.md"
echo "wrote $out/formulas.md"
