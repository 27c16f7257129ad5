#!/usr/bin/env bash
# Equal-error time against Mitsuba 3 on a glTF asset: samples/gltf_scene.py's all-metal variant
# (a checker-textured floor, a normal-mapped box, two spheres, a point light; every material
# Schlick's Fresnel of the base colour over GGX, which both renderers model, bench/gltf_mitsuba.py),
# at the asset's own camera, 256x256, 8 bounces, 2 threads.
#  1. Each renderer's converged image (REF_SPP samples, seed 1000): the two differ by design in
#     small ways (texture filtering), so each is measured against its own.
#  2. RUNS interleaved runs at SPP (run r uses seed r), whole processes timed: the median wall
#     time and relMSE against the renderer's own reference, and error x time relative to
#     Mitsuba's (the equal-error time ratio when error falls as 1/spp).
# usage: MITSUBA_PYTHON=<venv>/bin/python bench/gltf_equal_error.sh [BUILD_DIR] [OUT_DIR]
#        (env: SPP=64 REF_SPP=2048 RUNS=3 DEVICE=: kdrender's device, unset: its default)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=$(realpath "${1:-build}")
OUT=$(realpath -m "${2:-gltf-equal-error}")
. bench/common.sh
SPP=${SPP:-64}
REF_SPP=${REF_SPP:-2048}
RUNS=${RUNS:-3}
[[ -x ${MITSUBA_PYTHON:-} ]] || { echo "gltf_equal_error.sh: error: MITSUBA_PYTHON must name a Python with mitsuba" >&2; exit 2; }
mkdir -p "$OUT"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
export KDRAY_CACHE_DIR=$WORK/kdray-cache
SIZE="--width 256 --height 256 --max-bounces 8"
DEVICE_ARGS=""
if [[ ${DEVICE:-} == host ]]; then DEVICE_ARGS="--device host --threads 2"; elif [[ -n ${DEVICE:-} ]]; then DEVICE_ARGS="--device $DEVICE"; fi

machine_line
/usr/bin/python3 samples/gltf_scene.py "$WORK/asset" --metal
"$KDCONVERT" "$WORK/asset/textured-scene.gltf" "$WORK/asset.kdscene" > /dev/null
"$KDBUILD" "$WORK/asset.kdscene" "$WORK/asset.kdtree" > /dev/null
SCENE="$WORK/asset.kdscene $WORK/asset.kdtree"
now() { date +%s.%N; }
# render NAME SPP SEED OUT.exr: one image by that renderer
render() {
  case $1 in
    kdray) "$KDRENDER" $SCENE -o "$4" $SIZE --spp "$2" --seed "$3" $DEVICE_ARGS -q ;;
    mitsuba) "$MITSUBA_PYTHON" bench/gltf_mitsuba.py "$WORK/asset" "$4" $SIZE --spp "$2" --seed "$3" --threads 2 --metal \
      > /dev/null ;;
  esac
}
for name in kdray mitsuba; do
  [[ -f $OUT/$name-reference.exr ]] || render $name "$REF_SPP" 1000 "$OUT/$name-reference.exr"
done
echo "references: $OUT/{kdray,mitsuba}-reference.exr, $REF_SPP spp"
render kdray 1 0 "$WORK/warm.exr"  # warm the program cache
for ((r = 0; r < RUNS; ++r)); do
  for name in kdray mitsuba; do
    start=$(now)
    render $name "$SPP" "$r" "$WORK/$name.exr"
    end=$(now)
    echo "$(awk "BEGIN {print $end - $start}") $("$KDCOMPARE" "$WORK/$name.exr" "$OUT/$name-reference.exr" --json \
      | json_field relmse)" >> "$WORK/$name.txt"
  done
done
echo "== gltf_scene.py --metal, $SIZE, $SPP spp, 2 threads, kdrender ${DEVICE_ARGS:-on its default device}; median of $RUNS interleaved runs"
declare -A wall err
for name in kdray mitsuba; do
  wall[$name]=$(cut -d' ' -f1 "$WORK/$name.txt" | median)
  err[$name]=$(cut -d' ' -f2 "$WORK/$name.txt" | median)
done
printf '%-10s %-8s %-10s %s\n' renderer wall_s relmse "error x wall / Mitsuba's"
for name in kdray mitsuba; do
  printf '%-10s %-8.3f %-10.3e %.3f\n' "$name" "${wall[$name]}" "${err[$name]}" \
    "$(awk "BEGIN {print ${wall[$name]} * ${err[$name]} / (${wall[mitsuba]} * ${err[mitsuba]})}")"
done
for name in kdray mitsuba; do echo "$name runs (wall relmse): $(tr '\n' ';' < "$WORK/$name.txt")"; done
