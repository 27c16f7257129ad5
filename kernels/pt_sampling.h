/* Sampling helpers for the path tracer. */
#ifndef PT_SAMPLING_H
#define PT_SAMPLING_H

#include "kd_math.h"

#define PT_PI 3.14159265358979f
#define PT_INV_PI 0.318309886183791f

KD_LANE_FN kd_lane pt_max3(kd_lane3 v) { return fmax(v.x, fmax(v.y, v.z)); }
KD_LANE_FN kd_lane pt_luminance(kd_lane3 c) { return (c.x + c.y + c.z) * (1.0f / 3.0f); }
KD_INLINE float3 pt_load3(KD_GLOBAL const float* array, uint index) {
  return KD_FLOAT3(array[3 * index], array[3 * index + 1], array[3 * index + 2]);
}

/* Guides of the cdf searches (the environment's table, kernels/pt_environment.h; the emitters'
 * table, kernels/pt_direct_light.h). A search returns the first of n ascending cdf values (the
 * last 1) that exceeds u, for 0 <= u < 1. Its guide holds G + 1 indices, G = pt_cdf_guide_size(n):
 * for k < G the index the search returns for u = k / G, and n - 1 for k = G. The answer grows
 * with u, so for k = pt_cdf_guide_cell(n, u) it lies between guide[k] and guide[k + 1], and u * G
 * is exact (G is a power of two): a bisection of that range returns the very index a bisection
 * of the whole cdf returns, after one or two dependent reads of the table instead of log2(n),
 * each of which waited on a cache miss in a large table (bench/LOG.md, "The environment's table
 * searched from guides"). */

/* G: the largest power of two up to n / 16 (at least 1), so that a cell holds about one cache
 * line of cdf values. */
KD_INLINE kd_u32 pt_cdf_guide_size(kd_u32 n) {
  const kd_u32 cells = n >> 4 > 1u ? n >> 4 : 1u;
#ifdef __OPENCL_VERSION__
  return 1u << (31u - clz(cells));
#else
  return 1u << (31 - __builtin_clz(cells));
#endif
}

/* k, the guide's cell that u falls in. */
KD_INLINE kd_u32 pt_cdf_guide_cell(kd_u32 n, float u) {
  const kd_u32 cells = pt_cdf_guide_size(n);
  const kd_u32 k = (kd_u32)(u * (float)cells);
  return k < cells ? k : cells - 1u;
}

/* Orthonormal basis around unit n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited"). */
KD_LANE_FN void pt_basis(kd_lane3 n, kd_lane3* t, kd_lane3* b) {
  kd_lane sign = copysign((kd_lane)1.0f, n.z);
  kd_lane a = -1.0f / (sign + n.z);
  kd_lane c = n.x * n.y * a;
  *t = KD_LANE3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  *b = KD_LANE3(c, sign + n.y * n.y * a, -n.y);
}

KD_LANE_FN kd_lane3 pt_to_world(kd_lane3 v, kd_lane3 n) {
  kd_lane3 t, b;
  pt_basis(n, &t, &b);
  return v.x * t + v.y * b + v.z * n;
}

/* Cosine-weighted direction around n; pdf = cos(theta) / pi. */
KD_LANE_FN kd_lane3 pt_sample_cosine(kd_lane3 n, kd_lane u1, kd_lane u2) {
  kd_lane r = sqrt(u1);
  kd_lane phi = 2.0f * PT_PI * u2;
  kd_lane z = sqrt(fmax((kd_lane)0.0f, 1.0f - u1));
  kd_lane sin_phi, cos_phi;
  kd_sincos(phi, &sin_phi, &cos_phi);
  return pt_to_world(KD_LANE3(r * cos_phi, r * sin_phi, z), n);
}

/* Uniform point on a triangle as barycentrics b1, b2 of vertices 1 and 2. */
KD_LANE_FN void pt_sample_triangle(kd_lane u1, kd_lane u2, kd_lane* b1, kd_lane* b2) {
  kd_lane s = sqrt(u1);
  *b1 = s * (1.0f - u2);
  *b2 = s * u2;
}

/* Barycentrics of vertices 1 and 2 of the point q0 + d of the plane through q0 with edges e1, e2. */
KD_INLINE float2 pt_barycentrics(float3 d, float3 e1, float3 e2) {
  float d11 = kd_dot(e1, e1), d12 = kd_dot(e1, e2), d22 = kd_dot(e2, e2);
  float p1 = kd_dot(d, e1), p2 = kd_dot(d, e2);
  float inverse = 1.0f / (d11 * d22 - d12 * d12);
  return KD_FLOAT2((d22 * p1 - d12 * p2) * inverse, (d11 * p2 - d12 * p1) * inverse);
}

KD_LANE_FN kd_lane pt_power_heuristic(kd_lane pdf_a, kd_lane pdf_b) {
  kd_lane a = pdf_a * pdf_a;
  kd_lane b = pdf_b * pdf_b;
  return a / (a + b);
}

/* One coordinate of pt_offset_origin's (below) before the move by the largest: a few ULPs of its
 * own magnitude along n, or a fixed tiny distance near 0. */
KD_LANE_FN kd_lane pt_offset_coordinate(kd_lane p, kd_lane n) {
  const float origin = 1.0f / 32.0f;
  const float float_scale = 1.0f / 65536.0f;
  const float int_scale = 256.0f;
  /* integer steps of the bit pattern that move p along n */
  kd_lane steps = int_scale * n;
  kd_lane stepped = kd_lane_step_bits(p, kd_lane_to_int(kd_select(p < 0.0f, -steps, steps)));
  return kd_select(fabs(p) < origin, p + float_scale * n, stepped);
}
/* A secondary-ray origin that cannot re-hit the surface it leaves: p moved along the geometric
 * normal n (facing the side the ray leaves to) by a few ULPs of each coordinate's own magnitude, or
 * by a fixed tiny distance near 0 (Wachter & Binder 2019, Ray Tracing Gems ch. 6), and then by
 * 2^-19 of p's largest coordinate. The ray/triangle test takes the vertices relative to the ray's
 * origin, so the rounding error of its t grows with the distances in the scene, not with the
 * coordinate a surface lies at: from a wall in the plane x = 0, moved 1.5e-5 off it, shadow rays
 * of the Cornell box met the wall again at t = +3e-8 (0.4% of them, in the trees whose leaf held
 * the wall and the origin together, so the image depended on the tree). */
KD_LANE_FN kd_lane3 pt_offset_origin(kd_lane3 p, kd_lane3 n) {
  const float scene_scale = 0x1p-19f;
  kd_lane3 moved =
      KD_LANE3(pt_offset_coordinate(p.x, n.x), pt_offset_coordinate(p.y, n.y), pt_offset_coordinate(p.z, n.z));
  kd_lane largest = fmax(fmax(fabs(p.x), fabs(p.y)), fabs(p.z));
  return moved + (scene_scale * largest) * n;
}

#endif /* PT_SAMPLING_H */
