#!/bin/sh
# Bad input: each case must give one clear line on stderr (what, where, what to do), a non-zero exit
# code, no output file, and no crash. Usage: bad_input.sh FATHOM SOURCE_DIR [FAULT_SHIM]
fathom=$1
src=$2
shim=$3
tmp=$(mktemp -d)
# on any exit (a failure, a ctest timeout's TERM, Ctrl+C): the small tmpfs below is unmounted first
trap 'umount "$tmp/small" 2>/dev/null; rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
passed=0
failed=0

# expect NAME EXIT_CODE NEEDLE [MAX_LINES] -- COMMAND...
expect() {
    name=$1 code=$2 needle=$3 lines=$4
    shift 5
    rm -f "$tmp/out.png" "$tmp/out.exr"
    "$@" >"$tmp/stdout" 2>"$tmp/stderr"
    got=$?
    why=""
    [ "$got" -eq "$code" ] || why="exit code $got, expected $code"
    grep -qF -- "$needle" "$tmp/stderr" || why="$why; stderr lacks '$needle'"
    n=$(wc -l <"$tmp/stderr")
    [ "$n" -le "$lines" ] || why="$why; $n lines on stderr (at most $lines)"
    ls "$tmp"/out.* "$tmp"/.out.* >/dev/null 2>&1 && why="$why; a (partial) output file was left"
    if [ -z "$why" ]; then
        passed=$((passed + 1))
        echo "ok   $name: $(head -n 1 "$tmp/stderr")"
    else
        failed=$((failed + 1))
        echo "FAIL $name: $why"
        sed 's/^/     | /' "$tmp/stderr"
    fi
}

out="--output $tmp/out.png --size 33x21 --spp 1 --quiet"

expect unknown-scene 1 "unknown scene 'nosuch' (known: csg" 1 -- "$fathom" --scene nosuch $out
expect missing-file 1 "scene file '$tmp/missing.json' not found" 1 -- "$fathom" --scene "$tmp/missing.json" $out

printf '{\n  "program": "csg",\n  "materials": { "a": { "roughness": 0.5 }\n  "objects": []\n}\n' >"$tmp/bad.json"
expect malformed-json 1 "$tmp/bad.json:4:" 1 -- "$fathom" --scene "$tmp/bad.json" $out

printf '{"program": "csg", "materials": {"a": {"texture": "no/such.png"}},\n "objects": [{"shape": "sphere", "material": "a"}]}\n' >"$tmp/tex.json"
expect missing-texture 1 "materials.a.texture: file '$tmp/no/such.png' not found" 1 -- "$fathom" --scene "$tmp/tex.json" $out

expect bad-size 2 "bad --size '0x-3'" 1 -- "$fathom" --size 0x-3 --output "$tmp/out.png"
expect bad-spp 2 "bad --spp '-1'" 1 -- "$fathom" --spp -1 --output "$tmp/out.png"
expect bad-fov 2 "bad --fov '400'" 1 -- "$fathom" --fov 400 --output "$tmp/out.png"
expect bad-extension 2 "must end in .png or .exr" 1 -- "$fathom" --output "$tmp/out.jpg"
expect unknown-option 2 "unknown option '--colour'" 1 -- "$fathom" --colour red
# cameras and videos
expect bad-projection 1 "camera.projection" 1 -- "$fathom" --set camera.projection=cylinder $out
expect up-along-view 1 "camera.up: is zero or along the view" 1 -- "$fathom" --set camera.up=0,-1.1,-6.2 $out
expect bad-aperture 1 "camera.aperture" 1 -- "$fathom" --set camera.aperture=-1 $out
expect position-with-lens 1 "--aov position needs a pinhole camera" 1 -- "$fathom" --set camera.aperture=0.1 --aov position --output "$tmp/out.exr" --size 33x21 --quiet
expect video-without-path 2 "a video is a flight's" 1 -- "$fathom" --output "$tmp/out.mp4"
expect bad-video-crf 2 "bad --video crf='99'" 1 -- "$fathom" render --path "$src/docs/flight/csg.json" --output "$tmp/out.mp4" --video crf=99
expect webm-h264 2 "a WebM file holds vp9 or av1" 1 -- "$fathom" render --path "$src/docs/flight/csg.json" --output "$tmp/out.webm" --video codec=h264
# a GPU asked for by number never falls back to software quietly (this machine has no hardware EGL
# device, or not 99 of them); a number that is not one is refused
expect egl-device-missing 1 "FATHOM_EGL_DEVICE=99: no such hardware EGL device" 1 -- env FATHOM_EGL_DEVICE=99 "$fathom" $out
expect egl-device-bad 1 "FATHOM_EGL_DEVICE='gpu0' is not a device number" 1 -- env FATHOM_EGL_DEVICE=gpu0 "$fathom" $out
# a binary without its modules (copied alone): the image library it needs for an EXR is named, the
# PNG it writes itself still works (data/lazy/lazy.h)
mkdir "$tmp/lonely" && cp "$fathom" "$tmp/lonely/fathom"
expect module-missing 1 "fathom_image.so, which reads and writes images through OpenImageIO, is not beside" 1 -- \
    "$tmp/lonely/fathom" --output "$tmp/out.exr" --size 33x21 --spp 1 --quiet
