#!/bin/sh
# Materials of real assets (issue "Light real assets"), measured against Mitsuba 3 and the baseline:
#  1. samples/gltf_scene.py's glTF, lit by its point light, against Mitsuba 3 (bench/gltf_mitsuba.py,
#     a `point` emitter of the same W/sr): channel means, the all-metal variant (materials both
#     model alike) and the full scene (glTF plastics: kdray's coat against Mitsuba's roughplastic).
#  2. Mitsuba's roughplastic diffuse term against kdray's at several roughnesses (BSDF evaluations).
#  3. An emitter-only Cornell box: kernel options and render time against a baseline kdrender
#     (one that reads version 2 scenes), interleaved, medians of 5.
# usage: bench/materials.sh BUILD_DIR [BASELINE_BUILD_DIR] [MITSUBA_PYTHON]
set -eu
BUILD=$1
BASELINE=${2:-}
MITSUBA=${3:-/work/venv-mitsuba/bin/python}
HERE=$(cd "$(dirname "$0")" && pwd)
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
median() { sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
seconds() { grep render_seconds | grep -o '[0-9.]*'; }
SIZE="--width 96 --height 96 --spp 256 --max-bounces 8"

for variant in metal plastic; do
  flag=$([ $variant = metal ] && echo --metal || true)
  /usr/bin/python3 "$HERE/../samples/gltf_scene.py" "$WORK/$variant" $flag
  "$BUILD/tools/kdconvert/kdconvert" "$WORK/$variant/textured-scene.gltf" "$WORK/$variant.kdscene" > /dev/null
  "$BUILD/tools/kdbuild/kdbuild" "$WORK/$variant.kdscene" "$WORK/$variant.kdtree" > /dev/null
  "$BUILD/tools/kdrender/kdrender" "$WORK/$variant.kdscene" "$WORK/$variant.kdtree" -o "$WORK/$variant-kd.exr" $SIZE --quiet
  "$MITSUBA" "$HERE/gltf_mitsuba.py" "$WORK/$variant" "$WORK/$variant-mi.exr" $SIZE $flag > /dev/null
  echo "== glTF with a point light, $variant variant, 96x96, 256 spp, 8 bounces"
  for image in kd mi; do echo "$image: $(oiiotool --stats "$WORK/$variant-$image.exr" | grep 'Stats Avg' | head -1)"; done
done

echo "== roughplastic diffuse term: Mitsuba / kdray (rows: alpha; columns: theta_o 0.5, 30, 60, 80 deg, theta_i 0)"
"$MITSUBA" - <<'PY'
import math
import mitsuba as mi
mi.set_variant("scalar_rgb")
def fresnel(c, eta):
    s2 = (1 - c * c) / eta ** 2
    if s2 >= 1:
        return 1.0
    ct = math.sqrt(1 - s2)
    rs, rp = (c - eta * ct) / (c + eta * ct), (eta * c - ct) / (eta * c + ct)
    return 0.5 * (rs * rs + rp * rp)
def kdray_diffuse(ci, co, eta=1.5):  # kernels/pt_bsdf.h, pt_metal_rough_eval's base term, albedo 1
    x = 1 / eta
    fdr = -1.4399 * x * x + 0.7099 * x + 0.6681 + 0.0636 / x
    return ci / math.pi * (1 - fresnel(ci, eta)) * (1 - fresnel(co, eta)) / (eta * eta * (1 - fdr))
for alpha in (0.01, 0.09, 0.25, 0.49, 1.0):
    plastic = lambda d: mi.load_dict({"type": "roughplastic", "alpha": alpha, "distribution": "ggx", "nonlinear": False,
                                      "diffuse_reflectance": {"type": "rgb", "value": [d] * 3}})
    white, black = plastic(1.0), plastic(0.0)
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(0, 0, 1)
    si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
    row = []
    for degrees in (0.5, 30, 60, 80):
        t = math.radians(degrees)
        wo = mi.Vector3f(math.sin(t), 0, math.cos(t))
        diffuse = white.eval(mi.BSDFContext(), si, wo)[0] - black.eval(mi.BSDFContext(), si, wo)[0]
        row.append("%.3f" % (diffuse / kdray_diffuse(math.cos(t), 1.0)))
    print(alpha, " ".join(row))
PY

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
