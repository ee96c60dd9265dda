#!/usr/bin/env bash
# Runs every fuzz target of a fuzz build (`make fuzz`) for a set time, one after another, one job
# each, and prints one line per target: its time, executions and result. Exits 1 when any target
# crashed (or leaked, ran out of memory or hung past the timeout); the input that did it is kept
# in <build>/fuzz/crashes/<target>/ and named in the output.
#
#   scripts/run-fuzzers.sh [build-fuzz] [seconds per target, 600] [target ...]
#
# Each target reads its seeds (generated in <build>/fuzz/seeds/<target>, checked in under
# fuzz/corpus/<target>) and grows its own corpus in <build>/fuzz/work/<target>, kept between runs.
set -uo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:-build-fuzz}" && pwd)"
seconds="${2:-600}"
shift 2 2>/dev/null || shift $#
targets=("$@")
if [ "${#targets[@]}" -eq 0 ]; then
  mapfile -t targets < "$build/fuzz/targets.txt"
fi

failed=0
for target in "${targets[@]}"; do
  [ -n "$target" ] || continue
  binary="$build/fuzz/${target}_fuzzer"
  work="$build/fuzz/work/$target"
  crashes="$build/fuzz/crashes/$target"
  log="$build/fuzz/logs/$target.log"
  mkdir -p "$work" "$crashes" "$(dirname "$log")"
  seeds=()
  for dir in "$build/fuzz/seeds/$target" "$root/fuzz/corpus/$target"; do
    [ -d "$dir" ] && seeds+=("$dir")
  done
  start=$(date +%s)
  # -timeout: an input that takes longer is a hang; -rss_limit_mb (and the malloc limit it sets):
  # a reader that allocates what a short input claims is a finding too.
  "$binary" -max_total_time="$seconds" -timeout=25 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$crashes/" "$work" "${seeds[@]}" > "$log" 2>&1
  status=$?
  took=$(( $(date +%s) - start ))
  executions=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  corpus=$(find "$work" -type f | wc -l)
  if [ "$status" -eq 0 ]; then
    printf 'fuzz: %-14s %5d s %12s executions  corpus %5d  ok\n' \
      "$target" "$took" "${executions:-?}" "$corpus"
  else
    failed=1
    input=$(grep -o 'Test unit written to [^ ]*' "$log" | tail -1 | sed 's/Test unit written to //')
    reason=$(grep -m1 -o 'ERROR: [A-Za-z]*Sanitizer: [^ ]*\|ERROR: libFuzzer: [a-z-]*\|check failed: .*' "$log")
    printf 'fuzz: %-14s %5d s %12s executions  corpus %5d  CRASH (%s) input %s, log %s\n' \
      "$target" "$took" "${executions:-?}" "$corpus" "${reason:-exit $status}" "${input:-?}" "$log"
  fi
done
exit "$failed"
