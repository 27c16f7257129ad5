/* One path's state and the steps that advance it: begin at the camera, shade a closest hit
 * (emission with MIS, Russian roulette, next-event estimation, BSDF sampling), resolve the
 * shadow ray, add the finished sample to the film. The megakernel runs these steps in a loop
 * per work-item; the wavefront form runs each step as its own kernel over a buffer of paths.
 * Compiles as C++ too: librender/src/render_host.cpp runs it on the CPU (kdrender --device host),
 * and tests/render/cpu_integrator.h checks that against the kernel bit for bit. */
#ifndef PT_PATH_H
#define PT_PATH_H

#include "kd_traverse.h"
#include "pt_bsdf.h"
#include "pt_lights.h"
#include "pt_material.h"
#include "pt_rng.h"
#include "pt_scene_args.h"
#include "pt_spherical_triangle.h"
#include "pt_types.h"

/* Russian roulette from this bounce on, surviving with probability min(sqrt(max throughput), 1):
 * the square root keeps more dim paths alive than min(max throughput, 1) would, which costs a
 * few more rays and saves more variance (measured in bench/LOG.md, "Sampler"). */
#define PT_ROULETTE_START 4u

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
  scene.kd = kd_scene_view(nodes, 0, leaf_triangles, leaf_vertices, params->bounds_min[0], params->bounds_min[1],
                           params->bounds_min[2], params->bounds_max[0], params->bounds_max[1], params->bounds_max[2]);
  scene.triangle_vertices = triangle_vertices;
  scene.indices = indices;
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

/* Corner 0, 1 or 2 of a triangle, from the gathered vertices. */
KD_INLINE float3 pt_corner(KD_GLOBAL const float* triangle_vertices, uint triangle, uint corner) {
  return vload3(corner, triangle_vertices + KD_TRIANGLE_FLOATS * triangle);
}

KD_INLINE RayRecord pt_ray(float3 origin, float3 direction, float tmax) {
  RayRecord ray = {origin.x, origin.y, origin.z, direction.x, direction.y, direction.z, 0.0f, tmax};
  return ray;
}
/* Both values of the sample's dimension pair starting at even `dimension` (kernels/pt_rng.h). */
KD_INLINE float2 pt_sample2(KD_GLOBAL const PtRenderParams* params, uint sample_hash, uint sample, uint dimension) {
  PtBits2 bits = pt_hashed_bits2(params->sampler, sample_hash, sample, dimension);
  return KD_FLOAT2(pt_bits_to_unit(bits.x), pt_bits_to_unit(bits.y));
}
/* Sample value `dim` (PT_DIM_*, kernels/pt_rng.h) of the path's current bounce, or both values
 * of the pair starting at even `dim`. */
