#!/bin/sh
# Writes docs/bench/README.md from the bench's CSV files (run after `fathom bench ... --out docs/bench`):
# each run's preset table and the effects its scene uses, then what each preset guarantees (the worst
# case over the runs whose reference converged).
# Usage: sh docs/bench/index.sh [DIR] [OUT]
#   reads DIR/*-knobs.csv, *-effects.csv, *-summary.md (and whether *-report.html is there) [the
#   folder of this script: docs/bench]; writes OUT [DIR/README.md] once the whole page is made (a
#   failed run leaves the old file as it was).
set -eu
dir=${1:-$(dirname "$0")}
out=${2:-$dir/README.md}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp" "$out.new.$$"' EXIT
trap 'exit 130' INT TERM
export LC_ALL=C # the runs in byte order, numbers with a decimal point

# the runs: NAME of every NAME-knobs.csv, sorted
for f in "$dir"/*-knobs.csv; do
    [ -e "$f" ] || { echo "index.sh: no *-knobs.csv in $dir" >&2; exit 1; }
    name=${f##*/}
    echo "${name%-knobs.csv}"
done | sort >"$tmp/runs"
# what the page needs of each run, one file a run: "report 0|1", the summary's convergence line, the
# knob and effect CSVs (each checked to be there: a missing file fails the run here)
while read -r name; do
    for f in "$dir/$name-knobs.csv" "$dir/$name-effects.csv" "$dir/$name-summary.md"; do
        [ -r "$f" ] || { echo "index.sh: $f is missing" >&2; exit 1; }
    done
    { [ -e "$dir/$name-report.html" ] && echo 1 || echo 0; } >"$tmp/$name.report"
done <"$tmp/runs"

# One awk over every run's files, in order: the run's name, then its three files (FILENAME tells which).
args=
while read -r name; do
    args="$args $name"
done <"$tmp/runs"
# shellcheck disable=SC2086 # one word a run
set -- $args
files=
for name; do
    files="$files $tmp/$name.report $dir/$name-summary.md $dir/$name-knobs.csv $dir/$name-effects.csv"
