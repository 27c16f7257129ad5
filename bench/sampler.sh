#!/usr/bin/env bash
# Sampler benchmark on the sample Cornell box (SCENE=cornell-box) or the Cornell box with the
# Stanford bunny on its floor (SCENE=cornell-bunny, written by bench/cornell_bunny.py from the
# corpus), 256x256, 8 max bounces (as Cycles counts), SPP (64) samples per pixel:
#  1. kdrender --sampler sobol and --sampler independent, and, when the yardsticks are installed
#     (../shared/yardsticks), Blender Cycles 3.4 and Mitsuba 3 (llvm_ad_rgb, multijitter,
#     max_depth = bounces + 2), 2 threads each: whole processes timed side by side, interleaved
#     in one loop, RUNS runs (run r uses seed r); prints the median wall time, the median kdrender
#     render_seconds and the median relMSE against one converged reference, and error x time
#     relative to Cycles and to Mitsuba (equal-error time ratios when error falls as 1/spp);
#  2. speed-vs-error CSVs for both samplers and one log-log plot (scripts/speed_vs_error.py).
# The reference is REFERENCE (an EXR of the same view) or else a kdrender sobol render of
# REFERENCE_SPP samples with seed 1000 (slow: about 16x the 64-spp render).
# usage: bench/sampler.sh [BUILD_DIR] [OUT_DIR]
#        (env: SCENE=cornell-box RUNS=3 SPP=64 REFERENCE= REFERENCE_SPP=1024 SERIES=1 DEVICE=)
# DEVICE names kdrender's device for part 1 (host: `--device host --threads 2`); unset, kdrender
# picks its own.
# SERIES=0 skips the speed-vs-error series (part 2).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=$(realpath "${1:-build}")
OUT=$(realpath -m "${2:-sampler-bench}")
RUNS=${RUNS:-3}
SCENE=${SCENE:-cornell-box}
SERIES=${SERIES:-1}
REFERENCE_SPP=${REFERENCE_SPP:-1024}
mkdir -p "$OUT"
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
. bench/common.sh
case $SCENE in
  cornell-box) OBJ=$PWD/samples/cornell-box.obj ;;
  cornell-bunny) bench/cornell_bunny.py "$WORK" > /dev/null && OBJ=$WORK/cornell-bunny.obj ;;
  *) echo "sampler.sh: error: SCENE must be cornell-box or cornell-bunny, not '$SCENE'" >&2 && exit 2 ;;
esac
VIEW="--cam-pos 278,273,-800 --cam-target 278,273,0 --fov 39.3077"
SIZE="--width 256 --height 256 --max-bounces 8"
SPP=${SPP:-64}
export KDRAY_CACHE_DIR=$WORK/kdray-cache

relmse() { "$KDCOMPARE" "$1" "$REFERENCE" --json | json_field relmse; }
now() { date +%s.%N; }

machine_line
scene_files "$OBJ" cornell
CORNELL="$WORK/cornell.kdscene $WORK/cornell.kdtree"
if [[ -z "${REFERENCE:-}" ]]; then
  REFERENCE=$OUT/reference.exr
  echo "reference: kdrender $SIZE --spp $REFERENCE_SPP --seed 1000 (sobol)"
  "$KDRENDER" $CORNELL -o "$REFERENCE" $VIEW $SIZE --spp "$REFERENCE_SPP" --seed 1000 -q
fi
echo "reference: $REFERENCE"
"$KDRENDER" $CORNELL -o "$WORK/warm.exr" $VIEW --width 8 --height 8 --spp 1 -q  # warm the program cache

DEVICE_ARGS=""
if [[ ${DEVICE:-} == host ]]; then DEVICE_ARGS="--device host --threads 2"; elif [[ -n ${DEVICE:-} ]]; then DEVICE_ARGS="--device $DEVICE"; fi

renderers=(sobol independent)
have_cycles=0 have_mitsuba=0
if command -v blender > /dev/null && [[ -f $YARDSTICKS/cycles_render.py ]]; then have_cycles=1 && renderers+=(cycles); fi
if [[ -x $MITSUBA_PYTHON && -f $YARDSTICKS/mitsuba_render.py ]]; then have_mitsuba=1 && renderers+=(mitsuba); fi

