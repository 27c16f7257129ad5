/* Tables of the rough dielectric coat of glTF non-metals (Mitsuba 3's roughplastic model), built
 * by librender (kdray/coat_tables.h) for each index of refraction eta the scene's
 * metallic-roughness materials use, and read by pt_metal_rough_eval (kernels/pt_bsdf.h):
 *  - the transmittance T(cos theta, alpha) of the rough interface seen from outside: the energy
 *    of its GGX refraction lobe (Fresnel 1 - F per microfacet, Smith masking of the refracted
 *    direction), which is less than 1 - (its reflectance) because single-scattering microfacet
 *    models lose what scatters between facets;
 *  - the internal reflectance F_int(alpha): the cosine-weighted hemispherical mean,
 *    2 * integral of R(mu) mu dmu, of the interface's GGX reflection lobe seen from inside
 *    (relative index 1 / eta, total internal reflection included).
 * Layout (floats): [0] the number of etas n, [1..n] the etas, then one block per eta of
 * PT_COAT_ALPHAS rows at alpha_j = (j / (PT_COAT_ALPHAS - 1))^2 (even in glTF's perceptual
 * roughness sqrt(alpha), where the values change smoothly: linear interpolation between rows is
 * then within 0.2% for cos theta >= 0.2; alpha below 1e-3 is 1e-3, as the GGX code clamps it);
 * row j holds F_int(alpha_j) and then T at cos theta = i / (PT_COAT_COSINES - 1) (Mitsuba 3's
 * grid). Lookups are bilinear; alpha above 1 (beyond glTF's range) reads the alpha = 1 row.
 * Compiles as OpenCL C and as C++. */
#ifndef PT_COAT_H
#define PT_COAT_H

#include "kd_compat.h"

#define PT_COAT_COSINES 64
#define PT_COAT_ALPHAS 32
#define PT_COAT_ROW (PT_COAT_COSINES + 1)
#define PT_COAT_BLOCK (PT_COAT_ALPHAS * PT_COAT_ROW)

/* Where a lookup reads: the first float of the lower alpha row, and the weight of the upper one. */
typedef struct PtCoatRow {
  kd_i32 row;
  float alpha_weight;
} PtCoatRow;

/* The rows of (eta, alpha). The host builds a block for every eta a material uses, so the search
 * always finds one (the first block otherwise). */
KD_INLINE PtCoatRow pt_coat_row(KD_GLOBAL const float* table, float eta, float alpha) {
  kd_i32 n = (kd_i32)table[0];
  kd_i32 block = 0;
  for (kd_i32 i = 0; i < n; ++i)
    if (table[1 + i] == eta) {
      block = i;
      break;
    }
  float x = sqrt(fmin(fmax(alpha, 0.0f), 1.0f)) * (float)(PT_COAT_ALPHAS - 1);
  kd_i32 j = (kd_i32)fmin(floor(x), (float)(PT_COAT_ALPHAS - 2));
  PtCoatRow r;
  r.row = 1 + n + block * PT_COAT_BLOCK + j * PT_COAT_ROW;
  r.alpha_weight = x - (float)j;
  return r;
}

KD_INLINE float pt_coat_lerp(float a, float b, float t) { return a + (b - a) * t; }

/* F_int at the row's alpha. */
KD_INLINE float pt_coat_internal_reflectance(KD_GLOBAL const float* table, PtCoatRow r) {
  return pt_coat_lerp(table[r.row], table[r.row + PT_COAT_ROW], r.alpha_weight);
}

/* T at the row's alpha for light arriving from outside at cos theta = cos_theta. */
KD_INLINE float pt_coat_transmittance(KD_GLOBAL const float* table, PtCoatRow r, float cos_theta) {
  float x = fmin(fmax(cos_theta, 0.0f), 1.0f) * (float)(PT_COAT_COSINES - 1);
  kd_i32 i = (kd_i32)fmin(floor(x), (float)(PT_COAT_COSINES - 2));
  float t = x - (float)i;
  KD_GLOBAL const float* lo = table + r.row + 1 + i;
  KD_GLOBAL const float* hi = lo + PT_COAT_ROW;
  return pt_coat_lerp(pt_coat_lerp(lo[0], lo[1], t), pt_coat_lerp(hi[0], hi[1], t), r.alpha_weight);
}

#endif /* PT_COAT_H */
