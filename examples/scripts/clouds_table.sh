#!/usr/bin/env bash
# Runs every real-cloud scenario (examples/scenarios/clouds/*.yaml, written by generate.py there)
# with seed 1 and the default time limit (10 s), and prints the table of
# examples/scenarios/clouds/README.md: per cloud and hand, the stable loops with their verdicts,
# the outcome, the perception and planning times (planning: `run --json`'s seconds, when a
# claspable loop was planned for). Each run's result.json, sensed.png and pictures stay in
# OUT/<scenario>/.
# Usage: examples/scripts/clouds_table.sh [path/to/claspplan] [OUT]   (defaults: build/claspplan,
# /tmp/clouds). Extra options for `claspplan run` may follow in CLASPPLAN_RUN_ARGS (e.g.
# "--no-pictures").
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
exe=${1:-$here/../build/claspplan}
out=${2:-/tmp/clouds}
mkdir -p "$out"
echo "| cloud | hand | exit | stable loops: claspable / all | verdicts | outcome | perception s | planning s |"
echo "|---|---|---|---|---|---|---|---|"
for yaml in "$here"/scenarios/clouds/*.yaml; do
  name=$(basename "$yaml" .yaml)
  dir="$out/$name"
  rm -rf "$dir"
  set +e
  # shellcheck disable=SC2086
  "$exe" run "$yaml" --out "$dir" --json --seed 1 ${CLASPPLAN_RUN_ARGS:-} >"$dir.stdout.json" \
    2>"$dir.stderr.txt"
  rc=$?
  set -e
  python3 - "$name" "$rc" "$dir" <<'PY'
import collections, json, os, sys
name, rc, d = sys.argv[1], int(sys.argv[2]), sys.argv[3]
cloud, hand = name.rsplit("_", 1)
try:
    stdout = json.load(open(d + ".stdout.json"))
except (OSError, ValueError):
    stdout = {}
try:
    result = json.load(open(os.path.join(d, "result.json")))
except (OSError, ValueError):
    result = {}
loops = result.get("loops", [])
claspable = sum(1 for l in loops if l["verdict"] == "claspable")
counts = collections.Counter(l["verdict"] for l in loops)
verdicts = ", ".join("%d %s" % (n, v) for v, n in sorted(counts.items())) or "none"
if stdout.get("verified"):
    outcome = "verified clasp (VLk %.2f)" % stdout.get("virtual_linking", 0)
elif stdout.get("success"):
    outcome = "clasp found, not verified"
else:
    reason = stdout.get("reason") or stdout.get("error") or open(d + ".stderr.txt").read().strip()
    outcome = reason.splitlines()[-1] if reason else "?"
    if len(outcome) > 160:
        outcome = outcome[:157] + "..."
seconds = "%.2f" % stdout["seconds"] if "seconds" in stdout else "-"
try:
    perception = "%.2f" % json.load(open(os.path.join(d, "timing.json")))["perception"]
except (OSError, ValueError, KeyError):
    perception = "-"
print("| %s | %s | %d | %d / %d | %s | %s | %s | %s |" % (
    cloud, hand, rc, claspable, len(loops), verdicts, outcome.replace("|", "/"), perception,
    seconds))
PY
done
