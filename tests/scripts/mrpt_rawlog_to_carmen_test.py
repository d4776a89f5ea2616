#!/usr/bin/env python3
"""scripts/mrpt_rawlog_to_carmen.py on a made-up rawlog in MRPT's serialization: 60 scans,
each after its odometry, stamped anew 0.9 s apart as the benchmark's converted files are.
The FLASER lines carry the ranges (right to left, invalid ones at the maximum range) and the
odometry; with relations whose stamps lie on a 0.44 s lattice (a few ms of jitter, gaps of
one to five periods) starting at the 7th scan, every named scan gets its relation's stamp.
Where the odometry is stored one scan ahead of its scan, the scans say which scan each
relation names and the odometry is re-paired. A rawlog with an object it does not read, and
relations that fit no period, are exit 2."""
import gzip
import math
import os
import struct
import subprocess
import sys
import tempfile

import walls

SCRIPT = os.path.join(sys.argv[1], "scripts", "mrpt_rawlog_to_carmen.py")


# A corridor 20 m x 6 m with pillars along both walls: segments (x0, y0, x1, y1).
WALLS = [(0, 0, 20, 0), (20, 0, 20, 6), (20, 6, 0, 6), (0, 6, 0, 0)] + [
    wall for x, y in ((3, 1), (7, 4.5), (11, 1), (15, 4.5), (17.5, 1.5))
    for wall in walls.box(x, y, 0.5)]


def cast(x, y, a):
    return walls.cast(WALLS, x, y, a)


def header(name, version):
    return bytes([0x80 | len(name)]) + name.encode() + bytes([version])


def string(text):
    return struct.pack("<I", len(text)) + text.encode()


def odometry(x, y, th, stamp):
    pose = header("mrpt::poses::CPose2D", 1) + struct.pack("<ddd", x, y, th) + b"\x88"
    return (header("mrpt::obs::CObservationOdometry", 2) + pose + string("ODOMETRY") +
            struct.pack("<QBB", stamp, 0, 0) + b"\x88")


def scan(ranges, valid, stamp):
    sensor = (header("mrpt::poses::CPose3D", 3) + struct.pack("<ddd", 0.0, 0.0, 0.0) +
              struct.pack("<9d", 1, 0, 0, 0, 1, 0, 0, 0, 1) + b"\x88")
    n = len(ranges)
    return (header("mrpt::obs::CObservation2DRangeScan", 7) +
            struct.pack("<fBf", math.pi, 1, 81.0) + sensor + struct.pack("<I", n) +
            struct.pack(f"<{n}f", *ranges) + bytes(valid) + struct.pack("<fQf", 0.01, stamp, 0.0) +
            string("FLASER") + struct.pack("<dB", 0.0, 0) + b"\x88")


def main():
    # 0.25 m a scan down the corridor, weaving and turning up to 0.4 rad. The relations name
    # scans by the scans' poses; the odometry may be stored with another scan (rawlog()).
    poses = [(2.0 + 0.25 * i, 3.0 + 0.8 * math.sin(0.2 * i), 0.4 * math.sin(0.25 * i))
             for i in range(60)]

    def rawlog(odometry_ahead):
        """The objects; the odometry stored with scan i is pose i + odometry_ahead's."""
        blob = b""
        for i, (x, y, th) in enumerate(poses):
            fake = 133000000000000000 + i * 9000000  # 0.9 s apart, in 100 ns ticks
            blob += odometry(*poses[min(i + odometry_ahead, 59)], fake)
            ranges = [cast(x, y, th + math.radians(b - 90)) for b in range(180)]
            blob += scan(ranges, [0 if b == 5 else 1 for b in range(180)], fake)
        return blob
    true = [1000.0 + 0.44 * i + 0.003 * math.sin(7 * i) for i in range(60)]
    named = [6, 7, 9, 10, 14, 15, 16, 19, 24, 25, 27, 30, 31, 35, 36, 40, 41, 45, 50, 52]

    def relation(a, b):
        (xa, ya, ta), (xb, yb, tb) = poses[a], poses[b]
        c, s = math.cos(ta), math.sin(ta)
        dx, dy = c * (xb - xa) + s * (yb - ya), -s * (xb - xa) + c * (yb - ya)
        return f"{true[a]:.6f} {true[b]:.6f} {dx:.6f} {dy:.6f} 0 0 0 {tb - ta:.6f}\n"

    with tempfile.TemporaryDirectory() as d:
        raw, rel, out = (os.path.join(d, n) for n in ("log.rawlog", "log.relations", "log.clf"))
        with gzip.open(raw, "wb") as f:
            f.write(rawlog(0))
        with open(rel, "w") as f:
            f.writelines(relation(a, b) for a, b in zip(named, named[1:]))
        run = lambda *args: subprocess.run([sys.executable, SCRIPT, *args], capture_output=True,
                                           text=True)
        done = run(raw, out, rel)
        assert done.returncode == 0, done.stderr
        lines = [l.split() for l in open(out)]
        assert len(lines) == 60 and all(l[0] == "FLASER" and l[1] == "180" for l in lines)
        first = lines[0]
        # Right to left, as FLASER's: the order kept; beam 5, invalid, at the maximum range.
        assert abs(float(first[2]) - cast(*poses[0][:2], poses[0][2] - math.pi / 2)) < 1e-3
        assert float(first[2 + 5]) == 81.0, first[:8]
        assert [round(float(v), 6) for v in lines[3][182:188]] == [
            round(v, 6) for v in poses[3] * 2], lines[3][182:188]
        for i in named:
            assert abs(float(lines[i][188]) - true[i]) < 1e-6, (i, lines[i][188], true[i])
        for i in range(60):
            assert abs(float(lines[i][188]) - true[i]) < 0.01, (i, lines[i][188], true[i])
        # The odometry stored one scan ahead of its scan: re-paired, the first scan dropped.
        with gzip.open(raw, "wb") as f:
            f.write(rawlog(1))
        done = run(raw, out, rel)
        assert done.returncode == 0 and "odometry stored -1" in done.stderr, done.stderr
        lines = [l.split() for l in open(out)]
        assert len(lines) == 59, len(lines)  # scan 0's odometry is not in the log
        for line, pose in zip(lines, poses[1:]):
            assert [round(float(v), 6) for v in line[182:185]] == [round(v, 6) for v in pose]
        for i in named:
            assert abs(float(lines[i - 1][188]) - true[i]) < 1e-6, (i, lines[i - 1][188])
        # An object it does not read.
        with gzip.open(raw, "wb") as f:
            f.write(rawlog(0) + header("mrpt::obs::CObservationImage", 1))
        bad = run(raw, out, rel)
        assert bad.returncode == 2 and "CObservationImage" in bad.stderr, bad.stderr
        # Relations on no fixed period.
        with gzip.open(raw, "wb") as f:
            f.write(rawlog(0))
        with open(rel, "w") as f:
            jittered = [1000.0 + 0.44 * i + 0.12 * math.sin(3.7 * i) for i in range(41)]
            f.writelines(f"{a:.6f} {b:.6f} 0.2 0 0 0 0 0\n" for a, b in zip(jittered, jittered[1:]))
        off = run(raw, out, rel)
        assert off.returncode == 2 and "fit no fixed scan period" in off.stderr, off.stderr
        assert run(os.path.join(d, "none.rawlog"), out).returncode == 2
    print("ok")


if __name__ == "__main__":
    main()
