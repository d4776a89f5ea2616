#!/usr/bin/env python3
"""scripts/trajectory_stretch.py on made-up runs: a rotated, shifted copy of the truth loses
nothing to a rigid fit; one 1 % short along x shows stretch 1.0101 and an affine error of
0, against a run's truth or a replay's reference, also when the stamps repeat (paired line by
line); a missing truth file is exit 2."""
import math
import os
import subprocess
import sys
import tempfile

SCRIPT = os.path.join(sys.argv[1], "scripts", "trajectory_stretch.py")


def write_tum(path, poses, stamp=lambda t: t * 0.2):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        for t, (x, y) in enumerate(poses):
            f.write(f"{stamp(t):.6f} {x:.9f} {y:.9f} 0 0 0 0 1\n")


def run(args):
    return subprocess.run([sys.executable, SCRIPT] + args, capture_output=True, text=True)


def main():
    truth = [(10.0 * math.cos(0.05 * k) + 0.1 * k, 4.0 * math.sin(0.05 * k)) for k in range(400)]
    c, s = math.cos(0.3), math.sin(0.3)
    moved = [(c * x - s * y + 2.0, s * x + c * y - 1.0) for x, y in truth]
    short = [(x / 1.0101 + 0.5, y) for x, y in truth]
    with tempfile.TemporaryDirectory() as d:
        write_tum(os.path.join(d, "truth", "trajectory.tum"), truth)
        write_tum(os.path.join(d, "moved", "trajectory.tum"), moved)
        write_tum(os.path.join(d, "short", "trajectory.tum"), short)
        out = run([d])
        assert out.returncode == 0, out.stderr
        rows = {line.split()[0]: line.split() for line in out.stdout.splitlines()[1:]}
        assert set(rows) == {"moved", "short"}, out.stdout
        assert float(rows["moved"][2]) < 1e-6 and float(rows["moved"][3]) < 1e-6, out.stdout
        assert rows["moved"][4:] == ["1.0000", "1.0000"], out.stdout
        assert float(rows["short"][2]) > 0.01, out.stdout  # the rigid fit cannot undo it
        assert float(rows["short"][3]) < 1e-6, out.stdout
        assert rows["short"][4:] == ["1.0101", "1.0000"], out.stdout
        missing = run([os.path.join(d, "nowhere")])
        assert missing.returncode == 2 and "truth/trajectory.tum" in missing.stderr
    # A replay's directory: the log's reference poses stand where a run's truth does.
    with tempfile.TemporaryDirectory() as d:
        write_tum(os.path.join(d, "reference", "trajectory.tum"), truth)
        write_tum(os.path.join(d, "short", "trajectory.tum"), short)
        out = run([d])
        assert out.returncode == 0, out.stderr
        rows = [line.split() for line in out.stdout.splitlines()[1:]]
        assert [r[0] for r in rows] == ["short"], out.stdout
        assert rows[0][4:] == ["1.0101", "1.0000"], out.stdout
    # A log whose clock is broken (the infinite-corridor log: all but four scans stamped
    # 4294970000): the files pair line by line, not on the few distinct stamps.
    broken = lambda t: -0.5 * t if t < 4 else 4294970000.0
    with tempfile.TemporaryDirectory() as d:
        write_tum(os.path.join(d, "reference", "trajectory.tum"), truth, broken)
        write_tum(os.path.join(d, "short", "trajectory.tum"), short, broken)
        out = run([d])
        assert out.returncode == 0, out.stderr
        rows = [line.split() for line in out.stdout.splitlines()[1:]]
        assert rows[0][1] == "400" and rows[0][4:] == ["1.0101", "1.0000"], out.stdout
    print("ok")


if __name__ == "__main__":
    main()
