#!/bin/sh
# Builds librugo's libFuzzer targets with clang in build-fuzz/ and runs each for a bounded time.
#   scripts/fuzz.sh               each target for 20 s
#   scripts/fuzz.sh 300           each target for 300 s
#   scripts/fuzz.sh -runs=100000  each target for 100000 inputs
#   scripts/fuzz.sh 20 fuzz_baked only the named targets
# New inputs go to build-fuzz/corpus/<target> (the checked-in seeds in fuzz/corpus/<target> are only
# read); a crash leaves build-fuzz/artifacts/<target>-crash-* and makes this script fail.
# Environment: RUGO_FUZZ_BUILD (default build-fuzz), CC (default clang), RUGO_FUZZ_JOBS (default 2),
# RUGO_FUZZ_CORPUS (where new inputs go, default build-fuzz/corpus; one directory per target),
# RUGO_FUZZ_SEED (libFuzzer's -seed; unset: a new seed each run). With a seed, -runs=N and a fresh
# corpus, a run repeats on the same machine and checkout: scripts/test.sh uses that so the suite's
# verdict does not depend on luck or machine speed.
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${RUGO_FUZZ_BUILD:-$root/build-fuzz}
corpus=${RUGO_FUZZ_CORPUS:-$build/corpus}
limit=${1:-20}
[ $# -gt 0 ] && shift
targets=${*:-fuzz_shape_json fuzz_baked fuzz_contacts fuzz_import fuzz_bridge}
case $limit in
    -runs=*) budget=$limit ;;
    *[!0-9]*|''|0) echo "usage: $0 [SECONDS | -runs=N] [TARGET...]" >&2; exit 2 ;;
    *) budget=-max_total_time=$limit ;;
esac
seed=
norand=
if [ -n "${RUGO_FUZZ_SEED:-}" ]; then
    seed="-seed=$RUGO_FUZZ_SEED -reload=0" # (-reload: a timer)
    # Coverage also depends on heap addresses (e.g. which of two buffers lies lower), so a seed alone
    # does not repeat a run: turn off address randomisation where the machine allows it.
    if setarch "$(uname -m)" -R true 2>/dev/null; then
        norand="setarch $(uname -m) -R"
    else
        echo "fuzz: setarch -R not permitted here; the seeded run may differ from run to run" >&2
    fi
fi
cc=${CC:-clang}
command -v "$cc" >/dev/null 2>&1 || { echo "fuzz: $cc not found (apt-get install clang libclang-rt-14-dev)" >&2; exit 1; }

cmake -S "$root/fuzz" -B "$build" -DCMAKE_C_COMPILER="$cc" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
# fuzz_bridge exists only where Box2D and clang++ are (fuzz/CMakeLists.txt): skip it elsewhere, loudly.
if [ $# -eq 0 ] && ! grep -q "^fuzz_bridge:" "$build/Makefile" 2>/dev/null; then
    echo "fuzz: fuzz_bridge not configured (needs libbox2d-dev and clang++); skipped" >&2
    targets=$(echo "$targets" | sed 's/ fuzz_bridge//')
fi
cmake --build "$build" -j "${RUGO_FUZZ_JOBS:-2}" --target $targets

status=0
for t in $targets; do
    mkdir -p "$corpus/$t" "$build/artifacts"
    echo "fuzz: $t ($budget${seed:+ $seed})"
    # -max_len: the seeds are small; larger inputs mostly cost time. -timeout: a hang is a finding.
    if ! $norand "$build/$t" "$corpus/$t" "$root/fuzz/corpus/$t" "$budget" $seed -max_len=16384 -timeout=20 \
        -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build/artifacts/$t-" \
        >"$build/$t.log" 2>&1; then
        echo "fuzz: $t FAILED; see $build/$t.log and $build/artifacts/" >&2
        tail -n 40 "$build/$t.log" >&2
        status=1
    else
        grep -E "^stat::number_of_executed_units|^stat::new_units_added" "$build/$t.log" | sed "s/^/fuzz: $t /"
    fi
done
exit $status