# run NAME SEED: renders one 64-spp image to $WORK/NAME.exr, appends "wall render_s relmse" to $WORK/NAME.txt
run() {
  local name=$1 seed=$2 start end render_s=0
  start=$(now)
  case $name in
    sobol | independent)
      render_s=$("$KDRENDER" $CORNELL -o "$WORK/$name.exr" $VIEW $SIZE --spp $SPP --seed "$seed" --sampler "$name" \
        $DEVICE_ARGS --json | json_field render_seconds) ;;
    cycles)
      blender -b --factory-startup --python "$YARDSTICKS/cycles_render.py" -- --obj "$OBJ" --out "$WORK/$name.exr" \
        --spp $SPP --width 256 --height 256 --max-bounces 8 --cam-pos 278,273,-800 --cam-target 278,273,0 \
        --fov 39.3077 --threads 2 --seed "$seed" > /dev/null 2>&1 ;;
    mitsuba)
      "$MITSUBA_PYTHON" "$YARDSTICKS/mitsuba_render.py" --obj "$OBJ" --out "$WORK/$name.exr" --spp $SPP --width 256 \
        --height 256 --max-bounces 8 --cam-pos 278,273,-800 --cam-target 278,273,0 --fov 39.3077 --threads 2 \
        --seed "$seed" --sampler multijitter > /dev/null 2>&1 ;;
  esac
  end=$(now)
  echo "$(awk "BEGIN {print $end - $start}") $render_s $(relmse "$WORK/$name.exr")" >> "$WORK/$name.txt"
}

echo
echo "== $SCENE, $SIZE, $SPP spp, 2 threads, kdrender ${DEVICE_ARGS:-on its default device}; median of $RUNS interleaved runs (seed = run)"
for ((r = 0; r < RUNS; ++r)); do
  for name in "${renderers[@]}"; do run "$name" "$r"; done
done
declare -A wall err
printf '%-12s %-8s %-9s %-10s %-24s %s\n' renderer wall_s render_s relmse "error x wall / Cycles'" \
  "error x wall / Mitsuba's"
for name in "${renderers[@]}"; do
  wall[$name]=$(cut -d' ' -f1 "$WORK/$name.txt" | median)
  err[$name]=$(cut -d' ' -f3 "$WORK/$name.txt" | median)
done
for name in "${renderers[@]}"; do
  ratio=- mratio=-
  if ((have_cycles)); then ratio=$(awk "BEGIN {printf \"%.3f\", ${wall[$name]} * ${err[$name]} / (${wall[cycles]} * ${err[cycles]})}"); fi
  if ((have_mitsuba)); then mratio=$(awk "BEGIN {printf \"%.3f\", ${wall[$name]} * ${err[$name]} / (${wall[mitsuba]} * ${err[mitsuba]})}"); fi
  printf '%-12s %-8.3f %-9.3f %-10.3e %-24s %s\n' "$name" "${wall[$name]}" "$(cut -d' ' -f2 "$WORK/$name.txt" | median)" \
    "${err[$name]}" "$ratio" "$mratio"
done
for name in "${renderers[@]}"; do echo "$name runs (wall render relmse): $(tr '\n' ';' < "$WORK/$name.txt")"; done
((SERIES)) || exit 0

echo
echo "== speed vs error, both samplers: $OUT/sampler-{sobol,independent}.csv, $OUT/sampler.png"
for name in sobol independent; do
  /usr/bin/python3 scripts/speed_vs_error.py run $CORNELL --csv "$OUT/sampler-$name.csv" --max-spp $SPP \
    --reference "$REFERENCE" --kdrender "$KDRENDER" --kdcompare "$KDCOMPARE" -- $VIEW --sampler "$name" > /dev/null
done
/usr/bin/python3 scripts/speed_vs_error.py plot "$OUT/sampler-sobol.csv" "$OUT/sampler-independent.csv" \
  -o "$OUT/sampler.png" --title "$SCENE 256x256, 8 bounces: sobol vs independent"
for name in sobol independent; do
  /usr/bin/python3 -c "
import csv, sys
rows = list(csv.DictReader(line for line in open(sys.argv[1]) if not line.startswith('#')))
print('$name: ' + ', '.join(f\"{r['spp']} spp {float(r['seconds']):.2f} s relMSE {float(r['relmse']):.3e}\" for r in rows))
" "$OUT/sampler-$name.csv"
done
