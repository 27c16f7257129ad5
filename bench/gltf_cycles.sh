#!/usr/bin/env bash
# Blender's glTF exports rendered by kdray against Cycles' render of the same Blender scene
# (issue 24). For each scene (bench/gltf_cycles/room.py and its options):
#  1. Blender builds the scene, saves OUT/NAME.blend, exports OUT/NAME.glb (Blender's exporter,
#     default settings plus export_cameras and export_lights) and renders with Cycles on the CPU:
#     the reference at REF_SPP (seed 1) and an independent render at LOW_SPP (seed 2), both
#     kept in OUT and reused when present (Cycles takes minutes per reference on 2 cores);
#  2. kdconvert, kdbuild and kdrender at the asset's own camera with no camera option but
#     --width (the reference's width; the height is kdray's to choose), at LOW_SPP and REF_SPP,
#     8 bounces;
#  3. kdcompare against the Cycles reference: each channel's mean (kdray's against Cycles') and
#     relMSE, beside the relMSE of Cycles' own LOW_SPP render. Issue 24 asks for every channel
#     mean within 8% and kdray's relMSE at LOW_SPP at most 5x Cycles'. When kdray's image is
#     not the reference's size, the means are still given and relMSE is not;
#  4. the part of the difference that is Blender's Principled BSDF: Cycles renders the same
#     .blend at REF_SPP with its rough plastics as Lambertian surfaces (bench/gltf_cycles/
#     lambert.py; by the glTF specification such a plastic is within 1% of Lambertian), kept in
#     OUT as NAME-cycles-lambert-REF_SPPspp.exr, and kdray's REF_SPP means are given against it.
# usage: bench/gltf_cycles.sh [BUILD_DIR] [OUT_DIR]
#        (env: SCENES="NAME=ROOM_OPTIONS;..." REF_SPP=1024 LOW_SPP=64 THREADS=2 BLENDER=blender
#         CYCLES_ONLY=1: the Blender part alone, e.g. the references ahead of a kdray build)
#   SCENES defaults to three: quad (the issue's room, lit by its emissive ceiling quad), point
#   (the same room lit by a 100 W point light instead) and wide (another layout, 16:9, another
#   lens and camera). Scenes of your own: e.g. SCENES="mine=--layout-seed 42 --width 400
#   --height 225 --cam-pos=-1,-2.7,1.4 --cam-target 0.5,1,0.7"; room.py's header lists its options.
set -euo pipefail
BUILD=${1:-}
OUT=$(realpath -m "${2:-gltf-cycles}")
. "$(dirname "$0")/common.sh"
cd "$ROOT"
REF_SPP=${REF_SPP:-1024}
LOW_SPP=${LOW_SPP:-64}
THREADS=${THREADS:-2}
BLENDER=${BLENDER:-blender}
SCENES=${SCENES:-"quad=;point=--light point;wide=--layout-seed 7 --width 384 --height 216 --lens 24 --cam-pos=-1.2,-2.8,1.5 --cam-target 0.4,0.8,0.9"}
mkdir -p "$OUT"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
export KDRAY_CACHE_DIR=$WORK/kdray-cache

now() { date +%s.%N; }
seconds_since() { awk "BEGIN {printf \"%.1f\", $(now) - $1}"; }
# cycles NAME SPP SEED OPTIONS...: OUT/NAME.glb and .blend, and OUT/NAME-cycles-SPPspp.exr unless present.
cycles() {
  local name=$1 spp=$2 seed=$3 exr=$OUT/$1-cycles-$2spp.exr
  shift 3
  if [[ -f $exr && -f $OUT/$name.glb ]]; then
    echo "$name: Cycles $spp spp: $exr (present, reused)"
    return
  fi
  "$BLENDER" -b --factory-startup --python bench/gltf_cycles/room.py -- --out-dir "$OUT" --name "$name" "$@" \
    --exr "$exr" --spp "$spp" --seed "$seed" --threads "$THREADS" > "$OUT/$name-cycles-${spp}spp.log" 2>&1
  echo "$name: Cycles $spp spp, seed $seed: $(sed -n 's/^CYCLES_RENDER_TIME_S \([0-9.]*\).*/\1/p' \
    "$OUT/$name-cycles-${spp}spp.log") s render: $exr"
}
image_size() { oiiotool --info "$1" | sed -n 's/.* : *\([0-9]*\) x *\([0-9]*\),.*/\1 \2/p'; }
# means FILE: the R, G and B means of an image (kdcompare of the image with itself).
means() {
  "$KDCOMPARE" "$1" "$1" --json > "$WORK/self.json"
  for ch in R G B; do json_field per_channel "$ch" mean_test < "$WORK/self.json"; done | paste -sd ' ' -
}
relmse() { "$KDCOMPARE" "$1" "$2" --json | json_field relmse; }

