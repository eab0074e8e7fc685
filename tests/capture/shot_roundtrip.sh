#!/bin/sh
# A shot remembers how it was made: `fathom --scene SHOT` renders the same image again, bit for bit
# (PNG and EXR), command-line overrides win over the shot's, and a damaged description is one clear error.
# Usage: shot_roundtrip.sh FATHOM
fathom=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0 failed=0
check() { if eval "$2"; then passed=$((passed + 1)); echo "ok   $1"; else failed=$((failed + 1)); echo "FAIL $1"; fi; }
"$fathom" --scene mandelbulb --set fractal.power=6 --camera 0.3,0.5,2.2 --look-at 0,0,0 --size 96x54 --spp 2 \
    --output "$tmp/a.png" --quiet
check "a shot renders" '[ -s "$tmp/a.png" ]'
"$fathom" --scene "$tmp/a.png" --output "$tmp/b.png" --quiet
check "reopened PNG: the same file" 'cmp -s "$tmp/a.png" "$tmp/b.png"'
"$fathom" --scene "$tmp/a.png" --output "$tmp/c.exr" --quiet && "$fathom" --scene "$tmp/c.exr" --output "$tmp/d.png" --quiet
check "through an EXR: the same file" 'cmp -s "$tmp/a.png" "$tmp/d.png"'
"$fathom" --scene "$tmp/a.png" --set fractal.power=8 --output "$tmp/e.png" --quiet
check "an override on top changes the image" '! cmp -s "$tmp/a.png" "$tmp/e.png"'
check "the override is remembered after the shot's" 'grep -aq "fractal.power=6\",\"quality.spp=2\",\"fractal.power=8\"" "$tmp/e.png"'
"$fathom" --scene "$tmp/a.png" --size 48x27 --output "$tmp/f.png" --quiet
check "a new size on the command line wins" '[ -s "$tmp/f.png" ] && ! cmp -s "$tmp/a.png" "$tmp/f.png"'
sed 's/"yaw":/"yaw":"x",/' "$tmp/a.png" >"$tmp/bad.png" # also breaks the PNG's chunk lengths
"$fathom" --scene "$tmp/bad.png" --output "$tmp/g.png" --quiet 2>"$tmp/err"
check "a damaged shot: exit 1, one line, no file" '[ $? -eq 1 ] && [ $(wc -l <"$tmp/err") -eq 1 ] && [ ! -e "$tmp/g.png" ]'
"$fathom" --scene "$tmp/nosuch.png" --output "$tmp/i.png" --quiet 2>"$tmp/err2"
check "a missing shot: one line naming it" 'grep -q "nosuch.png" "$tmp/err2" && [ $(wc -l <"$tmp/err2") -eq 1 ]'
# a saved view (as the window's B writes it) renders with --view, and an unknown one lists the saved
mkdir -p "$tmp/views"
printf '{"3": {"scene": "%s", "sets": ["fractal.power=5"], "camera": {"position": [0.1, 0.2, 2.5], "yaw": 0.25, "pitch": -0.125, "fov_y": 0.75}, "size": [64, 36]}}\n' \
    "$("$fathom" --scene mandelbulb --print-variant | sed -n 's/^scene [^ ]* (\(.*\)):.*/\1/p')" >"$tmp/views/mandelbulb.json"
FATHOM_VIEWS_DIR="$tmp/views" "$fathom" --scene mandelbulb --view 3 --output "$tmp/v.png" --quiet
check "--view renders the saved view" 'grep -aq "\"yaw\":0.25,\"pitch\":-0.125" "$tmp/v.png" && grep -aq "fractal.power=5" "$tmp/v.png"'
FATHOM_VIEWS_DIR="$tmp/views" "$fathom" --scene mandelbulb --view 4 --output "$tmp/w.png" --quiet 2>"$tmp/err3"
check "an unknown view: one line listing the saved ones" 'grep -q "no saved view .4. .*(3)" "$tmp/err3" && [ ! -e "$tmp/w.png" ]'
echo "shot_roundtrip: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
