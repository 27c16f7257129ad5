/* What every step of a path shares: the scene's buffers (PtSceneData, made from the kernel
 * arguments), one path's state (PtPath), its sample values and rays, and its start at the camera.
 * Direct lighting (kernels/pt_direct_light.h), film accumulation (kernels/pt_film.h) and
 * shading (kernels/pt_path.h) build on it. */
#ifndef PT_PATH_STATE_H
#define PT_PATH_STATE_H

#include "kd_traverse.h"
#include "pt_material.h"
#include "pt_rng.h"
#include "pt_scene_args.h"
#include "pt_types.h"

typedef struct PtSceneData {
  KdSceneView kd;
  KD_GLOBAL const float* triangle_vertices; /* KD_TRIANGLE_FLOATS per triangle: shading positions */
  KD_GLOBAL const kd_u32* indices;  /* 3 per triangle: vertex numbers of normals and uvs */
  KD_GLOBAL const kd_u32* material_ids;
  KD_GLOBAL const PtMaterial* materials;
  KD_GLOBAL const float* normals;  /* KD_FEATURE_NORMALS */
  KD_GLOBAL const float* uvs;      /* KD_FEATURE_TEXTURES */
  KD_GLOBAL const float* tangents; /* KD_FEATURE_NORMAL_MAP: x, y, z, w per vertex */
  KD_GLOBAL const PtTexture* textures;
  KD_GLOBAL const float4* texels;
  KD_GLOBAL const PtLight* lights;
  KD_GLOBAL const kd_u32* light_guide; /* pt_pick_light's (kernels/pt_sampling.h) */
  KD_GLOBAL const float* env_texels;    /* KD_FEATURE_ENVIRONMENT: RGB (kernels/pt_environment.h) */
  KD_GLOBAL const float* env_cdf;
  KD_GLOBAL const PtPunctual* punctuals; /* KD_FEATURE_PUNCTUAL */
} PtSceneData;

/* The argument list every path-tracing kernel starts with (kernels/pt_scene_args.h), and the one
 * place a PtSceneData is made from it: by the kernels, and by the C++ build from the same
 * buffers' contents. */
#define PT_SCENE_ARG(type, name) KD_GLOBAL const type *name,
#define PT_SCENE_ARGS PT_SCENE_BUFFERS(PT_SCENE_ARG, PT_SCENE_ARG) KD_GLOBAL const PtRenderParams *params
#define PT_SCENE_ARG_NAME(type, name) name,

KD_INLINE PtSceneData pt_make_scene(PT_SCENE_ARGS) {
  PtSceneData scene;
  scene.kd = kd_scene_view(nodes, leaf_blocks, params->bounds_min[0], params->bounds_min[1],
                           params->bounds_min[2], params->bounds_max[0], params->bounds_max[1], params->bounds_max[2]);
  /* Every shading buffer is the scene field of its own name. */
#define PT_SCENE_SKIP(type, name)
#define PT_SCENE_SET(type, name) scene.name = name;
  PT_SCENE_BUFFERS(PT_SCENE_SKIP, PT_SCENE_SET)
#undef PT_SCENE_SET
#undef PT_SCENE_SKIP
  return scene;
}
#define PT_MAKE_SCENE() pt_make_scene(PT_SCENE_BUFFERS(PT_SCENE_ARG_NAME, PT_SCENE_ARG_NAME) params)

typedef struct PtPath {
  float3 origin, direction;
  float3 throughput, radiance;
  float3 shadow_origin, shadow_span; /* shadow ray: origin + t * span, 0 < t < 1 */
  float3 shadow_contribution;
  float3 albedo, normal;             /* first-hit AOVs */
  float depth;
  float bsdf_pdf;                    /* pdf of the last BSDF sample, 0 after a delta lobe */
  kd_u32 pixel, sample, bounce;
  kd_u32 sample_hash;                /* pt_sample_hash of (pixel, sample): shared by its values */
  kd_i32 alive, shadow_pending;
} PtPath;
KD_STATIC_ASSERT(sizeof(PtPath) == PT_PATH_BYTES, "PT_PATH_BYTES is the size of PtPath");

/* Corner 0, 1 or 2 of a triangle, from the per-triangle copy of its corners. */
KD_INLINE float3 pt_corner(KD_GLOBAL const float* triangle_vertices, uint triangle, uint corner) {
  return vload3(corner, triangle_vertices + KD_TRIANGLE_FLOATS * triangle);
}

KD_INLINE RayRecord pt_ray(float3 origin, float3 direction, float tmax) {
  RayRecord ray = {origin.x, origin.y, origin.z, direction.x, direction.y, direction.z, 0.0f, tmax};
  return ray;
}
/* The sample values of the path's current bounce (kernels/pt_rng.h), read by PT_DIM_*: one value,
 * or both values of the pair starting at an even one. */
