#!/usr/bin/env python3
"""Prints the CI benchmark figures and their ratios to the recorded baseline.

Ratios > TOLERANCE are flagged as possible regressions (or noise: CI machines are shared);
nothing fails. With --record the current figures become the baseline.
"""
import json
import os
import sys

TOLERANCE = 1.5


def current_figures(out_dir):
    figures = {}
    for name in sorted(os.listdir(out_dir)):
        if not name.endswith("_bench.json"):
            continue
        with open(os.path.join(out_dir, name)) as f:
            data = json.load(f)
        for b in data.get("benchmarks", []):
            figures[f"{name[:-5]}:{b['name']}:cpu_ms"] = b["cpu_time"] * {
                "ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
    summary = os.path.join(out_dir, "corridor_3", "summary.json")
    if os.path.exists(summary):
        with open(summary) as f:
            s = json.load(f)
        for mode, m in s["modes"].items():
            figures[f"corridor_3:{mode}:wall_time_s"] = m["wall_time_s"]
            figures[f"corridor_3:{mode}:time_per_obs_mean_ms"] = m["time_per_obs_ms"]["mean"]
            figures[f"corridor_3:{mode}:nodes_final"] = m["nodes_final"]
            figures[f"corridor_3:{mode}:ate_rmse_m"] = m["ate_rmse_m"]
            figures[f"corridor_3:{mode}:blur_mean_cm"] = m["blur"]["mean_cm"]
    return figures


def main():
    out_dir, baseline_path = sys.argv[1], sys.argv[2]
    record = "--record" in sys.argv[3:]
    figures = current_figures(out_dir)
    if record:
        with open(baseline_path, "w") as f:
            json.dump(figures, f, indent=1, sort_keys=True)
            f.write("\n")
        print(f"ci-bench: recorded {len(figures)} figures in {baseline_path}")
        return
    baseline = {}
    if os.path.exists(baseline_path):
        with open(baseline_path) as f:
            baseline = json.load(f)
    print(f"{'figure':70s} {'now':>12s} {'baseline':>12s} {'ratio':>7s}")
    flagged = 0
    for key in sorted(figures):
        now = figures[key]
        base = baseline.get(key)
        if base is None or base == 0:
            print(f"{key:70s} {now:12.4g} {'-':>12s} {'-':>7s}")
            continue
        ratio = now / base
        flag = ""
        # Lower is better for every figure here: times, errors, blur and node counts.
        if ratio > TOLERANCE:
            flag = "  <-- slower/worse than recorded (or a noisy machine)"
            flagged += 1
        print(f"{key:70s} {now:12.4g} {base:12.4g} {ratio:7.2f}{flag}")
    print(f"ci-bench: {len(figures)} figures, {flagged} flagged above {TOLERANCE}x "
          "(flags are informational; CI does not fail on them)")


if __name__ == "__main__":
    main()
