#!/usr/bin/env python3
"""scripts/closures_per_lap.py on a made-up run: three laps of a 200 m circle and a short
last stretch; one mode closes in laps 2 and 3, the other only in lap 2 (one lap open); the
last stretch is not a lap; a missing truth file is exit 2."""
import math
import os
import subprocess
import sys
import tempfile

SCRIPT = os.path.join(sys.argv[1], "scripts", "closures_per_lap.py")


def main():
    radius = 200.0 / (2 * math.pi)  # 63.7 m across: the far side is beyond AWAY_M
    with tempfile.TemporaryDirectory() as d:
        os.makedirs(os.path.join(d, "truth"))
        with open(os.path.join(d, "truth", "trajectory.tum"), "w") as f:
            for k in range(3 * 200 + 10):  # 1 m a second: laps start at 0, 200 and 400 s
                a = 2 * math.pi * k / 200.0
                f.write(f"{k:.1f} {radius * math.sin(a):.4f} {radius * (1 - math.cos(a)):.4f}"
                        " 0 0 0 0 1\n")
        for mode, stamps in (("standard", [250.0, 260.0, 450.0]), ("pruned", [300.0, 605.0])):
            os.makedirs(os.path.join(d, mode))
            with open(os.path.join(d, mode, "loops.csv"), "w") as f:
                f.write("stamp_current_s,stamp_old_s,injected,correct\n")
                f.writelines(f"{s},10.0,0,1\n" for s in stamps)
        out = subprocess.run([sys.executable, SCRIPT, d], capture_output=True, text=True)
        assert out.returncode == 0, out.stderr
        rows = {l.split()[0]: l.split()[1:] for l in out.stdout.splitlines()[1:]}
        assert rows["standard"] == ["3", "0", "0,2,1"], out.stdout
        assert rows["pruned"] == ["3", "1", "0,1,0"], out.stdout  # 605 s: the last stretch
        missing = subprocess.run([sys.executable, SCRIPT, os.path.join(d, "nowhere")],
                                 capture_output=True, text=True)
        assert missing.returncode == 2 and "truth/trajectory.tum" in missing.stderr
    print("ok")


if __name__ == "__main__":
    main()