done
# shellcheck disable=SC2086 # names without spaces (the bench makes them from scene names)
awk -v runs="$*" '
function fail(msg) { print "index.sh: " msg > "/dev/stderr"; failed = 1; exit 1 }
function line(s) { out[++n] = s }
# the columns of a CSV by their header names
function header(   i) { delete col; for (i = 1; i <= NF; i++) col[$i] = i }
function v(name) { if (!(name in col)) fail(FILENAME ": no column " name); return $(col[name]) }
function max(a, b) { return a > b ? a : b }
function min(a, b) { return a < b ? a : b }
# the summary line "... differs from it by RMSE R ..., F % flipped ...": R and F into conv[]
function convergence(s,   i, rest) {
    while ((i = index(s, "differs from it by RMSE ")) > 0) {
        s = substr(s, i + length("differs from it by RMSE "))
        if (match(s, /^[0-9.]+ /)) {
            conv["rmse"] = substr(s, 1, RLENGTH - 1)
            rest = substr(s, RLENGTH + 1)
            if (match(rest, /, [0-9.]+ % flipped/)) {
                conv["flips"] = substr(rest, RSTART + 2, RLENGTH - length(" % flipped") - 2)
                return 1
            }
        }
    }
    return 0
}
# the end of one run: its heading, links, preset table (gathered in rows[]) and used effects
function finish_run(   report, converged, i) {
    if (!found) fail(name "-summary.md: no \"differs from it by RMSE ... % flipped\" line")
    converged = conv["flips"] + 0 <= MAX_REFERENCE_FLIPS && conv["rmse"] + 0 <= MAX_REFERENCE_RMSE
    if (!converged) unconverged = unconverged (unconverged == "" ? "" : ", ") name
    line("## " name); line("")
    line((has_report ? sprintf("[report (HTML)](%s-report.html) · [overview](%s-overview.png) · ", name, name) : "") \
         sprintf("[summary, every knob](%s-summary.md) · [plot](%s-plot.png) · [CSV](%s-knobs.csv) · " \
                 "[effects](%s-effects.csv), %s. Reference against a stricter render: RMSE %.4f, %.2f %% flipped " \
                 "pixels%s.", name, name, name, name, size, conv["rmse"], conv["flips"],
                 converged ? "" : " (**not converged**: left out of the guarantees below)"))
    line("")
    line("| preset | ms per image | RMSE | PSNR dB | depth mean / max (pixel footprints) | flips % | IoU | edge px | steps/px | out of steps % |")
    line("|---|---|---|---|---|---|---|---|---|---|")
    for (i = 1; i <= nrows; i++) {
        split(rows[i], r, SUBSEP)
        line(sprintf("| %s | %.1f | %.4f | %.1f | %.3f / %.2f | %.2f | %.4f | %.1f | %.1f | %.2f |", r[1], r[2], r[3], r[4],
                     r[5], r[6], 100 * r[7], r[8], r[9], r[10], 100 * r[11]))
        if (r[1] != "reference" && converged) {
            if (!(r[1] in rmse)) fail(name "-knobs.csv: preset " r[1] " is not one of draft, interactive, final, reference")
            rmse[r[1]] = max(rmse[r[1]], r[3] + 0)
            depth[r[1]] = max(depth[r[1]], r[5] + 0)
            depth_max[r[1]] = max(depth_max[r[1]], r[6] + 0)
            flips[r[1]] = max(flips[r[1]], 100 * r[7])
            iou[r[1]] = min(iou[r[1]], r[8] + 0)
            edge[r[1]] = max(edge[r[1]], r[9] + 0)
        }
    }
    if (used != "") { line(""); line("Effects this scene uses, ms per 1-spp frame: " used ".") }
    line("")
}
BEGIN {
    MAX_REFERENCE_FLIPS = 1.0 # % of pixels: a reference that flips more against a stricter render is not converged
    MAX_REFERENCE_RMSE = 0.1  # nor one whose colour is further than this from it (deep_zoom 0.126)
    npresets = split("draft interactive final reference", PRESETS, " ")
    for (i = 1; i <= npresets; i++) {
        rmse[PRESETS[i]] = depth[PRESETS[i]] = depth_max[PRESETS[i]] = flips[PRESETS[i]] = edge[PRESETS[i]] = 0
        iou[PRESETS[i]] = 1
    }
    nruns = split(runs, RUNS, " ")
    line("# What accuracy costs"); line("")
    line("Made by `fathom bench` on this repository'"'"'s scenes: every accuracy knob swept on its own, the presets,")
    line("and every effect compiled out / in / in but switched off, each measured for time (median of 3 images")
    line("after a warm-up, wall clock around glFinish) and for error against a reference render of the same two")
    line("views (colour RMSE and PSNR of the 8-bit image, depth error in pixel footprints, hit/miss flips, the")
    line("IoU of the hit masks and how far the farthest flipped pixel lies from the reference'"'"'s silhouette, steps).")
    line("The reference is the `reference` preset at 64 spp with every hit located at float resolution")
    line("(`quality.refine=64`): it does not share the near-miss bias of the hit threshold it judges. Fractals")
    line("are the exception by definition: the footprint rule defines their surface at a level of detail.")
    line("Each run'"'"'s summary says how its reference was checked for convergence. Runs made since the bench")
    line("learned them also have an HTML report (one self-contained page: the overview of the presets and the")
    line("Pareto front, one small plot a knob, the tables, the machine), times with their 95 % intervals and a")
    line("Pareto front built from them. Every shipped scene has a run. Remade (2026-11-27, llvmpipe, 2 cores) with")
    line("`for s in csg himalaya jacksboro mandelbox mandelbulb menger noise; do build/fathom bench --scene $s --size 240x135 --runs 3 --out docs/bench; done`,")
    line("`build/fathom bench --scene jacksboro --name jacksboro-linear --set terrain.method=linear --size 240x135 --runs 3 --out docs/bench`,")
    line("and `build/fathom bench --scene S --quick --out docs/bench` (160x90, three values a knob) for spray, dem and the")
    line("formula scenes; then `sh docs/bench/index.sh`. A fractal'"'"'s reference often flips more than 1 % of its")
    line("pixels against a stricter one: a stricter threshold *is* a finer level of detail there, a different surface;")
    line("a reference more than 0.1 RMSE from the stricter one (the deep zoom'"'"'s, at the edge of float precision) is")
    line("not converged either, and both are left out of the guarantees. fragment-mandelbox (2026-11-29) prices")
    line("Fragmentarium'"'"'s hit rule against fathom'"'"'s footprint rule side by side, on the example fragment:")
    line("`build/fathom bench --scene docs/fragments/mandelbox.frag --name fragment-mandelbox --size 240x135 --runs 3 --knob hit_rule=footprint,fragment --knob detail=-4,-3.6,-3.3,-3,-2.6 --knob max_steps=64,128,300,600 --out docs/bench`;")
    line("its reference is the fragment'"'"'s own rule at its own Detail, so another Detail (or the footprint rule) is a")
    line("different surface, not a worse render of the same one; under that rule a ray out of steps is background, so")
    line("the cost of too few steps shows in the IoU (0.69 at 64 steps), not in the out-of-steps share."); line("")
    run = 0
}
# a run starts at its .report file (one line: 1 if it has an HTML report)
FILENAME ~ /\.report$/ {
    if (run) finish_run()
    name = RUNS[++run]; has_report = ($1 == 1); found = 0; nrows = 0; used = ""; size = ""
    next
}
FILENAME ~ /-summary\.md$/ { if (!found) found = convergence($0); next }
FNR == 1 { FS = ","; $0 = $0; header(); next }
FILENAME ~ /-knobs\.csv$/ {
    if (size == "") size = v("width") "x" v("height")
    if (v("knob") == "preset")
        rows[++nrows] = v("value") SUBSEP v("ms_per_image") SUBSEP v("rmse") SUBSEP v("psnr_db") SUBSEP v("depth_mean_fp") \
                        SUBSEP v("depth_max_fp") SUBSEP v("flip_share") SUBSEP v("iou") SUBSEP v("edge_max_px") \
                        SUBSEP v("mean_steps") SUBSEP v("out_of_steps_share")
    next
}
FILENAME ~ /-effects\.csv$/ {
    if (v("in_scene") == "1")
        used = used (used == "" ? "" : "; ") sprintf("%s %.1f out / %.1f in / %.1f in but off", v("effect"),
                                                    v("ms_compiled_out"), v("ms_compiled_in"), v("ms_compiled_in_switched_off"))
    next
}
END {
    if (failed) exit 1
    if (run) finish_run()
    line("## What each preset guarantees (worst case over the runs whose reference converged)"); line("")
    line(sprintf("Left out: %s (their reference flipped more than %.0f %% of pixels against a stricter render, or its" \
                 " colour differed by more than %g RMSE; see each summary).", unconverged == "" ? "none" : unconverged,
                 MAX_REFERENCE_FLIPS, MAX_REFERENCE_RMSE)); line("")
    line("| preset | colour RMSE ≤ | mean depth error ≤ (pixel footprints) | max depth error (any pixel) | flipped pixels ≤ | silhouette IoU ≥ | silhouette edge moves ≤ (pixels) |")
    line("|---|---|---|---|---|---|---|")
    for (i = 1; i < npresets; i++) {
        p = PRESETS[i]
        line(sprintf("| %s | %.3f | %.2f | %.1f | %.1f %% | %.4f | %.1f |", p, rmse[p], depth[p], depth_max[p], flips[p], iou[p],
                     edge[p]))
    }
    line(""); line("IoU is over the worst of the two views; edge moves: the farthest flipped pixel from the reference'"'"'s")
    line("silhouette (a flip inside an object, where a thin gap or hole closes or opens, counts too). Max depth")
    line("errors come from a handful of grazing pixels; the mean is the figure that describes the image.")
    for (i = 1; i <= n; i++) print out[i]
}' $files >"$tmp/README.md"
[ -s "$tmp/README.md" ] || { echo "index.sh: nothing written" >&2; exit 1; }
cp "$tmp/README.md" "$out.new.$$"
mv -f "$out.new.$$" "$out"
echo "wrote $out for $(echo "$*" | sed 's/ /, /g')"
