#!/usr/bin/env python3
"""Does a corrected CARMEN log's odometry keep the sign of a reversing step?

    scripts/reversing_steps.py LOG-corrected.log.gz

For every scan, the step from the previous scan's corrected pose to the ODOM just before this
scan (the raw step, as io/carmen_recovery.hpp rebuilds it) is compared with the step between
the two corrected poses, in the previous scan's frame. Over the steps where both move more
than 5 cm along the robot's x, prints how many the corrected poses move forward and backward,
and on how many the odometry moves the other way, with the first few of those.
(freiburg-079-corrected: 74 backward steps, all 74 read as forward by the odometry.)"""
import gzip
import math
import sys


def step(p, q):
    """x and y of q in p's frame."""
    c, s = math.cos(p[2]), math.sin(p[2])
    dx, dy = q[0] - p[0], q[1] - p[1]
    return c * dx + s * dy, -s * dx + c * dy


def main():
    path = sys.argv[1]
    opener = gzip.open if path.endswith(".gz") else open
    last_scan = odom = None
    forward = backward = flipped = 0
    examples = []
    with opener(path, "rt") as f:
        for line in f:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "ODOM":
                odom = tuple(map(float, fields[1:4]))
            elif fields[0] == "FLASER":
                n = int(fields[1])
                scan = tuple(map(float, fields[2 + n:5 + n]))
                if last_scan is not None and odom is not None:
                    raw, corrected = step(last_scan, odom)[0], step(last_scan, scan)[0]
                    if abs(raw) > 0.05 and abs(corrected) > 0.05:
                        backward += corrected < 0
                        forward += corrected >= 0
                        if (raw < 0) != (corrected < 0):
                            flipped += 1
                            examples.append((float(fields[-3]), raw, corrected))
                last_scan, odom = scan, None
    print(f"steps forward {forward}, backward {backward}, odometry the other way {flipped}")
    for t, raw, corrected in examples[:5]:
        print(f"  t {t:.1f} s: odometry {raw:+.3f} m, corrected poses {corrected:+.3f} m")


if __name__ == "__main__":
    main()
