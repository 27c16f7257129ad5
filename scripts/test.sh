#!/usr/bin/env bash
# Builds and runs the whole test suite twice: a Release build, then once more under
# AddressSanitizer + UndefinedBehaviorSanitizer. Exits non-zero if any test fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs="$(nproc)"

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DKDRAY_BUILD_TESTS=ON
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs"

cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKDRAY_SANITIZE=ON -DKDRAY_BUILD_TESTS=ON
cmake --build build-sanitize -j"$jobs"
# PoCL's LLVM allocates for the process lifetime; leak checking would report the driver, not us.
ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-sanitize --output-on-failure -j"$jobs"

# The multi-threaded builder and the CPU traversal under ThreadSanitizer. Debian's oneTBB is not
# instrumented, so reports that arise inside it are suppressed (tests/tsan.supp); kdray's own
# code is never suppressed.
cmake -S . -B build-tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKDRAY_TSAN=ON -DKDRAY_BUILD_TESTS=ON
cmake --build build-tsan -j"$jobs" --target kdtree_tests
TSAN_OPTIONS="suppressions=$PWD/tests/tsan.supp halt_on_error=1 second_deadlock_stack=1" \
  ctest --test-dir build-tsan --output-on-failure -j"$jobs" -R '^(KdBuild|KdTraverse)\.'

# Every fuzz target for a minute (scripts/fuzz.sh builds them with clang in build-fuzz).
bash scripts/fuzz.sh 60
