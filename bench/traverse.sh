#!/usr/bin/env bash
# Traversal benchmark: the same ray files traced by kdray (C++ path and the PoCL kernel) and by
# Embree 3 (rtcIntersect1, high-quality build, robust mode off), random and camera rays, on the
# Cornell box (32 triangles), the bunny (69k) and bunny_sub2 (1.1M). Prints Mrays/s (median of
# $RUNS runs, the three tracers interleaved in each run), the ratio to Embree, and kdray's per-ray
# work: inner-node steps, leaves, triangle tests (kdtrace --json) and instructions (callgrind over
# the host build's trace_closest, one thread, on 20000 rays of the same kind: random rays of seed 1,
# camera rays at 160x125; "-" without valgrind). Compiles bench/embree_trace.cpp itself (needs
# libembree-dev); the project's CMake never builds it. Each tracer's clock times the tracing
# alone: kdtrace, on every device, and the harness make their hits' storage before it starts.
#   BUILD=build RUNS=3 RAYS=4000000 THREADS=2 [MESHES="NAME=PATH ..."] bench/traverse.sh
# RAYS: 4M by default, so that a run on the Cornell box's tree (in cache, about 17M rays a second
# on 2 cores) lasts a quarter of a second: runs of 1M, 60 ms, moved with the machine's swings
# (bench/LOG.md, "The ray's axes without a branch").
# MESHES: corpus paths, or absolute ones (bench/make_meshes.py's, say), each named.
# BASELINE=other/build adds a "before" kdtrace (another build of kdray) to every run.
set -euo pipefail
. "$(dirname "$0")/common.sh"
baseline="${BASELINE:-}"
runs="${RUNS:-3}"
rays="${RAYS:-4000000}"
threads="${THREADS:-2}"
work="${WORK:-${TMPDIR:-/tmp}/kdray-bench-traverse}"
meshes=(${MESHES:-cornell=cornell-box/mcguire/CornellBox-Original.obj bunny=bunny/bun_zipper.ply bunny_sub2=large/bunny_sub2.ply})
mkdir -p "$work"
embree="$work/embree_trace"
if [[ ! -x "$embree" || "$ROOT/bench/embree_trace.cpp" -nt "$embree" ]]; then
  g++ -O2 -std=c++17 -o "$embree" "$ROOT/bench/embree_trace.cpp" -lembree3 -pthread
fi

# field FILE KEY...: a value of the JSON document in FILE (nested keys).
field() { json_field "${@:2}" < "$1"; }
# median_of VALUES...
median_of() { printf "%s\n" "$@" | median; }
# instructions_per_ray SCENE TREE RAYS COUNT: instructions trace_closest executes per ray (host build,
# in AVX2 lanes where kdtrace runs them; its chunking adds about 26 a ray).
instructions_per_ray() {
  if ! command -v valgrind > /dev/null; then echo "-"; return; fi
  valgrind --tool=callgrind --callgrind-out-file=/dev/null --toggle-collect='kdray::trace_closest(*' \
    "$KDTRACE" "$1" "$2" --rays "$3" --threads 1 --quiet 2>&1 |
    awk -v n="$4" '/Collected :/ {printf "%.0f", $NF / n}'
}

echo "# kdray traversal benchmark: $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')," \
     "L3 $(lscpu | awk -F: '/L3/ {gsub(/^ +/, "", $2); print $2}')"
echo "# $threads threads; medians of $runs interleaved runs; random rays: $rays, camera rays: 1024x768;" \
     "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
printf "%-11s %-7s %8s %8s %8s %8s %7s %7s %7s %7s %7s %7s %6s %s\n" mesh rays embree cpu pocl before cpu/E pocl/E before/E \
  steps leaves tris instr "variant(pocl)"
for entry in "${meshes[@]}"; do
  name="${entry%%=*}"
  scene="$work/$name.kdscene"
  tree="$work/$name.kdtree"
  [[ -f "$scene" ]] || "$KDCONVERT" "$(corpus_file "${entry#*=}")" "$scene" --quiet > /dev/null
  readable_by "$BUILD" "$tree" || "$KDBUILD" "$scene" "$tree" --quiet > /dev/null
  # Named by their count: the work folder is kept between runs, and another RAYS needs its own file.
  random_file="$work/$name.random.$rays.rays"
  [[ -f "$random_file" ]] ||
    "$KDTRACE" "$scene" "$tree" --generate random --count "$rays" --seed 1 --write-rays "$random_file" > /dev/null
  [[ -f "$work/$name.camera.rays" ]] ||
    "$KDTRACE" "$scene" "$tree" --generate camera --width 1024 --height 768 --write-rays "$work/$name.camera.rays" > /dev/null
  [[ -f "$work/$name.random.small.rays" ]] ||
    "$KDTRACE" "$scene" "$tree" --generate random --count 20000 --seed 1 --write-rays "$work/$name.random.small.rays" > /dev/null
  [[ -f "$work/$name.camera.small.rays" ]] ||
    "$KDTRACE" "$scene" "$tree" --generate camera --width 160 --height 125 --write-rays "$work/$name.camera.small.rays" > /dev/null
  for kind in random camera; do
    ray_file="$work/$name.camera.rays"
    [[ $kind == random ]] && ray_file="$random_file"
    e=() c=() p=() b=()
    for ((run = 0; run < runs; ++run)); do
      e+=("$("$embree" "$scene" "$ray_file" "$threads" | sed 's/.*: \([0-9.]*\) Mrays.*/\1/')")
      "$KDTRACE" "$scene" "$tree" --rays "$ray_file" --threads "$threads" --json > "$work/cpu.json"
      c+=("$(field "$work/cpu.json" mrays_per_s)")
      "$KDTRACE" "$scene" "$tree" --rays "$ray_file" --device cpu --json > "$work/pocl.json"
      p+=("$(field "$work/pocl.json" mrays_per_s)")
      if [[ -n "$baseline" ]]; then
        "$baseline/tools/kdtrace/kdtrace" "$scene" "$tree" --rays "$ray_file" --threads "$threads" --json > "$work/before.json"
        b+=("$(field "$work/before.json" mrays_per_s)")
      fi
    done
    em="$(median_of "${e[@]}")" cm="$(median_of "${c[@]}")" pm="$(median_of "${p[@]}")"
    bm="-" br="-"
    if [[ -n "$baseline" ]]; then
      bm="$(awk -v a="$(median_of "${b[@]}")" 'BEGIN {printf "%.2f", a}')"
      br="$(awk -v a="$bm" -v b="$em" 'BEGIN {printf "%.2f", a / b}')"
    fi
    printf "%-11s %-7s %8.2f %8.2f %8.2f %8s %7.2f %7.2f %7s %7.1f %7.2f %7.2f %6s %s\n" "$name" "$kind" "$em" "$cm" "$pm" "$bm" \
      "$(awk -v a="$cm" -v b="$em" 'BEGIN {print a / b}')" "$(awk -v a="$pm" -v b="$em" 'BEGIN {print a / b}')" "$br" \
      "$(field "$work/cpu.json" per_ray inner_steps)" "$(field "$work/cpu.json" per_ray leaves)" \
      "$(field "$work/cpu.json" per_ray triangle_tests)" \
      "$(instructions_per_ray "$scene" "$tree" "$work/$name.$kind.small.rays" 20000)" "$(field "$work/pocl.json" variant)"
  done
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
