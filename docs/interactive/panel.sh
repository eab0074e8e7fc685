#!/bin/sh
# What the parameter panel costs a window frame: the window at 1280x720 flying forward (W held down by
# xdotool under Xvfb) for FRAMES frames, with the panel open and closed, interleaved RUNS times; the
# window's own --frames summary (the whole frame and the panel's share, moving and still, wall clock
# around glFinish). Prints docs/interactive/panel.md's table.
# Usage: sh docs/interactive/panel.sh [FATHOM] [RUNS] [FRAMES]   (needs xvfb-run and xdotool)
fathom=$(realpath "${1:-build/fathom}")
runs=${2:-3}
frames=${3:-150}
one() { # SCENE PANEL-FLAG: one run, its summary line
    xvfb-run -a -s "-screen 0 1280x720x24" sh -c "
        xdotool mousemove 640 360
        '$fathom' --scene $1 --size 1280x720 --frames $frames $2 2>&1 | grep 'frames at' &
        sleep 5; xdotool keydown w; wait; xdotool keyup w" 2>/dev/null
}
echo "| scene | panel | moving frames | median ms (fps) | the panel's ms | the swap's ms | still: median ms | the panel's ms |"
echo "|---|---|---:|---:|---:|---:|---:|---:|"
for scene in csg mandelbulb jacksboro; do
    for r in $(seq 1 "$runs"); do
        for p in --panel ""; do
            one $scene "$p" | sed -n 's/.*(panel \([a-z]*\)): \([0-9]*\) moving, median \([0-9.]*\) ms (\([0-9.]*\) fps), the panel \([0-9.]*\) ms of it, the swap \([0-9.]*\) ms; [0-9]* still, median \([0-9.]*\) ms, the panel \([0-9.]*\) ms.*/| '$scene' | \1 | \2 | \3 (\4) | \5 | \6 | \7 | \8 |/p'
        done
    done
done