expect backend-env-bad 1 "FATHOM_BACKEND='vulkan' is not a backend" 1 -- env FATHOM_BACKEND=vulkan "$fathom" $out
expect backend-bad 2 "bad --backend 'cuda': use auto, fragment or compute" 1 -- "$fathom" --backend cuda $out
expect unknown-set-key 1 "materials.glass.iro: unknown key 'iro'" 1 -- "$fathom" --set materials.glass.iro=1.3 $out
expect bad-set-value 1 "materials.glass.ior: expected a number from 1 to 4 (from the override materials.glass.ior=9)" 1 -- "$fathom" --set materials.glass.ior=9 $out
# a fragment's own look is a fragment's only; the hit rules are two, by name; Detail within the renderers' range,
# and the user's --set named as the culprit, not a line of the preset it overrides
expect look-not-fragment 1 "fractal.look: fragment is a Fragmentarium fragment's own renderer: mandelbulb is none (take fathom)" 1 -- \
    "$fathom" --scene mandelbulb --set fractal.look=fragment $out
expect hit-rule-unknown 1 "fractal.hit_rule: unknown hit rule 'relative' (known: footprint, fragment)" 1 -- \
    "$fathom" --scene mandelbulb --set fractal.hit_rule=relative $out
expect detail-above-range 1 "fractal.detail: expected a number from -7 to 0 (from the override fractal.detail=0.5)" 1 -- \
    "$fathom" --scene "$src/docs/fragments/mandelbox.frag" --set fractal.detail=0.5 $out
expect unwritable-output 1 "folder '$tmp/no/such/dir' does not exist: make it (mkdir -p '$tmp/no/such/dir')" 1 -- "$fathom" --output "$tmp/no/such/dir/out.png" --size 33x21 --quiet

# ---- hostile files ------------------------------------------------------------------------------
# a 68-byte PNG whose header claims 200000x200000 (zlib data for 10 bytes): refused before allocating
printf '\211\120\116\107\015\012\032\012\000\000\000\015\111\110\104\122\000\003\015\100\000\003\015\100\010\002\000\000\000\166\131\037\135\000\000\000\013\111\104\101\124\170\234\143\140\200\001\000\000\012\000\001\177\200\164\136\000\000\000\000\111\105\116\104\256\102\140\202' >"$tmp/huge.png"
sed "s|no/such.png|huge.png|" "$tmp/tex.json" >"$tmp/huge.json"
expect huge-texture-header 1 "is 200000x200000: larger than the 16384x16384" 1 -- "$fathom" --scene "$tmp/huge.json" $out
printf '{"program": "terrain", "materials": {"rock": {}}, "terrain": {"heightmap": "huge.png", "spacing": [1, 1], "height_min": 0, "height_max": 1}}' >"$tmp/hugeterrain.json"
expect huge-heightmap-header 1 "is 200000x200000: larger than the 65536x65536" 1 -- "$fathom" --scene "$tmp/hugeterrain.json" $out
# a PNG cut short: libpng's own complaint is folded into fathom's one line
head -c 120 "$src/terrains/jacksboro.png" >"$tmp/cut.png"
sed "s|no/such.png|cut.png|" "$tmp/tex.json" >"$tmp/cut.json"
expect corrupt-png 1 "cannot read image '$tmp/cut.png'" 1 -- "$fathom" --scene "$tmp/cut.json" $out

# a heightmap whose header claims 16384x16384 16-bit grey (allowed), under a 1.2 GB address-space limit:
# the allocation fails, which must be a clean error (skipped where the limit stops fathom from starting,
# as it does a sanitizer build)
printf '\211\120\116\107\015\012\032\012\000\000\000\015\111\110\104\122\000\000\100\000\000\000\100\000\020\000\000\000\000\334\063\223\033\000\000\000\013\111\104\101\124\170\234\143\140\200\001\000\000\012\000\001\177\200\164\136\000\000\000\000\111\105\116\104\256\102\140\202' >"$tmp/h16.png"
printf '{"program": "terrain", "materials": {"rock": {}}, "terrain": {"heightmap": "h16.png", "spacing": [1, 1], "height_min": 0, "height_max": 1}}' >"$tmp/h16.json"
if sh -c 'ulimit -v 1200000; exec "$0" --version' "$fathom" >/dev/null 2>&1; then
    expect out-of-memory 1 "out of memory" 1 -- sh -c 'ulimit -v 1200000; exec "$0" "$@"' "$fathom" --scene "$tmp/h16.json" $out
else
    echo "skip out-of-memory: fathom does not start under a 1.2 GB address-space limit here"
fi

