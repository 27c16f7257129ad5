/* Materials: Lambertian diffuse (also the reflection of emitters), perfect mirror, GGX rough
 * conductor (Walter et al. 2007), smooth dielectric and glTF metallic-roughness (the glTF 2.0
 * specification's BRDF, its Appendix B: a Fresnel mix of a Lambertian base and a GGX layer,
 * blended by metallic with a GGX conductor).
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

#if defined(KD_FEATURE_GLOSSY) || defined(KD_FEATURE_METALLIC_ROUGHNESS)
#define PT_GGX_CODE
#endif

/* The BSDFs' functions are lane functions (kernels/kd_lane.h): the host's paths in lanes shade 8
 * paths at a time with them. */
#ifdef PT_GGX_CODE
KD_LANE_FN kd_lane pt_ggx_d(kd_lane cos_h, kd_lane alpha2) {
  kd_lane c2 = cos_h * cos_h;
  kd_lane denom = c2 * (alpha2 - 1.0f) + 1.0f;
  return alpha2 / (PT_PI * denom * denom);
}
KD_LANE_FN kd_lane pt_ggx_g1(kd_lane cos_v, kd_lane alpha2) {
  kd_lane c2 = cos_v * cos_v;
  kd_lane tan2 = fmax(0.0f, 1.0f - c2) / fmax(c2, 1e-12f);
  return 2.0f / (1.0f + sqrt(1.0f + alpha2 * tan2));
}
/* Schlick's (1 - cos)^5, the share of 1 - f0 that a Fresnel factor adds to f0. */
KD_LANE_FN kd_lane pt_schlick_weight(kd_lane cos_theta) {
  kd_lane m = clamp(1.0f - cos_theta, 0.0f, 1.0f);
  return (m * m) * (m * m) * m;
}
KD_LANE_FN kd_lane3 pt_schlick(kd_lane3 f0, kd_lane cos_theta) {
  return f0 + (1.0f - f0) * pt_schlick_weight(cos_theta);
}
/* GGX's alpha for a roughness, kept off 0 so that D stays finite. */
KD_LANE_FN kd_lane pt_ggx_alpha(kd_lane roughness) { return fmax(roughness, 1e-3f); }
KD_LANE_FN kd_lane pt_ggx_alpha2(kd_lane roughness) {
  kd_lane alpha = pt_ggx_alpha(roughness);
  return alpha * alpha;
}
/* D(h) for the half vector h of wo and wi, with wo . h and the pdf of drawing wi by
 * pt_ggx_sample_wi: its visible normal's density G1(wo) (wo . h) D(h) / cos(wo), over the
 * reflection's 4 (wo . h). Where `below` (wo or wi not on the side of n), *pdf and *o_h are left
 * as they are. */
KD_LANE_FN kd_lane pt_ggx_half_vector_d(kd_lane alpha2, kd_lane3 n, kd_lane3 wo, kd_lane3 wi, KD_LANE_MASK below,
                                       kd_lane* pdf, kd_lane* o_h) {
  kd_lane3 h = kd_normalize(wo + wi);
  kd_lane cos_h = kd_dot(n, h);
  kd_lane cos_o = kd_dot(n, wo);
  *o_h = kd_select(below, *o_h, kd_dot(wo, h));
  kd_lane d = pt_ggx_d(cos_h, alpha2);
  *pdf = kd_select(below, *pdf, d * pt_ggx_g1(cos_o, alpha2) / (4.0f * cos_o));
  return d;
}
/* A GGX lobe's D * G / (4 cos(wo)) (its f * cos(wi) without the Fresnel factor), the pdf of
 * sampling wi by pt_ggx_sample_wi, and wo . h. G is the separable Smith G of the rough conductor,
 * or where height_correlated the glTF specification's height-correlated Smith masking-shadowing
 * function, 2 cos_o cos_i / (cos_o sqrt(a2 + (1 - a2) cos_i^2) + cos_i sqrt(a2 + (1 - a2) cos_o^2)). */
