#!/usr/bin/env bash
# Speed against error on samples/gltf_scene.py's glTF lit by its point light (as authored, or
# VARIANT=flat: without the ridged box's normal map, or VARIANT=metal), kdray against Mitsuba 3
# (bench/gltf_mitsuba.py: llvm_ad_rgb, multijitter, 2 threads), SIZE x SIZE, 8 bounces:
#  1. converged references: Mitsuba at REF_SPP (its own seed) and kdray at REF_SPP (seed 1000);
#  2. each renderer at the spp counts SPPS, whole processes timed side by side, interleaved,
#     RUNS runs (seed = run): median wall seconds, and relMSE (kdcompare) against Mitsuba's
#     reference and against the renderer's own reference (noise alone, without the renderers'
#     difference in what they converge to).
# usage: bench/gltf_error.sh [BUILD_DIR] [OUT_DIR]
#        (env: VARIANT=plastic SIZE=96 REF_SPP=4096 SPPS="16 64 256" RUNS=3 MITSUBA_PYTHON=...)
set -euo pipefail
BUILD=${1:-}
OUT=$(realpath -m "${2:-gltf-error}")
. "$(dirname "$0")/common.sh"
cd "$ROOT"
VARIANT=${VARIANT:-plastic}
SIZE=${SIZE:-96}
REF_SPP=${REF_SPP:-4096}
SPPS=${SPPS:-16 64 256}
RUNS=${RUNS:-3}
mkdir -p "$OUT"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
export KDRAY_CACHE_DIR=$WORK/kdray-cache
DIMS="--width $SIZE --height $SIZE --max-bounces 8"

SCRIPTS=$PWD
case $VARIANT in
  plastic | metal) ;;
  flat)  # copies of the two scene scripts without the ridged box's normal map
    mkdir -p "$WORK/flat/bench" "$WORK/flat/samples"
    cp bench/gltf_mitsuba.py "$WORK/flat/bench/"
    sed 's/, "normal_texture": "ridges.png"}/}/' samples/gltf_scene.py > "$WORK/flat/samples/gltf_scene.py"
    SCRIPTS=$WORK/flat ;;
  *) echo "gltf_error.sh: error: VARIANT must be plastic, flat or metal, not '$VARIANT'" >&2 && exit 2 ;;
esac
FLAG=$([[ $VARIANT = metal ]] && echo --metal || true)
/usr/bin/python3 "$SCRIPTS/samples/gltf_scene.py" "$WORK/scene" $FLAG > /dev/null
scene_files "$WORK/scene/textured-scene.gltf" scene

relmse() { "$KDCOMPARE" "$1" "$2" --json | json_field relmse; }
now() { date +%s.%N; }
render() {  # NAME SPP SEED OUT
  case $1 in
    kdray) "$KDRENDER" "$WORK/scene.kdscene" "$WORK/scene.kdtree" -o "$4" $DIMS --spp "$2" \
      --seed "$3" --quiet ;;
    mitsuba) "$MITSUBA_PYTHON" "$SCRIPTS/bench/gltf_mitsuba.py" "$WORK/scene" "$4" $DIMS --spp "$2" --seed "$3" \
      $FLAG > /dev/null ;;
  esac
}

machine_line
for name in mitsuba kdray; do
  ref=$OUT/reference-$name-$VARIANT-${REF_SPP}spp-${SIZE}.exr
  if [[ ! -f $ref ]]; then
    start=$(now)
    render $name "$REF_SPP" 1000 "$ref"
    echo "reference $name: $REF_SPP spp, $(awk "BEGIN {printf \"%.1f\", $(now) - $start}") s wall"
  fi
done
MI_REF=$OUT/reference-mitsuba-$VARIANT-${REF_SPP}spp-${SIZE}.exr
render kdray 1 0 "$WORK/warm.exr"  # the program cache
echo "reference means: Mitsuba $(oiiotool --stats "$MI_REF" | sed -n 's/.*Stats Avg: *//p' | head -1)," \
  "kdray $(oiiotool --stats "$OUT/reference-kdray-$VARIANT-${REF_SPP}spp-${SIZE}.exr" | sed -n 's/.*Stats Avg: *//p' | head -1 | cut -d' ' -f1-3)"
echo "kdray reference / Mitsuba reference relMSE: $(relmse "$OUT/reference-kdray-$VARIANT-${REF_SPP}spp-${SIZE}.exr" "$MI_REF")"

for ((r = 0; r < RUNS; ++r)); do
  for spp in $SPPS; do
    for name in kdray mitsuba; do
      start=$(now)
      render $name "$spp" "$r" "$WORK/$name.exr"
      wall=$(awk "BEGIN {print $(now) - $start}")
      echo "$wall $(relmse "$WORK/$name.exr" "$MI_REF") $(relmse "$WORK/$name.exr" "$OUT/reference-$name-$VARIANT-${REF_SPP}spp-${SIZE}.exr")" \
        >> "$WORK/$name-$spp.txt"
    done
  done
done
echo
echo "== $VARIANT, ${SIZE}x${SIZE}, 8 bounces, medians of $RUNS interleaved runs (whole processes)"
printf '%-8s %5s %8s %14s %14s\n' renderer spp wall_s "relMSE vs mi" "relMSE vs own"
for spp in $SPPS; do
  for name in kdray mitsuba; do
    f=$WORK/$name-$spp.txt
    printf '%-8s %5s %8.2f %14.4e %14.4e\n' $name "$spp" "$(cut -d' ' -f1 "$f" | median)" \
      "$(cut -d' ' -f2 "$f" | median)" "$(cut -d' ' -f3 "$f" | median)"
  done
done
for f in "$WORK"/*-*.txt; do echo "$(basename "$f" .txt): $(tr '\n' ';' < "$f")"; done
