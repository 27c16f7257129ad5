#!/usr/bin/env bash
# Renderer benchmarks, medians of 3:
#  1. the sample Cornell box at 256x256, 8 max bounces, 16/64/256 spp (whole kdrender command
#     and its render_seconds), next to Blender Cycles 3.4's 1.18 s / 4.44 s / 19.2 s;
#  2. megakernel against wavefront at 16 spp;
#  3. cold and warm OpenCL program builds;
#  4. traversal-kernel Mrays/s for camera and random rays on the k-d tree benchmark meshes.
# usage: bench/render.sh [BUILD_DIR]   (a Release build; render_trace_bench is in BUILD_DIR/bench)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=$(realpath "${1:-build}")
. bench/common.sh
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
TRACE_BENCH=$BUILD/bench/render_trace_bench
VIEW="--cam-pos 278,273,-800 --cam-target 278,273,0 --cam-up 0,1,0 --fov 39.3077"
export KDRAY_CACHE_DIR=$WORK/kdray-cache POCL_CACHE_DIR=$WORK/pocl-cache

machine_line
echo "device: $("$KDRENDER" --device list | grep default)"
scene_files samples/cornell-box.obj cornell
CORNELL="$WORK/cornell.kdscene $WORK/cornell.kdtree"

echo
echo "== program build (pt_megakernel.cl, Cornell features): cold, then warm (disk cache)"
for run in cold warm; do
  echo "$run: $("$KDRENDER" $CORNELL -o "$WORK/b.exr" $VIEW --width 8 --height 8 --spp 1 --json | json_field build_seconds) s"
done

# render SPP [extra flags]: prints "median wall seconds, median render_seconds"
render() {
  local spp=$1; shift
  local walls=() renders=()
  for run in 1 2 3; do
    local start end report
    start=$(date +%s.%N)
    report=$("$KDRENDER" $CORNELL -o "$WORK/r.exr" $VIEW --width 256 --height 256 --max-bounces 8 --spp "$spp" --json "$@")
    end=$(date +%s.%N)
    walls+=("$(awk "BEGIN {print $end - $start}")")
    renders+=("$(echo "$report" | json_field render_seconds)")
  done
  printf '%s %s\n' "$(printf '%s\n' "${walls[@]}" | median)" "$(printf '%s\n' "${renders[@]}" | median)"
}

echo
echo "== Cornell box 256x256, 8 bounces: kdrender $CORNELL -o r.exr $VIEW --width 256 --height 256 --max-bounces 8 --spp N"
echo "spp  wall_s  render_s  cycles_s"
for spp in 16 64 256; do
  case $spp in 16) cycles=1.18 ;; 64) cycles=4.44 ;; 256) cycles=19.2 ;; esac
  read -r wall rend < <(render "$spp")
  printf '%-4s %-7.3f %-9.3f %s\n' "$spp" "$wall" "$rend" "$cycles"
done

echo
echo "== megakernel vs wavefront (Cornell 256x256, 16 spp; same image bytes)"
read -r wall rend < <(render 16)
echo "megakernel: wall $wall s, render $rend s"
read -r wall rend < <(render 16 --wavefront)
echo "wavefront:  wall $wall s, render $rend s"

echo
echo "== traversal kernel Mrays/s (1M camera rays, 1M random rays; median of 3): render_trace_bench SCENE TREE 1000000"
for mesh in bunny/stanford-bunny.obj dragon/dragon_vcg_100k.ply large/bunny_sub2.ply large/dragons_4x4.ply; do
  name=$(basename "${mesh%.*}")
  scene_files "$CORPUS/$mesh" "$name" 2> /dev/null
  "$TRACE_BENCH" "$WORK/$name.kdscene" "$WORK/$name.kdtree" 1000000 |
    /usr/bin/python3 -c "import json,sys; r=json.load(sys.stdin); print(f\"$name ({r['triangles']} tris): camera {r['camera_mrays_per_s']:.2f}, random {r['random_mrays_per_s']:.2f}\")"
  rm -f "$WORK/$name.kdscene" "$WORK/$name.kdtree"
done