KD_LANE_FN kd_lane pt_ggx_lobe(kd_lane roughness, int height_correlated, kd_lane3 n, kd_lane3 wo, kd_lane3 wi,
                              kd_lane* pdf, kd_lane* o_h) {
  *pdf = 0.0f;
  *o_h = 1.0f;
  kd_lane cos_o = kd_dot(n, wo), cos_i = kd_dot(n, wi);
  KD_LANE_MASK below = (cos_o <= 0.0f) | (cos_i <= 0.0f);
  if (!kd_any(!below)) return (kd_lane)0.0f;
  kd_lane alpha2 = pt_ggx_alpha2(roughness);
  kd_lane d = pt_ggx_half_vector_d(alpha2, n, wo, wi, below, pdf, o_h);
  kd_lane value;
  if (height_correlated) {
    kd_lane g_denominator = cos_o * sqrt(alpha2 + (1.0f - alpha2) * cos_i * cos_i) +
                            cos_i * sqrt(alpha2 + (1.0f - alpha2) * cos_o * cos_o);
    value = d * cos_i / (2.0f * g_denominator);
  } else {
    kd_lane g = pt_ggx_g1(cos_o, alpha2) * pt_ggx_g1(cos_i, alpha2);
    value = d * g / (4.0f * cos_o);
  }
  return kd_select(below, (kd_lane)0.0f, value);
}
/* f * cos(wi) and the pdf of sampling wi by pt_ggx_sample_wi. */
KD_LANE_FN kd_lane3 pt_ggx_eval(kd_lane3 color, kd_lane roughness, kd_lane3 n, kd_lane3 wo, kd_lane3 wi, kd_lane* pdf) {
  kd_lane o_h;
  kd_lane common = pt_ggx_lobe(roughness, 0, n, wo, wi, pdf, &o_h);
  return kd_select(common > 0.0f, pt_schlick(color, o_h) * common, KD_LANE3(0.0f, 0.0f, 0.0f));
}
/* wo reflected about a normal drawn from those visible from wo (Heitz, "Sampling the GGX
 * Distribution of Visible Normals", JCGT 7(4), 2018): in the frame of n, wo stretched by alpha
 * to the hemisphere configuration, a point of the projected disk's visible part, lifted to the
 * hemisphere and unstretched. The sample's weight keeps only Fresnel and G2 / G1(wo), so smooth
 * metals add far less noise than with half vectors drawn from D(h) cos(h). */
