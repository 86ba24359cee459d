#!/bin/sh
# Every test: set up what is missing, then build and run the whole suite twice — a normal build with
# warnings as errors, and an AddressSanitizer + UndefinedBehaviorSanitizer build — and finally a short
# libFuzzer run of each fuzz target (clang; docs/fuzzing.md has the long-run command).
set -eu
cd "$(dirname "$0")/.."
sh scripts/setup.sh
jobs="$(nproc 2>/dev/null || echo 2)"
status=0
for variant in normal sanitize; do
    dir="build-test-$variant"
    san=OFF
    [ "$variant" = sanitize ] && san=ON
    echo "=== $variant build ($dir) ==="
    cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRUGO_WARNINGS_AS_ERRORS=ON -DRUGO_ENABLE_ASSERTS=ON \
        -DRUGO_SANITIZE="$san" >/dev/null
    cmake --build "$dir" -j "$jobs"
    (cd "$dir" && ctest --output-on-failure -j "$jobs") || status=1
done
echo "=== fuzz (short run) ==="
# Seeded and counted, on a fresh corpus of its own (build-fuzz/corpus, the long runs', is kept): the
# same inputs on each run in the same checkout (docs/fuzzing.md).
rm -rf build-fuzz/suite-corpus
RUGO_FUZZ_CORPUS=build-fuzz/suite-corpus RUGO_FUZZ_SEED=1 sh scripts/fuzz.sh -runs=30000 || status=1
exit $status