# a heightmap with only NaN and infinite heights (PFM: a float image a shell can write); NaN among real
# heights are nodata holes (test_terrain nodata_holes)
printf 'Pf\n3 2\n-1.0\n' >"$tmp/nan.pfm"
printf '\000\000\300\177\000\000\300\177\000\000\200\177\000\000\200\177\000\000\300\177\000\000\300\177' >>"$tmp/nan.pfm"
printf '{"program": "terrain", "materials": {"rock": {}}, "terrain": {"heightmap": "nan.pfm", "spacing": [1, 1]}}' >"$tmp/nan.json"
expect nan-heights 1 "has no heights: all 6 texels are nodata or NaN" 1 -- "$fathom" --scene "$tmp/nan.json" $out
# DEMs through GDAL: an ASCII grid with a cell size but no CRS (unit unknown), a file GDAL cannot read,
# and a height range given for a DEM whose values are metres
printf 'ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 0.001\n1 2 3\n4 5 6\n' >"$tmp/dem.asc"
printf '{"program": "terrain", "materials": {"rock": {}}, "terrain": {"heightmap": "dem.asc"}}' >"$tmp/asc.json"
expect dem-without-crs 1 "has a pixel size (0.001 x 0.001) but no CRS, so its unit is unknown: set terrain.spacing" 1 -- "$fathom" --scene "$tmp/asc.json" $out
printf 'II*\000garbage' >"$tmp/junk.tif"
printf '{"program": "terrain", "materials": {"rock": {}}, "terrain": {"heightmap": "junk.tif", "spacing": [1, 1]}}' >"$tmp/badtif.json"
expect unreadable-dem 1 "cannot read DEM '$tmp/junk.tif'" 1 -- "$fathom" --scene "$tmp/badtif.json" $out
# a VRT header claiming 60000x60000 (43 GB to draw whole) and one beyond the side limit
printf '<VRTDataset rasterXSize="60000" rasterYSize="60000"><VRTRasterBand dataType="Int16" band="1"/></VRTDataset>' >"$tmp/big.vrt"
# beyond memory it streams (tests/geo/test_terrain_stream.c); a cache too small for four tiles is said before
# the DEM is read
expect dem-cache-too-small 1 "terrain.cache_mb=1 holds 0 of its 1.3 MB tiles; give it at least 6" 1 -- "$fathom" --dem "$tmp/big.vrt" --set terrain.spacing=30,30 --set terrain.cache_mb=1 $out
expect cache-below-range 1 "terrain.cache_mb: expected a number from 0 to 999999" 1 -- "$fathom" --scene himalaya --set terrain.cache_mb=-1 $out
expect cache-above-range 1 "terrain.cache_mb: expected a number from 0 to 999999" 1 -- "$fathom" --scene himalaya --set terrain.cache_mb=1000000 $out
printf '<VRTDataset rasterXSize="5000000" rasterYSize="2"><VRTRasterBand dataType="Int16" band="1"/></VRTDataset>' >"$tmp/wide.vrt"
expect dem-beyond-side 1 "is 5000000x2: the largest side fathom reads is 4194304 texels" 1 -- "$fathom" --dem "$tmp/wide.vrt" --set terrain.spacing=30,30 $out
expect dem-not-found 1 "--dem: file 'no/such.tif' not found (a path from the folder you are in)" 1 -- "$fathom" --dem no/such.tif $out
expect dem-and-scene 2 "--scene and --dem both name what to render: give one" 1 -- "$fathom" --dem "$tmp/dem.asc" --scene csg $out
expect dem-without-crs-cli 1 "has a pixel size (0.001 x 0.001) but no CRS" 1 -- "$fathom" --dem "$tmp/dem.asc" $out
expect dem-with-range 1 "is a DEM whose values are heights already: remove terrain.height_min" 1 -- "$fathom" --scene himalaya --set terrain.height_min=0 --set terrain.height_max=9000 $out
expect infinite-spacing 1 "terrain.spacing: expected [dx, dz]" 1 -- "$fathom" --scene jacksboro --set terrain.spacing=1e400,90 $out
expect reversed-heights 1 "terrain.height_max: 10 is below height_min 500" 1 -- "$fathom" --scene jacksboro --set terrain.height_min=500 --set terrain.height_max=10 $out
mkdir -p "$tmp/side"
cp "$src/terrains/jacksboro.png" "$tmp/side/dem.png"
printf '{"spacing": [1e400, 90], "height_min": 0, "height_max": 1}' >"$tmp/side/dem.json"
printf '{"program": "terrain", "materials": {"rock": {}}, "terrain": {"heightmap": "dem.png"}}' >"$tmp/side/scene.json"
expect sidecar-infinite-spacing 1 "dem.json: spacing: expected [dx, dz]" 1 -- "$fathom" --scene "$tmp/side/scene.json" $out
printf '{"spacing": [90, 90], "height_min": 900, "height_max": 100}' >"$tmp/side/dem.json"
expect sidecar-reversed-heights 1 "dem.json: height_min, height_max:" 1 -- "$fathom" --scene "$tmp/side/scene.json" $out