KD_LANE_FN kd_lane3 pt_ggx_sample_wi(kd_lane roughness, kd_lane3 n, kd_lane3 wo, kd_lane u1, kd_lane u2) {
  kd_lane alpha = pt_ggx_alpha(roughness);
  kd_lane3 t, b;
  pt_basis(n, &t, &b);
  kd_lane3 vh = kd_normalize(KD_LANE3(alpha * kd_dot(wo, t), alpha * kd_dot(wo, b), kd_dot(wo, n)));
  kd_lane lensq = vh.x * vh.x + vh.y * vh.y;
  KD_LANE_MASK along_n = !(lensq > 0.0f);
  kd_lane inverse_length = 1.0f / sqrt(kd_select(along_n, (kd_lane)1.0f, lensq));
  kd_lane3 t1 = kd_select(along_n, KD_LANE3(1.0f, 0.0f, 0.0f),
                          KD_LANE3(-vh.y * inverse_length, vh.x * inverse_length, 0.0f));
  kd_lane3 t2 = kd_cross(vh, t1);
  kd_lane r = sqrt(u1);
  kd_lane phi = 2.0f * PT_PI * u2;
  kd_lane sin_phi, cos_phi;
  kd_sincos(phi, &sin_phi, &cos_phi);
  kd_lane p1 = r * cos_phi;
  kd_lane s = 0.5f * (1.0f + vh.z);
  kd_lane p2 = (1.0f - s) * sqrt(fmax(0.0f, 1.0f - p1 * p1)) + s * (r * sin_phi);
  kd_lane3 nh = p1 * t1 + p2 * t2 + sqrt(fmax(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  kd_lane3 h = pt_to_world(kd_normalize(KD_LANE3(alpha * nh.x, alpha * nh.y, fmax(0.0f, nh.z))), n);
  return 2.0f * kd_dot(wo, h) * h - wo;
}
#endif

#ifdef KD_FEATURE_GLASS
/* Unpolarised Fresnel reflectance for cos_i on the side of index eta_i into eta_t. */
KD_LANE_FN kd_lane pt_fresnel_dielectric(kd_lane cos_i, kd_lane cos_t, kd_lane eta_i, kd_lane eta_t) {
  kd_lane rs = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
  kd_lane rp = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
  return 0.5f * (rs * rs + rp * rp);
}
/* Smooth glass seen from wo (entering: from the front, the outside): the probability of
 * reflection, with the relative index eta and the cosines of wo and of the refracted direction
 * for pt_glass_refraction. */
KD_LANE_FN kd_lane pt_glass_reflectance(kd_lane ior, KD_LANE_MASK entering, kd_lane3 n, kd_lane3 wo, kd_lane* eta,
                                     kd_lane* cos_i, kd_lane* cos_t) {
  kd_lane eta_i = kd_select(entering, (kd_lane)1.0f, ior);
  kd_lane eta_t = kd_select(entering, ior, (kd_lane)1.0f);
  *eta = eta_i / eta_t;
  *cos_i = fmin(kd_dot(n, wo), 1.0f);
  kd_lane sin2_t = *eta * *eta * fmax(0.0f, 1.0f - *cos_i * *cos_i);
  *cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
  return kd_select(sin2_t >= 1.0f, (kd_lane)1.0f, pt_fresnel_dielectric(*cos_i, *cos_t, eta_i, eta_t));
}
KD_LANE_FN kd_lane3 pt_glass_refraction(kd_lane eta, kd_lane cos_i, kd_lane cos_t, kd_lane3 n, kd_lane3 wo) {
  return kd_normalize(-eta * wo + (eta * cos_i - cos_t) * n);
}
#endif

#ifdef KD_FEATURE_METALLIC_ROUGHNESS
/* The dielectric's Schlick Fresnel, f0 from its index of refraction (0.04 at glTF's 1.5). */
KD_LANE_FN kd_lane pt_gltf_dielectric_fresnel(kd_lane ior, kd_lane cos_theta) {
  kd_lane r = (ior - 1.0f) / (ior + 1.0f);
  kd_lane f0 = r * r;
  return f0 + (1.0f - f0) * pt_schlick_weight(cos_theta);
}
/* Probability of drawing wi from the GGX lobe rather than the cosine one: the metal's weight plus
 * the dielectric's specular share at wo, estimated with Fresnel at wo . n in place of wo . h (the
 * layer reflects F, the base (1 - F) times its colour), so that a sample's weight stays close to
 * the albedo whichever lobe drew it. */
KD_LANE_FN kd_lane pt_gltf_ggx_probability(kd_lane metallic, kd_lane ior, kd_lane3 color, kd_lane cos_o) {
  kd_lane f = pt_gltf_dielectric_fresnel(ior, cos_o);
  kd_lane diffuse = (1.0f - f) * pt_luminance(color);
  kd_lane p_specular = kd_select(f + diffuse > 0.0f, f / (f + diffuse), (kd_lane)1.0f);
  return metallic + (1.0f - metallic) * p_specular;
}
/* f * cos(wi) and pdf of glTF metallic-roughness (the specification's Appendix B):
 * mix(dielectric, metal, metallic) with metal = specular * Schlick(color, wo . h) and
 * dielectric = (1 - F) color / pi + F specular, F = Schlick(f0 of ior, wo . h). The pdf is the
 * mixture of the two lobes pt_bsdf_sample draws from. */
KD_LANE_FN kd_lane3 pt_metal_rough_eval(kd_lane roughness, kd_lane ior, kd_lane metallic, kd_lane3 color, kd_lane3 n,
                                        kd_lane3 wo, kd_lane3 wi, kd_lane* pdf) {
  kd_lane ggx_pdf, o_h;
  kd_lane specular = pt_ggx_lobe(roughness, 1, n, wo, wi, &ggx_pdf, &o_h);  /* the glTF specular layer */
  kd_lane cos_o = kd_dot(n, wo), cos_i = kd_dot(n, wi);
  *pdf = 0.0f;
  KD_LANE_MASK below = (cos_o <= 0.0f) | (cos_i <= 0.0f);
  kd_lane3 none = KD_LANE3(0.0f, 0.0f, 0.0f);
  if (!kd_any(!below)) return none;
  kd_lane3 metal = pt_schlick(color, o_h) * specular;
  kd_lane f = pt_gltf_dielectric_fresnel(ior, o_h);
  kd_lane f_specular = f * specular;
  kd_lane3 dielectric = color * ((1.0f - f) * cos_i * PT_INV_PI) + KD_LANE3(f_specular, f_specular, f_specular);
  kd_lane p_ggx = pt_gltf_ggx_probability(metallic, ior, color, cos_o);
  *pdf = kd_select(below, *pdf, p_ggx * ggx_pdf + (1.0f - p_ggx) * cos_i * PT_INV_PI);
  return kd_select(below, none, metallic * metal + (1.0f - metallic) * dielectric);
}
#endif

KD_INLINE int pt_is_delta(uint type) { return type == PT_MIRROR || type == PT_DIELECTRIC; }

/* f * |cos(wi)| for the non-delta lobes, and the pdf pt_bsdf_sample would give wi. */
KD_INLINE float3 pt_bsdf_eval(const PtMaterial* m, float3 color, float3 n, float3 wo, float3 wi, float* pdf) {
#ifdef KD_FEATURE_METALLIC_ROUGHNESS
  if (m->type == PT_METALLIC_ROUGHNESS)
    return pt_metal_rough_eval(m->roughness, m->ior, m->metallic, color, n, wo, wi, pdf);
#endif
#ifdef KD_FEATURE_GLOSSY
  if (m->type == PT_ROUGH_CONDUCTOR) return pt_ggx_eval(color, m->roughness, n, wo, wi, pdf);
#endif
  float cos_i = kd_dot(n, wi);
  if (cos_i <= 0.0f || pt_is_delta(m->type)) {
    *pdf = 0.0f;
    return kd_splat3(0.0f);
  }
  *pdf = cos_i * PT_INV_PI;
  return color * (cos_i * PT_INV_PI);
}

/* entering: wo is on the front (winding) side, which for a dielectric is the outside. u_lobe
 * picks the lobe of layered materials. */
KD_INLINE PtBsdfSample pt_bsdf_sample(const PtMaterial* m, float3 color, float3 n, float3 wo, int entering, float u1,
                                   float u2, float u_lobe) {
  PtBsdfSample s;
  s.is_delta = 0;
  s.transmits = 0;
#ifdef KD_FEATURE_MIRROR
  if (m->type == PT_MIRROR) {
    s.wi = 2.0f * kd_dot(wo, n) * n - wo;
    s.weight = color;
    s.pdf = 0.0f;
    s.is_delta = 1;
    return s;
  }
#endif
#ifdef KD_FEATURE_GLASS
  if (m->type == PT_DIELECTRIC) {
    float eta, cos_i, cos_t;
    float reflectance = pt_glass_reflectance(m->ior, entering, n, wo, &eta, &cos_i, &cos_t);
    s.pdf = 0.0f;
    s.is_delta = 1;
    if (u1 < reflectance) {
      s.wi = 2.0f * cos_i * n - wo;
      s.weight = kd_splat3(1.0f);
    } else {
      s.wi = pt_glass_refraction(eta, cos_i, cos_t, n, wo);
      s.weight = color * (eta * eta); /* radiance is scaled by (eta_i/eta_t)^2 across the boundary */
      s.transmits = 1;
    }
    return s;
  }
#endif
#ifdef KD_FEATURE_GLOSSY
  if (m->type == PT_ROUGH_CONDUCTOR) {
    s.wi = pt_ggx_sample_wi(m->roughness, n, wo, u1, u2);
    float3 f_cos = pt_ggx_eval(color, m->roughness, n, wo, s.wi, &s.pdf);
    s.weight = s.pdf > 0.0f ? f_cos / s.pdf : kd_splat3(0.0f);
    return s;
  }
#endif
#ifdef KD_FEATURE_METALLIC_ROUGHNESS
  if (m->type == PT_METALLIC_ROUGHNESS) {
    if (u_lobe < pt_gltf_ggx_probability(m->metallic, m->ior, color, kd_dot(n, wo)))
      s.wi = pt_ggx_sample_wi(m->roughness, n, wo, u1, u2);
    else
      s.wi = pt_sample_cosine(n, u1, u2);
    float3 f_cos = pt_metal_rough_eval(m->roughness, m->ior, m->metallic, color, n, wo, s.wi, &s.pdf);
    s.weight = s.pdf > 0.0f ? f_cos / s.pdf : kd_splat3(0.0f);
    return s;
  }
#endif
  (void)entering;
  (void)u_lobe;
  s.wi = pt_sample_cosine(n, u1, u2);
  s.pdf = fmax(kd_dot(n, s.wi), 0.0f) * PT_INV_PI;
  s.weight = s.pdf > 0.0f ? color : kd_splat3(0.0f);
  return s;
}

#endif /* PT_BSDF_H */
