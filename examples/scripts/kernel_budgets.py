#!/usr/bin/env python3
"""Runs the kernel benchmarks that have a speed budget and reports each figure against it.

Usage: examples/scripts/kernel_budgets.py [build/test/claspplan_kernel_bench] [--json]
                                          [--repetitions N]

Each figure is the median of N runs of its benchmark (default 3; a benchmark that sets its own
repetitions keeps them). Prints a Markdown table (kernel, budget, measured, ratio) where a ratio
above 1 is over budget, and exits 1 when any kernel is over budget or did not run (2 when the
benchmark binary cannot be run or an option is wrong). Not a test: these machines are noisy; run
it on a quiet machine and read the ratios.
"""
import json
import re
import subprocess
import sys

# (label, benchmark name, statistic, budget, unit). "time": real time per iteration in seconds
# (the median over repetitions when the benchmark repeats), at most; "rate": items per second, at
# least; "speedup": the time of the second name over this one's, at least.
BUDGETS = [
    ("Gauss sum, segment pairs per second (100x100)", "BM_GaussSum/100", "rate", 10e6, "pairs/s"),
    ("Gauss sum, segment pairs per second (1000x1000)", "BM_GaussSum/1000", "rate", 10e6, "pairs/s"),
    ("closed-curve Lk by crossing count", "BM_LinkingNumberCrossings", "time", 5e-6, "s"),
    ("one control step, kr5_icub", "BM_ControlStepIcub", "time", 50e-6, "s"),
    ("FK + finger-curve points and Jacobians, kr5_icub", "BM_IcubFkAndFingerCurveJacobians", "time",
     20e-6, "s"),
    ("collision check vs a 30,000-triangle object near a clasp (median)",
     "BM_IcubCollisionCheck30kNearObject/repeats:9", "time", 100e-6, "s"),
    ("two 640x480 depth PNGs -> loops -> targets, 2,000 points", "BM_DepthFileToTargets/2000/1",
     "time", 50e-3, "s"),
    ("two 1280x960 depth PNGs -> targets, 10,000 points", "BM_DepthFileToTargets/10000/2", "time",
     1.0, "s"),
    ("two 1280x960 depth PNGs -> targets, 40,000 points", "BM_DepthFileToTargets/40000/2", "time",
     1.0, "s"),
    ("sensed space (free/occupied/unknown) of two 640x480 views, 5 mm voxels",
     "BM_SensedSpace/0", "time", 150e-3, "s"),
    ("the same, and 1.7 mm voxels near a handle-sized loop (the planner's map)",
     "BM_SensedSpace/2", "time", 150e-3, "s"),
    ("escape search, gravity and approach stages on a secure clasp",
     "BM_EscapeSearch/1/iterations:5", "time", 0.2, "s"),
    ("secure-clasp check, one thread, against its reference",
     ("BM_SecureClaspChecker/1/iterations:5", "BM_SecureClaspReference/1/iterations:2"), "speedup",
     5.0, "x"),
]
UNIT_SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def run(binary, names, repetitions):
    pattern = "^(" + "|".join(re.escape(n) for n in names) + ")$"
    command = [binary, "--benchmark_filter=" + pattern, "--benchmark_format=json"]
    if repetitions > 1:
        command += [f"--benchmark_repetitions={repetitions}",
                    "--benchmark_report_aggregates_only=true"]
    try:
        out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"kernel_budgets: cannot run {binary}: {e}", file=sys.stderr)
        sys.exit(2)
    return json.loads(out)["benchmarks"]


def measured(rows, name, statistic):
    mine = [r for r in rows if r.get("run_name", r["name"]) == name]
    median = [r for r in mine if r.get("aggregate_name") == "median"]
    row = (median or [r for r in mine if r.get("run_type") != "aggregate"] or [None])[0]
    if row is None:
        return None
    if statistic == "rate":
        return row.get("items_per_second")
    return row["real_time"] * UNIT_SECONDS[row["time_unit"]]


def show(value, unit):
    if unit == "pairs/s":
        return f"{value / 1e6:.1f} M/s"
    if unit == "x":
        return f"{value:.1f}x"
    for name, scale in (("s", 1.0), ("ms", 1e-3), ("µs", 1e-6)):
        if value >= scale or name == "µs":
            return f"{value / scale:.3g} {name}"
    return str(value)


def names(budget):
    return budget[1] if isinstance(budget[1], tuple) else (budget[1],)


def figure(rows, name, statistic):
    if statistic != "speedup":
        return measured(rows, name, statistic)
    ours, reference = (measured(rows, n, "time") for n in name)
    return reference / ours if ours and reference else None


def main():
    args = [a for a in sys.argv[1:] if a != "--json"]
    if any(a in ("-h", "--help") for a in args):
        print(__doc__.strip())
        return 0
    repetitions = 3
    if "--repetitions" in args:
        at = args.index("--repetitions")
        try:
            repetitions = int(args[at + 1])
            if repetitions < 1:
                raise ValueError
        except (IndexError, ValueError):
            print("kernel_budgets: --repetitions needs a whole number >= 1", file=sys.stderr)
            return 2
        del args[at:at + 2]
    binary = args[0] if args else "build/test/claspplan_kernel_bench"
    rows = run(binary, [n for b in BUDGETS for n in names(b)], repetitions)
    report, over = [], 0
    for label, name, statistic, budget, unit in BUDGETS:
        value = figure(rows, name, statistic)
        if value is None:  # a renamed or removed benchmark must not pass unseen
            ratio = None
            over += 1
        else:
            ratio = value / budget if statistic == "time" else budget / value
            over += ratio > 1.0
        report.append({"kernel": label, "benchmark": " / ".join(names((label, name))),
                       "budget": budget, "measured": value,
                       "unit": unit, "ratio": ratio})
    if "--json" in sys.argv[1:]:
        print(json.dumps({"kernels": report, "over_budget": over}, indent=2))
    else:
        print("| kernel | budget | measured | ratio (> 1: over budget) |")
        print("|---|---|---|---|")
        for r in report:
            bound = ("≤ " if r["unit"] == "s" else "≥ ") + show(r["budget"], r["unit"])
            got = "not run" if r["measured"] is None else show(r["measured"], r["unit"])
            ratio = "-" if r["ratio"] is None else f"{r['ratio']:.2f}"
            print(f"| {r['kernel']} | {bound} | {got} | {ratio} |")
        print(f"\n{over} of {len(report)} kernels over budget or not run")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
