#!/usr/bin/env python3
"""Summarises a `claspplan bench --suite paper` run against the paper's figures (Sec. V-A, V-B).

Usage: examples/scripts/paper_summary.py OUT/cases.csv

Prints, for the 60 cases (every row but chair_obstructed_*): verified runs, cases verified at least
once and at every seed, cycles after the pre-expansion within 52 and under 10 (the paper: all 60
within 52, 37 under 10), planning seconds; verified runs per object and hand; and the obstructed
chair's verified runs (the paper: 606 cycles, 248 nodes).
"""
import csv
import statistics
import sys
from collections import defaultdict

HANDS = ["sdh", "dlr", "icub", "armar3"]
OBJECTS = ["purse", "bag", "travelbag", "lawnmower", "chair"]


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(sys.argv) == 2 else 2
    try:
        rows = list(csv.DictReader(open(sys.argv[1], newline="")))
    except OSError as e:
        print(f"paper_summary: {e}", file=sys.stderr)
        return 2
    # TS-RRT's runs only: not the tolerance sweep's, not the baselines'.
    rows = [r for r in rows if r.get("tolerance", "0.00") in ("0.00", "-") and not r.get("method")]
    cases = [r for r in rows if not r["name"].startswith("chair_obstructed")]
    verified = [r for r in cases if r["verified"] == "1"]
    cycles = [int(r["cycles"]) for r in verified]
    seconds = [float(r["seconds"]) for r in verified]
    by_case = defaultdict(list)
    for r in cases:
        by_case[r["name"]].append(r["verified"] == "1")
    print(f"60 cases: {len(verified)} of {len(cases)} runs verified; "
          f"{sum(any(v) for v in by_case.values())} of {len(by_case)} cases at least once, "
          f"{sum(all(v) for v in by_case.values())} at every seed")
    if verified:
        print(f"cycles after the pre-expansion: {sum(c <= 52 for c in cycles)} within 52, "
              f"{sum(c < 10 for c in cycles)} under 10, at most {max(cycles)}")
        print(f"planning seconds: median {statistics.median(seconds):.2f}, "
              f"at most {max(seconds):.2f}")
    table = defaultdict(lambda: [0, 0])
    for r in cases:
        parts = r["name"].split("_")
        cell = table[(parts[0], parts[-1])]
        cell[0] += r["verified"] == "1"
        cell[1] += 1
    print("\n| object | " + " | ".join(HANDS) + " |")
    print("|---|" + "---|" * len(HANDS))
    for o in OBJECTS:
        print(f"| {o} | " + " | ".join(f"{table[(o, h)][0]}/{table[(o, h)][1]}" for h in HANDS) + " |")
    print("\nobstructed chair, verified runs (hand, seed, cycles, nodes, seconds):")
    for r in rows:
        if r["name"].startswith("chair_obstructed") and r["verified"] == "1":
            print(f"  {r['name'].split('_')[-1]} {r['seed']} {r['cycles']} {r['nodes']} "
                  f"{float(r['seconds']):.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
