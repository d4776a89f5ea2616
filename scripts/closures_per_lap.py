#!/usr/bin/env python3
"""Whether every lap of a looped route closed a loop.

Usage: scripts/closures_per_lap.py RUN_DIR [MODE ...]

RUN_DIR is a `lifelong run` output (or a sweep cell) with truth/trajectory.tum and
MODE/loops.csv (default: every mode directory with a loops.csv). A lap ends where the true
path comes back within RETURN_M of its start after going more than AWAY_M from it; a last
stretch shorter than a tenth of the mean lap is not a lap. For each mode it prints the laps,
the accepted closures whose current scan falls in each lap, and how many laps after the first
closed none (the first lap has nothing to close against). Issue #31 asks "every lap closed"
of big_loop_2h. Standard library only.
"""
import csv
import math
import os
import sys

RETURN_M = 1.0
AWAY_M = 50.0


def lap_starts(truth_path):
    """Stamps where each lap starts, and the run's last stamp."""
    poses = []
    for line in open(truth_path):
        f = line.split()
        if len(f) >= 3 and not f[0].startswith("#"):
            poses.append((float(f[0]), float(f[1]), float(f[2])))
    if not poses:
        return [], 0.0
    x0, y0 = poses[0][1], poses[0][2]
    starts, away = [poses[0][0]], False
    for t, x, y in poses:
        d = math.hypot(x - x0, y - y0)
        if d > AWAY_M:
            away = True
        elif away and d < RETURN_M:
            starts.append(t)
            away = False
    return starts, poses[-1][0]


def laps(starts, end):
    """(from, to) per lap; a last stretch under a tenth of the mean lap joins no count."""
    bounds = list(zip(starts, starts[1:] + [end]))
    if len(bounds) > 1:
        mean = (starts[-1] - starts[0]) / (len(starts) - 1)
        if bounds[-1][1] - bounds[-1][0] < 0.1 * mean:
            bounds.pop()
    return bounds


def main():
    if len(sys.argv) < 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    run = sys.argv[1]
    truth = os.path.join(run, "truth", "trajectory.tum")
    if not os.path.isfile(truth):
        print(f"closures_per_lap: {truth}: no such file", file=sys.stderr)
        sys.exit(2)
    modes = sys.argv[2:] or sorted(
        m for m in os.listdir(run) if os.path.isfile(os.path.join(run, m, "loops.csv")))
    bounds = laps(*lap_starts(truth))
    print("mode laps laps_after_first_without_closure closures_per_lap")
    for mode in modes:
        path = os.path.join(run, mode, "loops.csv")
        if not os.path.isfile(path):
            print(f"closures_per_lap: {path}: no such file", file=sys.stderr)
            sys.exit(2)
        stamps = [float(r["stamp_current_s"]) for r in csv.DictReader(open(path))]
        per_lap = [sum(1 for s in stamps if a <= s < b) for a, b in bounds]
        open_laps = sum(1 for n in per_lap[1:] if n == 0)
        print(mode, len(per_lap), open_laps, ",".join(str(n) for n in per_lap))


if __name__ == "__main__":
    main()