# scene files: a key twice, absurd nesting, a camera looking at itself
printf '{"program": "csg", "objects": [{"shape": "sphere", "radius": 1, "radius": -2}]}' >"$tmp/dup.json"
expect duplicate-key 1 "objects.0.radius: the key 'radius' appears twice" 1 -- "$fathom" --scene "$tmp/dup.json" $out
{ printf '{"program": "csg", "title": '; i=0; while [ $i -lt 1100 ]; do printf '['; i=$((i + 1)); done
  i=0; while [ $i -lt 1100 ]; do printf ']'; i=$((i + 1)); done; printf '}'; } >"$tmp/deep.json"
expect deep-nesting 1 "brackets nested deeper than 1000 levels" 1 -- "$fathom" --scene "$tmp/deep.json" $out
printf '{"program": "csg", "camera": {"position": [1, 2, 3], "look_at": [1, 2, 3]}, "objects": []}' >"$tmp/cam.json"
expect camera-at-look-at 1 "camera.look_at: is the camera's position" 1 -- "$fathom" --scene "$tmp/cam.json" $out
expect cli-camera-at-look-at 2 "--camera and --look-at are the same point" 1 -- "$fathom" --camera 0,1,5 --look-at 0,1,5 $out
expect no-display-bad-scene 1 "unknown scene 'nosuch'" 1 -- env -u DISPLAY -u WAYLAND_DISPLAY "$fathom" --scene nosuch --frames 1

# droplet files: each bad one is one line naming file, line and column (tests/droplets/test_droplets.c has more)
drops() { # NAME CSV-TEXT EXPECTED
    printf '%b' "$2" >"$tmp/drops.csv"
    expect "droplets-$1" 1 "$3" 1 -- "$fathom" --set droplets.file="$tmp/drops.csv" $out
}
drops empty '' "droplets file '$tmp/drops.csv' holds no droplets"
drops no-radius 'Points:0,Points:1,Points:2\n1,2,3\n' ":1: no radius or diameter column"
drops nan 'x,y,z,r\n0,1,0,0.01\n0,1,0,nan\n' ":3: column 4 (r): nan is not a finite number"
drops negative 'x,y,z,diameter\n0,1,0,-2e-3\n' ":2: column 4 (diameter): -2e-3: a droplet's size must be positive"
drops text 'x,y,z,r\n0,one,0,0.01\n' ":2: column 2 (y): 'one' is not a number"
expect droplets-missing-file 1 "droplets.file: file '$tmp/nodrops.csv' not found" 1 -- "$fathom" --set droplets.file="$tmp/nodrops.csv" $out
expect droplets-missing-key 1 "droplets.file: missing" 1 -- "$fathom" --set droplets.ior=1.5 $out

# flights: the path file and the frame pattern are checked before anything renders
printf '{"keys": [{"time": 0, "position": [0, 1, 5], "yaw": 0, "pitch": 0}, {"time": 1, "position": [1, 1, 5], "yaw": 0, "pitch": 0}]}' >"$tmp/path.json"
printf '{"keys": [{"time": 1, "position": [0, 1, 5], "yaw": 0, "pitch": 0}, {"time": 1, "position": [1, 1, 5], "yaw": 0, "pitch": 0}]}' >"$tmp/badpath.json"
flight="--size 33x21 --spp 1 --quiet"
expect render-no-output 2 "fathom render needs --output" 1 -- "$fathom" render --scene csg
expect path-no-pattern 2 "needs exactly one %d" 1 -- "$fathom" render --path "$tmp/path.json" --output "$tmp/out.png" $flight
expect path-no-output 2 "--path renders a flight's frames: give --output" 1 -- "$fathom" render --path "$tmp/path.json" $flight
expect path-with-camera 2 "--path gives the camera for every frame" 1 -- "$fathom" render --path "$tmp/path.json" --camera 0,1,2 --output "$tmp/out%d.png" $flight
expect path-bad-frames 2 "bad --frames '5-2': the range ends before it starts" 1 -- "$fathom" render --path "$tmp/path.json" --frames 5-2 --output "$tmp/out%d.png" $flight
expect path-bad-file 1 "keys.1.time: 1 is not after the previous key's 1" 1 -- "$fathom" render --path "$tmp/badpath.json" --output "$tmp/out%d.png" $flight
expect path-missing-file 1 "$tmp/nopath.json" 1 -- "$fathom" render --path "$tmp/nopath.json" --output "$tmp/out%d.png" $flight
expect path-past-end 1 "ends at frame 30" 1 -- "$fathom" render --path "$tmp/path.json" --frames 40-50 --output "$tmp/out%d.png" $flight
# a FIFO as the path file waited forever for a writer; times of 6e7 s overflowed the frame count
mkfifo "$tmp/fifo.json"
expect path-fifo 1 "'$tmp/fifo.json' is not a regular file" 1 -- timeout 20 "$fathom" render --path "$tmp/fifo.json" --output "$tmp/out%d.png" $flight
printf '{"keys": [{"time": 0, "position": [0, 1, 5], "yaw": 0, "pitch": 0}, {"time": 6e7, "position": [1, 1, 5], "yaw": 0, "pitch": 0}]}' >"$tmp/longpath.json"
expect path-huge-time 1 "keys.1.time: expected a number from -86400 to 86400" 1 -- "$fathom" render --path "$tmp/longpath.json" --output "$tmp/out%d.png" $flight
ls "$tmp"/out*.png >/dev/null 2>&1 && { failed=$((failed + 1)); echo "FAIL flights: a frame was written by a refused flight"; }

