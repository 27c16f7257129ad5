/* The environment light: an equirectangular (lat-long) radiance map around the scene, looked up
 * bilinearly and importance-sampled from a piecewise-constant 2D distribution.
 *
 * Mapping (Mitsuba 3's `envmap`, +Y up), for a direction d in the map's own frame:
 *   u = atan2(d.x, -d.z) / 2pi wrapped to [0, 1),  v = acos(d.y) / pi  (v = 0: top row, +Y)
 * column i has its centre at u = (i + 0.5) / W and row j at v = j / (H - 1), so the first row is
 * the zenith and the last the nadir (Mitsuba 3 aligns rows to the poles, not to texel centres:
 * matching that removes a per-pixel error of up to half a texel towards the poles against its
 * renders); u wraps, v clamps. The map is turned about +Y by the rotation in PtRenderParams
 * (world = R_y(angle) * map frame, counter-clockwise seen from above).
 *
 * Sampling distribution: cell (i, j) of the W x H grid over [0,1)^2 has weight
 * luminance(texel) * sin(theta_j), theta_j = pi (j + 0.5) / H. The table `cdf` holds H rows of W
 * conditional cdf values (row j at j * W, each ending in 1), then the H values of the marginal
 * cdf over rows, then the guides of the H rows (pt_cdf_guide_size(W) + 1 each, row j's at
 * W H + H + j (pt_cdf_guide_size(W) + 1)) and the marginal's (pt_cdf_guide_size(H) + 1): words
 * that are integers, not floats. The density in (u, v) is then p_row(j) p_col(i | j) W H, and
 * over solid angle that divided by 2 pi^2 sin(theta).
 *
 * Compiles as OpenCL C and as C++ (the host tests check the table against histograms). */
#ifndef PT_ENVIRONMENT_H
#define PT_ENVIRONMENT_H

#include "kd_compat.h"
#include "pt_sampling.h"
#include "pt_types.h"

/* Index of the first of n ascending cdf values that exceeds u, for 0 <= u < 1 (cdf[n - 1] = 1 > u),
 * searched from its guide (kernels/pt_sampling.h), whose words here are integers stored in the
 * float table. A cell with zero probability repeats its predecessor's value and so is never
 * returned. */
KD_INLINE kd_u32 pt_cdf_find(KD_GLOBAL const float* cdf, kd_u32 n, KD_GLOBAL const float* guide, float u) {
  const kd_u32 k = pt_cdf_guide_cell(n, u);
  kd_u32 lo = kd_as_uint(guide[k]), hi = kd_as_uint(guide[k + 1u]);
  while (lo < hi) {
    kd_u32 mid = (lo + hi) / 2;
    if (u < cdf[mid]) hi = mid; else lo = mid + 1;
  }
  return lo;
}

/* Where in the table the guide of row j starts (j = height: the marginal's); with j = height + 1,
 * the table's size. The one statement of the guides' layout, for the kernels and for the table's
 * builder (librender's environment_sampling_table). */
KD_INLINE kd_u32 pt_env_guide_offset(kd_u32 width, kd_u32 height, kd_u32 j) {
  const kd_u32 row_guide = pt_cdf_guide_size(width) + 1u;
  return width * height + height + (j <= height ? j * row_guide : height * row_guide + pt_cdf_guide_size(height) + 1u);
}
KD_INLINE KD_GLOBAL const float* pt_env_guide(KD_GLOBAL const float* cdf, kd_u32 width, kd_u32 height, kd_u32 j) {
  return cdf + pt_env_guide_offset(width, height, j);
}

/* Probability of cell i of a cdf. */
KD_INLINE float pt_cdf_cell(KD_GLOBAL const float* cdf, kd_u32 i) { return cdf[i] - (i > 0 ? cdf[i - 1] : 0.0f); }

/* Position within the chosen cell of a cdf, in [0, 1), from the same uniform number that chose it. */
KD_INLINE float pt_cdf_remap(KD_GLOBAL const float* cdf, kd_u32 i, float u) {
  float below = i > 0 ? cdf[i - 1] : 0.0f;
  float t = (u - below) / (cdf[i] - below);
  return t < 0.0f ? 0.0f : (t < 0.99999994f ? t : 0.99999994f);
}

