#!/usr/bin/env python3
"""An MRPT rawlog of odometry and 2D scans as a CARMEN log that `lifelong replay` reads.

Usage: scripts/mrpt_rawlog_to_carmen.py RAWLOG OUT.clf [RELATIONS]

RAWLOG is an observation-only MRPT rawlog (gzip or plain): a sequence of serialized
mrpt::obs::CObservationOdometry (version 2) and mrpt::obs::CObservation2DRangeScan (version
7) objects, as MOLAorg/mola_test_datasets ships the benchmark's logs (datasets/radish/, among
them mit-killian.rawlog, whose CARMEN original is too large to fetch here). Each scan becomes
a FLASER line: its ranges (invalid ones at the scan's maximum range), the laser pose (the
odometry composed with the scan's sensor pose, turned to the plane) and the odometry pose
of the latest odometry object. The scan's own fan is not written: FLASER's 180 beams span
-90 to +90 degrees, which is what the benchmark's 180-beam SICK scans are.

The converter that made those files stamped every object anew (0.9 s apart, at the time of
conversion), so their original stamps, which the benchmark's relations name, are gone. With
RELATIONS, the stamps are recovered: the laser ran at a fixed period, so the relations'
stamps fall on a lattice t = t0 + P k (k the scan's index). The indices are unwrapped in
order with P fitted as they go, then P and t0 by least squares. Which scan the first of them
is, the scans say: the shift at which the relations between scans under 3 s apart align
their two scans best (the share of returns within 10 cm). Each scan a relation names then
gets that relation's stamp, and the others the lattice's. The odometry is checked the same
way: where its heading changes agree best with the relations at another shift, it is stored
with the wrong scan, and each scan takes the odometry that many objects away (Killian's
rawlog: the odometry stored with scan n is scan n+1's). It stops (exit 2) when the stamps do
not fit a lattice (a residual over a fifth of P). Standard library only (and
relation_scan_check.py beside it).
"""
import gzip
import math
import os
import struct
import sys

import relation_scan_check  # its scan returns and alignment share

END_FLAG = 0x88


class Reader:
    """MRPT's binary serialization (little endian)."""

    def __init__(self, data):
        self.data, self.at = data, 0

    def take(self, n):
        if self.at + n > len(self.data):
            raise ValueError(f"truncated at byte {self.at}")
        chunk = self.data[self.at:self.at + n]
        self.at += n
        return chunk

    def unpack(self, fmt):
        values = struct.unpack("<" + fmt, self.take(struct.calcsize("<" + fmt)))
        return values if len(values) > 1 else values[0]

    def header(self):
        """(class name, version) of the next object."""
        length = self.take(1)[0]
        if not length & 0x80:
            raise ValueError(f"no object header at byte {self.at - 1}")
        return self.take(length & 0x7F).decode(), self.take(1)[0]

    def end(self):
        if self.take(1)[0] != END_FLAG:
            raise ValueError(f"no end of object at byte {self.at - 1}")

    def string(self):
        return self.take(self.unpack("I")).decode()


def expect(reader, name, version):
    got = reader.header()
    if got != (name, version):
        raise ValueError(f"{got[0]} version {got[1]} where {name} version {version} was expected")


def pose2d(reader):
    expect(reader, "mrpt::poses::CPose2D", 1)
    pose = reader.unpack("ddd")
    reader.end()
    return pose


def pose3d_in_plane(reader):
    expect(reader, "mrpt::poses::CPose3D", 3)
    x, y, _z = reader.unpack("ddd")
    rotation = reader.unpack("9d")  # row major
    reader.end()
    return x, y, math.atan2(rotation[3], rotation[0])


def odometry(reader):
    pose = pose2d(reader)
    reader.string()  # sensor label
    reader.unpack("Q")  # stamp
    if reader.unpack("B"):
        reader.unpack("ii")  # encoder ticks
    if reader.unpack("B"):
        reader.unpack("ddd")  # velocities
    reader.end()
    return pose


def scan(reader):
    """(ranges, laser pose in the robot frame)."""
    _aperture, right_to_left, max_range = reader.unpack("fBf")
    sensor = pose3d_in_plane(reader)
    n = reader.unpack("I")
    ranges = struct.unpack(f"<{n}f", reader.take(4 * n))
    valid = reader.take(n)
    reader.unpack("fQf")  # range sigma, stamp, beam aperture
    reader.string()  # sensor label
    reader.unpack("d")  # delta pitch
    if reader.unpack("B"):
        reader.take(4 * n)  # intensities
    reader.end()
    ranges = [r if ok else max_range for r, ok in zip(ranges, valid)]
    return (ranges if right_to_left else ranges[::-1]), sensor


