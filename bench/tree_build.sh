#!/usr/bin/env bash
# The binned tree build (kdbuild's default) against the exact sweep everywhere (kdbuild --exact)
# at the same cost settings: whole kdbuild process wall time and peak memory (/usr/bin/time -v),
# build seconds, SAH cost, and on one file of random rays (kdtrace --generate random, the same
# rays for both trees) the inner steps and triangle tests per ray, the traced cost
# K_T x inner steps + K_I x triangle tests (kdbuild's K_T and K_I) and kdtrace's Mrays/s.
# Medians of $RUNS runs, --threads 2 for both tools; every command is printed.
#   BUILD=build RUNS=3 RAYS=1000000 [BASELINE=KDBUILD] bench/tree_build.sh [MESH...]
# MESH: corpus paths relative to $CORPUS (default: the dragon, bunny_sub2 and dragons_4x4), or
# absolute paths (the meshes of bench/make_meshes.py, say).
# BASELINE: another kdbuild (an earlier commit's) measured the same way, its builds interleaved
# run by run with this build's on a shared machine (modes base-binned and base-exact; the modes'
# order is reversed every other run); the last
# column says whether its tree has the same bytes as this build's in the same mode.
set -euo pipefail
. "$(dirname "$0")/common.sh"
runs="${RUNS:-3}"
rays="${RAYS:-1000000}"
work="${WORK:-${TMPDIR:-/tmp}/kdray-bench-tree-build}"
mkdir -p "$work"
if [[ $# -eq 0 ]]; then set -- dragon/dragon_vcg_100k.ply large/bunny_sub2.ply large/dragons_4x4.ply; fi

echo "# $(machine_line)"
echo "# $(lscpu | grep -E 'Model name|L3' | tr -s ' ' | paste -sd ';')"
echo "# commit $(git -C "$ROOT" rev-parse --short HEAD), medians of $runs runs, $rays random rays (seed 1), --threads 2"
echo "# commands, per mesh and mode (MODE_FLAGS: none for binned, --exact for exact):"
echo "#   kdconvert MESH SCENE --quiet"
echo "#   /usr/bin/time -v kdbuild SCENE TREE MODE_FLAGS --json --quiet --threads 2"
echo "#   kdtrace SCENE TREE --generate random --count $rays --seed 1 --write-rays RAYS --json   (once per mesh)"
echo "#   kdtrace SCENE TREE --rays RAYS --threads 2 --json"
modes=(binned exact)
if [[ -n "${BASELINE:-}" ]]; then
  echo "# baseline: $BASELINE (modes base-binned, base-exact), interleaved run by run"
  modes+=(base-binned base-exact)
fi
printf "%-16s %-11s %9s %8s %6s %8s %9s %8s %8s %9s %7s %5s\n" mesh mode process_s build_s cpu_s peak_MiB sah inner tests \
  traced Mrays/s same
for mesh in "$@"; do
  name="$(basename "${mesh%.*}")"
  scene="$work/$name.kdscene"
  [[ -f "$scene" ]] || "$KDCONVERT" "$(corpus_file "$mesh")" "$scene" --quiet > /dev/null
  for mode in "${modes[@]}"; do : > "$work/$name.$mode.build.jsonl"; done
  for ((run = 0; run < runs; ++run)); do
    # Every other run takes the modes in reverse order (A B, B A, ...): on the VMs measured, a
    # process writing a tree is slow or fast by turns, so a fixed order gives one mode every
    # slow write (bench/LOG.md, "The load without a per-leaf wait…").
    order=("${modes[@]}")
    if ((run % 2 == 1)); then
      order=()
      for ((m = ${#modes[@]} - 1; m >= 0; --m)); do order+=("${modes[m]}"); done
    fi
    for mode in "${order[@]}"; do
      flags=()
      [[ "$mode" == *exact ]] && flags=(--exact)
      kdbuild="$KDBUILD"
      [[ "$mode" == base-* ]] && kdbuild="$BASELINE"
      /usr/bin/time -v -o "$work/time.txt" "$kdbuild" "$scene" "$work/$name.$mode.kdtree" "${flags[@]}" --json --quiet \
        --threads 2 > "$work/build.json"
      /usr/bin/python3 - "$work/build.json" "$work/time.txt" >> "$work/$name.$mode.build.jsonl" <<'PY'
import json, re, sys
report = json.load(open(sys.argv[1]))
time = open(sys.argv[2]).read()
clock = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): (\S+)", time).group(1)
seconds = 0.0
for part in clock.split(":"):
    seconds = seconds * 60 + float(part)
report["process_seconds"] = seconds
report["max_rss_mib"] = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", time).group(1)) / 1024
print(json.dumps(report))
PY
    done
  done
  for mode in "${modes[@]}"; do
    tree="$work/$name.$mode.kdtree"
    : > "$work/$name.$mode.trace.jsonl"
    same=-
    if [[ "$mode" == base-* ]]; then
      if cmp -s "$tree" "$work/$name.${mode#base-}.kdtree"; then same=yes; else same=no; fi
    fi
    ray_file="$work/$name.$rays.rays"
    [[ -f "$ray_file" ]] || "$KDTRACE" "$scene" "$tree" --generate random --count "$rays" --seed 1 \
      --write-rays "$ray_file" --json > /dev/null
    for ((run = 0; run < runs; ++run)); do
      "$KDTRACE" "$scene" "$tree" --rays "$ray_file" --threads 2 --json \
        | /usr/bin/python3 -c 'import json,sys; print(json.dumps(json.load(sys.stdin)))' >> "$work/$name.$mode.trace.jsonl"
    done
    /usr/bin/python3 - "$name" "$mode" "$work/$name.$mode.build.jsonl" "$work/$name.$mode.trace.jsonl" "$same" <<'PY'
import json, statistics, sys
builds = [json.loads(line) for line in open(sys.argv[3]) if line.strip()]
traces = [json.loads(line) for line in open(sys.argv[4]) if line.strip()]
median = lambda values: statistics.median(values)
settings = builds[0]["build_settings"]
inner = traces[0]["per_ray"]["inner_steps"]
tests = traces[0]["per_ray"]["triangle_tests"]
traced = settings["kt"] * inner + settings["ki"] * tests
print(f"{sys.argv[1]:<16} {sys.argv[2]:<11} {median(b['process_seconds'] for b in builds):9.2f} "
      f"{median(b['build_seconds'] for b in builds):8.2f} {median(b['build_cpu_seconds'] for b in builds):6.2f} "
      f"{median(b['max_rss_mib'] for b in builds):8.0f} "
      f"{builds[0]['sah_cost']:9.2f} {inner:8.3f} {tests:8.3f} {traced:9.2f} "
      f"{median(t['mrays_per_s'] for t in traces):7.3f} {sys.argv[5]:>5}")
PY
  done
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
