#!/bin/sh
# Materials of real assets (glTF, textures, punctual lights), measured against Mitsuba 3 and the baseline:
#  1. samples/gltf_scene.py's glTF, lit by its point light, against Mitsuba 3 (bench/gltf_mitsuba.py,
#     a `point` emitter of the same W/sr): channel means, whole image and per material, of the
#     all-metal variant, the scene as authored (glTF plastics: kdray's glTF BRDF against Mitsuba's
#     roughplastic, different models, so only the metal variant is meant to agree) and the authored
#     scene without its normal map.
#  2. An emitter-only Cornell box: kernel options and render time against a baseline kdrender
#     (one that reads version 2 scenes), interleaved, medians of 5.
# usage: bench/materials.sh BUILD_DIR [BASELINE_BUILD_DIR] [MITSUBA_PYTHON]
set -eu
BUILD=$1
BASELINE=${2:-}
HERE=$(cd "$(dirname "$0")" && pwd)
. "$HERE/common.sh"
MITSUBA=${3:-$MITSUBA_PYTHON}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
seconds() { grep render_seconds | grep -o '[0-9.]*'; }
SIZE="--width 96 --height 96 --spp 256 --max-bounces 8"

# The flat variant is the authored scene without its one normal map (the ridged box's), made from
# copies of the two scene scripts: it tells the plastics' agreement from the normal map's.
mkdir -p "$WORK/flat/bench" "$WORK/flat/samples"
cp "$HERE/gltf_mitsuba.py" "$WORK/flat/bench/"
sed 's/, "normal_texture": "ridges.png"}/}/' "$HERE/../samples/gltf_scene.py" > "$WORK/flat/samples/gltf_scene.py"
if grep -q 'normal_texture.*ridges' "$WORK/flat/samples/gltf_scene.py"; then
  echo "materials.sh: the ridged box's normal map is no longer where the flat variant removes it" >&2
  exit 1
fi
for variant in metal plastic flat; do
  flag=$([ $variant = metal ] && echo --metal || true)
  dir=$([ $variant = flat ] && echo "$WORK/flat" || echo "$HERE/..")
  /usr/bin/python3 "$dir/samples/gltf_scene.py" "$WORK/$variant" $flag
  "$BUILD/tools/kdconvert/kdconvert" "$WORK/$variant/textured-scene.gltf" "$WORK/$variant.kdscene" > /dev/null
  "$BUILD/tools/kdbuild/kdbuild" "$WORK/$variant.kdscene" "$WORK/$variant.kdtree" > /dev/null
  "$BUILD/tools/kdrender/kdrender" "$WORK/$variant.kdscene" "$WORK/$variant.kdtree" -o "$WORK/$variant-kd.exr" $SIZE --aov albedo --quiet
  "$MITSUBA" "$dir/bench/gltf_mitsuba.py" "$WORK/$variant" "$WORK/$variant-mi.exr" $SIZE $flag > /dev/null
  echo "== glTF with a point light, $variant variant, 96x96, 256 spp, 8 bounces: channel means, kdray / Mitsuba"
  # Per material: pixels grouped by kdray's first-hit albedo (rounded), the largest groups.
  "$MITSUBA" - "$WORK/$variant-kd.exr" "$WORK/$variant-mi.exr" <<'PY'
import sys
import numpy as np
import mitsuba as mi
mi.set_variant("scalar_rgb")
kd, ref = np.array(mi.Bitmap(sys.argv[1])), np.array(mi.Bitmap(sys.argv[2]))[:, :, :3]
image, albedo = kd[:, :, :3], kd[:, :, 3:6]
print("kdray   %.6f %.6f %.6f" % tuple(image.mean((0, 1))))
print("Mitsuba %.6f %.6f %.6f" % tuple(ref.mean((0, 1))))
print("ratio   %.4f %.4f %.4f" % tuple(image.mean((0, 1)) / ref.mean((0, 1))))
groups = {}
for y, x in np.ndindex(albedo.shape[:2]):
    groups.setdefault(tuple(np.round(albedo[y, x], 1)), []).append((y, x))
for key, pixels in sorted(groups.items(), key=lambda g: -len(g[1]))[:7]:
    ys, xs = map(list, zip(*pixels))
    if ref[ys, xs].sum() > 0:
        print("  albedo %.1f %.1f %.1f, %4d pixels: ratio %.4f %.4f %.4f" % (key + (len(pixels),) + tuple(image[ys, xs].sum(0) / ref[ys, xs].sum(0))))
PY
done

echo "== emitter-only Cornell box, 128x128, 32 spp: kernel options and render seconds (medians of 5, interleaved)"
VIEW="--cam-pos 278,273,-800 --cam-target 278,273,0 --cam-up 0,1,0 --fov 39.3077 --width 128 --height 128 --spp 32 --max-bounces 8"
"$BUILD/tools/kdconvert/kdconvert" "$HERE/../samples/cornell-box.obj" "$WORK/cb.kdscene" > /dev/null
"$BUILD/tools/kdbuild/kdbuild" "$WORK/cb.kdscene" "$WORK/cb.kdtree" > /dev/null
"$BUILD/tools/kdrender/kdrender" "$WORK/cb.kdscene" "$WORK/cb.kdtree" -o "$WORK/cb.exr" $VIEW --json | grep kernel_options
if [ -n "$BASELINE" ]; then
  "$BASELINE/tools/kdconvert/kdconvert" "$HERE/../samples/cornell-box.obj" "$WORK/cb-base.kdscene" > /dev/null
  "$BASELINE/tools/kdbuild/kdbuild" "$WORK/cb-base.kdscene" "$WORK/cb-base.kdtree" > /dev/null
  "$BASELINE/tools/kdrender/kdrender" "$WORK/cb-base.kdscene" "$WORK/cb-base.kdtree" -o "$WORK/cb-base.exr" $VIEW --json | grep kernel_options
  : > "$WORK/a"; : > "$WORK/b"
  for i in 1 2 3 4 5; do
    "$BASELINE/tools/kdrender/kdrender" "$WORK/cb-base.kdscene" "$WORK/cb-base.kdtree" -o "$WORK/cb-base.exr" $VIEW --json | seconds >> "$WORK/a"
    "$BUILD/tools/kdrender/kdrender" "$WORK/cb.kdscene" "$WORK/cb.kdtree" -o "$WORK/cb.exr" $VIEW --json | seconds >> "$WORK/b"
  done
  echo "baseline $(median < "$WORK/a") s, this build $(median < "$WORK/b") s"
  for image in cb-base cb; do echo "$image: $(oiiotool --stats "$WORK/$image.exr" | grep 'Stats Avg' | head -1)"; done
fi
