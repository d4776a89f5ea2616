#!/usr/bin/env python3
"""How well the sequential edges' heading sigma covers their heading error on a corrected log.

    scripts/sequential_heading_errors.py LOG-corrected.log.gz OUT/standard

OUT/<mode> is a `lifelong replay LOG --modes standard` mode directory (trajectory.tum: every
scan; graph.g2o: the nodes and edges). A node is placed on its scan by its pose (to 1e-5 m);
each edge between consecutive nodes is compared with the corrected poses' relative heading.
Prints the error's median, its robust sigma (1.4826 x median), 95th and 99th percentiles and
maximum, the edges' median heading sigma, and the share of errors beyond 3 of their sigmas.
The corrected poses jitter, so the errors are upper bounds."""
import gzip
import math
import statistics
import sys


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def main():
    log, run = sys.argv[1], sys.argv[2]
    reference = []
    with gzip.open(log, "rt") if log.endswith(".gz") else open(log) as f:
        for line in f:
            if line.startswith("FLASER"):
                fields = line.split()
                n = int(fields[1])
                reference.append(float(fields[4 + n]))  # the corrected heading
    scan_of = {}
    for i, line in enumerate(open(run + "/trajectory.tum")):
        f = line.split()
        scan_of[(round(float(f[1]), 5), round(float(f[2]), 5))] = i
    node_scan, errors, sigmas = {}, [], []
    for line in open(run + "/graph.g2o"):
        f = line.split()
        if f[0] == "VERTEX_SE2":
            node_scan[int(f[1])] = scan_of.get((round(float(f[2]), 5), round(float(f[3]), 5)))
        elif f[0] == "EDGE_SE2" and int(f[2]) == int(f[1]) + 1:
            a, b = node_scan.get(int(f[1])), node_scan.get(int(f[2]))
            info_theta = float(f[11])  # the last entry of the upper-triangular information
            if a is None or b is None or max(a, b) >= len(reference) or info_theta <= 0:
                continue
            errors.append(abs(wrap(float(f[5]) - wrap(reference[b] - reference[a]))))
            sigmas.append(1.0 / math.sqrt(info_theta))
    if not errors:
        sys.exit("no consecutive edges matched scans: is OUT/<mode> a replay of LOG?")
    e = sorted(errors)
    pct = lambda q: e[min(len(e) - 1, int(q * len(e)))]
    deg = math.degrees
    beyond = sum(err > 3 * s for err, s in zip(errors, sigmas)) / len(errors)
    print(f"{len(e)} steps: heading error median {deg(statistics.median(e)):.2f} deg, robust "
          f"sigma {deg(1.4826 * statistics.median(e)):.2f}, p95 {deg(pct(0.95)):.2f}, p99 "
          f"{deg(pct(0.99)):.2f}, max {deg(e[-1]):.1f}; edge sigma median "
          f"{deg(statistics.median(sigmas)):.2f} deg; beyond 3 sigma {beyond:.3f}")


if __name__ == "__main__":
    main()
