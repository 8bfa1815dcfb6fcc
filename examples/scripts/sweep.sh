#!/usr/bin/env bash
# Runs scenarios over seeds and prints one table row per scenario: verified clasps, the median
# and the longest planning time and the median cycles of the verified runs, and the most common
# reason of the others (with --controller-only: the controller reaching the goal, and the median
# steps).
# The result tables of docs/results.md, docs/real-objects.md and docs/speed.md come from this script.
#
#   examples/scripts/sweep.sh [--seeds "1 2 3 4"] [--bin build/claspplan] [--jobs 2]
#                             [--controller-only] SCENARIO.yaml...
set -euo pipefail
seeds="1 2 3 4"
bin="$(dirname "$0")/../../build/claspplan"
jobs=2
mode=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --seeds) seeds="$2"; shift 2 ;;
    --bin) bin="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --controller-only) mode="--controller-only"; shift ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) break ;;
  esac
done
[[ $# -gt 0 ]] || { echo "sweep.sh: give scenario files (see --help)" >&2; exit 2; }
[[ -x "$bin" ]] || { echo "sweep.sh: no claspplan at $bin (build it, or give --bin)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# One run: its --json summary line, saved per scenario and seed.
run_one() {
  local scenario="$1" seed="$2" out="$3"
  "$bin" run "$scenario" --seed "$seed" --no-pictures --json --out "$out.d" $mode >"$out.json" \
    2>/dev/null || true
}
export -f run_one
export bin mode
for s in "$@"; do
  for seed in $seeds; do
    printf '%s\t%s\t%s\n' "$s" "$seed" "$work/$(basename "$s" .yaml)_$seed"
  done
done | xargs -P "$jobs" -L 1 bash -c 'run_one "$0" "$1" "$2"'

field() { sed -n "s/^  \"$1\": \(.*\),\{0,1\}$/\1/p" "$2" | sed 's/,$//' | head -1; }
median() { sort -g | awk '{a[NR]=$1} END {if (NR == 0) print "-"; else if (NR % 2) print a[(NR+1)/2]; else printf "%.3g\n", (a[NR/2]+a[NR/2+1])/2}'; }

if [[ -n "$mode" ]]; then ok_key=success; count_key=steps; else ok_key=verified; count_key=cycles; fi
printf '| scenario | %s | median s | max s | median %s | other runs: main reason |\n|---|---|---|---|---|---|\n' \
  "$ok_key" "$count_key"
for s in "$@"; do
  name=$(basename "$s" .yaml)
  n=0; ok=0; : >"$work/t"; : >"$work/c"; : >"$work/r"
  for seed in $seeds; do
    f="$work/${name}_$seed.json"
    n=$((n + 1))
    if [[ "$(field "$ok_key" "$f")" == "true" ]]; then
      ok=$((ok + 1)); field seconds "$f" >>"$work/t"; field "$count_key" "$f" >>"$work/c"
    else
      reason=$(field reason "$f" | tr -d '"')
      # A bad input (exit 2) prints its one-line error instead of a summary.
      [[ -n "$reason" ]] || reason=$(field error "$f" | tr -d '"' | sed 's/^./error: &/')
      echo "${reason:-exit without a summary}" | cut -c1-90 >>"$work/r"
    fi
  done
  top=$(sort "$work/r" | uniq -c | sort -rn | head -1 | sed 's/^ *[0-9]* //')
  t=$(median <"$work/t")
  longest=$(sort -g "$work/t" | tail -1)
  [[ "$t" == "-" ]] || t=$(printf '%.2f' "$t")
  [[ -z "$longest" ]] && longest="-" || longest=$(printf '%.2f' "$longest")
  printf '| %s | %d/%d | %s | %s | %s | %s |\n' "$name" "$ok" "$n" "$t" "$longest" \
    "$(median <"$work/c")" "${top:--}"
done
