#!/usr/bin/env bash
# Scene and tree ready to trace against reading both files: the whole kdtrace process with one
# ray (less the process's start, measured as `kdtrace --version`), against `cat` of both files to
# /dev/null (a read from the page cache into one small, reused buffer) and against a read of each
# file into a fresh buffer of its size (what any loader that does not map the file pays for the
# memory). Medians of $RUNS runs, interleaved; the files are read once before, so all come from
# the page cache. BASELINE=other/build adds that build's kdtrace to every run, with a tree that
# build's kdbuild wrote (the tree format may differ between the two).
#   BUILD=build RUNS=7 bench/tree_load.sh [MESH...]     (default: large/bunny_sub2.ply)
set -euo pipefail
. "$(dirname "$0")/common.sh"
runs="${RUNS:-7}"
baseline="${BASELINE:-}"
WORK="${WORK:-${TMPDIR:-/tmp}/kdray-bench-tree-load}"
mkdir -p "$WORK"
meshes=("$@")
[[ ${#meshes[@]} -gt 0 ]] || meshes=(large/bunny_sub2.ply)

# seconds COMMAND...: wall seconds of one run of COMMAND.
seconds() {
  local start end
  start=$(date +%s%N)
  "$@" > /dev/null
  end=$(date +%s%N)
  awk -v a="$start" -v b="$end" 'BEGIN {printf "%.4f\n", (b - a) / 1e9}'
}
# fresh_read FILE...: each file read into a buffer of its size, allocated for it.
fresh_read() { python3 -c 'import sys
for path in sys.argv[1:]:
    with open(path, "rb", buffering=0) as f: f.readall()' "$@"; }
median_of() { printf "%s\n" "$@" | median; }

machine_line
printf "%-14s %9s %9s %9s %9s %9s %9s %9s\n" mesh "MB" "ready s" "before s" "start s" "cat s" "fresh s" "ready/cat"
for mesh in "${meshes[@]}"; do
  name=$(basename "${mesh%.*}")
  readable_by "$BUILD" "$WORK/$name.kdtree" || scene_files "$(corpus_file "$mesh")" "$name"
  files=("$WORK/$name.kdscene" "$WORK/$name.kdtree")
  baseline_files=("$WORK/$name.kdscene" "$WORK/$name.baseline.kdtree")
  [[ -z "$baseline" ]] || readable_by "$baseline" "${baseline_files[1]}" ||
    "$baseline/tools/kdbuild/kdbuild" "${baseline_files[@]}" > /dev/null
  cat "${files[@]}" > /dev/null
  ready=() before=() start=() plain=() fresh=()
  for ((run = 0; run < runs; ++run)); do
    ready+=("$(seconds "$KDTRACE" "${files[@]}" --generate random --count 1 --quiet)")
    [[ -z "$baseline" ]] ||
      before+=("$(seconds "$baseline/tools/kdtrace/kdtrace" "${baseline_files[@]}" --generate random --count 1 --quiet)")
    start+=("$(seconds "$KDTRACE" --version)")
    plain+=("$(seconds cat "${files[@]}")")
    fresh+=("$(seconds fresh_read "${files[@]}")")
  done
  python_start=$(median_of "$(seconds python3 -c pass)" "$(seconds python3 -c pass)" "$(seconds python3 -c pass)")
  r=$(median_of "${ready[@]}") s=$(median_of "${start[@]}") c=$(median_of "${plain[@]}")
  f=$(awk -v a="$(median_of "${fresh[@]}")" -v b="$python_start" 'BEGIN {printf "%.4f", a - b}')
  b="-"
  [[ -z "$baseline" ]] || b=$(awk -v a="$(median_of "${before[@]}")" -v s="$s" 'BEGIN {printf "%.4f", a - s}')
  printf "%-14s %9.1f %9.4f %9s %9.4f %9.4f %9.4f %9.2f\n" "$name" "$(stat -c %s "${files[@]}" | awk '{s += $1} END {print s / 1e6}')" \
    "$(awk -v a="$r" -v s="$s" 'BEGIN {print a - s}')" "$b" "$s" "$c" "$f" \
    "$(awk -v a="$r" -v s="$s" -v c="$c" 'BEGIN {print (a - s) / c}')"
done
echo "# ready, before: kdtrace with one ray less the start; fresh: python reading each file whole, less python's start"
