#!/usr/bin/env bash
# CI: builds the libFuzzer targets (test/fuzz; clang-14 with ASan and UBSan) in build-fuzz and runs
# each for FUZZ_SECONDS (default 20) from its committed seed corpus, two at a time. Fails on any
# crash, sanitizer report, uncaught exception other than std::invalid_argument, hang (> 10 s on
# one input) or out-of-memory; the input that did it is left in build-fuzz/crashes/<target>/.
# Inputs the fuzzers find go to build-fuzz/corpus/<target>/, never into the committed corpus.
set -euo pipefail
self="$(cd "$(dirname "$0")" && pwd)/$(basename "$0")"
cd "$(dirname "$0")/.."
export LSAN_OPTIONS="suppressions=$PWD/.ci/lsan.supp"  # leaks inside Debian libraries, explained

if [ "${1:-}" = "--one" ]; then  # internal: run one target
  t="$2"
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/crashes/$t"
  log="build-fuzz/fuzz_$t.log"
  if "build-fuzz/test/fuzz/fuzz_$t" "build-fuzz/corpus/$t" "test/fuzz/corpus/$t" \
      -max_total_time="${FUZZ_SECONDS:-20}" -timeout=10 -rss_limit_mb=2048 \
      -artifact_prefix="build-fuzz/crashes/$t/" -print_final_stats=1 >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    corpus=$(grep -o 'corp: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
    echo "fuzz_$t: ok, $runs executions, $corpus inputs in the corpus"
  else
    echo "fuzz_$t: FAILED (input in build-fuzz/crashes/$t/):"
    grep -E 'ERROR|SUMMARY|terminate|what\(\)|Test unit written' "$log" | head -20
    exit 1
  fi
  exit 0
fi

# -O1 with assertions on (no NDEBUG): quicker to build, and Eigen checks its indices.
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O1 \
  -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_C_COMPILER=clang-14 -DCLASPPLAN_FUZZ=ON \
  -DCLASPPLAN_BUILD_TESTS=OFF
cmake --build build-fuzz -j2 --target fuzzers
targets=$(ls test/fuzz/corpus)
echo "$targets" | xargs -P 2 -I{} "$self" --one {}
