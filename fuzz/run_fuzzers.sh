#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan) into build-fuzz and runs each for a
# bounded time, starting from the seed corpus in fuzz/corpus/<target>/ (read only) and a
# working corpus in build-fuzz/corpus/<target>/ that persists between runs.
#   fuzz/run_fuzzers.sh            # 60 s per target
#   fuzz/run_fuzzers.sh 300 graph  # 300 s, only fuzz_graph
# Crashes, timeouts and out-of-memory inputs land in build-fuzz/artifacts/<target>/; the
# script exits 1 when any target found one. Per-target logs: build-fuzz/logs/<target>.log.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET="${1:-60}"
shift || true
TARGETS=("$@")
[[ ${#TARGETS[@]} -eq 0 ]] && TARGETS=(world scenario carmen graph relations tum map)

CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DLIFELONG_BUILD_FUZZERS=ON -DLIFELONG_BUILD_TESTS=OFF -DLIFELONG_BUILD_BENCHMARKS=OFF \
  >/dev/null
cmake --build build-fuzz -j"${JOBS:-1}" --target "${TARGETS[@]/#/fuzz_}"

declare -A DICT=([world]=yaml [scenario]=yaml [carmen]=carmen [graph]=graph [relations]=numbers
  [tum]=numbers [map]=map)
status=0
for t in "${TARGETS[@]}"; do
  work="build-fuzz/corpus/$t" art="build-fuzz/artifacts/$t" log="build-fuzz/logs/$t.log"
  mkdir -p "$work" "$art" "$(dirname "$log")"
  # -rss_limit_mb / -malloc_limit_mb: a loader that allocates more than this on a
  # 4 KiB input has a bug; -timeout: one input must not take 10 s.
  if ! "build-fuzz/fuzz/fuzz_$t" "$work" "fuzz/corpus/$t" -dict="fuzz/${DICT[$t]}.dict" \
      -max_total_time="$SECONDS_PER_TARGET" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
      -malloc_limit_mb=512 -artifact_prefix="$art/" -print_final_stats=1 >"$log" 2>&1; then
    status=1
    echo "fuzz_$t: FOUND A PROBLEM, see $log and $art/"
  fi
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
  corpus=$(grep -o 'DONE .*corp: [0-9]*/[0-9]*[a-zA-Z]*' "$log" | grep -o '[0-9]*/[0-9]*[a-zA-Z]*$' || true)
  cov=$(grep -o 'DONE *cov: [0-9]* ft: [0-9]*' "$log" | grep -o 'cov: .*' || true)
  echo "fuzz_$t: ${SECONDS_PER_TARGET} s, ${execs:-?} runs, ${rate:-?} exec/s, ${cov:-cov ?}," \
    "corpus ${corpus:-?} (inputs/size), $(find "$work" -type f | wc -l) files in $work"
done
exit "$status"
