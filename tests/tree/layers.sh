#!/bin/sh
# layers.sh SOURCE_DIR: the tree shows the architecture, and the words about it cannot go stale.
#  1. The layers are the table in docs/guide/how-it-works.md ("## The layers"), top to bottom: every
#     folder of app/ that holds files is a row and every row exists. Every #include "..." in app/
#     names a header by its path under app/ and goes down the rows (a file may include its own
#     folder's headers).
#  2. No include cycle between modules (X.c and X.h are module X): tsort finds none.
#  3. No function in app/ or shaders/ is longer than 80 lines (style.md, rule 16), and no file in
#     app/, shaders/ or tests/ is longer than 600.
#  4. Every source file that a comment, README.md or docs/ cites (app/..., shaders/..., tests/...,
#     a bare NAME.c/.h/.glsl/.frag/.vert) exists.
#  6. The pure library (CMakeLists.txt's fathom_pure: no GL, tested under the sanitizers) includes no
#     gpu/ or window/ header.
#  5. Every global function in app/*.c carries its module's prefix: the file name's first word and '_'
#     (scene_json.c: scene_, res_csg_list.c: res_), or one of the few names below that a module owns
#     for its types (quality.c: knob_ and preset_, the QUALITY_KNOBS table's rows and presets).
# (Calls in a circle between files are tests/tree/calls.sh's, on the built libraries.)
set -u
cd "$1" || exit 2
fail=0
say() { echo "layers: $*"; fail=1; }

edges=$(mktemp)
trap 'rm -f "$edges" "$edges".*' EXIT INT TERM
# the rows: the first column of the guide's table, `main.c`, `window/`, ... `util.c`
sed -n '/^## The layers/,/^## /p' docs/guide/how-it-works.md | sed -n 's/^| `\([^`]*\)` |.*/\1/p' >"$edges.rows"
[ -s "$edges.rows" ] || say "docs/guide/how-it-works.md has no layer table under '## The layers'"
for row in $(grep '/$' "$edges.rows"); do
    [ -d "app/$row" ] || say "the guide's layer table names app/$row, which does not exist"
done
for d in $(cd app && find . -mindepth 1 -type d | sed 's#^\./##' | sort); do
    [ -n "$(find "app/$d" -maxdepth 1 -type f -print -quit)" ] || continue # a folder of folders
    grep -qxF "$d/" "$edges.rows" || say "app/$d/ is no row of the guide's layer table (docs/guide/how-it-works.md)"
done
files=$(cd app && find . -name '*.c' -o -name '*.h' -o -name '*.cpp' | sed 's#^\./##' | sort)
# each file's row: the longest row that names it or a folder above it
echo "$files" | awk 'NR == FNR { row[++n] = $0; next }
    { best = "x"; len = 0
      for (i = 1; i <= n; i++) {
          r = row[i]
          if ((r ~ /\/$/ ? index($0, r) == 1 : $0 == r) && length(r) > len) { best = i; len = length(r) }
      }
      print $0, best }' "$edges.rows" - >"$edges.floor"
for f in $files; do
    for inc in $(sed -n 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*\)".*/\1/p' "app/$f"); do
        [ -f "app/$inc" ] || { say "app/$f includes \"$inc\", which is no app/ path"; continue; }
        echo "$f $inc" >>"$edges"
    done
