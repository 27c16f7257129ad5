#!/usr/bin/env bash
# Speed against error for an HDRI-lit mesh, kdray against Mitsuba 3: the corpus's spot.obj
# (diffuse 0.8) under the corpus's courtyard.exr, SIZE x SIZE (128), 8 bounces as Cycles counts
# them (Mitsuba max_depth 10), 2 threads. The reference is Mitsuba's own render of REF_SPP
# (4096) samples, seed 1000, so neither renderer's series is measured against itself. For each
# spp in SPPS ("16 64 256"), RUNS (3) interleaved runs of each renderer (run r uses seed r),
# whole processes timed (kdrender reads a prebuilt scene and tree; Mitsuba reads the OBJ and
# builds its BVH, as it must); prints the medians and error x time of kdray over Mitsuba's,
# which is the equal-error time ratio where error falls as 1/spp.
# usage: bench/env_speed_vs_error.sh [BUILD_DIR] [MITSUBA_PYTHON]
set -euo pipefail
BUILD=${1:-}
. "$(dirname "$0")/common.sh"
MITSUBA=${2:-$MITSUBA_PYTHON}
cd "$ROOT"
RUNS=${RUNS:-3}
SPPS=${SPPS:-16 64 256}
REF_SPP=${REF_SPP:-4096}
SIZE=${SIZE:-128}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
now() { date +%s.%N; }

machine_line
OBJ=$CORPUS/misc/spot.obj
MAP=$CORPUS/hdri/courtyard.exr
scene_files "$OBJ" spot
VIEW="--width $SIZE --height $SIZE --max-bounces 8 --cam-pos 0,0.108431,3.57155 --cam-target 0,0.108431,0.190046 --fov 45"

mitsuba() {  # mitsuba SPP SEED OUT
  "$MITSUBA" $YARDSTICKS/mitsuba_render.py --obj "$OBJ" --out "$3" $VIEW --spp "$1" --seed "$2" \
    --env "$MAP" --threads 2 --sampler multijitter > /dev/null 2>&1
}
kdray() {  # kdray SPP SEED OUT
  "$KDRENDER" "$WORK/spot.kdscene" "$WORK/spot.kdtree" -o "$3" $VIEW --spp "$1" --seed "$2" --env "$MAP" --quiet
}

REFERENCE=$WORK/reference.exr
echo "reference: Mitsuba 3, $REF_SPP spp, seed 1000"
mitsuba "$REF_SPP" 1000 "$REFERENCE"
kdray 1 0 "$WORK/warm.exr"  # warm the program cache

# run NAME SPP SEED: appends "wall relmse" to $WORK/NAME-SPP.txt
run() {
  local start end
  start=$(now)
  "$1" "$2" "$3" "$WORK/$1.exr"
  end=$(now)
  echo "$(awk "BEGIN {print $end - $start}") $("$KDCOMPARE" "$WORK/$1.exr" "$REFERENCE" --json | json_field relmse)" \
    >> "$WORK/$1-$2.txt"
}

printf '%-5s %-9s %-11s %-9s %-11s %s\n' spp kdray_s kdray_relmse mitsuba_s mitsuba_relmse "error x time, kdray / Mitsuba"
for spp in $SPPS; do
  for ((r = 0; r < RUNS; ++r)); do run kdray "$spp" "$r" && run mitsuba "$spp" "$r"; done
  kd_s=$(cut -d' ' -f1 "$WORK/kdray-$spp.txt" | median)
  kd_e=$(cut -d' ' -f2 "$WORK/kdray-$spp.txt" | median)
  mi_s=$(cut -d' ' -f1 "$WORK/mitsuba-$spp.txt" | median)
  mi_e=$(cut -d' ' -f2 "$WORK/mitsuba-$spp.txt" | median)
  printf '%-5s %-9.3f %-11.4e %-9.3f %-11.4e %.3f\n' "$spp" "$kd_s" "$kd_e" "$mi_s" "$mi_e" \
    "$(awk "BEGIN {print $kd_s * $kd_e / ($mi_s * $mi_e)}")"
done
for name in kdray mitsuba; do
  for spp in $SPPS; do echo "$name $spp spp runs (wall relmse): $(tr '\n' ';' < "$WORK/$name-$spp.txt")"; done
done
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
