#!/bin/sh
# Renders turntable.jobs in one kdrender process: converts the Cornell box with the bunny
# (bench/cornell_bunny.py --layout turntable), builds its tree, then all 36 frames into OUT (default ../out/turntable).
#   samples/turntable.sh [BUILD_DIR] [OUT_DIR] [kdrender options for every frame]
# The options default to --width 256 --height 256 --spp 64 --max-bounces 8; options given
# replace them all (e.g. --width 128 --height 128 --spp 16 --resume).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../build}" && pwd)
out=${2:-$here/../out/turntable}
[ $# -ge 2 ] && shift 2 || shift $#
mkdir -p "$out"
cd "$out"
[ -f cornell-bunny.kdscene ] || {
  "$here/../bench/cornell_bunny.py" . --layout turntable > /dev/null
  "$build/tools/kdconvert/kdconvert" cornell-bunny.obj cornell-bunny.kdscene --quiet
}
[ -f cornell-bunny.kdtree ] || "$build/tools/kdbuild/kdbuild" cornell-bunny.kdscene cornell-bunny.kdtree --quiet
[ $# -gt 0 ] || set -- --width 256 --height 256 --spp 64 --max-bounces 8
exec "$build/tools/kdrender/kdrender" cornell-bunny.kdscene cornell-bunny.kdtree --jobs "$here/turntable.jobs" "$@"
