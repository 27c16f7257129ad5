// kernels/pt_path.h compiled as C++ for the host renderers (render_host.cpp, one path at a time;
// render_lanes.cpp, packets of paths), in the including file's anonymous namespace: no other file
// compiles it with these defines. Include it once, after anything the file hooks into the
// device code (PT_GIVEN_BOUNCE_BITS).
//
// Features. An OpenCL program is built for its scene's feature set (KD_FEATURE_*), which keeps
// PoCL's compile short and the kernel small. Here the integrator is compiled once with every
// feature in (KD_ALL_FEATURES) rather than in up to 2^14 variants: each KD_FEATURE_* part either
// acts only on data the scene has (a material's type, a texture index >= 0, a light count) or
// asks the scene's feature bits (PT_USES, kernels/pt_types.h), so where a feature is absent it
// does what the kernel built without it does, operation for operation. The MIS switch (KD_MIS_OFF)
// is compiled in and read from the bits the same way. tests/render/cpu_integrator_*_test.cpp
// check the films against kernels of different feature sets bit for bit.
//
// The files that include it are compiled with -ffp-contract=off (librender/CMakeLists.txt), as
// the kernels are (kd_compat.h).
#pragma once

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
#define KD_EMPTY_LEAF_NODES  // as the megakernel: the same hits, fewer node fetches

#include "scene_arrays.h"

#include <kernels/kd_types.h>
#include <kernels/kd_vector.h>
#include <kernels/pt_types.h>

namespace {
#include <kernels/pt_path.h>

// The device code's view of the scene arrays, as a kernel makes it from its arguments.
inline PtSceneData make_scene(const kdray::SceneArrays& arrays, const PtRenderParams* params) {
#define KD_HOST_GEOMETRY(type, name) const type* name = static_cast<const type*>(arrays.geometry.name.data);
#define KD_HOST_SHADING(type, name) const type* name = static_cast<const type*>(arrays.name.data);
  PT_SCENE_BUFFERS(KD_HOST_GEOMETRY, KD_HOST_SHADING)
#undef KD_HOST_GEOMETRY
#undef KD_HOST_SHADING
  return PT_MAKE_SCENE();
}
}  // namespace