# refute NAME TEXT: the last case's message must not contain TEXT
refute() {
    if grep -qF -- "$2" "$tmp/stderr"; then
        failed=$((failed + 1)); echo "FAIL $1: the message contains '$2'"; sed 's/^/     | /' "$tmp/stderr"
    else
        passed=$((passed + 1)); echo "ok   $1: no '$2' in it"
    fi
}
# the hostile campaign's other classes: a camera a float cannot place, a private file named as droplets
# (its first line is not echoed), a DEM's error blamed on --set, a 16-bit PNG whose header claims
# 20000x20000 over 9 bytes of data (refused after reading one block of rows, not 1.8 GB)
expect camera-far 2 "bad --camera '1e30,1e30,1e30': expected X,Y,Z within" 1 -- "$fathom" --camera 1e30,1e30,1e30 $out
printf 'user,password,token\nalice,hunter2,42\n' >"$tmp/secret.csv"
expect droplets-private-file 1 "no x column in the first row's 3 fields" 1 -- "$fathom" --set droplets.file="$tmp/secret.csv" $out
refute droplets-private-file-not-echoed hunter2
refute droplets-private-header-not-echoed password
expect dem-error-names-dem 1 "but no CRS" 1 -- "$fathom" --dem "$tmp/dem.asc" $out
refute dem-error-not-from-set "(from --set)"
printf '\211\120\116\107\015\012\032\012\000\000\000\015\111\110\104\122\000\000\116\040\000\000\116\040\020\000\000\000\000\226\213\305\246\000\000\000\013\111\104\101\124\170\234\143\140\200\002\000\000\011\000\001\373\122\270\251\000\000\000\000\111\105\116\104\256\102\140\202' >"$tmp/h20k.png"
printf '{"program": "terrain", "materials": {"rock": {}}, "terrain": {"heightmap": "h20k.png", "spacing": [1, 1], "height_min": 0, "height_max": 1}}' >"$tmp/h20k.json"
expect png-header-20000 1 "Not enough image data" 1 -- "$fathom" --scene "$tmp/h20k.json" $out
# stitch: the poster named as one of its tiles (the tile is kept), a tile that is not there
"$fathom" --output "$tmp/p.png" --size 33x20 --spp 1 --quiet --tile 1/2 && "$fathom" --output "$tmp/p.png" --size 33x20 --spp 1 --quiet --tile 2/2
cp "$tmp/p.tile-1-of-2.png" "$tmp/keep-tile.png"
expect stitch-over-a-tile 1 "is one of the tiles" 1 -- "$fathom" stitch --output "$tmp/p.tile-1-of-2.png" "$tmp/p.tile-1-of-2.png" "$tmp/p.tile-2-of-2.png"
cmp -s "$tmp/keep-tile.png" "$tmp/p.tile-1-of-2.png" || { failed=$((failed + 1)); echo "FAIL stitch-over-a-tile: the tile was changed"; }
expect stitch-missing-tile 1 "tile '$tmp/p.tile-3-of-2.png' not found" 1 -- "$fathom" stitch --output "$tmp/out.png" "$tmp/p.tile-1-of-2.png" "$tmp/p.tile-3-of-2.png"

# ---- outputs that cannot be written -------------------------------------------------------------
: >"$tmp/readonly.png"
chmod 0444 "$tmp/readonly.png"
expect readonly-output 1 "the file is read-only" 1 -- "$fathom" --output "$tmp/readonly.png" --size 33x21 --quiet
[ -s "$tmp/readonly.png" ] && { failed=$((failed + 1)); echo "FAIL readonly-output: the read-only file was replaced"; }
rm -f "$tmp/readonly.png"
mkdir "$tmp/adir.png"
expect output-is-folder 1 "it exists and is not a regular file" 1 -- "$fathom" --output "$tmp/adir.png" --size 33x21 --quiet
rmdir "$tmp/adir.png"
# a file-size limit (ulimit -f, 512-byte blocks) stands in for a full disk: the short file must not pass
for ext in png exr; do
    expect "file-size-limit-$ext" 1 "cannot write '$tmp/out.$ext'" 1 -- sh -c "ulimit -f 16; exec \"\$0\" \"\$@\"" \
        "$fathom" --output "$tmp/out.$ext" --size 320x180 --spp 1 --quiet
