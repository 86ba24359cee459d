#!/bin/sh
# One entry of the fuzzing ledger (docs/fuzzing.md, "Ledger"): runs one fuzz target for SECONDS at
# nice 19 starting from the checked-in corpus fuzz/corpus/<target>, merges what it found into that
# corpus (libFuzzer's -merge=1: only inputs that add coverage are added), appends a row
# date,target,executions,corpus_size,findings to fuzz/ledger.csv and rewrites the summary table of
# docs/fuzzing.md from the whole ledger.
#   scripts/fuzz_ledger.sh 3600 fuzz_contacts
#   scripts/fuzz_ledger.sh --summary            only rewrite the summary table
# Run one at a time on a shared machine. A finding (crash, leak, sanitizer report, timeout, broken
# property) is counted in the row, its input kept in build-fuzz/artifacts/, and the script exits 1.
# Environment: RUGO_FUZZ_BUILD (default build-fuzz), CC (default clang), CXX (default clang++),
# RUGO_FUZZ_MERGE (default 1; 0: copy the run's new inputs instead of merging, see below).
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
ledger=$root/fuzz/ledger.csv
doc=$root/docs/fuzzing.md

summary() {
    # Per target: the last run's date, the cumulative executions, the corpus after the last run, the
    # findings of all runs and the number of runs; rows in the order targets first appear.
    table=$(awk -F, 'NR > 1 && NF == 5 {
            if (!($2 in runs)) order[++n] = $2
            runs[$2]++; execs[$2] += $3; finds[$2] += $5; last[$2] = $1; size[$2] = $4
        }
        END {
            print "| target | date (last run) | executions (total) | corpus size | findings | runs |"
            print "|---|---|---:|---:|---:|---:|"
            for (i = 1; i <= n; ++i) {
                t = order[i]
                printf "| `%s` | %s | %.0f | %d | %d | %d |\n", t, last[t], execs[t], size[t], finds[t], runs[t]
            }
        }' "$ledger")
    awk -v table="$table" '
        /<!-- ledger summary begin/ { print; print table; skip = 1; next }
        /<!-- ledger summary end/ { skip = 0 }
        !skip { print }' "$doc" >"$doc.tmp"
    mv "$doc.tmp" "$doc"
}

if [ "${1:-}" = "--summary" ]; then
    summary
    exit 0
fi
[ $# -eq 2 ] || { echo "usage: $0 SECONDS TARGET | --summary" >&2; exit 2; }
seconds=$1
target=$2
case $seconds in *[!0-9]*|''|0) echo "fuzz_ledger: SECONDS must be a positive integer" >&2; exit 2 ;; esac
[ -d "$root/fuzz/corpus/$target" ] || { echo "fuzz_ledger: no fuzz/corpus/$target" >&2; exit 2; }

build=${RUGO_FUZZ_BUILD:-$root/build-fuzz}
cmake -S "$root/fuzz" -B "$build" -DCMAKE_C_COMPILER="${CC:-clang}" -DCMAKE_CXX_COMPILER="${CXX:-clang++}" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
nice -n 19 cmake --build "$build" -j 1 --target "$target" >/dev/null

work=$build/ledger/$target
rm -rf "$work"
mkdir -p "$work/run" "$build/artifacts"
cp "$root/fuzz/corpus/$target/"* "$work/run/"
before=$(ls "$build/artifacts" | grep -c "^$target-" || true)
rc=0
nice -n 19 "$build/$target" "$work/run" -max_total_time="$seconds" -max_len=16384 -timeout=20 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build/artifacts/$target-" \
    >"$work/run.log" 2>&1 || rc=$?
after=$(ls "$build/artifacts" | grep -c "^$target-" || true)
findings=$((after - before))
[ $rc -ne 0 ] && [ $findings -eq 0 ] && findings=1
# Executions: the final statistics, or after a crash the last status line ("#N ...").
executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/run.log" | tail -n 1)
[ -n "$executions" ] || executions=$(sed -n 's/^#\([0-9][0-9]*\).*/\1/p' "$work/run.log" | tail -n 1)
[ -n "$executions" ] || executions=0

if [ "${RUGO_FUZZ_MERGE:-1}" = 1 ]; then
    nice -n 19 "$build/$target" -merge=1 -max_len=16384 -timeout=20 -rss_limit_mb=2048 "$root/fuzz/corpus/$target" \
        "$work/run" >"$work/merge.log" 2>&1 || {
        echo "fuzz_ledger: merge failed; see $work/merge.log" >&2
        exit 1
    }
else
    # The merge re-runs every input: on a machine so loaded that nice 19 gets ~1 % of a core it takes
    # longer than the run. Then keep what the run added (libFuzzer saves only inputs that add coverage),
    # under their SHA-1 names, and minimise with a later merge.
    for f in "$work/run/"*; do
        [ -e "$root/fuzz/corpus/$target/$(basename "$f")" ] || cmp -s "$f" /dev/null ||
            cp "$f" "$root/fuzz/corpus/$target/$(sha1sum "$f" | cut -c1-40)"
    done
fi
corpus_size=$(ls "$root/fuzz/corpus/$target" | wc -l)
[ -f "$ledger" ] || echo "date,target,executions,corpus_size,findings" >"$ledger"
echo "$(date -u +%Y-%m-%d),$target,$executions,$corpus_size,$findings" >>"$ledger"
summary
echo "fuzz_ledger: $target: $executions executions in $seconds s, corpus $corpus_size, findings $findings"
if [ $findings -ne 0 ]; then
    echo "fuzz_ledger: see $work/run.log and $build/artifacts/$target-*" >&2
    tail -n 40 "$work/run.log" >&2
    exit 1
fi
