/* Direct lighting (next-event estimation): at a shading point, pick a light (an emissive
 * triangle, the environment or a punctual light), sample a direction towards it and set up the
 * shadow ray with the contribution it carries; then resolve that shadow ray. */
#ifndef PT_DIRECT_LIGHT_H
#define PT_DIRECT_LIGHT_H

#include "pt_bsdf.h"
#include "pt_lights.h"
#include "pt_material.h"
#include "pt_path_state.h"
#include "pt_spherical_triangle.h"

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

KD_INLINE void pt_path_resolve_shadow(PtPath* path, int occluded) {
  if (path->shadow_pending && !occluded) path->radiance += path->shadow_contribution;
  path->shadow_pending = 0;
}

/* Picks an emitter by its share of the emitted power: the first entry whose cdf exceeds u, searched
 * from the table's guide (kernels/pt_sampling.h). *u becomes u's position inside that entry's cdf
 * interval, a fresh uniform number in [0, 1) for sampling the picked light (stratified along with
 * the pick). */
KD_INLINE uint pt_pick_light(KD_GLOBAL const PtLight* lights, KD_GLOBAL const kd_u32* guide, uint count, float* u) {
  const kd_u32 k = pt_cdf_guide_cell(count, *u);
  uint lo = guide[k], hi = guide[k + 1u];
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
                          const PtBounceSamples* samples, const PtMaterial* m, float3 color, float3 p, float3 n,
                          float3 ng, float3 wo) {
  float2 pick_v = pt_bounce_sample2(samples, PT_DIM_LIGHT_PICK);
  float u = pick_v.x;
  uint tri = pt_pick_light(scene->lights, scene->light_guide, params->light_count, &u);
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
    float b1, b2;
    pt_sample_triangle(u, pick_v.y, &b1, &b2);
    bary = KD_FLOAT2(b1, b2);
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

/* The light sample towards the environment or a punctual light, for a kind number u past the
 * triangle lights' share (the environment's share first, then the punctual lights', the same
 * number rescaled picking one of them) and the environment's pair of sample values u_env.
 * Returns 0 where u picks no light. */
KD_INLINE int pt_sample_other_light(PtLightSample* ls, const PtSceneData* scene, KD_GLOBAL const PtRenderParams* params,
                                 float3 p, float u, float2 u_env) {
#ifdef KD_FEATURE_ENVIRONMENT
  if (u < params->select_environment) {
    *ls = pt_env_sample_light(scene->env_texels, scene->env_cdf, params, p, u_env);
    return 1;
  }
  u -= params->select_environment;
#endif
#ifdef KD_FEATURE_PUNCTUAL
  float rest = 1.0f - params->select_triangles - params->select_environment;
  if (params->punctual_count > 0 && rest > 0.0f) {
    *ls = pt_punctual_sample_light(scene->punctuals, params, p, fmin(u / rest, 0.99999994f));
    return 1;
  }
#endif
  (void)ls, (void)scene, (void)params, (void)p, (void)u, (void)u_env;
  return 0;
}

/* Picks a kind of light with the probabilities in params (its own sample dimension; rescaled, the
 * same number then picks a punctual light) and estimates its direct light. */
KD_INLINE void pt_next_event_any(PtPath* path, const PtSceneData* scene, KD_GLOBAL const PtRenderParams* params,
                              const PtBounceSamples* samples, const PtMaterial* m, float3 color, float3 p, float3 n,
                              float3 ng, float3 wo) {
#ifdef KD_FEATURE_EMISSION
  /* With triangle lights the only kind (select_triangles 1), every u picks them, so u is not
   * drawn; no other value depends on it (kernels/pt_rng.h: values are counter-based). A build
   * with every feature in, the host's, comes here for such scenes. */
  float u = params->select_triangles < 1.0f ? pt_bounce_sample(samples, PT_DIM_LIGHT_TYPE) : 0.0f;
  if (u < params->select_triangles) {
    pt_next_event(path, scene, params, samples, m, color, p, n, ng, wo);
    return;
  }
  u -= params->select_triangles;
#else
  float u = pt_bounce_sample(samples, PT_DIM_LIGHT_TYPE);
#endif
#ifdef KD_FEATURE_ENVIRONMENT
  float2 u_env = pt_bounce_sample2(samples, PT_DIM_ENV_U);
#else
  float2 u_env = KD_FLOAT2(0.0f, 0.0f);
#endif
  PtLightSample ls;
  if (pt_sample_other_light(&ls, scene, params, p, u, u_env))
    pt_shadow_towards(path, params, m, color, p, n, ng, wo, ls);
}
#endif

#endif /* PT_DIRECT_LIGHT_H */
