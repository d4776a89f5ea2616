#!/usr/bin/env python3
"""Which of a replay's large relation errors the log's own scans contradict.

Usage: scripts/relation_scan_check.py LOG RELATIONS MODE_DIR [MIN_ERROR_M] [OFFSET_S]

LOG is the CARMEN log that `lifelong replay LOG --relations RELATIONS -o OUT` read
(ROBOTLASER1 or FLASER lines; plain text), MODE_DIR one of OUT's mode directories
(its trajectory.tum), MIN_ERROR_M the relation error from which a pair is checked (default
0.2 m), OFFSET_S the relations' time offset that replay prints (default 0).

A relation of the benchmark (Kuemmerle et al. 2009) is a relative pose between two scans,
taken from a reference the authors aligned and checked by hand. Where our estimate and a
relation disagree, the two scans themselves can say which pose aligns them: for each such
pair this runs a point-to-point ICP (Besl and McKay 1992) from the relation's pose and from
ours, and prints the share of the second scan's returns within 10 cm of the first's at
each start and where each ICP ends. Two scans of a corridor can also align at an alias a door
further on, so for pairs at most 20 s apart the log's odometry is a second witness. Verdict
per pair:
  ours       ours aligns the scans at least twice as well as the relation (and >= 0.2), and
             the odometry, where it witnesses, is no nearer the relation than ours
  relation   the reverse
  split      the scans call it one way and the odometry is nearer the other
  no overlap neither aligns 10 % of the returns: a pair of scans cannot judge it
  unclear    otherwise
A pair's scans see one place from two poses, so this judges short relations well and long
ones (scans apart, facing away) not at all: evidence, not proof. Standard library only.
"""
import math
import os
import sys

NEAR_M = 0.1  # a return "aligned" within this of the other scan's
ICP_REACH_M = 0.3  # correspondences beyond this are dropped
MAX_RANGE_M = 20.0
ODOMETRY_WITNESS_S = 20.0  # pairs at most this far apart in time: the odometry has a say


def laser_lines(path):
    """(stamp, ranges, start, step, laser x offset in the robot frame, odometry pose) per
    laser line."""
    with open(path, errors="replace") as f:
        for line in f:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "ROBOTLASER1":
                n = int(fields[8])
                ranges = [float(r) for r in fields[9:9 + n]]
                i = 10 + n + int(fields[9 + n])
                lx, ly, _, rx, ry, rt = (float(v) for v in fields[i:i + 6])
                offset = math.cos(rt) * (lx - rx) + math.sin(rt) * (ly - ry)
                yield (float(fields[i + 11]), ranges, float(fields[2]), float(fields[4]), offset,
                       (rx, ry, rt))
            elif fields[0] == "FLASER":
                n = int(fields[1])
                ranges = [float(r) for r in fields[2:2 + n]]
                lx, ly, _, rx, ry, rt = (float(v) for v in fields[2 + n:8 + n])
                offset = math.cos(rt) * (lx - rx) + math.sin(rt) * (ly - ry)
                yield (float(fields[8 + n]), ranges, -math.pi / 2, math.pi / (n - 1 or 1), offset,
                       (rx, ry, rt))


def scan_points(ranges, start, step, offset):
    """The returns in the robot frame."""
    return [(r * math.cos(start + k * step) + offset, r * math.sin(start + k * step))
            for k, r in enumerate(ranges) if 0.05 < r < MAX_RANGE_M]


def load_tum(path):
    poses = {}
    for line in open(path):
        f = line.split()
        if len(f) >= 8 and not f[0].startswith("#"):
            poses[round(float(f[0]), 3)] = (float(f[1]), float(f[2]),
                                            2 * math.atan2(float(f[6]), float(f[7])))
    return poses


def between(a, b):
    dx, dy, c, s = b[0] - a[0], b[1] - a[1], math.cos(a[2]), math.sin(a[2])
    turn = math.atan2(math.sin(b[2] - a[2]), math.cos(b[2] - a[2]))
    return (c * dx + s * dy, -s * dx + c * dy, turn)


class Grid:
    """Nearest point within ICP_REACH_M by a hash of cells that size."""

    def __init__(self, points):
        self.cells = {}
        for p in points:
            self.cells.setdefault(self.key(p), []).append(p)

    @staticmethod
    def key(p):
        return (math.floor(p[0] / ICP_REACH_M), math.floor(p[1] / ICP_REACH_M))

    def nearest(self, p):
        kx, ky = self.key(p)
        best, best_d = None, ICP_REACH_M
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for q in self.cells.get((kx + dx, ky + dy), ()):
                    d = math.hypot(q[0] - p[0], q[1] - p[1])
                    if d < best_d:
                        best, best_d = q, d
        return best, best_d


def moved(points, t):
    c, s = math.cos(t[2]), math.sin(t[2])
    return [(c * x - s * y + t[0], s * x + c * y + t[1]) for x, y in points]


def aligned_share(grid, points, t):
    return sum(grid.nearest(p)[1] < NEAR_M for p in moved(points, t)) / max(len(points), 1)


