#!/usr/bin/env bash
# Scene benchmarks: conversion time of two corpus meshes, and the time to load the
# resulting .kdscene against a plain read of the same bytes. Medians of N runs (default 5).
# Usage: bench/scene.sh [BUILD_DIR] [N]      (BUILD_DIR defaults to ./build)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=$(realpath "${1:-build}")
runs="${2:-5}"
. bench/common.sh
kdinfo="$BUILD/tools/kdinfo/kdinfo"
load_bench="$BUILD/bench/scene_load_bench"
cmake --build "$BUILD" --target kdconvert kdinfo scene_load_bench >/dev/null
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }

machine_line
echo "median of $runs runs; files in the page cache (each command is run once before timing)"
printf '\n%-28s %10s %10s %10s %10s %12s %12s %7s\n' mesh triangles "wall s" "import s" "write s" "load s" "read s" ratio
for mesh in bunny/stanford-bunny.obj large/bunny_sub2.ply; do
  input="$CORPUS/$mesh"
  output="$work/$(basename "$mesh").kdscene"
  "$KDCONVERT" "$input" "$output" --quiet
  walls=(); imports=(); writes=(); loads=(); reads=()
  for ((run = 0; run < runs; ++run)); do
    start=$(now)
    summary=$("$KDCONVERT" "$input" "$output" --json)
    walls+=("$(echo "$(now) - $start" | bc -l)")
    imports+=("$(echo "$summary" | json_field import_seconds)")
    writes+=("$(echo "$summary" | json_field write_seconds)")
    # One process per measurement, alternating: read_scene (open, validate, checksum, copy
    # into the arrays, check every index) against a plain read of the same bytes.
    loads+=("$("$load_bench" "$output" load)")
    reads+=("$("$load_bench" "$output" read)")
  done
  triangles=$("$kdinfo" "$output" --json | json_field triangles)
  wall=$(printf '%s\n' "${walls[@]}" | median)
  import=$(printf '%s\n' "${imports[@]}" | median)
  write=$(printf '%s\n' "${writes[@]}" | median)
  load=$(printf '%s\n' "${loads[@]}" | median)
  read=$(printf '%s\n' "${reads[@]}" | median)
  printf '%-28s %10s %10.3f %10.3f %10.3f %12.4f %12.4f %7.2f\n' "$mesh" "$triangles" "$wall" "$import" "$write" \
    "$load" "$read" "$(echo "$load / $read" | bc -l)"
done
echo
echo "wall: kdconvert INPUT OUT.kdscene --json, whole process; import/write: its own timings"
echo "load: scene_load_bench OUT.kdscene load (read_scene); read: scene_load_bench OUT.kdscene read (read() into one buffer)"
echo "ratio = load / read (goal <= 1.5)"