/* Density over [0,1)^2 of pt_env_sample_uv at (u, v). */
KD_INLINE float pt_env_pdf_uv(KD_GLOBAL const float* cdf, kd_u32 width, kd_u32 height, float u, float v) {
  kd_u32 i = (kd_u32)(u * (float)width), j = (kd_u32)(v * (float)height);
  i = i < width ? i : width - 1;
  j = j < height ? j : height - 1;
  return pt_cdf_cell(cdf + width * height, j) * pt_cdf_cell(cdf + j * width, i) * (float)(width * height);
}

/* A point (u, v) in [0,1)^2 drawn from the table with two uniform numbers; returns its density. */
KD_INLINE float pt_env_sample_uv(KD_GLOBAL const float* cdf, kd_u32 width, kd_u32 height, float u1, float u2,
                                 float* u, float* v) {
  KD_GLOBAL const float* marginal = cdf + width * height;
  kd_u32 j = pt_cdf_find(marginal, height, pt_env_guide(cdf, width, height, height), u2);
  KD_GLOBAL const float* row = cdf + j * width;
  kd_u32 i = pt_cdf_find(row, width, pt_env_guide(cdf, width, height, j), u1);
  *u = ((float)i + pt_cdf_remap(row, i, u1)) / (float)width;
  *v = ((float)j + pt_cdf_remap(marginal, j, u2)) / (float)height;
  return pt_cdf_cell(marginal, j) * pt_cdf_cell(row, i) * (float)(width * height);
}

/* Map coordinates of world direction d (unit). */
KD_INLINE float2 pt_env_uv(KD_GLOBAL const PtRenderParams* params, float3 d) {
  float c = params->env_rotate_cos, s = params->env_rotate_sin;
  float x = c * d.x - s * d.z, z = s * d.x + c * d.z; /* R_y(-angle) d */
  float u = kd_atan2(x, -z) * (0.5f * PT_INV_PI);
  u -= floor(u);
  float v = kd_acos(clamp(d.y, -1.0f, 1.0f)) * PT_INV_PI;
  return KD_FLOAT2(u < 1.0f ? u : 0.0f, v);
}

/* World direction of map coordinates (u, v); *sin_theta receives sin(pi v). */
KD_INLINE float3 pt_env_direction(KD_GLOBAL const PtRenderParams* params, float2 uv, float* sin_theta) {
  float phi = 2.0f * PT_PI * uv.x, theta = PT_PI * uv.y;
  float st, ct, sp, cp;
  kd_sincos(theta, &st, &ct);
  kd_sincos(phi, &sp, &cp);
  float x = st * sp, y = ct, z = -st * cp;
  float c = params->env_rotate_cos, s = params->env_rotate_sin;
  *sin_theta = st;
  return KD_FLOAT3(c * x + s * z, y, -s * x + c * z); /* R_y(angle) */
}

KD_INLINE float3 pt_env_texel(KD_GLOBAL const float* texels, uint width, uint height, int x, int y) {
  x %= (int)width;
  x += x < 0 ? (int)width : 0;
  y = clamp(y, 0, (int)height - 1);
  return vload3((uint)y * width + (uint)x, texels);
}

/* Bilinear radiance at map coordinates (u, v), strength applied; rows as the mapping above. */
KD_INLINE float3 pt_env_lookup(KD_GLOBAL const float* texels, KD_GLOBAL const PtRenderParams* params, float2 uv) {
  uint w = params->env_width, h = params->env_height;
  float fx = uv.x * (float)w - 0.5f, fy = uv.y * (float)(h - 1);
  float x0 = floor(fx), y0 = floor(fy);
  float ax = fx - x0, ay = fy - y0;
  int ix = (int)x0, iy = (int)y0;
  float3 top = kd_mix3(pt_env_texel(texels, w, h, ix, iy), pt_env_texel(texels, w, h, ix + 1, iy), ax);
  float3 bottom = kd_mix3(pt_env_texel(texels, w, h, ix, iy + 1), pt_env_texel(texels, w, h, ix + 1, iy + 1), ax);
  return params->env_strength * kd_mix3(top, bottom, ay);
}

/* Solid-angle density with which next-event estimation picks direction d (light choice included). */
KD_INLINE float pt_env_pdf(KD_GLOBAL const float* cdf, KD_GLOBAL const PtRenderParams* params, float2 uv) {
  float sin_theta = kd_sin(PT_PI * uv.y);
  if (!(sin_theta > 0.0f)) return 0.0f;
  return params->select_environment * pt_env_pdf_uv(cdf, params->env_width, params->env_height, uv.x, uv.y) /
         (2.0f * PT_PI * PT_PI * sin_theta);
}

#endif /* PT_ENVIRONMENT_H */
