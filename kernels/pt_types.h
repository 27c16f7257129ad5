/* Path-tracer structs shared between the host (librender) and the device, byte for byte.
 * Only kd_u32/kd_i32/float members and float[4] instead of float3 (16 bytes on devices): with
 * every member 4 bytes wide there is no padding, so the layout is the declaration order on both
 * sides. The KD_STATIC_ASSERTs, checked by the C++ compiler and by the kernel build, pin the sizes
 * and the offsets that a float3 or a reordered member would move. */
#ifndef PT_TYPES_H
#define PT_TYPES_H

#include "kd_compat.h"
#include "pt_codes.h"

/* alpha_cutoff: a ray passes where alpha < alpha_cutoff (glTF MASK; 0 for opaque materials), or,
 * when it is negative, with probability 1 - alpha (glTF BLEND). */
typedef struct PtMaterial {
  float base_color[3];
  kd_u32 type; /* PT_DIFFUSE... (pt_codes.h) */
  float emission[3];
  float roughness; /* GGX alpha */
  float ior;
  kd_i32 texture;  /* base colour (its alpha is alpha too): index into the PtTexture table or -1 */
  float metallic;
  float alpha;
  float alpha_cutoff;
  kd_i32 metal_rough_texture; /* linear; G scales sqrt(roughness), B metallic */
  kd_i32 normal_texture;      /* linear tangent-space normal map */
  kd_i32 emissive_texture;
} PtMaterial;
KD_STATIC_ASSERT(sizeof(PtMaterial) == 64 && KD_OFFSETOF(PtMaterial, type) == 12 &&
                     KD_OFFSETOF(PtMaterial, emission) == 16 && KD_OFFSETOF(PtMaterial, emissive_texture) == 60,
                 "PtMaterial: 64 bytes, members where the other side reads them");

/* Texels are linear RGBA float4 (decoded from sRGB on the host), rows top to bottom. */
typedef struct PtTexture {
  kd_u32 first_texel;
  kd_u32 width, height;
  kd_u32 pad;
} PtTexture;
KD_STATIC_ASSERT(sizeof(PtTexture) == 16 && KD_OFFSETOF(PtTexture, width) == 4 && KD_OFFSETOF(PtTexture, height) == 8,
                 "PtTexture: 16 bytes, members where the other side reads them");

/* One entry of the power-weighted emitter table: pick light i when cdf[i-1] <= u < cdf[i]. */
typedef struct PtLight {
  kd_u32 triangle;
  float cdf;
} PtLight;
KD_STATIC_ASSERT(sizeof(PtLight) == 8 && KD_OFFSETOF(PtLight, cdf) == 4,
                 "PtLight: 8 bytes, members where the other side reads them");

/* A punctual light (KD_FEATURE_PUNCTUAL), sampled by next-event estimation only. Point and spot
 * lights have an intensity in W/sr, directional lights an irradiance in W/m^2 (`power`). Spot cone:
 * full intensity within the inner half-angle, none outside the outer one, the glTF falloff between
 * (cos_inner, cos_outer hold the cosines). */
typedef struct PtPunctual {
  float position[3];
  kd_u32 type; /* PT_PUNCTUAL_* (pt_codes.h) */
  float direction[3]; /* unit, the way the light shines (spot, directional) */
  float cos_inner;
  float power[3];
  float cos_outer;
} PtPunctual;
KD_STATIC_ASSERT(sizeof(PtPunctual) == 48 && KD_OFFSETOF(PtPunctual, direction) == 16 &&
                     KD_OFFSETOF(PtPunctual, power) == 32 && KD_OFFSETOF(PtPunctual, cos_outer) == 44,
                 "PtPunctual: 48 bytes, members where the other side reads them");

typedef struct PtRenderParams {
  float cam_origin[4];
  float cam_forward[4]; /* unit */
  float cam_right[4];   /* scaled by tan(fov/2) * aspect; orthographic: by half the view's width */
  float cam_up[4];      /* scaled by tan(fov/2); orthographic: by half the view's height */
  float bounds_min[4];  /* root voxel of the k-d tree */
  float bounds_max[4];
  kd_u32 width, height;
  kd_u32 sample_offset, sample_count; /* this launch renders samples offset..offset+count-1 */
  kd_u32 seed;
  kd_u32 max_bounces;
  kd_u32 light_count;
  float light_area_pdf_scale; /* 1 / sum(luminance(Le) * area): area pdf = luminance(Le) * scale */
  kd_u32 aov_mask;      /* PT_AOV_* */
  kd_u32 film_channels; /* pt_film_channel_count(aov_mask) */
  kd_u32 sampler;       /* PT_SAMPLER_* (pt_codes.h) */
  kd_u32 env_width, env_height; /* KD_FEATURE_ENVIRONMENT: the map (kernels/pt_environment.h) */
  float env_rotate_cos, env_rotate_sin;
  /* Next-event estimation first picks a kind of light: emissive triangles, the environment or a
   * punctual light, with these probabilities (punctual: the rest). */
  float select_triangles, select_environment;
  kd_u32 punctual_count;
  float env_strength;
  kd_u32 features; /* PT_FEATURE_* (pt_codes.h) of the scene */
} PtRenderParams;
KD_STATIC_ASSERT(sizeof(PtRenderParams) == 176 && KD_OFFSETOF(PtRenderParams, width) == 96 &&
                     KD_OFFSETOF(PtRenderParams, sampler) == 136 && KD_OFFSETOF(PtRenderParams, features) == 172,
                 "PtRenderParams: 176 bytes, members where the other side reads them");

/* Whether the scene uses feature `bit` (PT_FEATURE_*, pt_codes.h) in code compiled under its
 * KD_FEATURE_* define. An OpenCL program is built for its scene's features, so there the answer is
 * always yes and costs nothing. The C++ build defines KD_ALL_FEATURES (and every KD_FEATURE_*) and
 * asks params: a part compiled in then does exactly what the kernel without it does wherever the
 * scene lacks the feature. The other KD_FEATURE_* parts need no bit: they act only on data the
 * scene has (a material's type, a texture index >= 0, a light count > 0). */
#ifdef KD_ALL_FEATURES
#define PT_USES(params, bit) (((params)->features & (bit)) != 0u)
#else
#define PT_USES(params, bit) 1
#endif

/* Bytes of one PtPath (kernels/pt_path_state.h, checked there): the host sizes wavefront buffers by it. */
#define PT_PATH_BYTES 176

#endif /* PT_TYPES_H */
