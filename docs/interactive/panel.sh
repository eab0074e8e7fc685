#!/bin/sh
# What the parameter panel costs a window frame: the window at 1280x720 flying forward (W held down by
# xdotool under Xvfb, from 5 s after it opens) for FRAMES frames, with the panel open and closed,
# interleaved RUNS times; the window's own --frames summary (the whole frame and the panel's share,
# moving and still, wall clock around glFinish). Prints docs/interactive/panel.md's table; writes no file.
# Usage: sh docs/interactive/panel.sh [FATHOM] [RUNS] [FRAMES] [SCENES] [SIZE]
#   defaults: build/fathom 3 150 "csg mandelbulb jacksboro" 1280x720. Needs xvfb-run and xdotool (the
#   README's test install line: xvfb xauth xdotool); exit 77 where they are missing.
set -eu
fathom=$(realpath "${1:-build/fathom}")
runs=${2:-3}
frames=${3:-150}
scenes=${4:-csg mandelbulb jacksboro}
size=${5:-1280x720}
w=${size%x*} h=${size#*x}
for p in xvfb-run xdotool; do
    command -v "$p" >/dev/null 2>&1 || { echo "panel.sh: skip: $p is not installed (apt-get install xvfb xauth xdotool)" >&2; exit 77; }
done
one() { # SCENE PANEL-FLAG: one run, its summary line
    xvfb-run -a -s "-screen 0 ${w}x${h}x24" sh -c "
        xdotool mousemove $((w / 2)) $((h / 2))
        '$fathom' --scene $1 --size $size --frames $frames $2 2>&1 | grep 'frames at' &
        sleep 5; xdotool keydown w; wait; xdotool keyup w" 2>/dev/null || true
}
echo "| scene | panel | moving frames | median ms (fps) | the panel's ms | the swap's ms | still: median ms | the panel's ms |"
echo "|---|---|---:|---:|---:|---:|---:|---:|"
for scene in $scenes; do
    for r in $(seq 1 "$runs"); do
        for p in --panel ""; do
            row=$(one "$scene" "$p" | sed -n 's/.*(panel \([a-z]*\)): \([0-9]*\) moving, median \([0-9.]*\) ms (\([0-9.]*\) fps), the panel \([0-9.]*\) ms of it, the swap \([0-9.]*\) ms; [0-9]* still, median \([0-9.]*\) ms, the panel \([0-9.]*\) ms.*/| '"$scene"' | \1 | \2 | \3 (\4) | \5 | \6 | \7 | \8 |/p')
            [ -n "$row" ] || { echo "panel.sh: no frame summary from the window on $scene (run $r${p:+, $p})" >&2; exit 1; }
            echo "$row"
        done
    done
done
