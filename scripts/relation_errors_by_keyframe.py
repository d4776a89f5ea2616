#!/usr/bin/env python3
"""Relation errors of a replayed log, split by how many of the pair's scans are keyframes.

    scripts/relation_errors_by_keyframe.py OUT/standard RELATIONS OFFSET_S

OUT/<mode> is a `lifelong replay ... --relations RELATIONS` mode directory
(trajectory.tum: every scan; graph.g2o: the keyframes, i.e. the nodes). OFFSET_S is the
relations' time offset that `replay` prints ("offset ... s"). A scan is a keyframe when its
pose is a vertex of graph.g2o (to 1e-5 m); the others are placed by odometry from their
node. Prints the mean translational error of the pairs with 0, 1 and 2 keyframes. Pairs
whose stamps match no scan to 1 ms are skipped, so the count is below replay's."""
import bisect
import math
import sys


def main():
    run, relations, offset = sys.argv[1], sys.argv[2], float(sys.argv[3])
    traj = []
    for line in open(run + "/trajectory.tum"):
        if line.startswith("#"):
            continue
        t, x, y, _z, _qx, _qy, qz, qw = map(float, line.split())
        traj.append((t, x, y, 2 * math.atan2(qz, qw)))
    stamps = [p[0] for p in traj]
    vertices = {(round(float(f[2]), 5), round(float(f[3]), 5))
                for f in (l.split() for l in open(run + "/graph.g2o")) if f[0] == "VERTEX_SE2"}

    def pose(t):
        i = bisect.bisect_left(stamps, t - 1e-4)
        return traj[i] if i < len(traj) and abs(stamps[i] - t) < 1e-3 else None

    errors = {0: [], 1: [], 2: []}
    for line in open(relations):
        f = line.split()
        a, b = pose(float(f[0]) - offset), pose(float(f[1]) - offset)
        if a is None or b is None:
            continue
        dx, dy = b[1] - a[1], b[2] - a[2]
        c, s = math.cos(a[3]), math.sin(a[3])
        err = math.hypot(c * dx + s * dy - float(f[2]), -s * dx + c * dy - float(f[3]))
        keyframes = sum((round(p[1], 5), round(p[2], 5)) in vertices for p in (a, b))
        errors[keyframes].append(err)
    every = [e for v in errors.values() for e in v]
    print(f"all: {len(every)} pairs, mean {sum(every) / len(every):.4f} m")
    for k, v in errors.items():
        if v:
            print(f"{k} keyframe(s): {len(v)} pairs, mean {sum(v) / len(v):.4f} m")


if __name__ == "__main__":
    main()