KD_INLINE float pt_path_sample(const PtPath* path, KD_GLOBAL const PtRenderParams* params, uint dim) {
  return pt_bits_to_unit(
      pt_hashed_bits(params->sampler, path->sample_hash, path->sample, PT_BOUNCE_DIMS(path->bounce) + dim));
}
KD_INLINE float2 pt_path_sample2(const PtPath* path, KD_GLOBAL const PtRenderParams* params, uint dim) {
  return pt_sample2(params, path->sample_hash, path->sample, PT_BOUNCE_DIMS(path->bounce) + dim);
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

/* Whether the shadow ray is blocked; with alpha-tested surfaces, the closest hits are walked and
 * those the ray passes through skipped (at most PT_MAX_ALPHA_LAYERS of them). */
KD_INLINE int pt_path_occluded(const PtSceneData* scene, const PtPath* path, KD_GLOBAL const PtRenderParams* params) {
  RayRecord ray = pt_shadow_ray(path);
#ifdef KD_FEATURE_ALPHA
  if (!PT_USES(params, PT_FEATURE_ALPHA)) return kd_intersect_any(&scene->kd, ray);
  uint key = pt_path_key(path, params) ^ 0x9e3779b9u; /* decided apart from the bounce ray's */
  for (int layer = 0; layer < PT_MAX_ALPHA_LAYERS; ++layer) {
    HitRecord hit = kd_intersect_closest(&scene->kd, ray);
    if (hit.triangle == KD_NO_HIT) return 0;
    if (!pt_alpha_passes(scene->indices, scene->material_ids, scene->materials, scene->uvs, scene->textures,
                         scene->texels, hit.triangle, hit.u, hit.v, key))
      return 1;
    ray.tmin = hit.t;
  }
  return 1;
#else
  (void)params;
  return kd_intersect_any(&scene->kd, ray);
#endif
}

KD_INLINE void pt_path_begin(PtPath* path, KD_GLOBAL const PtRenderParams* params, uint pixel, uint sample) {
  uint x = pixel % params->width, y = pixel / params->width;
  path->sample_hash = pt_sample_hash(params->sampler, params->seed, pixel, sample);
  float2 jitter = pt_sample2(params, path->sample_hash, sample, PT_DIM_CAMERA_X);
  float sx = 2.0f * ((float)x + jitter.x) / (float)params->width - 1.0f;
  float sy = 1.0f - 2.0f * ((float)y + jitter.y) / (float)params->height;
  float3 forward = vload3(0, params->cam_forward), right = vload3(0, params->cam_right);
  float3 up = vload3(0, params->cam_up);
  path->origin = vload3(0, params->cam_origin);
  path->direction = kd_normalize(forward + sx * right + sy * up);
#ifdef KD_FEATURE_ORTHOGRAPHIC
  if (PT_USES(params, PT_FEATURE_ORTHOGRAPHIC)) {
    path->origin = path->origin + sx * right + sy * up;
    path->direction = forward;
  }
#endif
  path->throughput = kd_splat3(1.0f);
  path->radiance = kd_splat3(0.0f);
  path->albedo = kd_splat3(0.0f);
  path->normal = kd_splat3(0.0f);
  path->depth = 0.0f;
  path->bsdf_pdf = 0.0f;
  path->pixel = pixel;
  path->sample = sample;
  path->bounce = 0;
  path->alive = 1;
  path->shadow_pending = 0;
}

/* Picks an emitter by its share of the emitted power: the first entry whose cdf exceeds u. *u
 * becomes u's position inside that entry's cdf interval, a fresh uniform number in [0, 1) for
 * sampling the picked light (stratified along with the pick). */
KD_INLINE uint pt_pick_light(KD_GLOBAL const PtLight* lights, uint count, float* u) {
  uint lo = 0, hi = count - 1;
  while (lo < hi) {
    uint mid = (lo + hi) / 2;
    if (*u < lights[mid].cdf) hi = mid; else lo = mid + 1;
  }
  float below = lo > 0 ? lights[lo - 1].cdf : 0.0f;
  float width = lights[lo].cdf - below;
  *u = width > 0.0f ? fmin((*u - below) / width, 0x1.fffffep-1f) : 0.0f;
  return lights[lo].triangle;
}

/* Next-event estimation on the emissive triangles: picks one by power, then a direction towards
 * it from the shading point p by solid angle or by area (kernels/pt_spherical_triangle.h). */
KD_INLINE void pt_next_event(PtPath* path, const PtSceneData* scene, KD_GLOBAL const PtRenderParams* params,
                          const PtMaterial* m, float3 color, float3 p, float3 n, float3 ng, float3 wo) {
  float2 pick_v = pt_path_sample2(path, params, PT_DIM_LIGHT_PICK);
  float u = pick_v.x;
  uint tri = pt_pick_light(scene->lights, params->light_count, &u);
  float3 q0 = pt_corner(scene->triangle_vertices, tri, 0);
  float3 q1 = pt_corner(scene->triangle_vertices, tri, 1);
  float3 q2 = pt_corner(scene->triangle_vertices, tri, 2);
  float3 scaled_normal = kd_cross(q1 - q0, q2 - q0);
  float twice_area = kd_length(scaled_normal);
  float3 light_normal = scaled_normal / twice_area;
  float3 a, b, c;
  float solid_angle = pt_spherical_solid_angle(p, q0, q1, q2, &a, &b, &c);
  float3 wi;
  float dist2;
  float2 bary = KD_FLOAT2(0.0f, 0.0f); /* of the point on the light, for textured emission */
  if (solid_angle > 0.0f) {
    wi = pt_sample_spherical_triangle(a, b, c, solid_angle, u, pick_v.y);
    float t = kd_dot(q0 - p, light_normal) / kd_dot(wi, light_normal);
    if (!(t > 0.0f && t < INFINITY)) return;
    dist2 = t * t;
#ifdef KD_FEATURE_EMISSIVE_TEXTURE
    bary = pt_barycentrics(p + t * wi - q0, q1 - q0, q2 - q0);
#endif
  } else {
    bary = pt_sample_triangle(u, pick_v.y);
    float3 to_light = q0 + bary.x * (q1 - q0) + bary.y * (q2 - q0) - p;
    dist2 = kd_dot(to_light, to_light);
    if (!(dist2 > 0.0f)) return;
    wi = to_light * kd_rsqrt(dist2);
  }
  float cos_light = -kd_dot(light_normal, wi);
  if (cos_light <= 0.0f) return; /* emitters are one-sided */
  float bsdf_pdf;
  float3 f_cos = pt_bsdf_eval(m, color, n, wo, wi, &bsdf_pdf);
  if (bsdf_pdf <= 0.0f || kd_dot(wi, ng) <= 0.0f) return;
  PtMaterial light = scene->materials[scene->material_ids[tri]];
  float3 emission = vload3(0, light.emission); /* what the emitter table's pdf is made of */
#ifdef KD_FEATURE_EMISSIVE_TEXTURE
  float3 radiance = pt_textured_emission(&light, scene->uvs, scene->textures, scene->texels, scene->indices + 3 * tri,
                                         bary.x, bary.y);
#else
  float3 radiance = emission;
#endif
  float pick_per_area = PT_SELECT_TRIANGLES(params) * pt_luminance(emission) * params->light_area_pdf_scale;
  float light_pdf = pt_triangle_light_pdf(pick_per_area, 0.5f * twice_area, solid_angle, dist2, cos_light);
  float weight = pt_mis_light(params, light_pdf, bsdf_pdf);
  float3 origin = pt_offset_origin(p, ng);
  float3 target = pt_offset_origin(p + sqrt(dist2) * wi, light_normal);
  path->shadow_origin = origin;
  path->shadow_span = target - origin;
  path->shadow_contribution = path->throughput * f_cos * radiance * (weight / light_pdf);
  path->shadow_pending = 1;
}

#if defined(KD_FEATURE_ENVIRONMENT) || defined(KD_FEATURE_PUNCTUAL)
/* Next-event estimation towards a sampled environment direction or punctual light. */
KD_INLINE void pt_shadow_towards(PtPath* path, KD_GLOBAL const PtRenderParams* params, const PtMaterial* m,
                              float3 color, float3 p, float3 n, float3 ng, float3 wo, PtLightSample ls) {
  if (kd_dot(ls.wi, ng) <= 0.0f || pt_max3(ls.value) <= 0.0f) return;
  float bsdf_pdf;
  float3 f_cos = pt_bsdf_eval(m, color, n, wo, ls.wi, &bsdf_pdf);
  if (pt_max3(f_cos) <= 0.0f) return;
  float weight = ls.pdf > 0.0f ? pt_mis_light(params, ls.pdf, bsdf_pdf) : 1.0f;
  float3 origin = pt_offset_origin(p, ng);
  path->shadow_origin = origin;
  path->shadow_span = ls.wi * ls.distance;
  path->shadow_contribution = path->throughput * f_cos * ls.value * weight;
  path->shadow_pending = 1;
}

/* Picks a kind of light with the probabilities in params (its own sample dimension; rescaled, the
 * same number then picks a punctual light) and estimates its direct light. */
KD_INLINE void pt_next_event_any(PtPath* path, const PtSceneData* scene, KD_GLOBAL const PtRenderParams* params,
                              const PtMaterial* m, float3 color, float3 p, float3 n, float3 ng, float3 wo) {
  float u = pt_path_sample(path, params, PT_DIM_LIGHT_TYPE);
#ifdef KD_FEATURE_EMISSION
  if (u < params->select_triangles) {
    pt_next_event(path, scene, params, m, color, p, n, ng, wo);
    return;
  }
#endif
  u -= params->select_triangles;
#ifdef KD_FEATURE_ENVIRONMENT
  if (u < params->select_environment) {
    pt_shadow_towards(path, params, m, color, p, n, ng, wo,
                      pt_env_sample_light(scene->env_texels, scene->env_cdf, params, p,
                                          pt_path_sample2(path, params, PT_DIM_ENV_U)));
    return;
  }
  u -= params->select_environment;
#endif
#ifdef KD_FEATURE_PUNCTUAL
  float rest = 1.0f - params->select_triangles - params->select_environment;
  if (params->punctual_count > 0 && rest > 0.0f) {
    pt_shadow_towards(path, params, m, color, p, n, ng, wo,
                      pt_punctual_sample_light(scene->punctuals, params, p, fmin(u / rest, 0.99999994f)));
  }
#endif
}
#endif

#ifdef KD_FEATURE_ENVIRONMENT
/* A ray that leaves the scene sees the environment (camera rays too), MIS-weighted against
 * next-event estimation when a BSDF sample sent it. */
KD_INLINE void pt_path_escape(PtPath* path, const PtSceneData* scene, KD_GLOBAL const PtRenderParams* params) {
  float2 uv = pt_env_uv(params, path->direction);
  float weight = 1.0f;
  if (path->bsdf_pdf > 0.0f) weight = pt_mis_bsdf(params, path->bsdf_pdf, pt_env_pdf(scene->env_cdf, params, uv));
  path->radiance += path->throughput * pt_env_lookup(scene->env_texels, params, uv) * weight;
}
#endif

/* Advances the path by its closest hit. Bounce k is the k-th surface the path meets; light
 * is gathered at it (emission, and next-event estimation for surface k+1's light) and a new
 * direction sampled while k <= max_bounces, as Cycles counts: max_bounces 0 is direct light only. */
KD_INLINE void pt_path_shade(PtPath* path, const PtSceneData* scene, KD_GLOBAL const PtRenderParams* params,
                          HitRecord hit) {
  path->shadow_pending = 0;
  if (hit.triangle == KD_NO_HIT) {
#ifdef KD_FEATURE_ENVIRONMENT
    if (PT_USES(params, PT_FEATURE_ENVIRONMENT)) pt_path_escape(path, scene, params);
#endif
    path->alive = 0;
    return;
  }
  uint k = path->bounce;
  KD_GLOBAL const kd_u32* idx = scene->indices + 3 * hit.triangle;
  float3 p0 = pt_corner(scene->triangle_vertices, hit.triangle, 0);
  float3 p1 = pt_corner(scene->triangle_vertices, hit.triangle, 1);
  float3 p2 = pt_corner(scene->triangle_vertices, hit.triangle, 2);
  float w0 = 1.0f - hit.u - hit.v;
  float3 p = w0 * p0 + hit.u * p1 + hit.v * p2;
  float3 wo = -path->direction;
  float3 ng = kd_normalize(kd_cross(p1 - p0, p2 - p0));
  int front = kd_dot(ng, wo) > 0.0f;
  float3 ng_facing = front ? ng : -ng;
  float3 n = ng_facing;
#ifdef KD_FEATURE_NORMALS
  if (PT_USES(params, PT_FEATURE_NORMALS)) {
    float3 ns = w0 * pt_load3(scene->normals, idx[0]) + hit.u * pt_load3(scene->normals, idx[1]) +
                hit.v * pt_load3(scene->normals, idx[2]);
    if (kd_dot(ns, ns) > 0.0f) {
      ns = kd_normalize(ns);
      n = kd_dot(ns, ng_facing) < 0.0f ? -ns : ns;
    }
  }
#endif
  PtMaterial m = scene->materials[scene->material_ids[hit.triangle]];
#ifdef KD_FEATURE_ALPHA
  if (m.alpha_cutoff != 0.0f && pt_alpha_passes(scene->indices, scene->material_ids, scene->materials, scene->uvs,
                                                scene->textures, scene->texels, hit.triangle, hit.u, hit.v,
                                                pt_path_key(path, params))) {
    path->origin = pt_offset_origin(p, -ng_facing); /* the same bounce goes on beyond */
    return;
  }
#endif
  float3 color = vload3(0, m.base_color);
  pt_apply_textures(&m, &color, &n, ng, ng_facing, scene->uvs, scene->tangents, scene->textures, scene->texels, idx,
                    hit.u, hit.v);
  if (k == 0) {
    path->albedo = color;
    path->normal = n;
    path->depth = hit.t;
  }
  float3 beta = path->throughput;
#ifdef KD_FEATURE_EMISSION
  if (m.type == PT_EMISSIVE && front && PT_USES(params, PT_FEATURE_EMISSION)) {
    float3 emission = vload3(0, m.emission);
#ifdef KD_FEATURE_EMISSIVE_TEXTURE
    float3 radiance = pt_textured_emission(&m, scene->uvs, scene->textures, scene->texels, idx, hit.u, hit.v);
#else
    float3 radiance = emission;
#endif
    float weight = 1.0f;
    if (path->bsdf_pdf > 0.0f) {
      /* the density next-event estimation gives this direction, measured from the ray's origin
       * (the previous shading point, moved off its surface by a few ulps) */
      float3 a, b, c;
      float solid_angle = pt_spherical_solid_angle(path->origin, p0, p1, p2, &a, &b, &c);
      float pick_per_area = PT_SELECT_TRIANGLES(params) * pt_luminance(emission) * params->light_area_pdf_scale;
      float light_pdf = pt_triangle_light_pdf(pick_per_area, 0.5f * kd_length(kd_cross(p1 - p0, p2 - p0)), solid_angle,
                                              hit.t * hit.t, kd_dot(ng, wo));
      weight = pt_mis_bsdf(params, path->bsdf_pdf, light_pdf);
    }
    path->radiance += beta * radiance * weight;
  }
#endif
  if (k > params->max_bounces) {
    path->alive = 0;
    return;
  }
  if (k >= PT_ROULETTE_START) {
    float survive = fmin(sqrt(pt_max3(beta)), 1.0f);
    if (pt_path_sample(path, params, PT_DIM_ROULETTE) >= survive) {
      path->alive = 0;
      return;
    }
    beta /= survive;
    path->throughput = beta;
  }
#if defined(KD_FEATURE_ENVIRONMENT) || defined(KD_FEATURE_PUNCTUAL)
  if (!pt_is_delta(m.type)) pt_next_event_any(path, scene, params, &m, color, p, n, ng_facing, wo);
#elif defined(KD_FEATURE_EMISSION)
  if (params->light_count > 0 && !pt_is_delta(m.type)) pt_next_event(path, scene, params, &m, color, p, n, ng_facing, wo);
#endif
  float2 u = pt_path_sample2(path, params, PT_DIM_BSDF_U);
#ifdef KD_FEATURE_METALLIC_ROUGHNESS
  float u_lobe = pt_path_sample(path, params, PT_DIM_LOBE);
#else
  float u_lobe = 0.0f;
#endif
  PtBsdfSample s = pt_bsdf_sample(&m, color, n, wo, front, u.x, u.y, u_lobe);
  float side = kd_dot(s.wi, ng_facing);
  if (pt_max3(s.weight) <= 0.0f || (s.transmits ? side >= 0.0f : side <= 0.0f)) {
    path->alive = 0;
    return;
  }
  path->throughput = beta * s.weight;
  path->bsdf_pdf = s.is_delta ? 0.0f : s.pdf;
  path->origin = pt_offset_origin(p, s.transmits ? -ng_facing : ng_facing);
  path->direction = s.wi;
  path->bounce = k + 1;
}

KD_INLINE void pt_path_resolve_shadow(PtPath* path, int occluded) {
  if (path->shadow_pending && !occluded) path->radiance += path->shadow_contribution;
  path->shadow_pending = 0;
}

/* Fixed-point value of one sample (see PT_FIXED_BITS); non-finite values count as 0. */
KD_INLINE long pt_fixed(float value, uint* nonfinite) {
  if (!isfinite(value)) {
    *nonfinite += 1;
    return 0;
  }
  value = clamp(value, -PT_FIXED_MAX, PT_FIXED_MAX);
  return (long)rint(value * (float)(1 << PT_FIXED_BITS));
}

/* Adds the finished sample into per-pixel channel sums: radiance, then the enabled AOVs. */
KD_INLINE void pt_path_accumulate(const PtPath* path, KD_GLOBAL const PtRenderParams* params, long* sums,
                               uint* nonfinite) {
  uint c = 0;
  sums[c++] += pt_fixed(path->radiance.x, nonfinite);
  sums[c++] += pt_fixed(path->radiance.y, nonfinite);
  sums[c++] += pt_fixed(path->radiance.z, nonfinite);
  if (params->aov_mask & PT_AOV_ALBEDO) {
    sums[c++] += pt_fixed(path->albedo.x, nonfinite);
    sums[c++] += pt_fixed(path->albedo.y, nonfinite);
    sums[c++] += pt_fixed(path->albedo.z, nonfinite);
  }
  if (params->aov_mask & PT_AOV_NORMAL) {
    sums[c++] += pt_fixed(path->normal.x, nonfinite);
    sums[c++] += pt_fixed(path->normal.y, nonfinite);
    sums[c++] += pt_fixed(path->normal.z, nonfinite);
  }
  if (params->aov_mask & PT_AOV_DEPTH) sums[c++] += pt_fixed(path->depth, nonfinite);
}

/* Traces sample `sample` of `pixel` to its end and adds it to the pixel's channel sums; returns
 * the number of rays traced. The megakernel's whole per-sample work, and the C++ build's. */
KD_INLINE uint pt_render_sample(const PtSceneData* scene, KD_GLOBAL const PtRenderParams* params, uint pixel, uint sample,
                             long* sums, uint* nonfinite) {
  uint rays = 0;
  PtPath path;
  pt_path_begin(&path, params, pixel, sample);
  while (path.alive) {
    HitRecord hit = kd_intersect_closest(&scene->kd, pt_path_ray(&path));
    ++rays;
    pt_path_shade(&path, scene, params, hit);
    if (path.shadow_pending) {
      ++rays;
      pt_path_resolve_shadow(&path, pt_path_occluded(scene, &path, params));
    }
  }
  pt_path_accumulate(&path, params, sums, nonfinite);
  return rays;
}

/* Traces samples sample_offset .. sample_offset + sample_count - 1 of `pixel` and adds their sums
 * to the pixel's film channels; returns the number of rays traced. The per-pixel work of the
 * megakernel and of the host renderer (librender/src/render_host.cpp). */
KD_INLINE ulong pt_render_pixel(const PtSceneData* scene, KD_GLOBAL const PtRenderParams* params, uint pixel,
                             KD_GLOBAL long* film, uint* nonfinite) {
  long sums[PT_MAX_FILM_CHANNELS];
  for (uint c = 0; c < PT_MAX_FILM_CHANNELS; ++c) sums[c] = 0;
  ulong rays = 0;
  for (uint i = 0; i < params->sample_count; ++i)
    rays += pt_render_sample(scene, params, pixel, params->sample_offset + i, sums, nonfinite);
  for (uint c = 0; c < params->film_channels; ++c) film[(size_t)pixel * params->film_channels + c] += sums[c];
  return rays;
}

#endif /* PT_PATH_H */
