#!/bin/sh
# Writes OUT.obj (and cornell-box.mtl beside it): the Cornell box of cornell-box.obj without its
# two blocks, and the corpus's Stanford bunny (69,451 triangles) standing on the middle of its
# floor, scaled 1500x (about 230 mm tall) in the white paint. The scene of the batch benchmark
# (bench/batch.sh) and of the turntable (turntable.sh).
#   samples/cornell-bunny.sh OUT.obj [CORPUS_DIR]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
out=${1:?usage: cornell-bunny.sh OUT.obj [CORPUS_DIR]}
corpus=${2:-$here/../../shared/corpus}
bunny=$corpus/bunny/stanford-bunny.obj
[ -f "$bunny" ] || { echo "cornell-bunny.sh: error: $bunny: no such file" >&2; exit 1; }
cp "$here/cornell-box.mtl" "$(dirname "$out")/"
# The bunny's bounds in the corpus file: x -0.0947..0.0610, y 0.0330..0.1873, z -0.0619..0.0588;
# its base goes to y = 0 and its middle to x = 278, z = 280.
awk -v scale=1500 -v dx=278 -v dy=0 -v dz=280 '
  FNR == NR {
    if ($1 == "o" && $2 == "short_block") { skipping = 1 }   # the blocks come last in the file
    if (!skipping) { print; if ($1 == "v") box_vertices++ }
    next
  }
  FNR == 1 { print "\no bunny\nusemtl white" }
  $1 == "v" {
    printf "v %.4f %.4f %.4f\n", ($2 + 0.01684) * scale + dx, ($3 - 0.032987) * scale + dy, ($4 + 0.00154) * scale + dz
  }
  $1 == "f" { printf "f %d %d %d\n", $2 + box_vertices, $3 + box_vertices, $4 + box_vertices }
' "$here/cornell-box.obj" "$bunny" > "$out.tmp"
mv "$out.tmp" "$out"
