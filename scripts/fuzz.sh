#!/usr/bin/env bash
# Builds the libFuzzer targets with clang into build-fuzz/ and runs each for a longer time
# (docs/FUZZING.md). They start from the seeds the build writes into build-fuzz/fuzz/seeds/
# (building a fuzz target writes its seeds) and, for fuzz_scene, the hand-made ones of
# fuzz/corpus/scene-handmade/. Inputs that find new coverage collect in
# build-fuzz/fuzz/corpus/<target>/ and are reused by the next run; a crash stops that fuzzer and
# leaves its reproducer in build-fuzz/fuzz/artifacts/<target>/.
# Usage: scripts/fuzz.sh [seconds per target, default 600] [extra libFuzzer flags...]
# FUZZ_TARGETS="protocol" (or "scene") runs only that target; both by default. The recorded
# long runs (docs/FUZZING.md) are FUZZ_TARGETS=protocol scripts/fuzz.sh 86400 -runs=10000000.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-600}"
shift || true
build="$root/build-fuzz"

if ! command -v clang++ >/dev/null; then
  echo "clang++ not found: run scripts/setup.sh clang libclang-rt-14-dev" >&2
  exit 1
fi
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DIGI_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
# The seed targets write build-fuzz/fuzz/seeds/ (the fuzz targets depend on them anyway).
cmake --build "$build" --target fuzz_protocol fuzz_scene fuzz_protocol_seeds fuzz_scene_seeds \
  -j "$(nproc)"

status=0
for target in ${FUZZ_TARGETS:-protocol scene}; do
  case "$target" in protocol | scene) ;; *) echo "FUZZ_TARGETS: no target '$target'" >&2; exit 2 ;; esac
  corpus="$build/fuzz/corpus/$target"
  artifacts="$build/fuzz/artifacts/$target"
  log="$build/fuzz/$target.log"
  seeds=("$build/fuzz/seeds/$target")
  if [ "$target" = scene ]; then seeds+=("$root/fuzz/corpus/scene-handmade"); fi
  mkdir -p "$corpus" "$artifacts"
  echo "== fuzz_$target: $seconds s (log: $log)"
  # New inputs go to the first folder; the seeds are only read.
  # -purge_allocator_interval=30: once a run's peak memory passes half of -rss_limit_mb (the
  # scene target's does, near 1 GB), libFuzzer hands the sanitizer's free memory back to the
  # system every second; a profile of fuzz_scene at 1.08 million inputs put 38 % of its time
  # there (madvise and TLB flushes). -reload=0: only this process writes the corpus, so listing
  # its folder again every second (4 % more there, 13,000 files) finds nothing new.
  if "$build/fuzz/fuzz_$target" -max_total_time="$seconds" -timeout=30 -print_final_stats=1 \
    -purge_allocator_interval=30 -reload=0 \
    -artifact_prefix="$artifacts/" "$@" "$corpus" "${seeds[@]}" >"$log" 2>&1; then
    result="ok"
  elif grep -q 'libFuzzer: run interrupted' "$log"; then
    # Stopped by a signal (Ctrl-C, kill -INT): no crash, and what it ran still counts.
    result="interrupted, no crash"
    status=1
  else
    result="FAILED (reproducer in $artifacts/)"
    status=1
  fi
  # The last status line ("#N DONE cov: ... ft: ... corp: ...") and the execution count.
  grep -E '^#[0-9]+' "$log" | tail -n 1 || true
  runs="$(grep -o 'number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')"
  rate="$(grep -o 'average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')"
  echo "fuzz_$target: $runs executions ($rate per second), $result"
done
exit "$status"
