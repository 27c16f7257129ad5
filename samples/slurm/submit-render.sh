#!/usr/bin/env bash
# Submits a sharded kdrender to Slurm: a job array with one task per sample range
# (render-shard.sh), and a merge job (merge-shards.sh) that runs when every task succeeded and
# merges the shards exactly into OUT.exr (kdrender --merge refuses missing or foreign shards).
# SCENE, TREE and OUT must be on storage every node sees; TREE is a .kdtree or a tree cache folder
# (kdbuild --cache DIR SCENE fills it once; each task then finds the tree there by the scene's
# geometry). Prints the array's and the merge job's ids.
#
#   submit-render.sh SCENE TREE OUT.exr SHARDS SPP [kdrender options for every shard...]
#   submit-render.sh /shared/s.kdscene /shared/tree-cache /shared/out/s.exr 16 1024 --width 1920 --height 1080
#
# Environment: KDRENDER (default: kdrender on PATH); SBATCH_OPTIONS, extra sbatch options for
# both jobs (partition, account, time limit, ...).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
if [ $# -lt 5 ]; then
  sed -n '2,14p' "$0" >&2
  exit 2
fi
scene=$(realpath "$1") tree=$(realpath "$2") out=$(realpath -m "$3") shards=$4 spp=$5
shift 5
case "$shards$spp" in *[!0-9]*) echo "submit-render.sh: error: SHARDS and SPP must be numbers" >&2; exit 2 ;; esac
if [ "$shards" -lt 1 ] || [ "$spp" -lt "$shards" ]; then
  echo "submit-render.sh: error: need 1 <= SHARDS <= SPP (got $shards shards of $spp samples)" >&2
  exit 2
fi
kdrender=$(command -v "${KDRENDER:-kdrender}") || { echo "submit-render.sh: error: no kdrender (set KDRENDER)" >&2; exit 1; }
logs=$out.logs
mkdir -p "$logs"
# shellcheck disable=SC2086  # SBATCH_OPTIONS is a list of options
array=$(sbatch --parsable ${SBATCH_OPTIONS:-} --job-name=kdray-shards --array=0-$((shards - 1)) \
  --output="$logs/shard-%a.log" "$here/render-shard.sh" "$kdrender" "$scene" "$tree" "$out" "$shards" "$spp" "$@")
array=${array%%;*}
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_OPTIONS:-} --job-name=kdray-merge --dependency=afterok:"$array" --kill-on-invalid-dep=yes \
  --output="$logs/merge.log" "$here/merge-shards.sh" "$kdrender" "$out" "$shards" "$spp")
merge=${merge%%;*}
echo "array $array merge $merge"
