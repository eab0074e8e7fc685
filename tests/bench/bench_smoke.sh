#!/bin/sh
# fathom bench on a tiny image: it must finish and write a well-formed CSV, PNG plots, a summary and a
# self-contained HTML report.
# (Timings are never checked: this machine is shared and noisy.) Usage: bench_smoke.sh FATHOM
fathom=$1
out=$(mktemp -d)
bench=
trap '[ -n "$bench" ] && kill $bench 2>/dev/null; rm -rf "$out"' EXIT
trap 'exit 130' INT TERM
passed=0 failed=0
check() { if eval "$2"; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL $1"; fi; }

"$fathom" bench --scene csg --size 40x24 --runs 2 --knob max_steps=16,64 --knob hit_k=4,1 \
    --knob resolution_scale=0.5 --out "$out" --quiet >"$out/stdout" 2>"$out/stderr"
check "bench exits 0" '[ $? -eq 0 ]'
csv="$out/csg-knobs.csv"
check "knob CSV written" '[ -s "$csv" ]'
check "knob CSV has 20 columns on every line" \
    '[ "$(awk -F, "{print NF}" "$csv" | sort -u)" = "20" ]'
check "every knob row's time lies in its interval" \
    '[ -z "$(tail -n +2 "$csv" | awk -F, "\$19 > \$7 || \$7 > \$20")" ]'
# 2 + 2 + 1 knob rows and 4 presets, plus the header
check "knob CSV has 10 lines" '[ "$(wc -l < "$csv")" -eq 10 ]'
check "times and errors are numbers >= 0" \
    '[ -z "$(tail -n +2 "$csv" | awk -F, "\$7 !~ /^[0-9.]+\$/ || \$8 !~ /^[0-9.]+\$/ || \$15 !~ /^[0-9.]+\$/")" ]'
check "silhouette IoU is in [0, 1]" \
    '[ -z "$(tail -n +2 "$csv" | awk -F, "\$13 < 0 || \$13 > 1")" ]'
check "the reference preset is on the Pareto front" \
    '[ "$(awk -F, "\$5 == \"preset\" && \$6 == \"reference\" {print \$18}" "$csv")" = 1 ]'
check "effects CSV lists every effect" \
    '[ "$(tail -n +2 "$out/csg-effects.csv" | wc -l)" -eq "$("$fathom" --print-variant | grep -c "^#define FX_.*_BIT")" ]'
check "each effect's three medians lie in their intervals" \
    '[ -z "$(tail -n +2 "$out/csg-effects.csv" | awk -F, "NF != 12 || \$7 > \$4 || \$4 > \$8 || \$9 > \$5 || \$5 > \$10 || \$11 > \$6 || \$6 > \$12")" ]'
check "plot is a PNG" '[ "$(head -c 8 "$out/csg-plot.png" | od -An -tx1 | tr -d " \n")" = "89504e470d0a1a0a" ]'
check "overview is a PNG" '[ "$(head -c 8 "$out/csg-overview.png" | od -An -tx1 | tr -d " \n")" = "89504e470d0a1a0a" ]'
check "summary links both plots" 'grep -q "](csg-plot.png)" "$out/csg-summary.md" && grep -q "](csg-overview.png)" "$out/csg-summary.md"'
html="$out/csg-report.html"
# the overview, the plot, the reference and a difference image a preset
check "the HTML report holds its seven images inline, and no other file" \
    '[ "$(grep -o "src=\"data:image/png;base64," "$html" | wc -l)" -eq 7 ] && [ "$(grep -o "src=\"" "$html" | wc -l)" -eq 7 ]'
check "... a difference image a preset, each a PNG of the image's size" \
    '(for p in draft interactive final reference; do f="$out/csg-diff-preset-$p.png"; [ "$(head -c 8 "$f" | od -An -tx1 | tr -d " \n")" = "89504e470d0a1a0a" ] && [ "$(od -An -tu1 -j16 -N8 "$f" | tr -s " " | sed "s/^ //")" = "0 0 0 40 0 0 0 24" ] || exit 1; done)'
check "... the plot it inlines is the plot written, byte for byte" \
    'grep -o "data:image/png;base64,[^\"]*" "$html" | sed -n 2p | cut -d, -f2 | base64 -d | cmp -s - "$out/csg-plot.png"'
check "... and a row for every knob setting, preset and effect" \
    '[ "$(grep -o "<tr[^>]*><td>" "$html" | wc -l)" -eq $((9 + $(tail -n +2 "$out/csg-effects.csv" | wc -l))) ]'
check "bad knob is refused" '! "$fathom" bench --knob nosuch=1 --size 8x8 2>/dev/null'
# against the path tracer: the model's approximations get rows, and the summary names the truth
"$fathom" bench --scene csg --size 24x16 --runs 1 --knob fx_ao=off,on --truth path --out "$out" --name truth \
    --quiet >/dev/null 2>&1
check "bench --truth path prices AO off and on" '[ "$(grep -c "^csg,24,16,2,fx_ao," "$out/truth-knobs.csv")" -eq 2 ]'
check "... against the path tracer" 'grep -q "the truth.*the path tracer" "$out/truth-summary.md"'
check "... with a difference image each, in the summary and the report" \
    '[ -s "$out/truth-diff-fx_ao-off.png" ] && [ -s "$out/truth-diff-fx_ao-on.png" ] && grep -q "truth-diff-fx_ao-on.png" "$out/truth-summary.md" && [ "$(grep -o "src=\"data:image/png" "$out/truth-report.html" | wc -l)" -eq 9 ]'
# a default sweep holds the scene's own value (the Apollonian's step_factor 0.3 is not among
# 0.6,0.8,0.9,1), --quick keeps it among its three values (hit_k 1 is not the middle of 8,4,2,1,0.5),
# and every panel rings it
"$fathom" bench --scene apollonian --quick --size 16x9 --runs 1 --out "$out" --quiet >/dev/null 2>&1
qcsv="$out/apollonian-knobs.csv"
check "a sweep holds the scene's own value: step_factor 0.3, 0.8, 1" \
    '[ "$(awk -F, "\$5 == \"step_factor\" {printf \"%s \", \$6}" "$qcsv")" = "0.3 0.8 1 " ]'
check "... --quick keeps it among its three: hit_k 8, 1, 0.5" \
    '[ "$(awk -F, "\$5 == \"hit_k\" {printf \"%s \", \$6}" "$qcsv")" = "8 1 0.5 " ]'
check "... and every panel rings it" \
    '[ "$(grep -c "point pt 6" "$out/apollonian-plot.gp")" -eq "$(tail -n +2 "$qcsv" | cut -d, -f5 | sort -u | wc -l)" ]'
# stopped half-way (as a user's Ctrl+C), a run keeps the rows it finished, whole lines, no temporary file
"$fathom" bench --scene csg --size 40x24 --runs 2 --knob max_steps=8,16,32,64,128,256,512 --knob spp=1,2,4,8 \
    --out "$out" --name stopped --quiet >/dev/null 2>&1 &
bench=$!
for i in $(seq 600); do
    [ -f "$out/stopped-knobs.csv" ] && [ "$(wc -l < "$out/stopped-knobs.csv")" -ge 3 ] && break
    sleep 0.2
done
kill -INT $bench 2>/dev/null
wait $bench
stopped=$?
bench=
check "a stopped run exits non-zero" '[ $stopped -ne 0 ]'
check "a stopped run keeps its finished rows" '[ "$(wc -l < "$out/stopped-knobs.csv")" -ge 3 ]'
check "... as whole lines" '[ "$(awk -F, "{print NF}" "$out/stopped-knobs.csv" | sort -u)" = "20" ]'
check "... and leaves no temporary file" '[ -z "$(ls -A "$out" | grep "\.tmp")" ]'
check "... nor a summary of a run not done" '[ ! -e "$out/stopped-summary.md" ]'
[ "$failed" -eq 0 ] || cat "$out/stderr"
echo "bench_smoke: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
