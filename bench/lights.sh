#!/usr/bin/env bash
# Light benchmarks, medians of 5:
#  1. environment map preparation: reading a 4096x2048 map (float EXR, half DWAB EXR, Radiance
#     HDR, resized from a corpus map) and building its sampling table (environment_bench);
#  2. the sample Cornell box (emissive triangles only) rendered by a baseline kdrender and this
#     one, interleaved: the environment and punctual code must cost it nothing;
#  3. an HDRI-lit mesh against Mitsuba 3 (llvm_ad_rgb, multijitter): channel means;
#  4. with a baseline: the bunny under 4096x2048 maps, the baseline and this build alternated
#     $ROUNDS times (9 by default): median render_seconds, the median of the paired ratios, and
#     the largest difference between the two images (kdcompare max_abs);
#  5. with a baseline: the Cornell box with the bunny made an emitter (69,453 emissive triangles,
#     bench/cornell_bunny.py), the same alternation.
# usage: [ROUNDS=9] bench/lights.sh BUILD_DIR [BASELINE_KDRENDER] [MITSUBA_PYTHON]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=$(realpath "${1:-build}")
BASELINE=${2:-}
. bench/common.sh
MITSUBA=${3:-$MITSUBA_PYTHON}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

machine_line

echo "== 1. 4096x2048 environment maps"
oiiotool "$CORPUS/hdri/courtyard.exr" --resize 4096x2048 -d float --compression zip -o "$WORK/map-float.exr"
oiiotool "$CORPUS/hdri/courtyard.exr" --resize 4096x2048 -d half --compression dwab -o "$WORK/map-half.exr"
oiiotool "$CORPUS/hdri/courtyard.exr" --resize 4096x2048 -o "$WORK/map.hdr"
for map in map-float.exr map-half.exr map.hdr; do
  echo "$map ($(du -h "$WORK/$map" | cut -f1)): $("$BUILD/bench/environment_bench" "$WORK/$map" 5)"
done

echo "== 2. Cornell box 256x256, 64 spp, 8 bounces: render_seconds, interleaved"
scene_files samples/cornell-box.obj cornell
VIEW="--cam-pos 278,273,-800 --cam-target 278,273,0 --fov 39.3077 --width 256 --height 256 --spp 64"
run() { "$1" "$WORK/$2.kdscene" "$WORK/cornell.kdtree" -o "$WORK/c.exr" $VIEW --json | json_field render_seconds; }
if [ -n "$BASELINE" ]; then
  # The baseline must read this build's scene files (a build of the same .kdscene version).
  : > "$WORK/a"; : > "$WORK/b"
  run "$BASELINE" cornell > /dev/null; run "$KDRENDER" cornell > /dev/null  # warm the program caches
  for i in 1 2 3 4 5; do run "$BASELINE" cornell >> "$WORK/a"; run "$KDRENDER" cornell >> "$WORK/b"; done
  echo "baseline $(median < "$WORK/a") s, this build $(median < "$WORK/b") s (runs: $(tr '\n' ' ' < "$WORK/a")| $(tr '\n' ' ' < "$WORK/b"))"
fi
echo "kernel options: $("$KDRENDER" "$WORK/cornell.kdscene" "$WORK/cornell.kdtree" -o "$WORK/c.exr" $VIEW --json | json_field kernel_options)"

echo "== 3. spot.obj under courtyard.exr, 128x128, 512 spp, 8 bounces: kdray vs Mitsuba 3"
scene_files "$CORPUS/misc/spot.obj" spot
SPOT="--width 128 --height 128 --max-bounces 8 --spp 512 --cam-pos 0,0.108431,3.57155 --cam-target 0,0.108431,0.190046 --fov 45"
"$KDRENDER" "$WORK/spot.kdscene" "$WORK/spot.kdtree" -o "$WORK/kd.exr" $SPOT --env "$CORPUS/hdri/courtyard.exr" --quiet
if [ -x "$MITSUBA" ]; then
  "$MITSUBA" $YARDSTICKS/mitsuba_render.py --obj "$CORPUS/misc/spot.obj" --out "$WORK/mi.exr" $SPOT \
    --env "$CORPUS/hdri/courtyard.exr" --threads 2 --sampler multijitter > /dev/null
  for image in kd mi; do echo "$image: $(oiiotool --stats "$WORK/$image.exr" | grep 'Stats Avg' | head -1)"; done
  "$KDCOMPARE" "$WORK/kd.exr" "$WORK/mi.exr" || true
fi

if [ -n "$BASELINE" ]; then
  # alternate LABEL RENDER...: `RENDER... KDRENDER IMAGE` prints the render_seconds of a render
  # written to $WORK/IMAGE.exr; the baseline and this build take turns $ROUNDS times, then their
  # medians, the median of the paired ratios and the images' largest difference are printed.
  alternate() {
    local label=$1 a b
    shift
    : > "$WORK/a"; : > "$WORK/b"; : > "$WORK/r"
    for ((i = 0; i < ${ROUNDS:-9}; ++i)); do
      a=$("$@" "$BASELINE" base) b=$("$@" "$KDRENDER" this)
      echo "$a" >> "$WORK/a"; echo "$b" >> "$WORK/b"; echo "$b / $a" | bc -l >> "$WORK/r"
    done
    echo "$label: baseline $(median < "$WORK/a") s, this build $(median < "$WORK/b") s," \
      "paired ratio $(printf %.3f "$(median < "$WORK/r")")," \
      "images' largest difference $("$KDCOMPARE" "$WORK/base.exr" "$WORK/this.exr" --json | json_field max_abs)"
  }

  echo "== 4. bunny under 4096x2048 maps, 256x256, 64 spp, 8 bounces: baseline / this build, alternated"
  scene_files "$CORPUS/bunny/bun_zipper.ply" bunny
  oiiotool "$CORPUS/hdri/sunset.exr" --resize 4096x2048 -d float --compression zip -o "$WORK/sunset.exr"
  BUNNY="--width 256 --height 256 --spp 64 --max-bounces 8"
  under() { "$2" "$WORK/bunny.kdscene" "$WORK/bunny.kdtree" -o "$WORK/$3.exr" $BUNNY --env "$WORK/$1.exr" --json |
    json_field render_seconds; }
  for map in map-float sunset; do alternate "$map" under "$map"; done

  echo "== 5. Cornell box with the bunny as an emitter, 256x256, 32 spp, 8 bounces: baseline / this build," \
    "alternated"
  bench/cornell_bunny.py "$WORK" > /dev/null
  # The bunny's group takes a material of its own that emits.
  awk '/^o bunny/ {bunny = 1} bunny && /^usemtl/ {print "usemtl glow"; bunny = 0; next} {print}' \
    "$WORK/cornell-bunny.obj" > "$WORK/glow.obj"
  printf '\nnewmtl glow\nKd 0.5 0.5 0.5\nKe 0.3 0.3 0.3\n' >> "$WORK/cornell-box.mtl"
  scene_files "$WORK/glow.obj" glow
  GLOW="--cam-pos 278,273,-800 --cam-target 278,273,0 --fov 39.3077 --width 256 --height 256 --spp 32"
  glowing() { "$1" "$WORK/glow.kdscene" "$WORK/glow.kdtree" -o "$WORK/$2.exr" $GLOW --json |
    json_field render_seconds; }
  alternate glow glowing
fi
