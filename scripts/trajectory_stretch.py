#!/usr/bin/env python3
"""How much of a trajectory's error is a stretch of the whole map.

Usage: scripts/trajectory_stretch.py RUN_DIR [MODE ...]

RUN_DIR is a `lifelong run` output (or a sweep cell) with truth/trajectory.tum, or a
`lifelong replay` output with reference/trajectory.tum (a log's reference poses), and
MODE/trajectory.tum (default: every mode directory present). For each mode it pairs the
poses by stamp, or line by line when the two files have as many poses and some stamp
repeats (a log whose clock is broken), and prints:
  rigid_m     RMS position error after the best rigid alignment (the ATE of summary.json)
  affine_m    RMS error after the best affine map (a rigid motion plus stretch and shear)
  stretch     the affine map's two principal scale factors (singular values), largest
              first: 1.0050 means the estimate is 0.5 % too short along that axis
Standard library only, so it runs wherever the CLI does.
"""
import math
import os
import sys


def load_tum(path):
    """The file's poses in order, as (stamp, (x, y))."""
    poses = []
    with open(path) as f:
        for line in f:
            fields = line.split()
            if not fields or fields[0].startswith("#"):
                continue
            poses.append((round(float(fields[0]), 3), (float(fields[1]), float(fields[2]))))
    return poses


def pair(est, truth):
    """The paired positions (estimate, truth): line by line when the files have as many
    poses and a stamp repeats in either, else by stamp."""
    repeats = any(len({s for s, _ in p}) < len(p) for p in (est, truth))
    if repeats and len(est) == len(truth):
        return [p for _, p in est], [p for _, p in truth]
    by_stamp = dict(truth)
    shared = [(s, p) for s, p in dict(est).items() if s in by_stamp]
    shared.sort()
    return [p for _, p in shared], [by_stamp[s] for s, _ in shared]


def solve3(m, v):
    """Solves the 3x3 system m x = v by Gaussian elimination with partial pivoting."""
    a = [row[:] + [v[i]] for i, row in enumerate(m)]
    for i in range(3):
        p = max(range(i, 3), key=lambda r: abs(a[r][i]))
        a[i], a[p] = a[p], a[i]
        for r in range(3):
            if r != i:
                f = a[r][i] / a[i][i]
                a[r] = [x - f * y for x, y in zip(a[r], a[i])]
    return [a[i][3] / a[i][i] for i in range(3)]


def rigid_rms(est, tru):
    n = len(est)
    me = [sum(p[k] for p in est) / n for k in (0, 1)]
    mt = [sum(p[k] for p in tru) / n for k in (0, 1)]
    c = s = 0.0
    for (ex, ey), (tx, ty) in zip(est, tru):
        ex, ey, tx, ty = ex - me[0], ey - me[1], tx - mt[0], ty - mt[1]
        c += ex * tx + ey * ty
        s += ex * ty - ey * tx
    th = math.atan2(s, c)
    co, si = math.cos(th), math.sin(th)
    err = 0.0
    for (ex, ey), (tx, ty) in zip(est, tru):
        ex, ey = ex - me[0], ey - me[1]
        err += (co * ex - si * ey + mt[0] - tx) ** 2 + (si * ex + co * ey + mt[1] - ty) ** 2
    return math.sqrt(err / n)


def affine_fit(est, tru):
    """Least-squares affine map est -> tru: rows (a, b, c) with t_k = a x + b y + c."""
    rows = []
    for k in (0, 1):
        m = [[0.0] * 3 for _ in range(3)]
        v = [0.0] * 3
        for (x, y), t in zip(est, tru):
            u = (x, y, 1.0)
            for i in range(3):
                v[i] += u[i] * t[k]
                for j in range(3):
                    m[i][j] += u[i] * u[j]
        rows.append(solve3(m, v))
    err = 0.0
    for (x, y), (tx, ty) in zip(est, tru):
        err += (rows[0][0] * x + rows[0][1] * y + rows[0][2] - tx) ** 2
        err += (rows[1][0] * x + rows[1][1] * y + rows[1][2] - ty) ** 2
    a, b, c, d = rows[0][0], rows[0][1], rows[1][0], rows[1][1]
    # Singular values of [[a, b], [c, d]].
    s1 = math.hypot(a + d, c - b) / 2.0
    s2 = math.hypot(a - d, c + b) / 2.0
    return math.sqrt(err / len(est)), (s1 + s2, abs(s1 - s2))


def main(argv):
    if len(argv) < 2:
        sys.stderr.write(__doc__)
        return 2
    run = argv[1]
    found = [
        os.path.join(run, d, "trajectory.tum")
        for d in ("truth", "reference")
        if os.path.exists(os.path.join(run, d, "trajectory.tum"))
    ]
    if not found:
        sys.stderr.write(
            f"{run}: neither truth/trajectory.tum nor reference/trajectory.tum "
            "(is it a run or replay directory?)\n"
        )
        return 2
    truth_path = found[0]
    truth = load_tum(truth_path)
    modes = argv[2:] or sorted(
        d
        for d in os.listdir(run)
        if d not in ("truth", "reference")
        and os.path.exists(os.path.join(run, d, "trajectory.tum"))
    )
    print("mode            poses   rigid_m  affine_m  stretch")
    for mode in modes:
        path = os.path.join(run, mode, "trajectory.tum")
        if not os.path.exists(path):
            sys.stderr.write(f"{path}: no such file\n")
            return 2
        e, t = pair(load_tum(path), truth)
        if len(e) < 3:
            sys.stderr.write(f"{path}: fewer than 3 poses paired with {truth_path}\n")
            return 2
        affine, (big, small) = affine_fit(e, t)
        print(f"{mode:<14} {len(e):6d}  {rigid_rms(e, t):7.3f}  {affine:8.3f}  "
              f"{big:.4f} {small:.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
