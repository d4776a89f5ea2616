#!/usr/bin/env bash
# CI benchmark step (after the tests): runs the hot-path benchmarks briefly and one short
# scenario, prints the key figures and compares them with bench/baseline.json as ratios.
# It flags slow-downs beyond the tolerance but never fails: shared CI machines are noisy.
# Usage: scripts/ci-bench.sh [--record]   (--record rewrites bench/baseline.json)
set -uo pipefail
cd "$(dirname "$0")/.."
out=build/ci-bench
mkdir -p "$out"
run_bench() {  # name filter
  if [ -x "build/bench/$1" ]; then
    "build/bench/$1" --benchmark_filter="$2" --benchmark_min_time=0.2 \
      --benchmark_format=json --benchmark_out="$out/$1.json" --benchmark_out_format=json \
      > /dev/null 2> "$out/$1.log" || echo "ci-bench: $1 failed (see $out/$1.log)"
  fi
}
run_bench frontend_bench 'BM_GridAddRemoveScan|BM_InformationGain|BM_GainIndex|BM_MatchIncremental|BM_MatchLoopClosure/32'
run_bench marginalization_bench 'BM_Marginalize(Exact|ChowLiu)/(6|20)$'
run_bench backend_bench 'BM_Optimize/(intel|input_M3500)$'
run_bench sim_bench 'BM_RayCastOfficeScan361'
run_bench map_keeper_bench 'BM_MapKeeperMove'
start=$(date +%s.%N)
build/apps/lifelong run scenarios/corridor_3.yaml -o "$out/corridor_3" > "$out/run.log" 2>&1 \
  || echo "ci-bench: lifelong run failed (see $out/run.log)"
end=$(date +%s.%N)
echo "$start $end" > "$out/run_wall.txt"
python3 scripts/ci_bench_compare.py "$out" bench/baseline.json "$@"
exit 0
