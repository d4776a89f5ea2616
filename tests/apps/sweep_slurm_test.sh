#!/usr/bin/env bash
# `lifelong sweep --slurm` against a real Slurm (issue #14): starts its own munged, slurmctld
# and slurmd (one node, this machine) with scripts/slurm-local.sh in a temp dir, runs a tiny
# sweep as a job array and checks that its aggregate.csv equals the local pool's (-j 2) in
# every figure that does not measure the machine (times, memory). Always stops its daemons.
# Exit 77 (skip) only where Slurm cannot run here: binaries missing, not root, or a daemon
# that exits at start (its log is printed).
# Usage: sweep_slurm_test.sh LIFELONG_BIN SOURCE_DIR
set -uo pipefail
bin=$1
src=$2
skip() { echo "SKIP: $*"; exit 77; }
for b in munged mungekey slurmctld slurmd sbatch squeue sinfo scontrol python3; do
  command -v "$b" >/dev/null || skip "$b not installed (scripts/install-deps.sh installs slurm-wlm and munge)"
done
[ "$(id -u)" -eq 0 ] || skip "the test's slurmd needs root (SlurmUser=root)"

t=$(mktemp -d /tmp/lifelong-slurm-test.XXXXXX)
# The daemons: scripts/slurm-local.sh, which a user without a cluster runs too.
slurm_local=$src/scripts/slurm-local.sh
cleanup() {
  "$slurm_local" stop "$t" >/dev/null
  rm -rf "$t"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; for f in "$t"/*.log; do echo "--- $f"; tail -n 30 "$f"; done; exit 1; }
"$slurm_local" start "$t" >"$t/start.out" 2>&1
case $? in
  0) ;;
  3) cat "$t/start.out"; skip "Slurm cannot run here (scripts/slurm-local.sh start exit 3)" ;;
  *) cat "$t/start.out"; fail "scripts/slurm-local.sh start failed" ;;
esac
export SLURM_CONF=$t/slurm.conf
cat "$t/start.out"

cat >"$t/spec.yaml" <<SPEC
scenarios: [$src/scenarios/corridor_3.yaml]
seeds: [1, 2]
modes: [standard]
SPEC
"$bin" sweep "$t/spec.yaml" -o "$t/local" -j 2 >"$t/local.out.log" 2>&1 || fail "the local sweep failed"
"$bin" sweep "$t/spec.yaml" -o "$t/slurm" --slurm --time 00:10:00 >"$t/sweep.out.log" 2>&1 ||
  fail "the slurm sweep failed"
cat "$t/sweep.out.log"
grep -q "^#SBATCH --array=0-1$" "$t/slurm/sweep.sbatch" || fail "no 2-task array in sweep.sbatch"
grep -q "^#SBATCH --time=00:10:00$" "$t/slurm/sweep.sbatch" || fail "no --time in sweep.sbatch"
grep -q "submitted slurm job [0-9]*: 2 of 2 cells" "$t/sweep.out.log" || fail "no submission line"
grep -q "slurm job [0-9]*: 2/2 tasks ended, 0 failed" "$t/sweep.out.log" || fail "no final progress"
ls "$t"/slurm/cells/slurm-*_1.out >/dev/null || fail "no task output file"
# Same figures as the local pool, except those that measure the machine.
python3 - "$t/local/aggregate.csv" "$t/slurm/aggregate.csv" <<'PY' || fail "aggregate.csv differs"
import csv, re, sys
machine = re.compile(r"^(wall_time_s|peak_rss_mb|time_per_obs_ms/|stage_ms/)")
def table(path):
    rows = list(csv.reader(open(path)))
    keep = [i for i, h in enumerate(rows[0]) if not machine.search(h)]
    return [[r[i] for i in keep] for r in rows], len(rows[0]) - len(keep)
a, dropped = table(sys.argv[1])
b, _ = table(sys.argv[2])
n = a[0].index("n")
if len(a) != 2 or a[1][n] != "2" or not dropped:
    sys.exit(f"expected one aggregate row over 2 runs and some timing columns: {a}")
if a != b:
    for x, y in zip(a, b):
        if x != y: print("local:", x, "\nslurm:", y)
    sys.exit(1)
print(f"aggregate.csv: {len(a) - 1} rows, {len(a[0])} columns equal ({dropped} machine-measuring columns left out)")
PY
# A second sweep finds every cell up to date and submits nothing.
"$bin" sweep "$t/spec.yaml" -o "$t/slurm" --slurm >"$t/again.out.log" 2>&1 || fail "the second slurm sweep failed"
grep -q "all 2 cells up to date: nothing submitted" "$t/again.out.log" || fail "the second sweep submitted: $(cat "$t/again.out.log")"

# A cell that fails (its world file is broken) is reported with its exit code and logs; the
# good cell of the same job array is collected.
sed 's|\.\./worlds/corridor\.yaml|broken_world.yaml|' "$src/scenarios/corridor_3.yaml" >"$t/broken.yaml"
grep -q broken_world "$t/broken.yaml" || fail "could not make the broken scenario"
echo 'walls: [[[0, 0], [1, oops' >"$t/broken_world.yaml"
cat >"$t/spec2.yaml" <<SPEC
scenarios: [$src/scenarios/corridor_3.yaml, $t/broken.yaml]
seeds: [3]
modes: [standard]
SPEC
"$bin" sweep "$t/spec2.yaml" -o "$t/fail" --slurm --sbatch-arg=--mem=100 >"$t/fail.out.log" 2>&1
code=$?
cat "$t/fail.out.log"
[ "$code" -eq 1 ] || fail "a sweep with a failed cell exits $code, not 1"
grep -q "^#SBATCH --mem=100$" "$t/fail/sweep.sbatch" || fail "no --sbatch-arg line in sweep.sbatch"
grep -q "^task [0-9]*_1 (cell broken-seed3) FAILED (exit 2), see $t/fail/cells/broken-seed3.run.log and $t/fail/cells/slurm-[0-9]*_1.out$" \
  "$t/fail.out.log" || fail "the failed task is not reported with its exit code and logs"
grep -q "broken_world.yaml" "$t/fail/cells/broken-seed3.run.log" || fail "the run.log does not name the broken file"
cat "$t/fail/sweep.sbatch"
grep -q "^failed: broken-seed3 (exit 2), log $t/fail/cells/broken-seed3.run.log$" "$t/fail.out.log" ||
  fail "no failed line"
grep -q "collected 1 runs of 1 cells (1 cells without a result)" "$t/fail.out.log" || fail "the good cell is not collected"

# Repaired, only that cell is submitted again: array task 0 runs plan cell 1.
cp "$src/worlds/corridor.yaml" "$t/broken_world.yaml"
"$bin" sweep "$t/spec2.yaml" -o "$t/fail" --slurm >"$t/repair.out.log" 2>&1 || fail "the repaired sweep failed"
grep -q "submitted slurm job [0-9]*: 1 of 2 cells (1 up to date)" "$t/repair.out.log" ||
  fail "the repaired sweep did not submit exactly the failed cell: $(cat "$t/repair.out.log")"
grep -q "^#SBATCH --array=0-0$" "$t/fail/sweep.sbatch" || fail "sweep.sbatch is no 1-task array"
grep -q "^cells=(1)$" "$t/fail/sweep.sbatch" || fail "sweep.sbatch does not map task 0 to cell 1"
grep -q "collected 2 runs of 2 cells$" "$t/repair.out.log" || fail "the repaired sweep did not collect both cells"

# --no-wait submits and returns; once the job has ended, collect gives the same table.
"$bin" sweep "$t/spec.yaml" -o "$t/later" --slurm --no-wait >"$t/later.out.log" 2>&1 || fail "--no-wait failed"
cat "$t/later.out.log"
job=$(sed -n 's/^submitted slurm job \([0-9]*\):.*/\1/p' "$t/later.out.log")
[ -n "$job" ] || fail "--no-wait printed no job id"
grep -q "lifelong sweep collect $t/later$" "$t/later.out.log" || fail "--no-wait does not say how to collect"
[ ! -f "$t/later/aggregate.csv" ] || fail "--no-wait collected before the job ended"
for _ in $(seq 300); do
  [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break
  sleep 1
done
"$bin" sweep collect "$t/later" >"$t/collect.out.log" 2>&1 || fail "collect failed"
cmp "$t/slurm/aggregate.csv" "$t/later/aggregate.csv" >/dev/null ||
  python3 - "$t/slurm/aggregate.csv" "$t/later/aggregate.csv" <<'PY' || fail "--no-wait's aggregate.csv differs"
import csv, re, sys
machine = re.compile(r"^(wall_time_s|peak_rss_mb|time_per_obs_ms/|stage_ms/)")
def table(path):
    rows = list(csv.reader(open(path)))
    keep = [i for i, h in enumerate(rows[0]) if not machine.search(h)]
    return [[r[i] for i in keep] for r in rows]
sys.exit(0 if table(sys.argv[1]) == table(sys.argv[2]) and len(table(sys.argv[1])) == 2 else 1)
PY
echo "PASS"
