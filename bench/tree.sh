#!/usr/bin/env bash
# k-d tree benchmarks: build time, peak memory and SAH cost of kdbuild, and CPU
# kdtrace rates for camera rays and random rays (origins uniform on the bounding sphere, aimed
# at uniform points in the bounding box), on the corpus meshes. Prints medians of $RUNS runs
# and every command it ran.
#   BUILD=build RUNS=5 RAYS=1000000 bench/tree.sh
#   BASELINE=/path/to/old/kdbuild BEST=3 bench/tree.sh   (builder before/after, see below)
set -euo pipefail
. "$(dirname "$0")/common.sh"
runs="${RUNS:-5}"
rays="${RAYS:-1000000}"
work="${WORK:-${TMPDIR:-/tmp}/kdray-bench-tree}"
meshes=(bunny=bunny/stanford-bunny.obj dragon_100k=dragon/dragon_vcg_100k.ply
        bunny_sub2=large/bunny_sub2.ply dragons_4x4=large/dragons_4x4.ply)
mkdir -p "$work"

# median_field FIELD FILE: the median of FIELD over the JSON documents (one per line) in FILE.
median_field() {
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

# Builder comparison, instead of the table below when BASELINE=path/to/an/older/kdbuild
# is set: both builders
# interleaved, best of $BEST runs on 2 threads, whether their trees are byte-identical, the
# scaling from bunny_sub2 to dragons_4x4 against n log n, and per-ray work (kdtree_counters:
# steps, leaves, triangle tests) with kdtrace rates on meshes the builder was not tuned on.
if [[ -n "${BASELINE:-}" ]]; then
best="${BEST:-3}"
counters="$BUILD/bench/kdtree_counters"
echo
echo "# builder comparison: $BASELINE (before) vs $KDBUILD (after), best of $best, --threads 2"
echo "# load average: $(cut -d' ' -f1-3 /proc/loadavg)"
printf "%-12s %10s %10s %10s %10s %10s %s\n" mesh before_s before_cpu after_s after_cpu speedup same_bytes
for name in bunny_sub2 dragons_4x4; do
  scene="$work/$name.kdscene"
  [[ -f "$scene" ]] || "$KDCONVERT" "$CORPUS/large/$name.ply" "$scene" --quiet > /dev/null
  : > "$work/$name.before.json"
  : > "$work/$name.after.json"
  for ((run = 0; run < best; ++run)); do
    run_json "$work/$name.before.json" "$BASELINE" "$scene" "$work/$name.before.kdtree" --json --quiet --threads 2
    run_json "$work/$name.after.json" "$KDBUILD" "$scene" "$work/$name.after.kdtree" --json --quiet \
      --threads 2
  done
  /usr/bin/python3 - "$name" "$work/$name.before.json" "$work/$name.after.json" \
    "$(cmp -s "$work/$name.before.kdtree" "$work/$name.after.kdtree" && echo yes || echo no)" <<'PY'
import json, sys
def best(path):
    runs = [json.loads(line) for line in open(path) if line.strip()]
    return min(r["build_seconds"] for r in runs), min(r["build_cpu_seconds"] for r in runs)
b, a = best(sys.argv[2]), best(sys.argv[3])
print(f"{sys.argv[1]:<12} {b[0]:10.3f} {b[1]:10.3f} {a[0]:10.3f} {a[1]:10.3f} {b[0] / a[0]:10.2f} {sys.argv[4]}")
PY
done
/usr/bin/python3 - "$work/bunny_sub2.after.json" "$work/dragons_4x4.after.json" <<'PY'
import json, math, sys
runs = [[json.loads(line) for line in open(path) if line.strip()] for path in sys.argv[1:]]
(n1, n2) = (r[0]["triangles"] for r in runs)
(c1, c2) = (min(x["build_cpu_seconds"] for x in r) for r in runs)
expected = n2 * math.log2(n2) / (n1 * math.log2(n1))
print(f"scaling bunny_sub2 -> dragons_4x4: triangles x{n2 / n1:.3f}, n log n x{expected:.3f}, build CPU x{c2 / c1:.3f}")
for r, name in zip(runs, ("bunny_sub2", "dragons_4x4")):
    x = min(r, key=lambda x: x["build_seconds"])
    print(f"{name}: phases {json.dumps({k: round(v, 3) for k, v in x['phase_seconds'].items()})}, "
          f"peak {x['peak_memory_mib']:.0f} MiB, tree {x['tree_bytes'] / 2**20:.1f} MiB, nodes {x['nodes']}")
PY

echo "# quality: SAH cost, per-ray work (camera 512x384, 200k random rays), kdtrace Mrays/s (1024x768 camera, 1M random)"
printf "%-12s %9s %9s %8s %8s %8s %8s %8s %8s %8s %8s\n" mesh triangles sah refs/tri cam_step cam_leaf cam_test \
  rnd_step rnd_leaf rnd_test cam/rnd_Mr
for entry in dragon_100k=dragon/dragon_vcg_100k.ply beetle=misc/beetle-alt.obj rocker_arm=misc/rocker-arm.obj \
             bunny_sub2=large/bunny_sub2.ply; do
  name="${entry%%=*}"
  scene="$work/$name.kdscene"
  [[ -f "$scene" ]] || "$KDCONVERT" "$CORPUS/${entry#*=}" "$scene" --quiet > /dev/null
  "$KDBUILD" "$scene" "$work/$name.q.kdtree" --json --quiet > "$work/$name.q.json"
  "$counters" "$scene" "$work/$name.q.kdtree" > "$work/$name.counters.json"
  camera="$("$KDTRACE" "$scene" "$work/$name.q.kdtree" --generate camera --json)"
  random="$("$KDTRACE" "$scene" "$work/$name.q.kdtree" --generate random --count 1000000 --json)"
  /usr/bin/python3 - "$name" "$work/$name.q.json" "$work/$name.counters.json" "$camera" "$random" <<'PY'
import json, sys
b, c = json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
cam, rnd = json.loads(sys.argv[4]), json.loads(sys.argv[5])
w = [c[k][f] for k in ("camera", "random") for f in ("steps_per_ray", "leaves_per_ray", "triangle_tests_per_ray")]
print(f"{sys.argv[1]:<12} {b['triangles']:9d} {b['sah_cost']:9.1f} {b['references_per_triangle']:8.3f} "
      + " ".join(f"{x:8.3f}" for x in w) + f" {cam['mrays_per_s']:.1f}/{rnd['mrays_per_s']:.2f}")
PY
done
exit 0
fi

echo "# kdray k-d tree benchmark: $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "# medians of $runs runs; random rays: $rays, camera rays: 1024x768; load average: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# build_cpu and random_cpu_s are process CPU seconds (all threads): on a shared machine they"
echo "# show the work when the wall times show the load"
printf "%-12s %10s %9s %9s %9s %10s %12s %12s %14s\n" mesh triangles build_s build_cpu peak_MiB sah_cost camera_Mrays random_Mrays random_cpu_s
for entry in "${meshes[@]}"; do
  name="${entry%%=*}"
  source="$CORPUS/${entry#*=}"
  scene="$work/$name.kdscene"
  tree="$work/$name.kdtree"
  [[ -f "$scene" ]] || "$KDCONVERT" "$source" "$scene" --quiet > /dev/null
  : > "$work/$name.build.json"
  : > "$work/$name.camera.json"
  : > "$work/$name.random.json"
  for ((run = 0; run < runs; ++run)); do
    run_json "$work/$name.build.json" "$KDBUILD" "$scene" "$tree" --json --quiet
    run_json "$work/$name.camera.json" "$KDTRACE" "$scene" "$tree" --generate camera \
      --width 1024 --height 768 --json
    run_json "$work/$name.random.json" "$KDTRACE" "$scene" "$tree" --generate random \
      --count "$rays" --seed 1 --json
  done
  triangles="$(median_field triangles "$work/$name.build.json")"
  printf "%-12s %10s %9s %9s %9s %10s %12s %12s %14s\n" "$name" "$triangles" \
    "$(median_field build_seconds "$work/$name.build.json")" "$(median_field build_cpu_seconds "$work/$name.build.json")" \
    "$(median_field peak_memory_mib "$work/$name.build.json")" "$(median_field sah_cost "$work/$name.build.json")" \
    "$(median_field mrays_per_s "$work/$name.camera.json")" "$(median_field mrays_per_s "$work/$name.random.json")" \
    "$(median_field cpu_seconds "$work/$name.random.json")"
done

: > "$work/bunny_sub2.bbox.json"
run_json "$work/bunny_sub2.bbox.json" "$KDBUILD" "$work/bunny_sub2.kdscene" \
  "$work/bunny_sub2.bbox.kdtree" --no-perfect-splits --json --quiet
echo "bunny_sub2 without perfect splits: sah_cost $(median_field sah_cost "$work/bunny_sub2.bbox.json")," \
  "build $(median_field build_seconds "$work/bunny_sub2.bbox.json") s"

echo "# commands (per mesh, SCENE=$work/<mesh>.kdscene, TREE=$work/<mesh>.kdtree):"
echo "#   kdconvert MESH SCENE --quiet"
echo "#   kdbuild SCENE TREE --json --quiet"
echo "#   kdtrace SCENE TREE --generate camera --width 1024 --height 768 --json"
echo "#   kdtrace SCENE TREE --generate random --count $rays --seed 1 --json"
echo "#   kdbuild bunny_sub2.kdscene bunny_sub2.bbox.kdtree --no-perfect-splits --json --quiet"

