#!/usr/bin/env bash
# CI: the whole test suite built with AddressSanitizer and UndefinedBehaviorSanitizer (g++), in
# its own build folder (build-asan). Any sanitizer report aborts the test that triggered it.
set -euo pipefail
cd "$(dirname "$0")/.."
# -O1: the sanitizers' usual level, about twice as quick to build as -O3; no NDEBUG, so that
# assertions (Eigen's index checks among them) are on too.
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g1"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O1 \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined"
cmake --build build-asan -j2
echo "sanitize: built in ${SECONDS} s"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS="suppressions=$PWD/.ci/lsan.supp"  # leaks inside Debian libraries, explained
# Skipped: Package.ConsumerBuildsAgainstInstalledTree builds a separate consumer project against
# the installed static libraries without the sanitizer runtimes (it cannot link), and what it
# checks, the installed package, the normal build's test run already checks.
ctest --test-dir build-asan --output-on-failure -j2 -E '^Package\.'
echo "sanitize: built and tested in ${SECONDS} s"
