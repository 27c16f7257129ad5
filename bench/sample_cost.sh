#!/usr/bin/env bash
# Cost of one sample on each CPU path of kdrender, on the Cornell box sample (256x256, 8 bounces,
# 2 threads): the slope of whole-process wall time between LOW and HIGH samples per pixel, so
# process start, scene load and kernel build drop out. Every path renders the same seed, and the
# films of the paths are compared (kdcompare, max abs difference; bit-identical paths give 0).
# Runs are interleaved across the paths (the machine may be shared), RUNS runs each.
# usage: [RUNS=3] [LOW=32] [HIGH=128] [PATHS="megakernel wavefront host"] bench/sample_cost.sh [BUILD_DIR]
# A path is one of: megakernel (PoCL), wavefront (PoCL, --wavefront), host (--device host
# --threads 2). Besides the wall times, the processes' CPU seconds (user + system), which a shared
# machine disturbs less.
set -euo pipefail
BUILD=$(realpath "${1:-build}")
. "$(dirname "$0")/common.sh"
RUNS=${RUNS:-3} LOW=${LOW:-32} HIGH=${HIGH:-128}
PATHS=${PATHS:-megakernel wavefront host}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
export KDRAY_CACHE_DIR=$WORK/kdray-cache POCL_CACHE_DIR=$WORK/pocl-cache
machine_line
scene_files "$ROOT/samples/cornell-box.obj" cornell
VIEW="--cam-pos 278,273,-800 --cam-target 278,273,0 --fov 39.3077"
SIZE="--width 256 --height 256 --max-bounces 8"

path_options() {
  case $1 in
    megakernel) echo "--device cpu" ;;
    wavefront) echo "--device cpu --wavefront" ;;
    host) echo "--device host --threads 2" ;;
    *) echo "sample_cost.sh: error: unknown path '$1'" >&2 && exit 2 ;;
  esac
}
for path in $PATHS; do  # warm the program caches
  "$KDRENDER" "$WORK/cornell.kdscene" "$WORK/cornell.kdtree" -o "$WORK/warm.exr" $VIEW --width 8 --height 8 --spp 1 \
    $(path_options "$path") -q
done
now() { date +%s.%N; }
for run in $(seq "$RUNS"); do
  for spp in $LOW $HIGH; do
    for path in $PATHS; do
      start=$(now)
      /usr/bin/time -f "%U %S" -o "$WORK/cpu" "$KDRENDER" "$WORK/cornell.kdscene" "$WORK/cornell.kdtree" \
        -o "$WORK/$path-$spp.exr" $VIEW $SIZE --spp "$spp" --seed 1 $(path_options "$path") --json > "$WORK/$path-$spp.json"
      echo "$(awk "BEGIN {print $(now) - $start}")" >> "$WORK/$path-$spp.walls"
      awk '{print $1 + $2}' "$WORK/cpu" >> "$WORK/$path-$spp.cpus"
    done
  done
  echo "run $run done, load average $(cut -d' ' -f1-3 /proc/loadavg)"
done
printf '%-12s %-10s %-10s %-12s %-14s %s\n' path "${LOW}spp_s" "${HIGH}spp_s" s_per_spp cpu_s_per_spp \
  "wall runs ($LOW; $HIGH)"
for path in $PATHS; do
  low=$(median < "$WORK/$path-$LOW.walls") high=$(median < "$WORK/$path-$HIGH.walls")
  cpu_low=$(median < "$WORK/$path-$LOW.cpus") cpu_high=$(median < "$WORK/$path-$HIGH.cpus")
  printf '%-12s %-10.3f %-10.3f %-12.4f %-14.4f %s; %s\n' "$path" "$low" "$high" \
    "$(awk "BEGIN {print ($high - $low) / ($HIGH - $LOW)}")" \
    "$(awk "BEGIN {print ($cpu_high - $cpu_low) / ($HIGH - $LOW)}")" "$(tr '\n' ' ' < "$WORK/$path-$LOW.walls")" \
    "$(tr '\n' ' ' < "$WORK/$path-$HIGH.walls")"
done
first=${PATHS%% *}
for path in $PATHS; do
  echo "$path: form $(json_field form < "$WORK/$path-$HIGH.json"), device $(json_field device < "$WORK/$path-$HIGH.json")," \
    "max abs difference from $first at $HIGH spp:" \
    "$("$KDCOMPARE" "$WORK/$path-$HIGH.exr" "$WORK/$first-$HIGH.exr" --json | json_field max_abs)"
done
