// The host renderer's inner loop (render_host_pixels.h), compiled twice from this one file: as
// is, and with KDRAY_HOST_PIXELS_X86_64_V3 defined and -march=x86-64-v3 (librender/CMakeLists.txt),
// where it also renders 8 paths at a time in AVX2 lanes for the scenes path_lanes.h can.
//
// Features. An OpenCL program is built for its scene's feature set (KD_FEATURE_*), which keeps
// PoCL's compile short and the kernel small. Here the integrator is compiled with every feature
// in (KD_ALL_FEATURES) rather than in up to 2^14 variants: each KD_FEATURE_* part either acts
// only on data the scene has (a material's type, a texture index >= 0, a light count) or asks
// the scene's feature bits (PT_USES, kernels/pt_types.h), so where a feature is absent it does
// what the kernel built without it does, operation for operation. The MIS switch (KD_MIS_OFF)
// is compiled in and read from the bits the same way. tests/render/cpu_integrator_*_test.cpp
// check the films against kernels of different feature sets bit for bit.
//
// Compiled with -ffp-contract=off (librender/CMakeLists.txt), as the kernels are (kd_compat.h).
#define KD_ALL_FEATURES
#define KD_FEATURE_EMISSION
#define KD_FEATURE_MIRROR
#define KD_FEATURE_GLOSSY
#define KD_FEATURE_GLASS
#define KD_FEATURE_METALLIC_ROUGHNESS
#define KD_FEATURE_ALPHA
#define KD_FEATURE_TEXTURES
#define KD_FEATURE_METAL_ROUGH_TEXTURE
#define KD_FEATURE_NORMAL_MAP
#define KD_FEATURE_EMISSIVE_TEXTURE
#define KD_FEATURE_NORMALS
#define KD_FEATURE_ENVIRONMENT
#define KD_FEATURE_PUNCTUAL
#define KD_FEATURE_ORTHOGRAPHIC
#define KD_MIS_OFF  // a switch, asked of the scene's bits as the features are
#ifdef KDRAY_HOST_PIXELS_X86_64_V3
#define PT_BOUNCE_BITS_IN_LANES  // one AVX2 register holds a bounce's first 8 sample values
#endif

#include "render_host_pixels.h"

#include <kdray/traverse.h>  // the packets of path_lanes.h

#include <algorithm>  // path_lanes.h's batch
#include <cstring>
#include <memory>
#include <utility>

#include <kernels/kd_vector.h>

#ifdef __AVX2__
#include <immintrin.h>  // for kernels/pt_rng.h, outside the namespace below
#endif

// The device code, in this file's own namespace: no other file compiles it with these defines.
namespace {
#include <kernels/pt_path.h>
#ifdef KDRAY_HOST_PIXELS_X86_64_V3
#include "path_lanes.h"
#endif
}  // namespace

namespace kdray {
#ifdef KDRAY_HOST_PIXELS_X86_64_V3
namespace host_pixels_x86_64_v3 {
#else
namespace host_pixels_generic {
#endif

namespace {
// The scene's arrays as the device code reads them (`params` is the name PT_MAKE_SCENE reads).
PtSceneData scene_data(const SceneArrays& arrays, const PtRenderParams* params) {
#define KD_HOST_GEOMETRY(type, name) const type* name = static_cast<const type*>(arrays.geometry.name.data);
#define KD_HOST_SHADING(type, name) const type* name = static_cast<const type*>(arrays.name.data);
  PT_SCENE_BUFFERS(KD_HOST_GEOMETRY, KD_HOST_SHADING)
#undef KD_HOST_GEOMETRY
#undef KD_HOST_SHADING
  return PT_MAKE_SCENE();
}
}  // namespace

uint64_t render_pixels(const SceneArrays& arrays, const PtRenderParams& pass, uint32_t begin, uint32_t end,
                       int64_t* film, uint32_t* nonfinite) {
  const PtRenderParams* params = &pass;
  const PtSceneData scene = scene_data(arrays, params);
  uint64_t rays = 0;
  for (uint32_t pixel = begin; pixel != end; ++pixel) rays += pt_render_pixel(&scene, params, pixel, film, nonfinite);
  return rays;
}

#ifdef KDRAY_HOST_PIXELS_X86_64_V3
bool paths_in_lanes_apply(size_t gathered_floats) {
  return path_lanes::apply(gathered_floats);
}

uint64_t render_pixels_in_lanes(const SceneArrays& arrays, const PtRenderParams& pass, uint32_t begin, uint32_t end,
                                int64_t* film, uint32_t* nonfinite) {
  const PtSceneData scene = scene_data(arrays, &pass);
  return path_lanes::render(&scene, &pass, begin, end, film, nonfinite);
}
#endif

}  // namespace host_pixels_generic or host_pixels_x86_64_v3
}  // namespace kdray
