/* Lights other than emissive triangles, as next-event estimation samples them, and the MIS
 * weights every light strategy uses. The environment (KD_FEATURE_ENVIRONMENT) and punctual lights
 * (KD_FEATURE_PUNCTUAL) are compiled only into kernels for scenes that have them. */
#ifndef PT_LIGHTS_H
#define PT_LIGHTS_H

#include "pt_environment.h"
#include "pt_sampling.h"
#include "pt_types.h"

/* Weights of a light sample and of a BSDF sample that found a light, given both strategies'
 * solid-angle densities. KD_MIS_OFF (a test switch) keeps the estimator unbiased without MIS:
 * light samples count in full, BSDF samples only where light sampling cannot reach. Compiled in,
 * it is asked of the scene's bits as a feature is (PT_USES: always on in an OpenCL build). */
#ifdef KD_MIS_OFF
#define PT_MIS_OFF(params) PT_USES(params, PT_FEATURE_MIS_OFF)
#else
#define PT_MIS_OFF(params) 0
#endif
KD_LANE_FN kd_lane pt_mis_light(KD_GLOBAL const PtRenderParams* params, kd_lane light_pdf, kd_lane bsdf_pdf) {
  if (PT_MIS_OFF(params)) return (kd_lane)1.0f;
  return pt_power_heuristic(light_pdf, bsdf_pdf);
}
KD_LANE_FN kd_lane pt_mis_bsdf(KD_GLOBAL const PtRenderParams* params, kd_lane bsdf_pdf, kd_lane light_pdf) {
  if (PT_MIS_OFF(params)) return kd_select(light_pdf > 0.0f, (kd_lane)0.0f, (kd_lane)1.0f);
  return pt_power_heuristic(bsdf_pdf, light_pdf);
}

/* Probability that next-event estimation samples the emissive triangles. */
#if defined(KD_FEATURE_ENVIRONMENT) || defined(KD_FEATURE_PUNCTUAL)
#define PT_SELECT_TRIANGLES(params) ((params)->select_triangles)
#else
#define PT_SELECT_TRIANGLES(params) 1.0f
#endif

/* A sampled direction towards a light: unoccluded up to `distance`, it brings `value` (radiance
 * or intensity over the sampling density, light choice included); pdf is the solid-angle density
 * for MIS, 0 for delta lights. */
typedef struct PtLightSample {
  float3 wi;
  float distance;
  float3 value;
  float pdf;
} PtLightSample;

/* Distance that takes a shadow ray from p out of the scene's bounds. */
KD_INLINE float pt_escape_distance(KD_GLOBAL const PtRenderParams* params, float3 p) {
  float3 lo = vload3(0, params->bounds_min), hi = vload3(0, params->bounds_max);
  return 1.01f * (kd_length(p - 0.5f * (lo + hi)) + 0.5f * kd_length(hi - lo)) + 1.0f;
}

#ifdef KD_FEATURE_ENVIRONMENT
KD_INLINE PtLightSample pt_env_sample_light(KD_GLOBAL const float* texels, KD_GLOBAL const float* cdf,
                                         KD_GLOBAL const PtRenderParams* params, float3 p, float2 u2d) {
  PtLightSample s;
  float u, v;
  float pdf_uv = pt_env_sample_uv(cdf, params->env_width, params->env_height, u2d.x, u2d.y, &u, &v);
  float2 uv = KD_FLOAT2(u, v);
  float sin_theta;
  s.wi = pt_env_direction(params, uv, &sin_theta);
  s.pdf = params->select_environment * pdf_uv / (2.0f * PT_PI * PT_PI * sin_theta);
  s.distance = pt_escape_distance(params, p);
  s.value = s.pdf > 0.0f ? pt_env_lookup(texels, params, uv) / s.pdf : kd_splat3(0.0f);
  return s;
}
#endif

#ifdef KD_FEATURE_PUNCTUAL
/* One of the punctual lights, chosen uniformly with u. */
KD_INLINE PtLightSample pt_punctual_sample_light(KD_GLOBAL const PtPunctual* lights, KD_GLOBAL const PtRenderParams* params,
                                              float3 p, float u) {
  uint count = params->punctual_count;
  uint index = (uint)(u * (float)count);
  PtPunctual light = lights[index < count - 1 ? index : count - 1];
  float select = (1.0f - params->select_triangles - params->select_environment) / (float)count;
  float3 power = vload3(0, light.power) / select;
  float3 direction = vload3(0, light.direction);
  PtLightSample s;
  s.pdf = 0.0f;
  if (light.type == PT_PUNCTUAL_DIRECTIONAL) {
    s.wi = -direction;
    s.distance = pt_escape_distance(params, p);
    s.value = power;
    return s;
  }
  float3 to_light = vload3(0, light.position) - p;
  float dist2 = kd_dot(to_light, to_light);
  s.distance = sqrt(dist2);
  s.wi = to_light / s.distance;
  s.value = dist2 > 0.0f ? power / dist2 : kd_splat3(0.0f);
  if (light.type == PT_PUNCTUAL_SPOT) {
    /* KHR_lights_punctual's falloff: the square of a linear ramp in cos between the cones. */
    float ramp = (kd_dot(direction, -s.wi) - light.cos_outer) / fmax(light.cos_inner - light.cos_outer, 1e-3f);
    ramp = clamp(ramp, 0.0f, 1.0f);
    s.value *= ramp * ramp;
  }
  return s;
}
#endif

#endif /* PT_LIGHTS_H */
