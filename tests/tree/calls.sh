#!/bin/sh
# calls.sh LIBRARY.a...: no two files of app/ call each other in a circle, directly or through others
# (docs/guide/how-it-works.md, "The layers"). A file's calls are the symbols its object file needs that
# another object file of the libraries defines (nm); tsort finds a circle in that graph. A piece that
# two files share belongs to one owner below both: the bench's loading (bench_load.c), the check's probes
# (check_probe.c).
set -u
[ $# -ge 1 ] || { echo "usage: calls.sh LIBRARY.a..." >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT INT TERM
for a in "$@"; do
    nm -A -g --defined-only "$a" | awk '$2 ~ /^[TDBRVW]$/ { n = split($1, p, ":"); print p[n - 1], $3 }'
done | sort -u >"$tmp/defined"
for a in "$@"; do
    nm -A -u "$a" | awk '{ n = split($1, p, ":"); print p[n - 1], $NF }'
done | sort -u >"$tmp/needed"
[ -s "$tmp/defined" ] || { echo "calls: no symbols in $*" >&2; exit 2; }
awk 'NR == FNR { owner[$2] = $1; next } ($2 in owner) && owner[$2] != $1 { print $1, owner[$2] }' \
    "$tmp/defined" "$tmp/needed" | sort -u >"$tmp/edges"
if ! tsort "$tmp/edges" >/dev/null 2>"$tmp/loops" || [ -s "$tmp/loops" ]; then
    echo "calls: files that call each other in a circle (give the shared piece one owner below both):"
    sed -n 's/^tsort: \([^ ]*\.o\)$/  \1/p; s/^tsort: .*loop.*/ circle:/p' "$tmp/loops"
    exit 1
fi
echo "calls: ok ($(wc -l <"$tmp/edges") calls between $(cut -d' ' -f1 "$tmp/edges" | sort -u | wc -l) files, no circle)"