done
# a really full disk where this machine lets us mount a small tmpfs (root, not in a locked container)
mkdir -p "$tmp/small"
if mount -t tmpfs -o size=64k fathomtest "$tmp/small" 2>/dev/null; then
    for ext in png exr; do
        expect "full-disk-$ext" 1 "cannot write '$tmp/small/full.$ext'" 1 -- "$fathom" --output "$tmp/small/full.$ext" --size 320x180 --spp 1 --quiet
        left=$(ls -A "$tmp/small")
        [ -z "$left" ] || { failed=$((failed + 1)); echo "FAIL full-disk-$ext: left $left"; }
    done
    umount "$tmp/small"
else
    echo "skip full-disk: cannot mount a tmpfs here (the file-size-limit cases cover the same path)"
fi

# a signal while the shot is being rendered into its temporary file: no file may remain
for sig in TERM INT; do
    rm -rf "$tmp/sig" && mkdir "$tmp/sig"
    "$fathom" --output "$tmp/sig/out.exr" --size 640x360 --spp 64 --quiet --aov depth,normal &
    pid=$!
    i=0
    while [ $i -lt 3000 ] && ! ls -A "$tmp/sig" | grep -q tmp; do sleep 0.01; i=$((i + 1)); done
    kill -$sig $pid
    wait $pid
    code=$?
    left=$(ls -A "$tmp/sig")
    if [ $i -lt 3000 ] && [ $code -ne 0 ] && [ -z "$left" ]; then
        passed=$((passed + 1)); echo "ok   signal-$sig: exit $code, nothing left"
    else
        failed=$((failed + 1)); echo "FAIL signal-$sig: waited $i polls, exit $code, left '$left'"
    fi
done

# a shader that does not compile: a copy of the data folder with one broken line
mkdir -p "$tmp/data"
cp -r "$src/shaders" "$src/scenes" "$src/textures" "$src/terrains" "$tmp/data/"
line=$(grep -n "const vec2 k = vec2(1.0, -1.0);" "$tmp/data/shaders/common/march.glsl" | cut -d: -f1)
sed -i "${line}s/.*/    const vec2 k = undeclared_thing;/" "$tmp/data/shaders/common/march.glsl"
expect shader-error 1 "common/march.glsl:$line:" 40 -- env FATHOM_DATA_DIR="$tmp/data" "$fathom" $out

expect no-display 1 "no display to open a window on" 1 -- env -u DISPLAY -u WAYLAND_DISPLAY "$fathom" --frames 1

# the command line's traps: an option given twice, --frames on a shot, a folder for a DEM, a formula
# name that is neither shipped nor in the user's folder (the message names the folder)
expect output-twice 2 "--output is given twice (the second time" 1 -- "$fathom" $out --output "$tmp/out.exr"
expect scene-twice 2 "--scene is given twice (the second time 'menger')" 1 -- "$fathom" --scene csg --scene menger $out
expect frames-with-output 2 "--frames counts the window's frames" 1 -- "$fathom" $out --frames 3
expect dem-folder 1 "--dem '$tmp' is a folder: give the elevation file in it" 1 -- "$fathom" --dem "$tmp" $out
expect formula-unknown-names-the-folder 1 "or put torus.glsl in $tmp/formulas (your formula folder" 1 -- \
    env FATHOM_FORMULAS="$tmp/formulas" "$fathom" --formula torus $out
# what works, and says what it is: an upper-case extension is a PNG (and reopens as a shot), the
# formula help names keys as --set takes them, the scene list has titles
if "$fathom" --size 16x9 --spp 1 --quiet --output "$tmp/UP.PNG" && [ "$(head -c 4 "$tmp/UP.PNG" | tail -c 3)" = PNG ] &&
    "$fathom" --scene "$tmp/UP.PNG" --size 16x9 --spp 1 --quiet --output "$tmp/again.Exr" && [ -s "$tmp/again.Exr" ]; then
    passed=$((passed + 1)); echo "ok   upper-case-extensions: UP.PNG written and reopened, again.Exr written"
else
    failed=$((failed + 1)); echo "FAIL upper-case-extensions: .PNG or .Exr refused"
fi
rm -f "$tmp/UP.PNG" "$tmp/again.Exr"
if "$fathom" --help-formula menger_kifs | grep -q '^  fractal\.twist  *vec3' &&
    "$fathom" --list-scenes | grep -q '^mandelbulb  *Mandelbulb, power 8'; then
    passed=$((passed + 1)); echo "ok   help-formula names fractal.KEY; --list-scenes has titles"
else
    failed=$((failed + 1)); echo "FAIL help-formula without fractal. or --list-scenes without titles"
fi

# fathom mesh: its options, a box with nothing in it, and no partial file (the output is out.ply)
mesh_out="--output $tmp/out.ply --quiet"
expect mesh-no-output 2 "fathom mesh needs --output FILE.ply" 1 -- "$fathom" mesh --scene torus
expect mesh-bad-extension 2 "bad mesh file name '$tmp/out.png': it must end in .ply, .stl, .obj, .glb, .3mf or .stp" 1 -- \
    "$fathom" mesh --output "$tmp/out.png"
