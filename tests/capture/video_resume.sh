#!/bin/sh
# A flight straight to video, killed part way (SIGKILL: nothing cleans up) and run again: the second run
# renders only the frames the first did not finish, and the video holds every frame of the path (frame
# count, size, each frame at 40.5 dB or better against its PNG: test_video), byte for byte the video the
# same frames make in another run. A killed run leaves no video
# and no temporary file; a farm's chunk (--frames) renders its frames and leaves the video to the run
# that completes them.
# Usage: video_resume.sh FATHOM SOURCE_DIR TEST_VIDEO
set -u
fathom=$1 src=$2 check=$3
dir=$(mktemp -d) || exit 1
pid=
trap 'test -n "$pid" && kill -9 "$pid" 2>/dev/null; rm -rf "$dir"' EXIT INT TERM
cd "$dir" || exit 1
fail() { echo "video_resume: $*" >&2; exit 1; }
flight="$src/docs/flight/csg.json"
frames=9 # the path's 8 s at 1 frame a second, frames 0-8

"$fathom" render --path "$flight" --fps 1 --size 640x360 --output f.mp4 --quiet &
pid=$!
i=0
while [ "$(ls f.mp4.frames 2>/dev/null | grep -c '\.png$')" -lt 3 ] && [ $i -lt 600 ]; do
    sleep 0.1
    i=$((i + 1))
done
kill -9 "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
pid=
done_before=$(ls f.mp4.frames | grep -c '\.png$')
[ "$done_before" -ge 3 ] || fail "no frames rendered in 60 s"
[ "$done_before" -lt $frames ] || fail "the render finished before it was killed: nothing to resume"
[ ! -e f.mp4 ] || fail "a killed render left f.mp4"
ls | grep -q 'tmp' && fail "a killed render left a temporary file: $(ls)"

"$fathom" render --path "$flight" --fps 1 --size 640x360 --output f.mp4 2>log || { cat log; fail "the resumed render failed"; }
grep -q "skipped (already there)" log || { cat log; fail "the resumed render did not say what it skipped"; }
skipped=$(sed -n 's/.* rendered, \([0-9]*\) skipped.*/\1/p' log)
[ "$skipped" -ge "$((done_before - 1))" ] || fail "resumed: $skipped skipped of $done_before on disk"
"$check" f.mp4 'f.mp4.frames/%05d.png' $frames || fail "the video is not the path's $frames frames"
ls | grep -q 'tmp' && fail "a temporary file is left: $(ls)"
# the same frames make the same video in another process (H.264's macroblock tree did not: issue 58 item 11;
# it showed on longer flights, here 33 frames at 160x96: two of three encodings differed)
"$fathom" render --path "$flight" --fps 4 --size 160x96 --spp 1 --output r.mp4 --quiet || fail "a short video"
for i in 1 2 3; do
    mv r.mp4 first.mp4
    "$fathom" render --path "$flight" --fps 4 --size 160x96 --spp 1 --output r.mp4 --quiet || fail "encoding again"
    cmp -s first.mp4 r.mp4 || fail "the same frames gave another H.264 stream: a resumed video is not reproducible"
done

# a farm's chunk: its frames, no video yet; the last run completes the frames and makes it
"$fathom" render --path "$flight" --fps 1 --size 640x360 --frames 0-4 --output g.webm 2>log || { cat log; fail "chunk"; }
[ ! -e g.webm ] || fail "a chunk of the flight made a video"
grep -q "4 of 9 frames are not rendered yet" log || { cat log; fail "the chunk did not say what is missing"; }
"$fathom" render --path "$flight" --fps 1 --size 640x360 --output g.webm --quiet || fail "completing the chunks"
"$check" g.webm 'g.webm.frames/%05d.png' $frames || fail "the WebM is not the path's $frames frames"

# bad input leaves nothing behind: an odd size cannot be yuv420p (one line, no video)
"$fathom" render --path "$flight" --fps 1 --size 639x360 --frames 0-1 --output h.mp4 --quiet 2>/dev/null
"$fathom" render --path "$flight" --fps 1 --size 639x360 --output h.mp4 --quiet 2>err && fail "an odd-sized yuv420p video was made"
grep -q "needs an even width and height" err || { cat err; fail "no clear line for an odd size"; }
[ ! -e h.mp4 ] || fail "a failed video left h.mp4"
echo "video_resume: killed after $done_before of $frames frames, resumed (skipped $skipped), the video whole"
