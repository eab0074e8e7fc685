#!/bin/sh
# Flights (fathom render --path): every frame of a range exactly once, each a reopenable shot; a rerun
# skips the frames on disk (resume) and renders only the missing ones, leaving the others untouched;
# a path with a parameter track changes the scene along the way; a path through a solid is refused.
# Usage: flight.sh FATHOM
fathom=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
cat >"$tmp/flight.json" <<JSON
{"keys": [
  {"time": 0, "position": [0, 1.7, 6.2], "look_at": [0, 0.6, 0], "fov": 50},
  {"time": 1, "position": [2.5, 1.2, 4.0], "look_at": [0, 0.6, 0]},
  {"time": 2, "position": [3.5, 1.0, 0.5], "look_at": [0, 0.6, 0], "fov": 40}
]}
JSON
mkdir "$tmp/out"
run() { "$fathom" render --path "$tmp/flight.json" --fps 4 --size 48x27 --spp 1 --output "$tmp/out/f_%03d.png" "$@"; }

# the whole path: 2 s at 4 frames a second = frames 0..8
run 2>"$tmp/log1" || { cat "$tmp/log1"; fail "the flight did not render"; }
n=$(ls "$tmp/out" | wc -l)
[ "$n" -eq 9 ] || fail "expected 9 frames, got $n: $(ls "$tmp/out")"
grep -q "9 frames rendered, 0 skipped" "$tmp/log1" || fail "summary: $(tail -1 "$tmp/log1")"

# resume: frames 3 and 7 lost; a rerun renders exactly those and leaves the rest as they were
cp "$tmp/out/f_000.png" "$tmp/keep.png"
touch -d '2001-01-01' "$tmp/out/f_000.png"
rm "$tmp/out/f_003.png" "$tmp/out/f_007.png"
run 2>"$tmp/log2" || { cat "$tmp/log2"; fail "the rerun failed"; }
grep -q "2 frames rendered, 7 skipped" "$tmp/log2" || fail "rerun summary: $(tail -1 "$tmp/log2")"
[ -f "$tmp/out/f_003.png" ] && [ -f "$tmp/out/f_007.png" ] || fail "the lost frames were not rendered again"
[ "$(date -r "$tmp/out/f_000.png" +%Y)" = 2001 ] || fail "frame 0 was rewritten"
cmp -s "$tmp/keep.png" "$tmp/out/f_000.png" || fail "frame 0 changed"

# what a killed run leaves: an empty frame (not fathom's, does not decode) is rendered again, and a
# temporary file whose writer is gone (no process 999999 here) is removed
: >"$tmp/out/f_004.png"
cp "$tmp/out/f_001.png" "$tmp/out/.f_002.png.tmp999999.png"
run 2>"$tmp/log5" || { cat "$tmp/log5"; fail "the run after a kill failed"; }
grep -q "1 frames rendered, 8 skipped" "$tmp/log5" || fail "after a kill: $(tail -1 "$tmp/log5")"
[ -s "$tmp/out/f_004.png" ] || fail "the empty frame 4 was not rendered again"
[ ! -e "$tmp/out/.f_002.png.tmp999999.png" ] || fail "the dead writer's temporary file was left"
grep -q "removed 1 temporary file" "$tmp/log5" || fail "no word of the removed temporary file: $(cat "$tmp/log5")"

# a range starting past the path's end is refused; one reaching past it renders what there is
run --frames 10-12 2>"$tmp/log3" && fail "frames past the path's end were accepted"
grep -q "ends at frame 8" "$tmp/log3" || fail "past the end: $(cat "$tmp/log3")"
run --frames 6-20 2>"$tmp/log4" || fail "a range reaching past the end failed: $(cat "$tmp/log4")"
grep -q "rendering 6-8" "$tmp/log4" && grep -q "0 frames rendered, 3 skipped" "$tmp/log4" || fail "past the end: $(cat "$tmp/log4")"
# a frame is a shot: --scene FRAME renders the same image again
"$fathom" --scene "$tmp/out/f_005.png" --output "$tmp/again.png" --quiet || fail "a frame does not reopen as a shot"
cmp -s "$tmp/again.png" "$tmp/out/f_005.png" || fail "frame 5 reopened renders a different image"

# a parameter track: the glass's index of refraction from 1.0 (invisible) to 1.9 over the path
cat >"$tmp/ior.json" <<JSON
{"keys": [
  {"time": 0, "position": [0, 1.2, 2.8], "look_at": [0, 0.7, 0.4], "set": {"materials.glass.ior": 1.0}},
  {"time": 1, "position": [0, 1.2, 2.8], "look_at": [0, 0.7, 0.4], "set": {"materials.glass.ior": 1.9}}
]}
JSON
mkdir "$tmp/ior"
"$fathom" render --path "$tmp/ior.json" --fps 1 --size 48x27 --spp 1 --output "$tmp/ior/f_%d.png" --quiet ||
    fail "the parameter track did not render"
cmp -s "$tmp/ior/f_0.png" "$tmp/ior/f_1.png" && fail "the parameter track changed nothing"
# a path through the glass sphere (centre (0, 0.7, 0.4), radius 0.7) is refused before anything renders
cat >"$tmp/through.json" <<JSON
{"keys": [
  {"time": 0, "position": [-2, 0.7, 0.4], "yaw": -90, "pitch": 0},
  {"time": 1, "position": [2, 0.7, 0.4], "yaw": -90, "pitch": 0}
]}
JSON
mkdir "$tmp/through"
"$fathom" render --path "$tmp/through.json" --fps 4 --size 48x27 --spp 1 --output "$tmp/through/f_%d.png" --quiet \
    2>"$tmp/log5" && fail "a path through the glass sphere was rendered"
grep -q "the camera is inside the scene's surface" "$tmp/log5" || fail "inside: $(cat "$tmp/log5")"
[ -z "$(ls "$tmp/through")" ] || fail "a refused path left frames"
echo "flight: 9 frames once each, resume renders only the 2 lost ones (and an empty one, and removes a dead run's temporary file), frames reopen as shots, tracks change the scene"
