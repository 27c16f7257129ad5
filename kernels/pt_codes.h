/* Numberings and constants that the scene model (libscene), the renderer (librender) and the
 * kernels agree on. Each is defined once here; the C++ enums take their values from these macros,
 * so a code cannot mean one thing on the host and another on the device. */
#ifndef PT_CODES_H
#define PT_CODES_H

#include "kd_compat.h"

/* Material kinds: PtMaterial::type, kdray::MaterialType and the .kdscene material records. */
#define PT_DIFFUSE 0u
#define PT_EMISSIVE 1u
#define PT_MIRROR 2u
#define PT_ROUGH_CONDUCTOR 3u
#define PT_DIELECTRIC 4u
#define PT_METALLIC_ROUGHNESS 5u

/* Punctual light kinds: PtPunctual::type and kdray::LightType. */
#define PT_PUNCTUAL_POINT 0u
#define PT_PUNCTUAL_SPOT 1u
#define PT_PUNCTUAL_DIRECTIONAL 2u

/* Samplers (kernels/pt_rng.h): PtRenderParams::sampler and kdray::Sampler. */
#define PT_SAMPLER_SOBOL 0u
#define PT_SAMPLER_INDEPENDENT 1u

/* Film channel layout: PT_RADIANCE_CHANNELS radiance sums, then each enabled AOV in the order
 * of its bit (albedo RGB, normal XYZ, depth). */
#define PT_RADIANCE_CHANNELS 3u
#define PT_AOV_ALBEDO 1u
#define PT_AOV_NORMAL 2u
#define PT_AOV_DEPTH 4u
#define PT_AOV_ALBEDO_CHANNELS 3u
#define PT_AOV_NORMAL_CHANNELS 3u
#define PT_AOV_DEPTH_CHANNELS 1u
#define PT_MAX_FILM_CHANNELS 10

KD_INLINE kd_u32 pt_film_channel_count(kd_u32 aov_mask) {
  return PT_RADIANCE_CHANNELS + ((aov_mask & PT_AOV_ALBEDO) ? PT_AOV_ALBEDO_CHANNELS : 0u) +
         ((aov_mask & PT_AOV_NORMAL) ? PT_AOV_NORMAL_CHANNELS : 0u) +
         ((aov_mask & PT_AOV_DEPTH) ? PT_AOV_DEPTH_CHANNELS : 0u);
}
KD_STATIC_ASSERT(PT_RADIANCE_CHANNELS + PT_AOV_ALBEDO_CHANNELS + PT_AOV_NORMAL_CHANNELS + PT_AOV_DEPTH_CHANNELS ==
                     PT_MAX_FILM_CHANNELS,
                 "PT_MAX_FILM_CHANNELS holds every channel");

/* Scene features: bits of PtRenderParams::features, and the KD_FEATURE_* defines of the same names
 * (librender's kernel_feature_bits picks them). An OpenCL program is built with the defines of its
 * scene's features only, so what a scene lacks is compiled out. The C++ build
 * (librender/src/render_host_pixels.cpp) compiles every feature in and reads these bits where a part
 * compiled in would otherwise run without the data it needs (PT_USES: kernels/pt_path.h and the
 * files it includes). */
#define PT_FEATURE_EMISSION (1u << 0)
#define PT_FEATURE_MIRROR (1u << 1)
#define PT_FEATURE_GLOSSY (1u << 2)
#define PT_FEATURE_GLASS (1u << 3)
#define PT_FEATURE_METALLIC_ROUGHNESS (1u << 4)
#define PT_FEATURE_ALPHA (1u << 5)
#define PT_FEATURE_TEXTURES (1u << 6)
#define PT_FEATURE_METAL_ROUGH_TEXTURE (1u << 7)
#define PT_FEATURE_NORMAL_MAP (1u << 8)
#define PT_FEATURE_EMISSIVE_TEXTURE (1u << 9)
#define PT_FEATURE_NORMALS (1u << 10)
#define PT_FEATURE_ENVIRONMENT (1u << 11)
#define PT_FEATURE_PUNCTUAL (1u << 12)
/* Not a feature but a test switch (KD_MIS_OFF): light samples at full weight, no MIS. */
#define PT_FEATURE_MIS_OFF (1u << 13)
#define PT_FEATURE_ORTHOGRAPHIC (1u << 14)

/* Fixed-point accumulation: every sample value is rounded to a multiple of 2^-PT_FIXED_BITS and
 * summed as int64, so the sum of a sample range does not depend on the order of the additions and
 * ranges rendered apart merge exactly. Values are clamped to +-PT_FIXED_MAX first. */
#define PT_FIXED_BITS 20
#define PT_FIXED_MAX 16777216.0f

#endif /* PT_CODES_H */
