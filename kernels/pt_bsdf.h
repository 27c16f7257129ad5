/* Materials: Lambertian diffuse (also the reflection of emitters), perfect mirror, GGX rough
 * conductor (Walter et al. 2007) and smooth dielectric. OpenCL C only.
 * Conventions: n is the shading normal turned to the side of wo; wo and wi point away from the
 * surface; "weight" is f * |cos| / pdf. Features a scene lacks are compiled out. */
#ifndef PT_BSDF_H
#define PT_BSDF_H

#include "pt_sampling.h"
#include "pt_types.h"

typedef struct PtBsdfSample {
  float3 wi;
  float3 weight;
  float pdf;       /* solid-angle pdf; 0 for delta lobes */
  int is_delta;
  int transmits;   /* wi leaves through the other side */
} PtBsdfSample;

#ifdef KD_FEATURE_GLOSSY
inline float pt_ggx_d(float cos_h, float alpha2) {
  float c2 = cos_h * cos_h;
  float denom = c2 * (alpha2 - 1.0f) + 1.0f;
  return alpha2 / (PT_PI * denom * denom);
}
inline float pt_ggx_g1(float cos_v, float alpha2) {
  float c2 = cos_v * cos_v;
  float tan2 = fmax(0.0f, 1.0f - c2) / fmax(c2, 1e-12f);
  return 2.0f / (1.0f + sqrt(1.0f + alpha2 * tan2));
}
inline float3 pt_schlick(float3 f0, float cos_theta) {
  float m = clamp(1.0f - cos_theta, 0.0f, 1.0f);
  float m5 = (m * m) * (m * m) * m;
  return f0 + (1.0f - f0) * m5;
}
inline float pt_ggx_alpha2(float roughness) {
  float alpha = fmax(roughness, 1e-3f);
  return alpha * alpha;
}
/* f * cos(wi) and the pdf of sampling wi by pt_ggx_sample. */
inline float3 pt_ggx_eval(float3 color, float roughness, float3 n, float3 wo, float3 wi, float* pdf) {
  *pdf = 0.0f;
  float cos_o = dot(n, wo), cos_i = dot(n, wi);
  if (cos_o <= 0.0f || cos_i <= 0.0f) return (float3)(0.0f);
  float3 h = normalize(wo + wi);
  float alpha2 = pt_ggx_alpha2(roughness);
  float cos_h = dot(n, h), o_h = dot(wo, h);
  float d = pt_ggx_d(cos_h, alpha2);
  *pdf = d * cos_h / (4.0f * o_h);
  float g = pt_ggx_g1(cos_o, alpha2) * pt_ggx_g1(cos_i, alpha2);
  return pt_schlick(color, o_h) * (d * g / (4.0f * cos_o));
}
#endif

#ifdef KD_FEATURE_GLASS
/* Unpolarised Fresnel reflectance for cos_i on the side of index eta_i into eta_t. */
inline float pt_fresnel_dielectric(float cos_i, float cos_t, float eta_i, float eta_t) {
  float rs = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
  float rp = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
  return 0.5f * (rs * rs + rp * rp);
}
#endif

inline int pt_is_delta(uint type) { return type == PT_MIRROR || type == PT_DIELECTRIC; }

/* f * |cos(wi)| for the non-delta lobes, and the pdf pt_bsdf_sample would give wi. */
inline float3 pt_bsdf_eval(const PtMaterial* m, float3 color, float3 n, float3 wo, float3 wi, float* pdf) {
#ifdef KD_FEATURE_GLOSSY
  if (m->type == PT_ROUGH_CONDUCTOR) return pt_ggx_eval(color, m->roughness, n, wo, wi, pdf);
#endif
  float cos_i = dot(n, wi);
  if (cos_i <= 0.0f || pt_is_delta(m->type)) {
    *pdf = 0.0f;
    return (float3)(0.0f);
  }
  *pdf = cos_i * PT_INV_PI;
  return color * (cos_i * PT_INV_PI);
}

/* entering: wo is on the front (winding) side, which for a dielectric is the outside. */
inline PtBsdfSample pt_bsdf_sample(const PtMaterial* m, float3 color, float3 n, float3 wo, int entering,
                                   float u1, float u2) {
  PtBsdfSample s;
  s.is_delta = 0;
  s.transmits = 0;
#ifdef KD_FEATURE_MIRROR
  if (m->type == PT_MIRROR) {
    s.wi = 2.0f * dot(wo, n) * n - wo;
    s.weight = color;
    s.pdf = 0.0f;
    s.is_delta = 1;
    return s;
  }
#endif
#ifdef KD_FEATURE_GLASS
  if (m->type == PT_DIELECTRIC) {
    float eta_i = entering ? 1.0f : m->ior;
    float eta_t = entering ? m->ior : 1.0f;
    float eta = eta_i / eta_t;
    float cos_i = fmin(dot(n, wo), 1.0f);
    float sin2_t = eta * eta * fmax(0.0f, 1.0f - cos_i * cos_i);
    float cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
    float reflectance = sin2_t >= 1.0f ? 1.0f : pt_fresnel_dielectric(cos_i, cos_t, eta_i, eta_t);
    s.pdf = 0.0f;
    s.is_delta = 1;
    if (u1 < reflectance) {
      s.wi = 2.0f * cos_i * n - wo;
      s.weight = (float3)(1.0f);
    } else {
      s.wi = normalize(-eta * wo + (eta * cos_i - cos_t) * n);
      s.weight = color * (eta * eta); /* radiance is scaled by (eta_i/eta_t)^2 across the boundary */
      s.transmits = 1;
    }
    return s;
  }
#endif
#ifdef KD_FEATURE_GLOSSY
  if (m->type == PT_ROUGH_CONDUCTOR) {
    float alpha2 = pt_ggx_alpha2(m->roughness);
    float tan2 = alpha2 * u1 / fmax(1.0f - u1, 1e-7f);
    float cos_h = 1.0f / sqrt(1.0f + tan2);
    float sin_h = sqrt(fmax(0.0f, 1.0f - cos_h * cos_h));
    float phi = 2.0f * PT_PI * u2;
    float3 h = pt_to_world((float3)(sin_h * cos(phi), sin_h * sin(phi), cos_h), n);
    s.wi = 2.0f * dot(wo, h) * h - wo;
    float3 f_cos = pt_ggx_eval(color, m->roughness, n, wo, s.wi, &s.pdf);
    s.weight = s.pdf > 0.0f ? f_cos / s.pdf : (float3)(0.0f);
    return s;
  }
#endif
  (void)entering;
  s.wi = pt_sample_cosine(n, u1, u2);
  s.pdf = fmax(dot(n, s.wi), 0.0f) * PT_INV_PI;
  s.weight = s.pdf > 0.0f ? color : (float3)(0.0f);
  return s;
}

#endif /* PT_BSDF_H */
