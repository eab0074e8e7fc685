#!/bin/sh
# The window driven as a person drives it: real key presses and typing under Xvfb (xdotool), the
# camera read back from the presets the window saves (Ctrl+S writes SCENE.fathom, a shot description).
#   - the csg scene: W flies into the glass sphere, which stops the camera outside it; S backs out and
#     D slides sideways (the camera used to stick at the first surface it touched);
#   - the Mandelbulb: W flies in (the speed follows the distance), S backs out again;
#   - the panel: Enter opens it with its key=value field ready, typing fractal.power=5 there changes the
#     image (two P screenshots differ) and the preset records the edit; Ctrl+Z takes it back;
#   - a user's scene in a folder: its preset opens after the folder has moved (the scene travels in it);
#   - Q rolls the camera, F focuses the lens on the point under the cursor, U levels the horizon;
#   - a Fragmentarium fragment: J opens its next preset (camera and parameters), Shift+J the one before.
# Usage: window_drive.sh FATHOM   (needs xvfb-run and xdotool; exits 77, skipped, without them)
fathom=$(realpath "$1")
command -v xdotool >/dev/null && command -v xvfb-run >/dev/null || { echo "window_drive: needs xdotool and xvfb-run"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export FATHOM_VIEWS_DIR="$tmp/views"
passed=0 failed=0
check() { if eval "$2"; then passed=$((passed + 1)); echo "ok   $1"; else failed=$((failed + 1)); echo "FAIL $1"; fi; }

# drive NAME FATHOM-ARGS... -- XDOTOOL-STEPS...: runs the window in $tmp/NAME under Xvfb and plays the
# steps (each an xdotool command, or "sleep S", or "wait GLOB": until a file matches it (files are
# written whole or not at all), or "save F": Ctrl+S and keep the preset it writes as F, outside the folder's *.fathom)
cat >"$tmp/drive.sh" <<'EOF'
#!/bin/sh
dir=$1; fathom=$2; shift 2
cd "$dir" || exit 1
args=""
while [ "$1" != "--" ]; do args="$args $1"; shift; done
shift
xdotool mousemove 100 60
"$fathom" $args --size 320x180 >"$dir/window.log" 2>&1 &
pid=$!
for i in $(seq 1 150); do xdotool search --name '^fathom$' >/dev/null 2>&1 && break; sleep 0.2; done
sleep 3
for step in "$@"; do
    case $step in
    sleep*) eval "$step" ;;
    wait*) i=0; while ! ls ${step#wait } >/dev/null 2>&1 && [ $i -lt 450 ]; do sleep 0.2; i=$((i + 1)); done ;; # 90 s at most
    save*) # Ctrl+S, then the preset it writes (a loaded machine may take many seconds to a frame)
        touch asked.tmp; sleep 0.1; xdotool key ctrl+s; i=0
        while [ -z "$(find . -maxdepth 1 -name '*.fathom' -newer asked.tmp)" ] && [ $i -lt 300 ]; do sleep 0.2; i=$((i + 1)); done
        sleep 0.3; cp "$(ls -t ./*.fathom | head -n 1)" "kept.tmp"; mv kept.tmp "${step#save }" ;;
    *) eval "xdotool $step"; sleep 0.5 ;;
    esac
done
kill $pid 2>/dev/null
wait $pid 2>/dev/null
EOF
drive() {
    name=$1
    shift
    mkdir -p "$tmp/$name"
    xvfb-run -a -s "-screen 0 640x480x24" sh "$tmp/drive.sh" "$tmp/$name" "$fathom" "$@" 2>/dev/null
}
# coordinate I (1..3) of a preset's camera position
pos() { sed 's/.*"position":\[\([^]]*\)\].*/\1/' "$1" | cut -d, -f"$2"; }
# the distance between two presets' positions, and a preset's distance from (X, Y, Z)
apart() { awk -v a="$(sed 's/.*"position":\[\([^]]*\)\].*/\1/' "$1")" -v b="$(sed 's/.*"position":\[\([^]]*\)\].*/\1/' "$2")" \
    'BEGIN { split(a, p, ","); split(b, q, ","); print sqrt((p[1]-q[1])^2 + (p[2]-q[2])^2 + (p[3]-q[3])^2) }'; }
