#!/usr/bin/env python3
"""Odometry error at the first revisit of a place, from a simulated CARMEN log.

Reads the TRUEPOS lines of a log written by `lifelong simulate` (true pose and odometry
pose of every scan), moves the odometry onto the truth at the first scan (odometry starts
at 0, 0, 0), and finds the first revisit: the first scan k whose true position lies
within --radius of the true position of an earlier scan j, with at least --min-travel
metres driven between j and k (so that standing still or turning on the spot is not a
revisit). It prints, for that pair:
  absolute  the odometry position and heading error at k (odometry aligned at the start);
  relative  the error of the odometry's motion from j to k against the true motion: what
            a mapper closing the loop j-k has to correct (equal to the absolute error when
            j is the first scan).
Usage: scripts/odometry_drift_at_revisit.py LOG[.gz] [--radius 1.0] [--min-travel 50]
       [--json]
Stdlib only."""

import argparse
import gzip
import json
import math
import sys


def compose(a, b):
    x, y, t = a
    c, s = math.cos(t), math.sin(t)
    return (x + c * b[0] - s * b[1], y + s * b[0] + c * b[1], t + b[2])


def inverse(a):
    x, y, t = a
    c, s = math.cos(t), math.sin(t)
    return (-c * x - s * y, s * x - c * y, -t)


def wrap(a):
    return math.atan2(math.sin(a), math.cos(a))


def read_truepos(path):
    opener = gzip.open if path.endswith(".gz") else open
    rows = []  # (stamp, true pose, odometry pose)
    with opener(path, "rt") as f:
        for n, line in enumerate(f, 1):
            if not line.startswith("TRUEPOS "):
                continue
            v = line.split()
            try:
                true = tuple(float(x) for x in v[1:4])
                odom = tuple(float(x) for x in v[4:7])
                stamp = float(v[7])
            except (IndexError, ValueError):
                sys.exit(f"{path}:{n}: malformed TRUEPOS line")
            rows.append((stamp, true, odom))
    if len(rows) < 2:
        sys.exit(f"{path}: fewer than 2 TRUEPOS lines (was it written by lifelong simulate?)")
    return rows


def first_revisit(rows, radius, min_travel):
    """(j, k, travelled metres) of the first revisit, or None. Cells of size radius make
    the search linear in the number of scans."""
    travelled = [0.0]
    for a, b in zip(rows, rows[1:]):
        travelled.append(travelled[-1] + math.hypot(b[1][0] - a[1][0], b[1][1] - a[1][1]))
    grid = {}
    for k, (_, (x, y, _), _) in enumerate(rows):
        cx, cy = int(math.floor(x / radius)), int(math.floor(y / radius))
        best = None
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for j in grid.get((cx + dx, cy + dy), ()):
                    if travelled[k] - travelled[j] < min_travel:
                        continue
                    tx, ty, _ = rows[j][1]
                    if math.hypot(x - tx, y - ty) <= radius and (best is None or j < best):
                        best = j
        if best is not None:
            return best, k, travelled[k] - travelled[best], travelled[k]
        grid.setdefault((cx, cy), []).append(k)
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("log")
    ap.add_argument("--radius", type=float, default=1.0,
                    help="true positions this close (m) are the same place (default 1)")
    ap.add_argument("--min-travel", type=float, default=50.0,
                    help="metres driven between the two visits at least (default 50)")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    args = ap.parse_args()
    rows = read_truepos(args.log)
    # Odometry in the world frame: T_world_odom = true_0 * odom_0^-1.
    t_world_odom = compose(rows[0][1], inverse(rows[0][2]))
    hit = first_revisit(rows, args.radius, args.min_travel)
    if hit is None:
        print(f"no revisit within {args.radius} m after {args.min_travel} m of travel "
              f"({len(rows)} scans)")
        return 1
    j, k, loop_m, total_m = hit
    (tj, true_j, odom_j), (tk, true_k, odom_k) = rows[j], rows[k]
    world_odom_k = compose(t_world_odom, odom_k)
    abs_pos = math.hypot(world_odom_k[0] - true_k[0], world_odom_k[1] - true_k[1])
    abs_yaw = wrap(world_odom_k[2] - true_k[2])
    rel_true = compose(inverse(true_j), true_k)
    rel_odom = compose(inverse(odom_j), odom_k)
    rel_pos = math.hypot(rel_odom[0] - rel_true[0], rel_odom[1] - rel_true[1])
    rel_yaw = wrap(rel_odom[2] - rel_true[2])
    out = {
        "log": args.log, "scans": len(rows),
        "first_visit": {"scan": j, "stamp_s": tj, "true": true_j},
        "revisit": {"scan": k, "stamp_s": tk, "true": true_k, "odometry": world_odom_k},
        "loop_length_m": round(loop_m, 2), "travelled_m": round(total_m, 2),
        "absolute_error_m": round(abs_pos, 3), "absolute_heading_error_deg":
            round(math.degrees(abs_yaw), 2),
        "relative_error_m": round(rel_pos, 3), "relative_heading_error_deg":
            round(math.degrees(rel_yaw), 2),
        "relative_error_per_loop_length": round(rel_pos / loop_m, 5),
    }
    if args.json:
        print(json.dumps(out))
        return 0
    print(f"{args.log}: {len(rows)} scans")
    print(f"first revisit: scan {k} at {tk:.1f} s ({true_k[0]:.2f}, {true_k[1]:.2f}) "
          f"revisits scan {j} at {tj:.1f} s; loop {loop_m:.1f} m, {total_m:.1f} m driven")
    print(f"absolute: odometry error {abs_pos:.3f} m, heading {math.degrees(abs_yaw):+.2f} deg")
    print(f"relative (loop {j}-{k}): {rel_pos:.3f} m ({100 * rel_pos / loop_m:.2f} % of the "
          f"loop), heading {math.degrees(rel_yaw):+.2f} deg")
    return 0


if __name__ == "__main__":
    sys.exit(main())
