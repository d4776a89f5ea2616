#!/usr/bin/env python3
"""scripts/relation_scan_check.py on a made-up log: two scans of a room with a pillar, taken
1 m apart. Where the relation is 0.4 m off and our estimate right, the scans side with ours;
where ours is 0.4 m off and the relation right, with the relation; a pair within the error
bar is not checked; a missing trajectory is exit 2 naming it."""
import math
import os
import subprocess
import sys
import tempfile

import walls

SCRIPT = os.path.join(sys.argv[1], "scripts", "relation_scan_check.py")
# A room 10 m x 6 m, and a pillar 0.6 m square at (6, 1): segments (x0, y0, x1, y1).
WALLS = [(0, 0, 10, 0), (10, 0, 10, 6), (10, 6, 0, 6), (0, 6, 0, 0)] + walls.box(6, 1, 0.6)


def cast(x, y, a):
    return walls.cast(WALLS, x, y, a)


def flaser(pose, stamp):
    ranges = " ".join(f"{cast(pose[0], pose[1], pose[2] - math.pi / 2 + k * math.pi / 180):.3f}"
                      for k in range(181))
    p = " ".join(f"{v:.6f}" for v in pose)
    return f"FLASER 181 {ranges} {p} {p} {stamp:.6f} host {stamp:.6f}\n"


def tum(stamp, pose):
    qz, qw = math.sin(pose[2] / 2), math.cos(pose[2] / 2)
    return f"{stamp:.6f} {pose[0]:.6f} {pose[1]:.6f} 0 0 0 {qz:.9f} {qw:.9f}\n"


def between(a, b):
    dx, dy, c, s = b[0] - a[0], b[1] - a[1], math.cos(a[2]), math.sin(a[2])
    return (c * dx + s * dy, -s * dx + c * dy, b[2] - a[2])


def relation(a, b, pose):
    return f"{a:.1f} {b:.1f} {pose[0]:.6f} {pose[1]:.6f} 0 0 0 {pose[2]:.6f}\n"


def main():
    poses = [(3.0, 3.0, 0.1), (4.0, 3.1, 0.15), (5.0, 2.9, 0.1), (6.0, 3.2, 0.2)]
    stamps = [100.0, 101.0, 102.0, 103.0]
    ours = list(poses)
    ours[3] = (poses[3][0] + 0.3, poses[3][1] - 0.3, poses[3][2])  # our last pose 0.42 m off
    wrong = between(poses[0], poses[1])
    wrong = (wrong[0] + 0.3, wrong[1] + 0.3, wrong[2])  # a relation 0.42 m off
    with tempfile.TemporaryDirectory() as d:
        with open(os.path.join(d, "room.log"), "w") as f:
            f.writelines(flaser(p, t) for p, t in zip(poses, stamps))
        os.makedirs(os.path.join(d, "standard"))
        with open(os.path.join(d, "standard", "trajectory.tum"), "w") as f:
            f.writelines(tum(t, p) for p, t in zip(ours, stamps))
        with open(os.path.join(d, "room.relations"), "w") as f:
            f.write(relation(100, 101, wrong))  # the scans side with ours
            f.write(relation(101, 102, between(poses[1], poses[2])))  # within the bar: unchecked
            f.write(relation(102, 103, between(poses[2], poses[3])))  # right: ours is off
        run = lambda args: subprocess.run([sys.executable, SCRIPT] + args, capture_output=True,
                                          text=True)
        out = run([os.path.join(d, "room.log"), os.path.join(d, "room.relations"),
                   os.path.join(d, "standard")])
        assert out.returncode == 0, out.stderr
        rows = [l for l in out.stdout.splitlines() if not l.startswith("#")]
        assert len(rows) == 2, out.stdout
        assert rows[0].split()[:2] == ["0.0", "1.0"] and rows[0].endswith("| ours"), out.stdout
        assert rows[1].split()[:2] == ["2.0", "3.0"] and rows[1].endswith("| relation"), out.stdout
        assert "# verdicts: ours 1, relation 1" in out.stdout, out.stdout
        missing = run([os.path.join(d, "room.log"), os.path.join(d, "room.relations"),
                       os.path.join(d, "nowhere")])
        assert missing.returncode == 2 and "nowhere/trajectory.tum" in missing.stderr, missing
    print("ok")


if __name__ == "__main__":
    main()
