#!/usr/bin/env bash
# Proof that a refactoring left behaviour unchanged (issue #32, item 7): maps corridor_3,
# office_5min and Intel's shipped raw log in every mode and prints one SHA-256 per output that
# the mapper decides (graph.g2o, map.pgm, trajectory.tum, loops.csv). Run it before and after a
# change and diff the two listings:
#
#   scripts/behaviour_hashes.sh > /tmp/before.txt   # at the old commit
#   scripts/behaviour_hashes.sh > /tmp/after.txt    # at the new one
#   diff /tmp/before.txt /tmp/after.txt
#
# Progress goes to WORK_DIR/progress.log. Timings and figures (timeline.csv, summary.json) are left out: they hold wall times.
# Usage: scripts/behaviour_hashes.sh [BUILD_DIR] [WORK_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
work=${2:-$(mktemp -d)}
lifelong="$build/apps/lifelong"
intel=../shared/datasets/intel/intel-raw-first1088s.clf.gz

[[ -x $lifelong ]] || { echo "error: $lifelong not built" >&2; exit 2; }
# Every named mode, as the program lists them (slam/mapping/mode.cpp's table).
modes=$("$lifelong" run --help | sed -n 's/.*comma-separated, of \(.*\), or POLICY+SPARSIFIER.*/\1/p' |
  tr -d ' ')
[[ -n $modes ]] || { echo "error: no mode list in '$lifelong run --help'" >&2; exit 2; }
mkdir -p "$work"
log="$work/progress.log"
printf 'loops:\n  global:\n    enabled: false\n' >"$work/no_global.yaml"
"$lifelong" run scenarios/corridor_3.yaml --modes "$modes" -o "$work/corridor_3" >"$log" 2>&1
"$lifelong" run scenarios/office_5min.yaml --modes "$modes" -o "$work/office_5min" >>"$log" 2>&1
"$lifelong" replay "$intel" --modes "$modes" -o "$work/intel" >>"$log" 2>&1
# The global place search is on by default; this run covers the local search alone.
"$lifelong" replay "$intel" --modes standard,pruned --config "$work/no_global.yaml" \
  -o "$work/intel_local" >>"$log" 2>&1

for run in corridor_3 office_5min intel intel_local; do
  for mode in ${modes//,/ }; do
    [[ $run == intel_local && $mode != standard && $mode != pruned ]] && continue
    for file in graph.g2o map.pgm trajectory.tum loops.csv; do
      path="$work/$run/$mode/$file"
      if [[ -f $path ]]; then
        echo "$(sha256sum <"$path" | cut -c1-16)  $run/$mode/$file"
      else
        echo "missing           $run/$mode/$file"
      fi
    done
  done
done
