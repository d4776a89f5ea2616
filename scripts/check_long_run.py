#!/usr/bin/env python3
"""Flatness of a long run (issue #15, "a day in the office") from one mode's timeline.csv.

    scripts/check_long_run.py OUT/pruned [--early 6 12] [--late-hours 6]

Compares the last `late-hours` of the run with hours [early_from, early_to):
  - nodes and peak RSS within 10 %;
  - time per observation: mean over the last 10 % of observations <= 1.5x the mean of the
    early window;
  - no NaN or inf in any CSV of the mode's directory, nor in summary.json next to it.
Prints one line per check and exits 1 when one fails, 2 on unreadable input.
"""
import argparse
import csv
import json
import math
import pathlib
import sys


def read_timeline(path):
    with open(path, newline="") as f:
        # Every numeric column; `sequential` is a word.
        return [{k: float(v) for k, v in row.items() if v != "" and k != "sequential"}
                for row in csv.DictReader(f)]


def mean(xs):
    return sum(xs) / len(xs) if xs else float("nan")


def non_finite_cells(path):
    bad = 0
    with open(path, newline="") as f:
        for row in csv.reader(f):
            for cell in row:
                if cell.strip().lower() in ("nan", "-nan", "inf", "-inf", "+inf"):
                    bad += 1
    return bad


def non_finite_json(node):
    if isinstance(node, float):
        return 0 if math.isfinite(node) else 1
    if isinstance(node, dict):
        return sum(non_finite_json(v) for v in node.values())
    if isinstance(node, list):
        return sum(non_finite_json(v) for v in node)
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mode_dir", type=pathlib.Path)
    ap.add_argument("--early", nargs=2, type=float, default=[6.0, 12.0], metavar=("FROM_H", "TO_H"))
    ap.add_argument("--late-hours", type=float, default=6.0)
    a = ap.parse_args()
    try:
        rows = read_timeline(a.mode_dir / "timeline.csv")
    except (OSError, ValueError, KeyError) as e:
        print(f"{a.mode_dir / 'timeline.csv'}: {e}", file=sys.stderr)
        return 2
    if not rows:
        print(f"{a.mode_dir / 'timeline.csv'}: no rows", file=sys.stderr)
        return 2
    end = rows[-1]["t_s"]
    early = [r for r in rows if a.early[0] * 3600 <= r["t_s"] < a.early[1] * 3600]
    late = [r for r in rows if r["t_s"] >= end - a.late_hours * 3600]
    last10 = rows[int(0.9 * len(rows)):]
    if not early or not late:
        print(f"the run ({end / 3600:.2f} h) does not cover both windows", file=sys.stderr)
        return 2
    ok = True

    def check(name, value, limit, passed):
        nonlocal ok
        ok = ok and passed
        print(f"{'ok  ' if passed else 'FAIL'} {name}: {value} (limit {limit})")

    n_early, n_late = mean([r["nodes"] for r in early]), mean([r["nodes"] for r in late])
    check("nodes, late / early mean", f"{n_late:.1f} / {n_early:.1f} = {n_late / n_early:.3f}",
          "0.9-1.1", 0.9 <= n_late / n_early <= 1.1)
    rss_early, rss_late = max(r["rss_mb"] for r in early), max(r["rss_mb"] for r in late)
    check("peak RSS MB, late / early", f"{rss_late:.1f} / {rss_early:.1f} = {rss_late / rss_early:.3f}",
          "0.9-1.1", 0.9 <= rss_late / rss_early <= 1.1)
    t_early, t_last = mean([r["time_ms"] for r in early]), mean([r["time_ms"] for r in last10])
    check("ms per observation, last 10 % / early mean",
          f"{t_last:.2f} / {t_early:.2f} = {t_last / t_early:.3f}", "<= 1.5", t_last / t_early <= 1.5)
    bad = sum(non_finite_cells(p) for p in a.mode_dir.glob("*.csv"))
    summary = a.mode_dir.parent / "summary.json"
    if summary.exists():
        bad += non_finite_json(json.loads(summary.read_text()))
    check("NaN or inf values in the CSVs and summary.json", bad, 0, bad == 0)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
