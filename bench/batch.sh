#!/usr/bin/env bash
# Batch throughput: the 36 frames of samples/turntable.jobs (the Cornell box with the
# Stanford bunny, bench/cornell_bunny.py --layout turntable) at 128x128, 16 spp, 8 bounces, rendered by one
# `kdrender --jobs` process against 36 separate kdrender processes (one per line), interleaved,
# median of RUNS (default 3) wall times. Checks that both give the same bytes for every frame.
# The program cache is warmed first, so neither side compiles kernels.
# usage: bench/batch.sh BUILD_DIR
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=$(realpath "${1:-build}")
. bench/common.sh
RUNS=${RUNS:-3}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
SETTINGS=(--width 128 --height 128 --spp 16 --max-bounces 8)
now() { date +%s.%N; }

machine_line
cd "$WORK"
"$ROOT/bench/cornell_bunny.py" . --layout turntable > /dev/null
scene_files cornell-bunny.obj scene
mapfile -t lines < <(sed -e 's/#.*//' -e '/^[[:space:]]*$/d' "$ROOT/samples/turntable.jobs")
echo "frames: ${#lines[@]}"
export KDRAY_CACHE_DIR=$WORK/program-cache
"$KDRENDER" scene.kdscene scene.kdtree -o warm.png --width 8 --height 8 --spp 1 --quiet

batch() {
  mkdir -p batch && cd batch
  "$KDRENDER" ../scene.kdscene ../scene.kdtree --jobs "$ROOT/samples/turntable.jobs" "${SETTINGS[@]}" --quiet
  cd ..
}
separate() {
  mkdir -p separate && cd separate
  local line
  for line in "${lines[@]}"; do
    # shellcheck disable=SC2086  # a jobs line is split into words as kdrender splits it (no quotes here)
    "$KDRENDER" ../scene.kdscene ../scene.kdtree $line "${SETTINGS[@]}" --quiet
  done
  cd ..
}
: > batch.times
: > separate.times
for run in $(seq "$RUNS"); do
  start=$(now); batch; echo "$(now) - $start" | bc -l >> batch.times
  start=$(now); separate; echo "$(now) - $start" | bc -l >> separate.times
  echo "run $run: batch $(tail -1 batch.times) s, separate $(tail -1 separate.times) s"
done
for image in batch/*.png; do cmp "$image" "separate/$(basename "$image")"; done
echo "every frame identical in both ($(ls batch/*.png | wc -l) PNGs)"
b=$(median < batch.times)
s=$(median < separate.times)
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
printf 'median of %d: batch %.2f s, separate %.2f s, speedup %.2fx (goal >= 1.5x)\n' "$RUNS" "$b" "$s" "$(echo "$s / $b" | bc -l)"