from() { awk -v a="$(sed 's/.*"position":\[\([^]]*\)\].*/\1/' "$1")" -v x="$2" -v y="$3" -v z="$4" \
    'BEGIN { split(a, p, ","); print sqrt((p[1]-x)^2 + (p[2]-y)^2 + (p[3]-z)^2) }'; }
ge() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a >= b) }'; }

# the glass sphere: radius 0.7 at (0, 0.7, 0.4)
drive csg --scene csg --camera 0,0.7,3 --look-at 0,0.7,0.4 -- \
    "keydown w" "sleep 7" "keyup w" "save ../csg-in" "keydown s" "sleep 1" "keyup s" "save ../csg-out" \
    "keydown d" "sleep 1" "keyup d" "save ../csg-side"
d=$(from "$tmp/csg-in" 0 0.7 0.4)
check "csg: W into the glass sphere stops outside it ($d m from its centre, radius 0.7)" 'ge "$d" 0.7 && ! ge "$d" 0.8'
b=$(apart "$tmp/csg-in" "$tmp/csg-out")
check "csg: S backs away from it ($b m)" 'ge "$b" 0.5'
s=$(apart "$tmp/csg-out" "$tmp/csg-side")
check "csg: D slides sideways ($s m)" 'ge "$s" 0.5'

# Q rolls (free flight), F focuses the lens on what is under the cursor (the centre while flying), U levels
drive roll --scene csg --set camera.aperture=0.05 -- "keydown q" "sleep 1" "keyup q" "key f" "sleep 2" "save ../rolled" \
    "key u" "sleep 1" "save ../level"
r=$(sed 's/.*"roll":\([^,}]*\).*/\1/' "$tmp/rolled")
check "Q rolls the camera (roll $r rad in the preset)" 'ge "$(awk -v r="$r" "BEGIN { print (r < 0 ? -r : r) }")" 0.3'
check "F focuses on the point under the cursor (the preset sets camera.focus)" 'grep -q "camera.focus=" "$tmp/rolled"'
check "U levels the horizon again" 'grep -q "\"roll\":0[,}]" "$tmp/level"'

drive bulb --scene mandelbulb --camera 0.3,0.5,2.2 --look-at 0,0,0 -- \
    "keydown w" "sleep 4" "keyup w" "save ../bulb-in" "keydown s" "sleep 2" "keyup s" "save ../bulb-out" "key m" "wait ./fathom-*.glb"
i=$(from "$tmp/bulb-in" 0 0 0)
o=$(from "$tmp/bulb-out" 0 0 0)
check "mandelbulb: W flies in ($i m from the centre, from 2.28)" '! ge "$i" 1.6'
glb=$(ls "$tmp/bulb"/fathom-*.glb 2>/dev/null | head -n 1)
check "mandelbulb: M saves the surface as a mesh (${glb##*/})" '[ -n "$glb" ] && [ "$(head -c 4 "$glb")" = glTF ]'
check "mandelbulb: S backs out again ($o m)" 'ge "$o" "$(awk -v i="$i" "BEGIN { print i + 0.02 }")"'

drive panel --scene mandelbulb -- "key p" "sleep 4" "key Return" "sleep 1" "type fractal.power=5" "key Return" "sleep 6" \
    "key p" "sleep 4" "save ../edited" "key ctrl+z" "sleep 2" "save ../undone"
shots=$(ls "$tmp/panel"/fathom-*.png 2>/dev/null | wc -l)
check "panel: two screenshots" '[ "$shots" -eq 2 ]'
check "panel: the typed edit changes the image" '! cmp -s $(ls "$tmp/panel"/fathom-*.png)'
check "panel: the preset records the edit" 'grep -q "\"sets\":\[\"fractal.power=5\"\]" "$tmp/edited"'
check "panel: Ctrl+Z takes it back" 'grep -q "\"sets\":\[\]" "$tmp/undone"'

