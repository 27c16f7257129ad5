#!/usr/bin/env bash
# Where a sample's time goes on the CPU, by part: `perf record` (software clock, no call graphs)
# of the host build (`kdrender --device host --threads 2`; the C++ build of the same kernel code
# that PoCL runs), 256x256, 8 bounces, and each sample put in one part by the source file of its
# instruction. The kernel's functions are inlined into a few large ones (the fast traversal into
# the pixel loop), so only the line tables say what code a sample is in: BUILD must be a build
# with them (`cmake -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS=-g`: the same code, debug
# information added). The parts, by file:
#   traversal   kd_geometry.h, kd_traverse*.h, kd_scene_view.h, kd_types.h, libkdtree's
#               traversal_*.cpp (closest and shadow rays, one at a time or in packets: ray setup,
#               the steps, the leaf and triangle tests)
#   samples     pt_rng.h: the sample values (hashed, scrambled Sobol' points)
#   light       pt_direct_light.h, pt_lights.h, pt_spherical_triangle.h, pt_environment.h:
#               next-event estimation
#   shading     pt_path.h, pt_bsdf.h, pt_material.h, pt_sampling.h, pt_texture*.h: the hit point,
#               emission with MIS, roulette, the BSDF's evaluation and sampling
#   math        kd_vector.h, kd_math.h, the C library's maths (float3 operations, sqrt, fmax...),
#               shared by light and shading
#   pixels      pt_path_state.h, pt_film.h, render_host_pixels.cpp: each path's start and camera ray,
#               the film's accumulation, the pixel loop
#   lanes       path_lanes.h, lane8.h, kd_lane.h and the AVX intrinsics' headers: the paths in lanes
#               (their step loop, gathers, masks, copies) and, since the line tables put each
#               inlined 8-float operation at lane8.h's operator, most of their light, shading and
#               math
#   start       the dynamic loader (the image module's OpenImageIO libraries load during the render)
#   rest        everything else: loading, the kernel, libraries
# KDRAY_HOST_LANES=off in the environment profiles one path at a time instead of the lanes.
# Scenes: the Cornell box sample, the Cornell box with the bunny (bench/cornell_bunny.py), and any
# asset kdconvert reads, given as arguments (framed by its own camera, or kdrender's default).
#   [SPP=32] bench/sample_parts.sh [BUILD_DIR] [ASSET...]
# Needs `perf` (Debian `linux-perf`) with access to software events, and binutils' addr2line
# (perf names a sample's source file with it: about a minute a scene).
set -euo pipefail
BUILD=$(realpath "${1:-build}")
shift || true
. "$(dirname "$0")/common.sh"
SPP=${SPP:-32}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
export KDRAY_CACHE_DIR=$WORK/kdray-cache
command -v perf > /dev/null || { echo "sample_parts.sh: error: perf is not installed (Debian: linux-perf)" >&2; exit 1; }
readelf -S "$KDRENDER" | grep -q debug_line || {
  echo "sample_parts.sh: error: $KDRENDER has no line tables: configure BUILD with -DCMAKE_CXX_FLAGS=-g" >&2
  exit 1
}
CORNELL_VIEW="--cam-pos 278,273,-800 --cam-target 278,273,0 --fov 39.3077"
SIZE="--width 256 --height 256 --max-bounces 8 --spp $SPP --device host --threads 2"

# parts PERF_DATA: one line, the percentage of each part, in the order of the header below.
parts() {
  perf report -i "$1" --no-children --sort srcfile --stdio 2> /dev/null | /usr/bin/python3 -c '
import re, sys
parts = [("traversal", r"^(kd_(geometry|traverse\w*|scene_view|types)\.h|traversal_\w+\.cpp)$"),
         ("samples", r"^pt_rng\.h$"),
         ("light", r"^pt_(direct_light|lights|spherical_triangle|environment)\.h$"),
         ("shading", r"^pt_(path|bsdf|material|sampling|texture\w*)\.h$"),
         ("math", r"^(kd_vector\.h|kd_math\.h|cmath|s_\w+\.S|e_\w+\.c|s_\w+\.c)$"),
         ("pixels", r"^(pt_path_state\.h|pt_film\.h|render_host_pixels\.cpp)$"),
         ("lanes", r"^(path_lanes\.h|lane8\.h|kd_lane\.h|avx\w*intrin\.h)$"),
         ("start", r"^(dl-\S+|do-rel\.h|strcmp\S*)$")]
totals = {name: 0.0 for name, _ in parts}
totals["rest"] = 0.0
for line in sys.stdin:
    m = re.match(r"\s*([0-9.]+)%\s+(\S*)\s*$", line)
    if not m: continue
    share, source = float(m.group(1)), m.group(2)
    for name, pattern in parts:
        if re.search(pattern, source):
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
printf "%-16s %7s %9s %9s %9s %9s %9s %9s %9s %9s %9s\n" scene "wall s" traversal samples light shading math pixels \
  lanes start rest
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
