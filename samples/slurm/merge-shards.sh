#!/usr/bin/env bash
# The merge job of submit-render.sh: merges OUT.shard-0..SHARDS-1.exr into OUT.exr; kdrender
# checks they are ranges of one render covering samples 0..SPP-1 exactly.
#   merge-shards.sh KDRENDER OUT.exr SHARDS SPP
set -euo pipefail
kdrender=$1 out=$2 shards=$3 spp=$4
inputs=()
for ((k = 0; k < shards; ++k)); do inputs+=("${out%.exr}.shard-$k.exr"); done
exec "$kdrender" --merge "${inputs[@]}" -o "$out" --spp "$spp"