done
bad=$(awk 'NR == FNR { floor[$1] = $2; next }
    function dir(p) { return p ~ /\// ? substr(p, 1, match(p, /\/[^\/]*$/)) : "" }
    { from = floor[$1]; to = floor[$2]
      if (from == "x") { if (!(($1) in told)) print "app/" $1 " is in no row of the layer table: put it in a row'"'"'s folder"; told[$1] = 1; next }
      if (dir($1) != dir($2) && to != "x" && to + 0 <= from + 0)
          print "app/" $1 " (row " from ") includes " $2 " (row " to "): includes go down the rows only" }' \
    "$edges.floor" "$edges")
[ -n "$bad" ] && say "$bad"
# Module X is X.c (or .cpp) with X.h. A header without a .c of its own (types, inline helpers, a
# module's internal declarations) is no module: what it includes counts for the files that include it.
sources=$(cd app && find . -name '*.c' -o -name '*.cpp' | sed 's#^\./##' | tr '\n' ' ')
awk -v sources="$sources" '
    BEGIN { n = split(sources, a, " "); for (i = 1; i <= n; i++) { f = a[i]; sub(/\.[a-z]+$/, "", f); src[f] = 1 } }
    { inc[$1] = inc[$1] " " $2 }
    function stem(f) { sub(/\.[a-z]+$/, "", f); return f }
    function walk(from, f,   n, a, i) {
        if (seen[from, f]++) return
        n = split(inc[f], a, " ")
        for (i = 1; i <= n; i++)
            if (stem(a[i]) in src) { if (stem(a[i]) != stem(from)) print stem(from), stem(a[i]) }
            else walk(from, a[i])
    }
    END { for (f in inc) if (stem(f) in src) walk(f, f) }
' "$edges" >"$edges.mod"
tsort "$edges.mod" >/dev/null 2>"$edges.err" || true
if [ -s "$edges.err" ]; then
    say "include cycle between modules (X.c and X.h are module X):"; cat "$edges.err"
fi
rm -f "$edges.err" "$edges.mod"

long=$(find app shaders -name '*.c' -o -name '*.cpp' -o -name '*.h' -o -name '*.glsl' -o -name '*.frag' \
           -o -name '*.vert' | sort | xargs awk -v MAX=80 -f tests/lib/funclen.awk)
[ -n "$long" ] && say "functions over 80 lines (split them into named steps):
$long"
big=$(find app shaders tests -type f \( -name '*.c' -o -name '*.cpp' -o -name '*.h' -o -name '*.glsl' -o -name '*.frag' \
          -o -name '*.vert' -o -name '*.comp' -o -name '*.sh' -o -name '*.txt' \) -not -path 'tests/golden/*' | sort |
      xargs wc -l | awk '$2 != "total" && $1 > 600 { print "  " $2 ": " $1 " lines" }')
[ -n "$big" ] && say "files over 600 lines (split them by what they cover):
$big"

# 4. cited files exist
cited=$(grep -rhoE '(app|shaders|tests|docs)/[A-Za-z0-9_./-]*[A-Za-z0-9_]\.(c|h|cpp|glsl|frag|vert|sh|md|json)\b' \
            app shaders tests CMakeLists.txt README.md docs --include='*.c' --include='*.h' --include='*.cpp' \
            --include='*.glsl' --include='*.frag' --include='*.vert' --include='*.sh' --include='*.md' \
            --include='CMakeLists.txt' | sort -u)
for p in $cited; do
    case $p in tests/probe.json | *NAME* | *FILE*) continue ;; esac # written by the GL tests; placeholders
    [ -e "$p" ] || say "'$p' is cited but does not exist (grep -rn '$p' to find where)"
done
# a test cited with one of its cases (`test_gl adaptive_sampling`) is a test file with that case
for cite in $(grep -rhoE '`test_[a-z_0-9]+ [a-z_0-9]+`' README.md docs --include='*.md' | tr ' ' ':' | tr -d '`' | sort -u); do
    file=$(find tests -name "${cite%%:*}.c" | head -1)
    if [ -z "$file" ] || ! grep -q "^static void ${cite#*:}(void \*\*" "$file"; then
        say "'${cite%%:*} ${cite#*:}' is cited but no test file ${cite%%:*}.c has the case ${cite#*:}"
    fi
done
# (a Fragmentarium include's name, DE-Raytracer.frag, is the host's file, not fathom's: app/scene/frag*.[ch]
# and shaders/frag/ name them)
names=$(grep -rhE '[A-Za-z0-9_]+\.(c|h|cpp|glsl|frag|vert)\b' app shaders --include='*.c' --include='*.h' \
            --include='*.cpp' --include='*.glsl' --include='*.frag' --include='*.vert' --exclude='frag*.[ch]' \
            --exclude-dir=frag | grep -v '^[[:space:]]*#[[:space:]]*include' |
        grep -oE '(^|[^A-Za-z0-9_/.<])[A-Za-z][A-Za-z0-9_]{2,}\.(c|h|cpp|glsl|frag|vert)\b' | sed 's/^[^A-Za-z]//' | sort -u)
for n in $names; do
    case $n in program.glsl | NAME.* | FILE.*) continue ;; esac # the generated virtual file; placeholders
    case $n in stb_*.h | cJSON.h | csv.h | gl.h | egl.h | glfw3.h | cmocka.h | gdal*.h | cpl_*.h | ogr_*.h) continue ;; esac
    [ -n "$(find app shaders tests -name "$n" -print -quit)" ] || say "'$n' is cited in app/ or shaders/ but no such file exists"
done

# 5. module prefixes (C++ files keep their helpers in an anonymous namespace)
for f in $(find app -name '*.c' | sort); do
    stem=$(basename "${f%.c}")
    case $stem in
    quality) also="knob_ preset_" ;;     # the knob table's rows and the presets
    terrain) also="heightfield_" ;;      # the heightfield type it loads
    resolution) also="res_" ;;           # the res_controller
    util) also="err_ sb_" ;;             # err_t and strbuf
    *) also="" ;;
    esac
    bad=$(awk -v pre="${stem%%_*}_ $also" '
        /^[A-Za-z]/ && !/^(static|typedef|extern|enum|union|#)/ && !/^struct [A-Za-z_]+ *\{/ && /\(/ && !/;[[:space:]]*$/ {
            line = $0; sub(/\(.*/, "", line); n = split(line, w, /[ \t*]+/); name = w[n]
            if (name == "main") next
            k = split(pre, p, " "); ok = 0
            for (i = 1; i <= k; i++) if (index(name, p[i]) == 1) ok = 1
            if (!ok) print FILENAME ":" FNR ": " name
        }' "$f")
    [ -n "$bad" ] && say "global functions without their module's prefix (${stem%%_*}_$also; or make them static):
$bad"
done

# 6. the pure library includes nothing of the GL layers
pure=$(awk '/add_library\(fathom_pure STATIC/ {f = 1; next} f && /\)/ {print; exit} f' CMakeLists.txt | tr -d ')' | tr ' ' '\n' | grep '\.c$')
[ -n "$pure" ] || say "CMakeLists.txt has no fathom_pure source list to check"
for f in $pure; do
    grep -n '^[[:space:]]*#[[:space:]]*include[[:space:]]*"\(gpu\|window\)/' "$f" |
        sed "s#^#$f:#; s#\$# (the pure library includes no GL header)#" | while IFS= read -r l; do echo "layers: $l"; done
    grep -q '^[[:space:]]*#[[:space:]]*include[[:space:]]*"\(gpu\|window\)/' "$f" && fail=1
done

[ $fail = 0 ] && echo "layers: ok ($(wc -l <"$edges") includes, every folder a row of the guide's table and every include down the rows, no cycle, no long function or file, every cited file exists, every global function prefixed, the pure library free of GL headers)"
exit $fail