def read_rawlog(path):
    """(ranges, laser pose, odometry pose) per scan, in order."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:2] == b"\x1f\x8b":
        data = gzip.decompress(data)
    reader, odom, scans = Reader(data), None, []
    while reader.at < len(data):
        name, version = reader.header()
        if (name, version) == ("mrpt::obs::CObservationOdometry", 2):
            odom = odometry(reader)
        elif (name, version) == ("mrpt::obs::CObservation2DRangeScan", 7):
            ranges, sensor = scan(reader)
            if odom is None:
                raise ValueError("a scan before any odometry")
            x, y, th = odom
            c, s = math.cos(th), math.sin(th)
            laser = (x + c * sensor[0] - s * sensor[1], y + s * sensor[0] + c * sensor[1],
                     th + sensor[2])
            scans.append((ranges, laser, odom))
        else:
            raise ValueError(f"{name} version {version} at byte {reader.at}: not read")
    return scans


def read_relations(path):
    """(stamp, stamp, dx, dy, dtheta) per relation."""
    relations = []
    for number, line in enumerate(open(path), 1):
        fields = line.split()
        if not fields or fields[0].startswith("#"):
            continue
        try:
            relations.append(tuple(float(fields[c]) for c in (0, 1, 2, 3, 7)))
        except (ValueError, IndexError):
            raise ValueError(f"{path}:{number}: not 'stamp stamp x y z roll pitch yaw'")
    return relations


def fit_lattice(stamps):
    """(t0, period, index of each stamp) for sorted stamps on t = t0 + period k. The indices
    are unwrapped in order, each gap divided by the period fitted to the stamps so far (from
    the smallest gap at first), so that a gap of a hundred periods still rounds right."""
    gaps = [b - a for a, b in zip(stamps, stamps[1:]) if b > a]
    if len(gaps) < 2:
        raise ValueError("too few distinct relation stamps")
    period, k = min(gaps), [0]
    n, sk, st, skk, skt = 1, 0.0, stamps[0], 0.0, 0.0
    for prev, t in zip(stamps, stamps[1:]):
        k.append(k[-1] + max(1, round((t - prev) / period)))
        n, sk, st = n + 1, sk + k[-1], st + t
        skk, skt = skk + k[-1] * k[-1], skt + k[-1] * t
        period = (n * skt - sk * st) / (n * skk - sk * sk)
    t0 = (st - period * sk) / n
    worst = max(abs(t - t0 - period * v) for t, v in zip(stamps, k))
    if worst > 0.2 * period:
        raise ValueError(f"the relation stamps fit no fixed scan period ({worst:.3f} s off)")
    return t0, period, k


class Scans:
    """The scans' returns as relation_scan_check.py reads them (FLASER: 1 degree apart from
    -90), each with its lookup grid, made once for the scans the relations name."""

    def __init__(self, scans):
        self.scans, self.seen = scans, {}

    def __getitem__(self, i):
        if i not in self.seen:
            points = relation_scan_check.scan_points(self.scans[i][0], -math.pi / 2,
                                                     math.radians(1.0), 0.0)
            self.seen[i] = (relation_scan_check.Grid(points), points)
        return self.seen[i]


def scan_agreement(scans, relations, index):
    """Mean share of returns the relations align (higher: the pairing the scans support)."""
    shares = [relation_scan_check.aligned_share(scans[index[a]][0], scans[index[b]][1],
                                                (dx, dy, dth))
              for a, b, dx, dy, dth in relations]
    return sum(shares) / max(len(shares), 1)


def odometry_disagreement(odom, relations, index):
    """Mean difference of heading change between the relations and the odometry (rad)."""
    errors = []
    for a, b, _dx, _dy, dth in relations:
        turn = odom[index[b]][2] - odom[index[a]][2] - dth
        errors.append(abs(math.atan2(math.sin(turn), math.cos(turn))))
    return sum(errors) / max(len(errors), 1)


def recover_stamps(scans, relations):
    """Stamps for the scans, and the odometry's lead in scans (module docstring)."""
    stamps = sorted({t for r in relations for t in r[:2]})
    t0, period, k = fit_lattice(stamps)
    span = k[-1] - k[0] + 1
    if span > len(scans):
        raise ValueError(f"the relations span {span} scan periods, the log has {len(scans)}")
    # Relations between scans under 3 s apart, every few of them: enough to tell the shifts.
    short = [r for r in relations if abs(r[1] - r[0]) < 3.0]
    short = short[::max(1, len(short) // 400)]
    shifts = range(len(scans) - span + 1)
    index = lambda c: {t: v + c for t, v in zip(stamps, k)}
    seen = Scans(scans)
    by_scans = max(shifts, key=lambda c: scan_agreement(seen, short, index(c)))
    odom = [o for _, _, o in scans]
    by_odometry = min(shifts, key=lambda c: odometry_disagreement(odom, short, index(c)))
    out = [t0 + period * (i - by_scans) for i in range(len(scans))]
    for t, v in zip(stamps, k):
        out[v + by_scans] = t  # k rises with every stamp: one stamp per scan
    return out, period, by_odometry - by_scans


def main():
    if len(sys.argv) not in (3, 4):
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    rawlog, out_path = sys.argv[1], sys.argv[2]
    for path in sys.argv[1:2] + sys.argv[3:]:
        if not os.path.isfile(path):
            print(f"mrpt_rawlog_to_carmen: {path}: no such file", file=sys.stderr)
            sys.exit(2)
    try:
        scans = read_rawlog(rawlog)
        lead = 0
        if len(sys.argv) == 4:
            stamps, period, lead = recover_stamps(scans, read_relations(sys.argv[3]))
            print(f"stamps recovered: a scan every {period:.6f} s; each scan takes the odometry"
                  f" stored {lead:+d} from it", file=sys.stderr)
        else:
            stamps = [0.1 * i for i in range(len(scans))]
    except ValueError as e:
        print(f"mrpt_rawlog_to_carmen: {rawlog}: {e}", file=sys.stderr)
        sys.exit(2)
    written = 0
    with open(out_path, "w") as out:
        for n, ((ranges, _, _), t) in enumerate(zip(scans, stamps)):
            if not 0 <= n + lead < len(scans):
                continue  # no odometry of its time
            written += 1
            laser, odom = scans[n + lead][1], scans[n + lead][2]
            values = " ".join(f"{v:.6f}" for v in laser + odom)
            out.write(f"FLASER {len(ranges)} {' '.join(f'{r:.3f}' for r in ranges)} {values} "
                      f"{t:.6f} mrpt {t:.6f}\n")
    print(f"{written} of {len(scans)} scans written to {out_path}", file=sys.stderr)


if __name__ == "__main__":
    main()
