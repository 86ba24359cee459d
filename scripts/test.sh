#!/bin/sh
# Every test: set up what is missing, then build and run the whole suite twice — a normal build with
# warnings as errors, and an AddressSanitizer + UndefinedBehaviorSanitizer build — and finally a short
# libFuzzer run of each fuzz target (clang; docs/fuzzing.md has the long-run command). The two builds
# are the presets normal and sanitize of CMakePresets.json (build-test-normal, build-test-sanitize).
set -eu
cd "$(dirname "$0")/.."
sh scripts/setup.sh
jobs="$(nproc 2>/dev/null || echo 2)"
status=0
for preset in normal sanitize; do
    echo "=== $preset build (build-test-$preset) ==="
    cmake --preset "$preset" >/dev/null
    cmake --build --preset "$preset" -j "$jobs"
    ctest --preset "$preset" -j "$jobs" || status=1
done
echo "=== fuzz (short run) ==="
# Seeded and counted, on a fresh corpus of its own (build-fuzz/corpus, the long runs', is kept): the
# same inputs on each run in the same checkout (docs/fuzzing.md).
rm -rf build-fuzz/suite-corpus
RUGO_FUZZ_CORPUS=build-fuzz/suite-corpus RUGO_FUZZ_SEED=1 sh scripts/fuzz.sh -runs=30000 \
    fuzz_shape_json fuzz_baked fuzz_contacts fuzz_import || status=1
# The bridge target builds a Box2D world per input (about 100 inputs a second): fewer runs keep CI short.
if command -v clang++ >/dev/null 2>&1 && [ -f /usr/include/box2d/box2d.h ]; then
    RUGO_FUZZ_CORPUS=build-fuzz/suite-corpus RUGO_FUZZ_SEED=1 sh scripts/fuzz.sh -runs=3000 fuzz_bridge || status=1
fi
exit $status
