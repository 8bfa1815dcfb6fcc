#!/usr/bin/env python3
"""Adds the camera a failed run names to its scenario and runs it again.

A run whose search mostly ran into space no camera saw, or whose insecure clasps mostly had
fingers stop on it, ends with a next best view in its reason and in result.json
(`next_best_view`). For every such run of a `claspplan bench` directory, this writes the scenario
with that camera appended to `object: cameras` (next to the original, as
`.<name>.seed<k>.next_view.yaml`, removed afterwards: mesh paths are relative to it), runs it with
the same seed and time limit, and prints a table: was the clasp verified with the added camera?
With --rounds N, a run that still fails and names another camera gets that one too, up to N
cameras; --jobs N runs N of the failed runs at once (one per core).
With --controller-only (for a bench run with it), the runs are the clasp controller's alone, and
a run counts when it succeeds as `run --controller-only` does (exit 0).

    ./build/claspplan bench examples/scenarios/conditions/*.yaml --seeds 4 --jobs 2 \\
        --time-limit 10 --out /tmp/conditions
    examples/scenarios/conditions/next_view_trial.py /tmp/conditions --time-limit 10 --jobs 2
"""
import argparse
import concurrent.futures
import json
import os
import re
import subprocess
import sys
import tempfile


def camera_line(view):
    p, t = view["position"], view["target"]
    return "    - {position: [%.2f, %.2f, %.2f], target: [%.2f, %.2f, %.2f]}  # next best view\n" % (
        *p, *t)


def with_camera(text, line):
    """The scenario's text with `line` after the last entry of `cameras:`."""
    lines = text.splitlines(keepends=True)
    start = next((i for i, l in enumerate(lines) if re.match(r"\s*cameras:\s*$", l)), None)
    if start is None:
        raise ValueError("no `cameras:` list")
    end = start + 1
    while end < len(lines) and re.match(r"\s+- \{position:", lines[end]):
        end += 1
    return "".join(lines[:end] + [line] + lines[end:])


def succeeded(a, summary):
    """A verified clasp; with --controller-only, the run's success (its exit 0)."""
    return summary.get("success" if a.controller_only else "verified", False)


def run_with(a, scenario, text, seed):
    """Runs the scenario's text as written beside it; the --json summary and the next view."""
    copy = os.path.join(os.path.dirname(scenario), ".%s.seed%d.next_view.yaml" %
                        (os.path.basename(scenario)[:-5], seed))
    try:
        with open(copy, "w") as f:
            f.write(text)
        with tempfile.TemporaryDirectory() as out:
            cmd = [a.claspplan, "run", copy, "--seed", str(seed), "--time-limit",
                   str(a.time_limit), "--out", out, "--json", "--no-pictures"]
            if a.controller_only:
                cmd.append("--controller-only")
            done = subprocess.run(cmd, capture_output=True, text=True)
            try:
                summary = json.loads(done.stdout)
            except json.JSONDecodeError:
                return {"verified": False, "reason": done.stderr.strip()}, None
            with open(os.path.join(out, "result.json")) as f:
                return summary, json.load(f).get("next_best_view")
    finally:
        os.remove(copy)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("bench_dir", help="a `claspplan bench --out` directory")
    ap.add_argument("--claspplan", default="./build/claspplan")
    ap.add_argument("--time-limit", type=float, default=10.0)
    ap.add_argument("--rounds", type=int, default=1,
                    help="add the next run's named camera too, up to this many cameras")
    ap.add_argument("--jobs", type=int, default=1,
                    help="runs at once (at most one per core: the runs have a time limit)")
    ap.add_argument("--controller-only", action="store_true",
                    help="run the clasp controller alone, as `run --controller-only`")
    a = ap.parse_args()
    if a.jobs < 1 or a.rounds < 1:
        sys.exit("--jobs and --rounds must be at least 1")
    runs = os.path.join(a.bench_dir, "runs")
    if not os.path.isdir(runs):
        sys.exit("%s: no runs/ directory (not a bench output)" % a.bench_dir)
    failed = []  # (run name, its result) for each run that named a camera
    for name in sorted(os.listdir(runs)):
        path = os.path.join(runs, name, "result.json")
        if not os.path.exists(path):
            continue
        with open(path) as f:
            result = json.load(f)
        if result.get("next_best_view"):
            failed.append((name, result))

    def trial(item):
        """One failed run again, a camera added per round until it succeeds or names none."""
        name, result = item
        view = result["next_best_view"]
        scenario = result["scenario"]
        with open(scenario) as f:
            text = f.read()
        added, after = [], {}
        for _ in range(a.rounds):
            if not view:
                break
            text = with_camera(text, camera_line(view))
            added.append(view)
            after, view = run_with(a, scenario, text, result["seed"])
            if succeeded(a, after):
                break
        cams = "<br>".join("`%s`" % camera_line(v).strip().split("  #")[0][2:] for v in added)
        shares = ", ".join("%.0f%%" % (100.0 * v["visible_voxels"] / max(v["unknown_voxels"], 1))
                           for v in added)
        row = (name, cams, shares, succeeded(a, after), after.get("reason", ""))
        print("%s: %s" % (name, "ok" if row[3] else row[4]), file=sys.stderr)
        return row

    # Each run is its own chain of rounds (its scenario copy is named by its seed), so runs can go
    # side by side; with a time limit, one per core keeps them comparable.
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        rows = list(pool.map(trial, failed))
    print("| run | cameras added | expected share seen | %s with them |" %
          ("succeeded" if a.controller_only else "verified"))
    print("|---|---|---|---|")
    for name, cam, share, ok, reason in rows:
        print("| %s | %s | %s | %s |" % (name, cam, share, "yes" if ok else "no: " + reason[:60]))
    print("\n%d of %d runs %s with the cameras their reasons named" %
          (sum(r[3] for r in rows), len(rows), "succeeded" if a.controller_only else "verified"))


if __name__ == "__main__":
    main()
