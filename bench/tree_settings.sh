#!/usr/bin/env bash
# Build settings judged by traced cost: for each mesh, one tree per setting (kdbuild options),
# then the same random and camera ray files traced through every tree, the trees interleaved in
# each run. Prints per tree: nodes, file size, build seconds, SAH cost, and per ray kind the inner
# steps, leaves and triangle tests per ray (kdtrace --json) and kdtrace's Mrays/s (median of $RUNS).
#   BUILD=build RUNS=3 RAYS=1000000 THREADS=2 bench/tree_settings.sh [MESH...]
# MESH: corpus paths relative to $CORPUS (default: the bunny, bunny_sub2 and dragons_4x4).
# SETTINGS: settings separated by ';', each a kdbuild option string ("" is the default), e.g.
#   SETTINGS='; --max-depth 30; --max-depth 26' bench/tree_settings.sh
set -euo pipefail
. "$(dirname "$0")/common.sh"
runs="${RUNS:-3}"
rays="${RAYS:-1000000}"
threads="${THREADS:-2}"
work="${WORK:-${TMPDIR:-/tmp}/kdray-bench-tree-settings}"
IFS=';' read -r -a settings <<< "${SETTINGS:-; --max-depth 30; --max-depth 28; --max-depth 26; --max-depth 24}"
mkdir -p "$work"
if [[ $# -eq 0 ]]; then set -- bunny/bun_zipper.ply large/bunny_sub2.ply large/dragons_4x4.ply; fi

# field FILE KEY...: a value of the JSON document in FILE (nested keys).
field() { json_field "${@:2}" < "$1"; }

echo "# $(machine_line)"
echo "# commit $(git -C "$ROOT" rev-parse --short HEAD), medians of $runs runs, $rays random rays (seed 1) and" \
  "1024x768 camera rays, --threads $threads"
printf "%-12s %-22s %7s %6s %6s %7s | %6s %5s %6s %7s | %6s %5s %6s %7s\n" mesh setting nodes MB build sah \
  r.steps r.lvs r.tris r.Mrays c.steps c.lvs c.tris c.Mrays
for mesh in "$@"; do
  name="$(basename "${mesh%.*}")"
  scene="$work/$name.kdscene"
  [[ -f "$scene" ]] || "$KDCONVERT" "$CORPUS/$mesh" "$scene" --quiet
  for i in "${!settings[@]}"; do
    # shellcheck disable=SC2086  # a setting is a list of options
    "$KDBUILD" "$scene" "$work/$name.$i.kdtree" ${settings[$i]} --threads "$threads" --json > "$work/$name.$i.build.json"
  done
  [[ -f "$work/$name.random.rays" ]] || "$KDTRACE" "$scene" "$work/$name.0.kdtree" --generate random \
    --count "$rays" --seed 1 --write-rays "$work/$name.random.rays" > /dev/null
  [[ -f "$work/$name.camera.rays" ]] || "$KDTRACE" "$scene" "$work/$name.0.kdtree" --generate camera \
    --width 1024 --height 768 --write-rays "$work/$name.camera.rays" > /dev/null
  for ((run = 0; run < runs; ++run)); do
    for i in "${!settings[@]}"; do
      for kind in random camera; do
        "$KDTRACE" "$scene" "$work/$name.$i.kdtree" --rays "$work/$name.$kind.rays" --threads "$threads" --json \
          > "$work/$name.$i.$kind.$run.json"
      done
    done
  done
  for i in "${!settings[@]}"; do
    build="$work/$name.$i.build.json"
    line="$(printf "%-12s %-22s %6.2fM %6.1f %6.2f %7.1f" "$name" "${settings[$i]:- default}" \
      "$(awk -v n="$(field "$build" nodes)" 'BEGIN {print n / 1e6}')" \
      "$(awk -v n="$(stat -c %s "$work/$name.$i.kdtree")" 'BEGIN {print n / 1048576}')" \
      "$(field "$build" build_seconds)" "$(field "$build" sah_cost)")"
    for kind in random camera; do
      json="$work/$name.$i.$kind.0.json"
      rate="$(for ((run = 0; run < runs; ++run)); do field "$work/$name.$i.$kind.$run.json" mrays_per_s; done | median)"
      line+="$(printf " | %6.1f %5.2f %6.2f %7.2f" "$(field "$json" per_ray inner_steps)" \
        "$(field "$json" per_ray leaves)" "$(field "$json" per_ray triangle_tests)" "$rate")"
    done
    echo "$line"
  done
done
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
