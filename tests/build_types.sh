#!/bin/sh
# build_types.sh SOURCE_DIR: fathom builds with every CMake build type, warnings as errors, and its pure
# tests pass in each (the ctest build is RelWithDebInfo, so the other three are built here). Debug and
# MinSizeRel with clang where it is installed (GCC otherwise), Release with GCC: both compilers, and
# GCC's -O3 warnings (maybe-uninitialized) that a -O2 build never shows. Builds go to a temporary
# folder that is removed on any exit.
set -u
src=$(cd "$1" && pwd) || exit 2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/fathom-build-types.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
cc_for() { # the compiler pair for a build type
    if [ "$1" != Release ] && command -v clang >/dev/null && command -v clang++ >/dev/null; then
        echo "clang clang++"
    else
        echo "gcc g++"
    fi
}
fail=0
for type in Debug Release MinSizeRel; do
    set -- $(cc_for $type)
    dir="$tmp/$type"
    log="$tmp/$type.log"
    echo "build_types: $type with $1"
    if ! CC=$1 CXX=$2 cmake -S "$src" -B "$dir" -DCMAKE_BUILD_TYPE=$type -DBUILD_TESTING=ON -DFATHOM_WERROR=ON >"$log" 2>&1 ||
       ! cmake --build "$dir" -j 2 --target pure_tests fathom >>"$log" 2>&1; then
        echo "build_types: $type with $1 does not build:"; grep -E 'error|warning' "$log" | head -20
        fail=1
        continue
    fi
    if ! ctest --test-dir "$dir" -L pure -E layers --output-on-failure >>"$log" 2>&1; then
        echo "build_types: $type with $1: pure tests fail:"; tail -30 "$log"
        fail=1
    fi
    "$dir/fathom" --version >/dev/null || { echo "build_types: $type: fathom --version fails"; fail=1; }
    rm -rf "$dir"
done
[ $fail = 0 ] && echo "build_types: Debug, Release and MinSizeRel build with warnings as errors and pass the pure tests"
exit $fail
