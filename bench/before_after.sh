#!/usr/bin/env bash
# Two builds of kdrender on the Cornell box sample, interleaved: whole-process wall time and,
# with a REFERENCE image of the same view, each render's relMSE; then how far the two builds'
# images for the same seed are apart. For changes that should only make the kernel faster (or
# change its arithmetic): the pictures must stay where they were.
# usage: [RUNS=3] [SPP=64] [REFERENCE=ref.exr] bench/before_after.sh BUILD_BEFORE BUILD_AFTER [OUT_DIR]
set -euo pipefail
BEFORE=$(realpath "$1") BUILD=$(realpath "$2")
OUT=$(realpath -m "${3:-before-after}")
RUNS=${RUNS:-3} SPP=${SPP:-64}
. "$(dirname "$0")/common.sh"
WORK=$OUT
mkdir -p "$WORK"
machine_line
scene_files "$ROOT/samples/cornell-box.obj" cornell
VIEW="--cam-pos 278,273,-800 --cam-target 278,273,0 --fov 39.3077"
SIZE="--width 256 --height 256 --max-bounces 8 --spp $SPP"
for build in "$BEFORE" "$BUILD"; do  # warm each build's program cache
  "$build/tools/kdrender/kdrender" "$WORK/cornell.kdscene" "$WORK/cornell.kdtree" -o "$WORK/warm.exr" $VIEW \
    --width 8 --height 8 --spp 1 -q
done
: > "$WORK/before.walls"
: > "$WORK/after.walls"
for run in $(seq "$RUNS"); do
  sides="before after"
  ((run % 2 == 0)) && sides="after before"  # A B, B A, ...: no side always runs first
  for side in $sides; do
    build=$BEFORE && [ "$side" = after ] && build=$BUILD
    start=$(date +%s.%N)
    "$build/tools/kdrender/kdrender" "$WORK/cornell.kdscene" "$WORK/cornell.kdtree" -o "$WORK/$side-$run.exr" $VIEW \
      $SIZE --seed "$run" -q
    wall=$(echo "$(date +%s.%N) - $start" | bc)
    echo "$wall" >> "$WORK/$side.walls"
    error=""
    [ -n "${REFERENCE:-}" ] && error="relmse $("$KDCOMPARE" "$WORK/$side-$run.exr" "$REFERENCE" --json | json_field relmse)"
    echo "run $run $side: wall ${wall} s $error (load $(cut -d' ' -f1 /proc/loadavg))"
  done
done
echo "median wall: before $(median < "$WORK/before.walls") s, after $(median < "$WORK/after.walls") s"
"$KDCOMPARE" "$WORK/after-1.exr" "$WORK/before-1.exr" --json > "$WORK/apart.json"
for channel in R G B; do
  echo "seed 1, channel $channel mean: before $(json_field per_channel $channel mean_reference < "$WORK/apart.json")," \
    "after $(json_field per_channel $channel mean_test < "$WORK/apart.json")"
done
echo "seed 1, relMSE between the two builds' images: $(json_field relmse < "$WORK/apart.json")"