def icp(grid, points, t, iterations=40):
    """Point-to-point ICP of `points` onto the grid's from pose t; the pose it ends at."""
    for _ in range(iterations):
        pairs = [(p, q) for p in moved(points, t) for q in [grid.nearest(p)[0]] if q]
        if len(pairs) < 10:
            return t
        n = len(pairs)
        mp = (sum(p[0] for p, _ in pairs) / n, sum(p[1] for p, _ in pairs) / n)
        mq = (sum(q[0] for _, q in pairs) / n, sum(q[1] for _, q in pairs) / n)
        d = [(p[0] - mp[0], p[1] - mp[1], q[0] - mq[0], q[1] - mq[1]) for p, q in pairs]
        sxx = sum(px * qx + py * qy for px, py, qx, qy in d)
        sxy = sum(px * qy - py * qx for px, py, qx, qy in d)
        a = math.atan2(sxy, sxx)
        c, s = math.cos(a), math.sin(a)
        tx, ty = mq[0] - (c * mp[0] - s * mp[1]), mq[1] - (s * mp[0] + c * mp[1])
        t = (c * t[0] - s * t[1] + tx, s * t[0] + c * t[1] + ty, t[2] + a)
        if abs(a) < 1e-5 and math.hypot(tx, ty) < 1e-4:
            break
    return t


def verdict(ours, rel, odometry):
    """The scans' call (shares aligned at ours and at the relation), unless the odometry,
    where it witnesses, lies nearer the pose they would reject (odometry: its distances in
    metres from ours and from the relation, or None)."""
    if max(ours, rel) < 0.1:
        return "no overlap"
    call = None
    if ours >= 0.2 and ours >= 2 * rel:
        call = "ours"
    elif rel >= 0.2 and rel >= 2 * ours:
        call = "relation"
    if call is None:
        return "unclear"
    if odometry is not None and (odometry[0] > odometry[1]) == (call == "ours"):
        return "split"
    return call


def judge(scan_a, scan_b, rel, ours, odometry):
    """One pair's row: shares aligned at the relation and at ours, where ICP from each ends
    (metres from ours) and its share, the odometry's distances, and the verdict."""
    grid = Grid(scan_a)
    at_rel, at_ours = aligned_share(grid, scan_b, rel), aligned_share(grid, scan_b, ours)
    from_rel, from_ours = icp(grid, scan_b, rel), icp(grid, scan_b, ours)
    off = lambda t: math.hypot(*between(t, ours)[:2])
    return {"at": (at_rel, at_ours),
            "from_rel": (off(from_rel), aligned_share(grid, scan_b, from_rel)),
            "from_ours": (off(from_ours), aligned_share(grid, scan_b, from_ours)),
            "odometry": odometry, "verdict": verdict(at_ours, at_rel, odometry)}


def print_row(a_s, b_s, error_m, row):
    odo = "%5.2f %5.2f" % row["odometry"] if row["odometry"] else "  -     - "
    print("%8.1f %8.1f %5.2f | %.2f %.2f | %5.2f %.2f | %5.2f %.2f | %s | %s" % (
        a_s, b_s, error_m, *row["at"], *row["from_rel"], *row["from_ours"], odo, row["verdict"]))


def relations_on_scans(path, offset_s, estimate, scans):
    """(a, b, relation) for each relation whose two stamps are scans of the log and poses of
    the estimate."""
    for line in open(path):
        f = line.split()
        if len(f) < 8 or f[0].startswith("#"):
            continue
        a, b = round(float(f[0]) - offset_s, 3), round(float(f[1]) - offset_s, 3)
        if a in estimate and b in estimate and a in scans and b in scans:
            yield a, b, (float(f[2]), float(f[3]), float(f[7]))


def main():
    if len(sys.argv) < 4:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    log, relations, mode_dir = sys.argv[1:4]
    min_error = float(sys.argv[4]) if len(sys.argv) > 4 else 0.2
    offset_s = float(sys.argv[5]) if len(sys.argv) > 5 else 0.0
    for path in (log, relations, mode_dir + "/trajectory.tum"):
        if not os.path.isfile(path):
            print(f"relation_scan_check: {path}: no such file", file=sys.stderr)
            sys.exit(2)
    estimate = load_tum(mode_dir + "/trajectory.tum")
    scans, odometry = {}, {}
    for stamp, ranges, start, step, offset, odom in laser_lines(log):
        scans[round(stamp, 3)] = scan_points(ranges, start, step, offset)
        odometry[round(stamp, 3)] = odom
    t0 = min(estimate) if estimate else 0.0
    counts, errors, kept = {}, [], []
    print("# from_s to_s error_m | aligned at relation, ours | ICP from relation: ends m from"
          " ours, aligned | ICP from ours: ends m from ours, aligned | odometry m from ours,"
          " from relation | verdict (s since the first pose)")
    for a, b, rel in relations_on_scans(relations, offset_s, estimate, scans):
        ours = between(estimate[a], estimate[b])
        errors.append(math.hypot(*between(rel, ours)[:2]))
        if errors[-1] < min_error:
            kept.append(errors[-1])
            continue
        odo = None
        if abs(b - a) <= ODOMETRY_WITNESS_S:
            o = between(odometry[a], odometry[b])
            odo = (math.hypot(*between(o, ours)[:2]), math.hypot(*between(o, rel)[:2]))
        row = judge(scans[a], scans[b], rel, ours, odo)
        counts[row["verdict"]] = counts.get(row["verdict"], 0) + 1
        if row["verdict"] != "ours":  # else the scans contradict it: out of the second mean
            kept.append(errors[-1])
        print_row(a - t0, b - t0, errors[-1], row)
    print("# verdicts:", ", ".join("%s %d" % kv for kv in sorted(counts.items())) or "none")
    if errors:
        print("# mean translational error: %.4f m over the %d relations on scans; %.4f m over the"
              " %d the scans do not contradict" % (sum(errors) / len(errors), len(errors),
                                                   sum(kept) / len(kept), len(kept)))


if __name__ == "__main__":
    main()
