#!/usr/bin/env bash
# One array task of submit-render.sh: renders shard $SLURM_ARRAY_TASK_ID of SHARDS, the samples
# of SPP that fall to it (the first SPP % SHARDS shards take one sample more), into OUT.shard-K.exr.
#   render-shard.sh KDRENDER SCENE TREE OUT.exr SHARDS SPP [kdrender options...]
# TREE is a .kdtree or a tree cache folder (kdbuild --cache), where the task finds the tree.
set -euo pipefail
kdrender=$1 scene=$2 tree=$3 out=$4 shards=$5 spp=$6
shift 6
k=${SLURM_ARRAY_TASK_ID:?render-shard.sh runs as a Slurm array task}
base=$((spp / shards)) extra=$((spp % shards))
count=$((base + (k < extra ? 1 : 0)))
offset=$((k * base + (k < extra ? k : extra)))
if [ -d "$tree" ]; then tree_args=(--cache "$tree"); else tree_args=("$tree"); fi
exec "$kdrender" "$scene" "${tree_args[@]}" -o "${out%.exr}.shard-$k.exr" --spp "$count" --sample-offset "$offset" --quiet "$@"
