#!/usr/bin/env bash
# Builds and runs the whole test suite twice: a Release build, then once more under
# AddressSanitizer + UndefinedBehaviorSanitizer; then the tree builder and traversal tests under
# ThreadSanitizer, and every fuzz target for a minute. Exits non-zero if any of it fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs="$(nproc)"

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DKDRAY_BUILD_TESTS=ON
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs"

cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKDRAY_SANITIZE=ON -DKDRAY_BUILD_TESTS=ON \
  -DKDRAY_BUILD_BENCH=OFF
cmake --build build-sanitize -j"$jobs"
# PoCL's LLVM allocates for the process lifetime; leak checking would report the driver, not us.
ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-sanitize --output-on-failure -j"$jobs"

# The multi-threaded tree builder and the CPU traversal under ThreadSanitizer, against a oneTBB
# built with ThreadSanitizer too (scripts/tsan-tbb.sh, RELIABILITY.md); only their test program
# is built.
bash scripts/tsan-tbb.sh build-tsan/onetbb
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKDRAY_TSAN=ON -DKDRAY_BUILD_TESTS=ON \
  -DKDRAY_BUILD_BENCH=OFF -DTBB_DIR="$PWD/build-tsan/onetbb/lib/cmake/TBB"
cmake --build build-tsan -j"$jobs" --target kdtree_tests
# Left out: tests whose time goes into single-threaded reference checks (brute force, the dragon's
# reference build), which the two runs above cover; nothing is suppressed.
TSAN_OPTIONS=halt_on_error=1 ctest --test-dir build-tsan --output-on-failure -j"$jobs" \
  -R '^(KdBuild|KdTraverse)\.' -E 'BruteForce|Dragon|NeverEscape'

# Every fuzz target for a minute (scripts/fuzz.sh builds them with clang in build-fuzz and
# writes their seed files with the tools in build/).
bash scripts/fuzz.sh 60 kdscene kdtree rays exr obj ply