# N records a flight the camera slid around the glass sphere (W into it, then W and D: along its
# surface). The spline through the two keys pressed cuts through it (render --path refuses that, the
# control below); the window adds keys from the way the camera flew, and the flight renders whole.
drive flight --scene csg --camera 0,0.7,3 --look-at 0,0.7,0.4 -- \
    "key n" "keydown w" "sleep 3" "keydown d" "sleep 5" "keyup d" "keyup w" "key n" "wait $FATHOM_VIEWS_DIR/csg.flight.json"
f=$FATHOM_VIEWS_DIR/csg.flight.json
keys=$(grep -c '"time"' "$f" 2>/dev/null)
check "flight: N twice around the glass sphere keeps $keys keys (2 pressed, the rest along the way flown)" \
    '[ "${keys:-0}" -gt 2 ]'
[ "${keys:-0}" -gt 2 ] || sed 's/^/     | /' "$tmp/flight/window.log"
"$fathom" render --path "$f" --output "$tmp/flight/f_%04d.png" --size 8x8 --quiet 2>"$tmp/flight.err"
check "flight: it renders whole ($(ls "$tmp/flight"/f_*.png 2>/dev/null | wc -l) frames)" \
    '[ ! -s "$tmp/flight.err" ] && [ -s "$tmp/flight/f_0000.png" ]'
{ echo '{ "keys": ['; grep '"time"' "$f" | sed -n '1p' | sed 's/}$/},/; s/},,$/},/'; grep '"time"' "$f" | tail -n 1 | sed 's/},$/}/'; echo '] }'; } \
    >"$tmp/two-keys.json"
check "flight: the two keys pressed alone cut through the sphere (render --path refuses them)" \
    '[ -s "$f" ] && ! "$fathom" render --path "$tmp/two-keys.json" --output "$tmp/flight/g_%04d.png" --size 8x8 --quiet 2>/dev/null'

# a fragment with two presets: J goes to the second (its camera and its radius), Shift+J back to the first
mkdir -p "$tmp/frag"
cat >"$tmp/frag/ball.frag" <<'EOF'
#include "DE-Raytracer.frag"
uniform float Radius; slider[0.1,1,2]
float DE(vec3 p) { return length(p) - Radius; }
#preset Default
Eye = 0,0,-5
Target = 0,0,0
#endpreset
#preset Side
Eye = 3,0,0
Target = 0,0,0
Radius = 0.5
#endpreset
EOF
drive frag --scene "$tmp/frag/ball.frag" -- "save ../frag-first" "key j" "sleep 2" "save ../frag-side" "key shift+j" "sleep 2" \
    "save ../frag-back"
# (the window's camera settles a few centimetres while the first frames draw)
check "fragment: it opens at its Default preset" '! ge "$(from "$tmp/frag-first" 0 0 -5)" 0.2'
check "fragment: J opens its next preset (camera and parameters)" \
    '! ge "$(from "$tmp/frag-side" 3 0 0)" 0.2 && grep -q "fractal.Radius=0.5" "$tmp/frag-side"'
check "fragment: Shift+J the one before" '! ge "$(from "$tmp/frag-back" 0 0 -5)" 0.2'

# a user's scene, its preset saved, the folder moved: the preset still opens (and renders)
mkdir -p "$tmp/mine"
cat >"$tmp/mine/ball.json" <<'EOF'
{ "program": "csg", "camera": {"position": [0, 1, 4], "look_at": [0, 0.5, 0]},
  "lights": [{"type": "directional", "direction": [0.3, 1, 0.2]}],
  "materials": {"red": {"base_color": [0.8, 0.1, 0.1]}},
  "objects": [{"shape": "sphere", "radius": 0.5, "position": [0, 0.5, 0], "material": "red"}] }
EOF
drive mine --scene "$tmp/mine/ball.json" -- "save $tmp/ball.fathom"
mv "$tmp/mine" "$tmp/moved"
"$fathom" --scene "$tmp/ball.fathom" --output "$tmp/ball.png" --size 64x36 --quiet 2>"$tmp/ball.err"
check "a user's scene travels in its preset (folder moved)" '[ -s "$tmp/ball.png" ] && [ ! -s "$tmp/ball.err" ]'

echo "window_drive: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