expect mesh-resolution 2 "bad --resolution '1': expected a whole number of cells from 2 to 8192" 1 -- \
    "$fathom" mesh --resolution 1 $mesh_out
expect mesh-box 2 "bad --box '0,0,0,1,-1,1': each of X1, Y1, Z1 must be above X0, Y0, Z0" 1 -- \
    "$fathom" mesh --box 0,0,0,1,-1,1 $mesh_out
expect mesh-tolerance-alone 2 "--tolerance bounds a simplification: give --triangles N too" 1 -- \
    "$fathom" mesh --tolerance 2 $mesh_out
expect mesh-options-elsewhere 2 "belong to fathom mesh" 1 -- "$fathom" --resolution 64 $out
expect mesh-with-size 2 "fathom mesh writes a mesh: --size" 1 -- "$fathom" mesh --size 64x36 $mesh_out
expect mesh-empty-box 1 "no surface to write to '$tmp/out.ply': the mesh is empty" 1 -- \
    "$fathom" mesh --scene torus --box 5,5,5,6,6,6 --resolution 8 $mesh_out
# an option of the other kind of scene: refused, not ignored (issue 58 item 20)
expect mesh-base-on-a-field 1 "--base sets how far a DEM's solid reaches below its lowest point; 'torus' is not" 1 -- \
    "$fathom" mesh --scene torus --base 5 --resolution 8 $mesh_out
expect mesh-box-on-a-dem 1 "--box chooses the part of a distance-field scene to mesh; a DEM's solid is its whole grid" 1 -- \
    "$fathom" mesh --scene jacksboro --box 0,0,0,1,1,1 $mesh_out
ls "$tmp"/out.ply "$tmp"/.out.ply.* >/dev/null 2>&1 && { failed=$((failed + 1)); echo "FAIL mesh: a file was left"; }

# GIS: viewshed and track options, an observer off the DEM, a sun date that does not exist, imagery that
# is not there; no file left (the outputs are out.tif, out.gpx, out.json)
dem="$src/terrains/himalaya.tif"
expect vs-no-observer 2 "fathom viewshed needs --observer LON,LAT" 1 -- "$fathom" viewshed --dem "$dem" --output "$tmp/out.tif"
expect vs-bad-observer 2 "bad --observer '86.9': expected LON,LAT in degrees" 1 -- \
    "$fathom" viewshed --dem "$dem" --observer 86.9 --output "$tmp/out.tif"
expect vs-png 2 "the viewshed is a GeoTIFF: end the name in .tif" 1 -- \
    "$fathom" viewshed --dem "$dem" --observer 86.9,28 --output "$tmp/out.png"
expect vs-off-dem 1 "is outside the DEM" 1 -- "$fathom" viewshed --dem "$dem" --observer 10,50 --output "$tmp/out.tif"
expect vs-refraction 2 "bad --refraction '3': expected a number from -1 to 1" 1 -- \
    "$fathom" viewshed --dem "$dem" --observer 86.9,28 --refraction 3 --output "$tmp/out.tif"
expect vs-no-georef 1 "has no georeferencing" 1 -- \
    "$fathom" viewshed --dem "$src/terrains/jacksboro.png" --observer 86.9,28 --output "$tmp/out.tif"
expect water-png 2 "the lakes are a GeoTIFF: end the name in .tif" 1 -- "$fathom" water --dem "$dem" --output "$tmp/out.png"
expect water-no-georef 1 "has no georeferencing: fathom water" 1 -- \
    "$fathom" water --dem "$src/terrains/jacksboro.png" --output "$tmp/out.tif"
expect water-depth 2 "bad --min-depth '-1': expected a number from 0 to 100000" 1 -- \
    "$fathom" water --dem "$dem" --min-depth -1 --output "$tmp/out.tif"
expect water-options-elsewhere 2 "--min-depth and --min-area belong to fathom water" 1 -- \
    "$fathom" viewshed --dem "$dem" --observer 86.9,28 --min-area 5 --output "$tmp/out.tif"
expect water-kind 1 "expected a level in metres, \"fill\" (the lakes the DEM implies) or a raster" 1 -- \
    "$fathom" --scene himalaya --set 'terrain.water=[1,2]' $out
expect water-nan 1 "terrain.water: 'nan' is no level: give a height in metres" 1 -- \
    "$fathom" --scene himalaya --set terrain.water=nan $out
expect curvature-kind 1 "terrain.curvature: expected true (the DEM drawn on the Earth's curvature) or false" 1 -- \
    "$fathom" --scene himalaya --set terrain.curvature=1 $out
expect water-linear 1 "lakes and rasters of water are drawn by terrain.method \"maxmip\"" 1 -- \
    "$fathom" --scene himalaya --set terrain.water=fill --set terrain.method=linear $out
