#!/usr/bin/env bash
# k-d tree benchmarks (issue 3): build time, peak memory and SAH cost of kdbuild, and CPU
# kdtrace rates for camera rays and random rays (origins uniform on the bounding sphere, aimed
# at uniform points in the bounding box), on the corpus meshes. Prints medians of $RUNS runs
# and every command it ran.
#   BUILD=build RUNS=5 RAYS=1000000 bench/tree.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${BUILD:-$root/build}"
corpus="${CORPUS:-$root/../shared/corpus}"
runs="${RUNS:-5}"
rays="${RAYS:-1000000}"
work="${WORK:-${TMPDIR:-/tmp}/kdray-bench-tree}"
meshes=(bunny=bunny/stanford-bunny.obj dragon_100k=dragon/dragon_vcg_100k.ply
        bunny_sub2=large/bunny_sub2.ply dragons_4x4=large/dragons_4x4.ply)
mkdir -p "$work"

# median FIELD FILE: the median of FIELD over the JSON documents (one per line) in FILE.
median() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import json, statistics, sys
values = [json.loads(line)[sys.argv[1]] for line in open(sys.argv[2]) if line.strip()]
median = statistics.median(values)
print(int(median) if float(median).is_integer() else f"{median:.4g}")
PY
}

# run_json OUT COMMAND...: runs COMMAND (which prints JSON) and appends it as one line to OUT.
run_json() {
  local out="$1"
  shift
  "$@" | /usr/bin/python3 -c 'import json,sys; print(json.dumps(json.load(sys.stdin)))' >> "$out"
}

echo "# kdray k-d tree benchmark: $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "# medians of $runs runs; random rays: $rays, camera rays: 1024x768; load average: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# build_cpu and random_cpu_s are process CPU seconds (all threads): on a shared machine they"
echo "# show the work when the wall times show the load"
printf "%-12s %10s %9s %9s %9s %10s %12s %12s %14s\n" mesh triangles build_s build_cpu peak_MiB sah_cost camera_Mrays random_Mrays random_cpu_s
for entry in "${meshes[@]}"; do
  name="${entry%%=*}"
  source="$corpus/${entry#*=}"
  scene="$work/$name.kdscene"
  tree="$work/$name.kdtree"
  [[ -f "$scene" ]] || "$build/tools/kdconvert/kdconvert" "$source" "$scene" --quiet > /dev/null
  : > "$work/$name.build.json"
  : > "$work/$name.camera.json"
  : > "$work/$name.random.json"
  for ((run = 0; run < runs; ++run)); do
    run_json "$work/$name.build.json" "$build/tools/kdbuild/kdbuild" "$scene" "$tree" --json --quiet
    run_json "$work/$name.camera.json" "$build/tools/kdtrace/kdtrace" "$scene" "$tree" --generate camera \
      --width 1024 --height 768 --json
    run_json "$work/$name.random.json" "$build/tools/kdtrace/kdtrace" "$scene" "$tree" --generate random \
      --count "$rays" --seed 1 --json
  done
  triangles="$(median triangles "$work/$name.build.json")"
  printf "%-12s %10s %9s %9s %9s %10s %12s %12s %14s\n" "$name" "$triangles" \
    "$(median build_seconds "$work/$name.build.json")" "$(median build_cpu_seconds "$work/$name.build.json")" \
    "$(median peak_memory_mib "$work/$name.build.json")" "$(median sah_cost "$work/$name.build.json")" \
    "$(median mrays_per_s "$work/$name.camera.json")" "$(median mrays_per_s "$work/$name.random.json")" \
    "$(median cpu_seconds "$work/$name.random.json")"
done

: > "$work/bunny_sub2.bbox.json"
run_json "$work/bunny_sub2.bbox.json" "$build/tools/kdbuild/kdbuild" "$work/bunny_sub2.kdscene" \
  "$work/bunny_sub2.bbox.kdtree" --no-perfect-splits --json --quiet
echo "bunny_sub2 without perfect splits: sah_cost $(median sah_cost "$work/bunny_sub2.bbox.json")," \
  "build $(median build_seconds "$work/bunny_sub2.bbox.json") s"

echo "# commands (per mesh, SCENE=$work/<mesh>.kdscene, TREE=$work/<mesh>.kdtree):"
echo "#   kdconvert MESH SCENE --quiet"
echo "#   kdbuild SCENE TREE --json --quiet"
echo "#   kdtrace SCENE TREE --generate camera --width 1024 --height 768 --json"
echo "#   kdtrace SCENE TREE --generate random --count $rays --seed 1 --json"
echo "#   kdbuild bunny_sub2.kdscene bunny_sub2.bbox.kdtree --no-perfect-splits --json --quiet"
