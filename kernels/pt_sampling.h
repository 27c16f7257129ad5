/* Sampling helpers for the path tracer. */
#ifndef PT_SAMPLING_H
#define PT_SAMPLING_H

#include "kd_math.h"

#define PT_PI 3.14159265358979f
#define PT_INV_PI 0.318309886183791f

KD_INLINE float pt_max3(float3 v) { return fmax(v.x, fmax(v.y, v.z)); }
KD_INLINE float pt_luminance(float3 c) { return (c.x + c.y + c.z) * (1.0f / 3.0f); }
KD_INLINE float3 pt_load3(KD_GLOBAL const float* array, uint index) {
  return KD_FLOAT3(array[3 * index], array[3 * index + 1], array[3 * index + 2]);
}

/* Orthonormal basis around unit n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited"). */
KD_INLINE void pt_basis(float3 n, float3* t, float3* b) {
  float sign = copysign(1.0f, n.z);
  float a = -1.0f / (sign + n.z);
  float c = n.x * n.y * a;
  *t = KD_FLOAT3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  *b = KD_FLOAT3(c, sign + n.y * n.y * a, -n.y);
}

KD_INLINE float3 pt_to_world(float3 v, float3 n) {
  float3 t, b;
  pt_basis(n, &t, &b);
  return v.x * t + v.y * b + v.z * n;
}

/* Cosine-weighted direction around n; pdf = cos(theta) / pi. */
KD_INLINE float3 pt_sample_cosine(float3 n, float u1, float u2) {
  float r = sqrt(u1);
  float phi = 2.0f * PT_PI * u2;
  float z = sqrt(fmax(0.0f, 1.0f - u1));
  float sin_phi, cos_phi;
  kd_sincos(phi, &sin_phi, &cos_phi);
  return pt_to_world(KD_FLOAT3(r * cos_phi, r * sin_phi, z), n);
}

/* Uniform point on a triangle as barycentrics of vertices 1 and 2. */
KD_INLINE float2 pt_sample_triangle(float u1, float u2) {
  float s = sqrt(u1);
  return KD_FLOAT2(s * (1.0f - u2), s * u2);
}

/* Barycentrics of vertices 1 and 2 of the point q0 + d of the plane through q0 with edges e1, e2. */
KD_INLINE float2 pt_barycentrics(float3 d, float3 e1, float3 e2) {
  float d11 = kd_dot(e1, e1), d12 = kd_dot(e1, e2), d22 = kd_dot(e2, e2);
  float p1 = kd_dot(d, e1), p2 = kd_dot(d, e2);
  float inverse = 1.0f / (d11 * d22 - d12 * d12);
  return KD_FLOAT2((d22 * p1 - d12 * p2) * inverse, (d11 * p2 - d12 * p1) * inverse);
}

KD_INLINE float pt_power_heuristic(float pdf_a, float pdf_b) {
  float a = pdf_a * pdf_a;
  float b = pdf_b * pdf_b;
  return a / (a + b);
}

/* A secondary-ray origin that cannot re-hit the surface it leaves: p moved along the geometric
 * normal n (facing the side the ray leaves to) by a few ULPs of each coordinate's own magnitude, or
 * by a fixed tiny distance near 0 (Wachter & Binder 2019, Ray Tracing Gems ch. 6), and then by
 * 2^-19 of p's largest coordinate. The ray/triangle test takes the vertices relative to the ray's
 * origin, so the rounding error of its t grows with the distances in the scene, not with the
 * coordinate a surface lies at: from a wall in the plane x = 0, moved 1.5e-5 off it, shadow rays
 * of the Cornell box met the wall again at t = +3e-8 (0.4% of them, in the trees whose leaf held
 * the wall and the origin together, so the image depended on the tree). */
KD_INLINE float3 pt_offset_origin(float3 p, float3 n) {
  const float origin = 1.0f / 32.0f;
  const float float_scale = 1.0f / 65536.0f;
  const float int_scale = 256.0f;
  const float scene_scale = 0x1p-19f;
  /* integer steps of the bit patterns (as unsigned, which wraps like the signed sum would) */
  kd_i32 ox = (kd_i32)(int_scale * n.x), oy = (kd_i32)(int_scale * n.y), oz = (kd_i32)(int_scale * n.z);
  float3 p_int = KD_FLOAT3(kd_as_float(kd_as_uint(p.x) + (kd_u32)(p.x < 0 ? -ox : ox)),
                           kd_as_float(kd_as_uint(p.y) + (kd_u32)(p.y < 0 ? -oy : oy)),
                           kd_as_float(kd_as_uint(p.z) + (kd_u32)(p.z < 0 ? -oz : oz)));
  float3 moved = KD_FLOAT3(fabs(p.x) < origin ? p.x + float_scale * n.x : p_int.x,
                           fabs(p.y) < origin ? p.y + float_scale * n.y : p_int.y,
                           fabs(p.z) < origin ? p.z + float_scale * n.z : p_int.z);
  float largest = fmax(fmax(fabs(p.x), fabs(p.y)), fabs(p.z));
  return moved + (scene_scale * largest) * n;
}

#endif /* PT_SAMPLING_H */