expect water-raster-missing 1 "$tmp/none.tif" 1 -- "$fathom" --scene himalaya --set terrain.water="$tmp/none.tif" $out
expect water-raster-size 1 "is 403 x 344 texels and the DEM 241 x 145: water is read on the DEM's own grid" 1 -- \
    "$fathom" --scene himalaya --set terrain.water="$src/terrains/jacksboro.png" $out
expect video-odd-size 1 "yuv420p needs an even width and height (this is 33x18)" 1 -- \
    "$fathom" render --path "$src/docs/flight/csg.json" --fps 2 --size 33x18 --spp 1 --output "$tmp/out.mp4"
expect track-both 2 "fathom track takes either --input TRACK" 1 -- "$fathom" track --dem "$dem" --output "$tmp/out.json"
expect track-not-a-track 1 "cannot open the track '$dem'" 1 -- \
    "$fathom" track --dem "$dem" --input "$dem" --output "$tmp/out.json"
expect track-gpx-ext 2 "end the name in .gpx or .kml" 1 -- \
    "$fathom" track --dem "$dem" --path "$src/docs/flight/himalaya-day.json" --output "$tmp/out.txt"
expect sun-date 1 "sun.date: expected a date" 1 -- "$fathom" --scene himalaya --set sun.date=2026-02-30 $out
expect sky-unknown 1 "unknown sky 'blue'" 1 -- "$fathom" --scene himalaya --set environment.sky=blue $out
expect imagery-missing 1 "$tmp/none.tif" 1 -- "$fathom" --scene himalaya --set terrain.imagery="$tmp/none.tif" $out
ls "$tmp"/out.* "$tmp"/.out.* >/dev/null 2>&1 && { failed=$((failed + 1)); echo "FAIL gis: a file was left"; }

# the write protocol's own faults, injected (tests/lib/fault_shim.c): a file's fsync, the rename, the
# folder's fsync after it; each leaves no file (nor a temporary one) and exits non-zero, and a file
# that was there before is kept as it was where the new one never replaced it
if [ -n "$shim" ] && [ ! -f "$shim" ]; then
    failed=$((failed + 1)); echo "FAIL write-faults: the shim $shim is not built (cmake --build B --target fault_shim)"
elif [ -n "$shim" ]; then
    mkdir -p "$tmp/faults"
    for fault in fsync rename dirfsync; do
        for ext in png exr ply 3mf; do
            rm -rf "$tmp/faults"/* "$tmp/faults"/.[!.]*
            case $ext in ply | 3mf) how="mesh --scene torus --resolution 8" ;; *) how="--size 32x18 --spp 1" ;; esac
            # shellcheck disable=SC2086 # how is the subcommand and its options
            expect "write-fault-$fault-$ext" 1 "cannot write '$tmp/faults/f.$ext'" 1 -- env LD_PRELOAD="$shim" \
                FATHOM_TEST_FAULT=$fault ASAN_OPTIONS=detect_leaks=0:verify_asan_link_order=0 \
                "$fathom" $how --output "$tmp/faults/f.$ext" --quiet
            left=$(ls -A "$tmp/faults")
            [ -z "$left" ] || { failed=$((failed + 1)); echo "FAIL write-fault-$fault-$ext: left $left"; }
        done
        echo "the user's file" >"$tmp/faults/kept.png"
        env LD_PRELOAD="$shim" FATHOM_TEST_FAULT=$fault ASAN_OPTIONS=detect_leaks=0:verify_asan_link_order=0 \
            "$fathom" --output "$tmp/faults/kept.png" --size 32x18 --spp 1 --quiet 2>/dev/null
        code=$?
        if [ $code -ne 0 ] && { [ $fault = dirfsync ] || [ "$(cat "$tmp/faults/kept.png")" = "the user's file" ]; } &&
            [ "$(ls -A "$tmp/faults")" = "$([ $fault = dirfsync ] || echo kept.png)" ]; then
            passed=$((passed + 1)); echo "ok   write-fault-$fault-over-a-file: exit $code, $(ls -A "$tmp/faults" | wc -l) file(s) left"
        else
            failed=$((failed + 1)); echo "FAIL write-fault-$fault-over-a-file: exit $code, left: $(ls -A "$tmp/faults")"
        fi
        rm -f "$tmp/faults"/*
    done
    # the shim passes calls on when no fault is asked for: the same command writes its file
    env LD_PRELOAD="$shim" ASAN_OPTIONS=detect_leaks=0:verify_asan_link_order=0 "$fathom" --output "$tmp/faults/ok.png" \
        --size 32x18 --spp 1 --quiet && [ -s "$tmp/faults/ok.png" ] && passed=$((passed + 1)) &&
        echo "ok   write-fault-none: the shim alone changes nothing" ||
        { failed=$((failed + 1)); echo "FAIL write-fault-none: no file written through the shim"; }
fi

echo "bad_input: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