KD_INLINE PtBounceSamples pt_path_samples(const PtPath* path, KD_GLOBAL const PtRenderParams* params) {
  return pt_bounce_samples(params->sampler, path->sample_hash, path->sample, PT_BOUNCE_DIMS(path->bounce));
}
KD_INLINE float pt_bounce_sample(const PtBounceSamples* samples, uint dim) {
  return pt_bits_to_unit(pt_bounce_bits(samples, dim));
}
KD_INLINE float2 pt_bounce_sample2(const PtBounceSamples* samples, uint dim) {
  PtBits2 bits = pt_bounce_bits2(samples, dim);
  return KD_FLOAT2(pt_bits_to_unit(bits.x), pt_bits_to_unit(bits.y));
}

KD_INLINE RayRecord pt_path_ray(const PtPath* path) { return pt_ray(path->origin, path->direction, INFINITY); }
KD_INLINE RayRecord pt_shadow_ray(const PtPath* path) { return pt_ray(path->shadow_origin, path->shadow_span, 1.0f); }

#ifdef KD_FEATURE_ALPHA
/* A number of the path's current bounce for hashing alpha decisions (kernels/pt_material.h). */
KD_INLINE uint pt_path_key(const PtPath* path, KD_GLOBAL const PtRenderParams* params) {
  return pt_hash32(params->seed ^ pt_hash32(path->pixel ^ pt_hash32(path->sample ^ pt_hash32(path->bounce))));
}
#define PT_MAX_ALPHA_LAYERS 64
#endif

/* The camera's film point of a sample at (px, py) in pixels (the pixel's corner plus the
 * sample's jitter), as sx, sy in [-1, 1] across the film, and the perspective camera's ray
 * direction through it: lane functions, written once for one path and for the host's lanes
 * (librender/src/path_lanes.h). */
KD_LANE_FN void pt_film_point(KD_GLOBAL const PtRenderParams* params, kd_lane px, kd_lane py, kd_lane* sx, kd_lane* sy) {
  *sx = 2.0f * px / (float)params->width - 1.0f;
  *sy = 1.0f - 2.0f * py / (float)params->height;
}
KD_LANE_FN kd_lane3 pt_perspective_direction(KD_GLOBAL const PtRenderParams* params, kd_lane sx, kd_lane sy) {
  const kd_lane3 forward = KD_LANE3(params->cam_forward[0], params->cam_forward[1], params->cam_forward[2]);
  const kd_lane3 right = KD_LANE3(params->cam_right[0], params->cam_right[1], params->cam_right[2]);
  const kd_lane3 up = KD_LANE3(params->cam_up[0], params->cam_up[1], params->cam_up[2]);
  return kd_normalize(forward + sx * right + sy * up);
}

/* A path's state at its start, but for its camera ray (pt_path_begin). */
KD_INLINE void pt_path_start(PtPath* path, uint pixel, uint sample, uint sample_hash) {
  path->throughput = kd_splat3(1.0f);
  path->radiance = kd_splat3(0.0f);
  path->albedo = kd_splat3(0.0f);
  path->normal = kd_splat3(0.0f);
  path->depth = 0.0f;
  path->bsdf_pdf = 0.0f;
  path->pixel = pixel;
  path->sample = sample;
  path->sample_hash = sample_hash;
  path->bounce = 0;
  path->alive = 1;
  path->shadow_pending = 0;
}

KD_INLINE void pt_path_begin(PtPath* path, KD_GLOBAL const PtRenderParams* params, uint pixel, uint sample) {
  uint x = pixel % params->width, y = pixel / params->width;
  pt_path_start(path, pixel, sample, pt_sample_hash(params->sampler, params->seed, pixel, sample));
  /* the camera's pair, read as the first values of a "bounce" that starts at dimension 0 */
  const PtBounceSamples camera = pt_bounce_samples(params->sampler, path->sample_hash, sample, PT_DIM_CAMERA_X);
  float2 jitter = pt_bounce_sample2(&camera, 0u);
  float sx, sy;
  pt_film_point(params, (float)x + jitter.x, (float)y + jitter.y, &sx, &sy);
  path->origin = vload3(0, params->cam_origin);
  path->direction = pt_perspective_direction(params, sx, sy);
#ifdef KD_FEATURE_ORTHOGRAPHIC
  if (PT_USES(params, PT_FEATURE_ORTHOGRAPHIC)) {
    float3 right = vload3(0, params->cam_right), up = vload3(0, params->cam_up);
    path->origin = path->origin + sx * right + sy * up;
    path->direction = vload3(0, params->cam_forward);
  }
#endif
}

#endif /* PT_PATH_STATE_H */