machine_line
IFS=';' read -r -a entries <<< "$SCENES"
for entry in "${entries[@]}"; do
  name=${entry%%=*}
  read -r -a options <<< "${entry#*=}"
  echo "== $name: room.py ${options[*]}"
  cycles "$name" "$REF_SPP" 1 "${options[@]}"
  cycles "$name" "$LOW_SPP" 2 "${options[@]}"
  ref=$OUT/$name-cycles-${REF_SPP}spp.exr
  low=$OUT/$name-cycles-${LOW_SPP}spp.exr
  lambert=$OUT/$name-cycles-lambert-${REF_SPP}spp.exr
  [[ -f $lambert ]] || "$BLENDER" -b --factory-startup "$OUT/$name.blend" --python bench/gltf_cycles/lambert.py -- \
    "$lambert" "$REF_SPP" > "$OUT/$name-cycles-lambert.log" 2>&1
  read -r width height < <(image_size "$ref")
  read -r -a ref_means < <(means "$ref")
  echo "Cycles ${width}x$height, $REF_SPP spp: means R G B ${ref_means[*]}"
  echo "Cycles $LOW_SPP spp: means $(means "$low"), relMSE against the reference $(relmse "$low" "$ref")"
  [[ ${CYCLES_ONLY:-} = 1 ]] && continue

  "$KDCONVERT" "$OUT/$name.glb" "$WORK/$name.kdscene" > "$WORK/$name-kdconvert.log" 2>&1 ||
    { cat "$WORK/$name-kdconvert.log"; exit 1; }
  grep -i "warn" "$WORK/$name-kdconvert.log" | sed "s/^/kdconvert: /" || true
  "$KDBUILD" "$WORK/$name.kdscene" "$WORK/$name.kdtree" > /dev/null
  for spp in $LOW_SPP $REF_SPP; do
    kd=$OUT/$name-kdray-${spp}spp.exr
    start=$(now)
    "$KDRENDER" "$WORK/$name.kdscene" "$WORK/$name.kdtree" -o "$kd" --width "$width" --spp "$spp" --max-bounces 8 \
      --seed 3 --quiet
    wall=$(seconds_since "$start")
    read -r kd_width kd_height < <(image_size "$kd")
    read -r -a kd_means < <(means "$kd")
    ratios=$(for c in 0 1 2; do awk "BEGIN {printf \"%+.1f%% \", 100 * (${kd_means[c]} / ${ref_means[c]} - 1)}"; done)
    within=$(for c in 0 1 2; do awk "BEGIN {d = ${kd_means[c]} / ${ref_means[c]} - 1; print (d < 0 ? -d : d) <= 0.08}"; done |
      grep -c 1 || true)
    echo "kdray $spp spp (${wall} s wall): ${kd_width}x$kd_height, means ${kd_means[*]} (${ratios% }" \
      "against Cycles; $within of 3 within 8%)"
    if [[ "$kd_width $kd_height" = "$width $height" ]]; then
      kd_relmse=$(relmse "$kd" "$ref")
      if [[ $spp = "$LOW_SPP" ]]; then
        cycles_relmse=$(relmse "$low" "$ref")
        echo "  relMSE $kd_relmse, $(awk "BEGIN {printf \"%.2f\", $kd_relmse / $cycles_relmse}")x Cycles' $cycles_relmse at $spp spp (at most 5x asked)"
      else
        echo "  relMSE $kd_relmse"
        read -r -a lambert_means < <(means "$lambert")
        echo "  against Cycles with Lambertian plastics (means ${lambert_means[*]}):" \
          "$(for c in 0 1 2; do awk "BEGIN {printf \"%+.1f%% \", 100 * (${kd_means[c]} / ${lambert_means[c]} - 1)}"; done)"
      fi
    else
      echo "  not the reference's size (${width}x$height): no relMSE"
    fi
  done
done
