#!/usr/bin/env bash
# Where a sample's time goes on the CPU, by part: `perf record` (software clock, no call graphs)
# of the host build (`kdrender --device host --threads 2`; the C++ build of the same kernel code
# that PoCL runs, whose symbols perf can name), 256x256, 8 bounces, and each sampled function
# put in one part by its name. The kernel's helpers are inlined into the functions named, so a
# part is what its functions do with what they inline:
#   traversal   kd_traverse and the leaf tests (closest and shadow rays)
#   light       next-event estimation (pt_next_event_any): the light pick, the spherical
#               triangle, the environment, the BSDF's evaluation, the MIS weights, their sample
#               values
#   shading     pt_path_shade: the hit point, emission with MIS, roulette, the BSDF's sampling,
#               their sample values
#   pixels      the pixel loop (HostRender::pass): each path's camera ray and sample values,
#               the film's accumulation
#   start       the dynamic loader's symbol lookups at process start
#   rest        everything else: loading, the kernel, libraries
# Scenes: the Cornell box sample, the Cornell box with the bunny (bench/cornell_bunny.py), and any
# asset kdconvert reads, given as arguments (framed by its own camera, or kdrender's default).
#   [SPP=32] bench/sample_parts.sh [BUILD_DIR] [ASSET...]
# Needs `perf` (Debian `linux-perf`) with access to software events.
set -euo pipefail
BUILD=$(realpath "${1:-build}")
shift || true
. "$(dirname "$0")/common.sh"
SPP=${SPP:-32}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
export KDRAY_CACHE_DIR=$WORK/kdray-cache
command -v perf > /dev/null || { echo "sample_parts.sh: error: perf is not installed (Debian: linux-perf)" >&2; exit 1; }
CORNELL_VIEW="--cam-pos 278,273,-800 --cam-target 278,273,0 --fov 39.3077"
SIZE="--width 256 --height 256 --max-bounces 8 --spp $SPP --device host --threads 2"

# parts PERF_DATA: one line, the percentage of each part, in the order of the header below.
parts() {
  perf report -i "$1" --no-children --sort sym --stdio 2> /dev/null | /usr/bin/python3 -c '
import re, sys
parts = [("traversal", r"kd_traverse|kd_intersect|traverse_"),
         ("light", r"pt_next_event|pt_spherical|pt_light|pt_environment|pt_direct"),
         ("shading", r"pt_path_shade|pt_bsdf|pt_material|pt_texture|pt_hashed|pt_sample"),
         ("pixels", r"HostRender::pass|pt_path_begin|pt_path_accumulate|pt_film|pt_camera"),
         ("start", r"do_lookup_x|_dl_|check_match|strcmp")]
totals = {name: 0.0 for name, _ in parts}
totals["rest"] = 0.0
for line in sys.stdin:
    m = re.match(r"\s*([0-9.]+)%\s+\[[.k]\]\s+(.*)", line)
    if not m: continue
    share, symbol = float(m.group(1)), m.group(2)
    for name, pattern in parts:
        if re.search(pattern, symbol):
            totals[name] += share
            break
    else:
        totals["rest"] += share
print(" ".join("%9.1f" % totals[name] for name in [p[0] for p in parts] + ["rest"]))'
}

# profile NAME SCENE TREE [VIEW...]: renders under perf, prints the scene's row.
profile() {
  local name=$1 scene=$2 tree=$3
  shift 3
  "$KDRENDER" "$scene" "$tree" -o "$WORK/warm.exr" "$@" --width 8 --height 8 --spp 1 --device host -q 2> /dev/null
  local start end
  start=$(date +%s.%N)
  perf record -q -e cpu-clock -F 2000 -o "$WORK/$name.perf" -- \
    "$KDRENDER" "$scene" "$tree" -o "$WORK/$name.exr" "$@" $SIZE -q 2> /dev/null
  end=$(date +%s.%N)
  printf "%-16s %7.2f %s\n" "$name" "$(awk -v a="$start" -v b="$end" 'BEGIN {print b - a}')" "$(parts "$WORK/$name.perf")"
}

machine_line
echo "kdrender --device host --threads 2, 256x256, 8 bounces, $SPP spp; % of perf's samples (cpu-clock, 2000 Hz)"
printf "%-16s %7s %9s %9s %9s %9s %9s %9s\n" scene "wall s" traversal light shading pixels start rest
scene_files "$ROOT/samples/cornell-box.obj" cornell
profile cornell-box "$WORK/cornell.kdscene" "$WORK/cornell.kdtree" $CORNELL_VIEW
"$ROOT/bench/cornell_bunny.py" "$WORK" > /dev/null
scene_files "$WORK/cornell-bunny.obj" cornell-bunny
profile cornell-bunny "$WORK/cornell-bunny.kdscene" "$WORK/cornell-bunny.kdtree" $CORNELL_VIEW
for asset in "$@"; do
  name=$(basename "${asset%.*}")
  scene_files "$(corpus_file "$asset")" "$name"
  profile "$name" "$WORK/$name.kdscene" "$WORK/$name.kdtree"
done
