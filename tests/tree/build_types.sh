#!/bin/sh
# build_types.sh SOURCE_DIR: fathom builds with every CMake build type, warnings as errors, and its pure
# tests pass in each (the ctest build is RelWithDebInfo, so the other three are built here). Debug and
# MinSizeRel with clang where it is installed (GCC otherwise), Release with GCC: both compilers, and
# GCC's -O3 warnings (maybe-uninitialized) that a -O2 build never shows. The clang MinSizeRel build is
# the fuzz build (libFuzzer, ASan + UBSan: -DFATHOM_FUZZ=ON): it builds fathom and the three fuzzers,
# and each fuzzer runs a few seconds on its seeds (tests/fuzz/run.sh), so the fuzzers keep building
# in CI's toolchain; its pure tests are the other two builds' (under the sanitizers they took minutes).
# Builds go to a temporary folder that is removed on any exit.
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
FUZZ_SMOKE_SECONDS=5
for type in Debug Release MinSizeRel; do
    set -- $(cc_for $type)
    dir="$tmp/$type"
    log="$tmp/$type.log"
    fuzz=OFF targets="pure_tests fathom"
    if [ $type = MinSizeRel ] && [ $1 = clang ]; then
        fuzz=ON targets="fathom fuzz_scene fuzz_droplets fuzz_readers"
    fi
    echo "build_types: $type with $1$([ $fuzz = ON ] && echo ', the fuzzers')"
    if ! CC=$1 CXX=$2 cmake -S "$src" -B "$dir" -DCMAKE_BUILD_TYPE=$type -DBUILD_TESTING=ON -DFATHOM_WERROR=ON \
            -DFATHOM_FUZZ=$fuzz >"$log" 2>&1 ||
       ! cmake --build "$dir" -j 2 --target $targets >>"$log" 2>&1; then
        echo "build_types: $type with $1 does not build:"; grep -E 'error|warning' "$log" | head -20
        fail=1
        continue
    fi
    if [ $fuzz = OFF ] && ! ctest --test-dir "$dir" -L pure -E layers --output-on-failure >>"$log" 2>&1; then
        echo "build_types: $type with $1: pure tests fail:"; tail -30 "$log"
        fail=1
    fi
    "$dir/fathom" --version >/dev/null || { echo "build_types: $type: fathom --version fails"; fail=1; }
    for target in scene droplets readers; do
        [ $fuzz = ON ] || break
        if FUZZ_BUILD="$dir" FUZZ_SECONDS=$FUZZ_SMOKE_SECONDS sh "$src/tests/fuzz/run.sh" 0 $target >"$tmp/fuzz.log" 2>&1; then
            echo "build_types: fuzz_$target: $(grep -o 'stat::number_of_executed_units: *[0-9]*' "$tmp/fuzz.log" | grep -o '[0-9]*$') runs in ${FUZZ_SMOKE_SECONDS} s, nothing found"
        else
            echo "build_types: fuzz_$target found something or did not run:"; tail -25 "$tmp/fuzz.log"
            fail=1
        fi
    done
    rm -rf "$dir"
done
[ $fail = 0 ] && echo "build_types: Debug, Release and MinSizeRel build with warnings as errors and pass the pure tests; the fuzzers run"
exit $fail
