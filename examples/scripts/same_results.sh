#!/usr/bin/env bash
# Runs every shipped scenario (examples/scenarios/**/*.yaml) with two builds of claspplan, bounded by
# cycles (so that neither run depends on the machine's speed), and compares their result.json byte
# for byte (result.json holds no timings). For refactors that must not change any result.
# Usage: examples/scripts/same_results.sh OLD_CLASPPLAN NEW_CLASPPLAN [OUT] [MAX_CYCLES] [JOBS]
#   (defaults: /tmp/same_results, 40 cycles, 2 jobs). Exit 1 when any result differs.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
old=$1 new=$2 out=${3:-/tmp/same_results} cycles=${4:-40} jobs=${5:-2}
rm -rf "$out" && mkdir -p "$out"
export old new out cycles
one() {
  yaml=$1
  name=$(echo "${yaml#*/scenarios/}" | tr '/' '_')
  name=${name%.yaml}
  for which in old new; do
    exe=${!which}
    "$exe" run "$yaml" --seed 1 --max-cycles "$cycles" --no-pictures --out "$out/$which/$name" \
      >/dev/null 2>"$out/$which.$name.stderr" || true
  done
  if cmp -s "$out/old/$name/result.json" "$out/new/$name/result.json"; then
    echo "same $name"
  elif [ ! -e "$out/old/$name/result.json" ] && [ ! -e "$out/new/$name/result.json" ] &&
    cmp -s "$out/old.$name.stderr" "$out/new.$name.stderr"; then
    echo "same $name (no result: the same error)"
  else
    echo "DIFFERENT $name"
  fi
}
export -f one
find "$here/scenarios" -name '*.yaml' | sort | xargs -P "$jobs" -I{} bash -c 'one {}' \
  | tee "$out/summary.txt"
total=$(wc -l <"$out/summary.txt")
different=$(grep -c '^DIFFERENT' "$out/summary.txt" || true)
echo "same_results: $((total - different)) of $total scenarios give the same result.json"
[ "$different" -eq 0 ]
