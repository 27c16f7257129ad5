// The path tracer's sampling functions (kernels/pt_sampling.h, kernels/pt_spherical_triangle.h)
// over 8 lanes (lane8.h), each lane with the scalar function's bits; a function here is the
// one of the same name with pt_ in front. Where the scalar function
// returns early for a case that is rare in a group of 8 (a triangle light sampled by solid
// angle), the lanes skip that part unless one of them needs it.
#pragma once

#include "lane8.h"

namespace lane8 {

inline f8 power_heuristic(f8 pdf_a, f8 pdf_b) {
  f8 a = pdf_a * pdf_a;
  f8 b = pdf_b * pdf_b;
  return a / (a + b);
}

inline void basis(V3 n, V3* t, V3* b) {
  f8 sign = vcopysign(splat(1.0f), n.z);
  f8 a = -1.0f / (sign + n.z);
  f8 c = n.x * n.y * a;
  *t = {1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x};
  *b = {c, sign + n.y * n.y * a, -n.y};
}
inline V3 to_world(V3 v, V3 n) {
  V3 t, b;
  basis(n, &t, &b);
  return v.x * t + v.y * b + v.z * n;
}
inline V3 sample_cosine(V3 n, f8 u1, f8 u2) {
  f8 r = vsqrt(u1);
  f8 phi = 2.0f * PT_PI * u2;
  f8 z = vsqrt(vmax(splat(0.0f), 1.0f - u1));
  f8 sin_phi, cos_phi;
  sincos(phi, &sin_phi, &cos_phi);
  return to_world({r * cos_phi, r * sin_phi, z}, n);
}

inline V3 offset_origin(V3 p, V3 n) {
  const float origin = 1.0f / 32.0f;
  const float float_scale = 1.0f / 65536.0f;
  const float int_scale = 256.0f;
  const float scene_scale = 0x1p-19f;
  auto moved = [&](f8 pc, f8 nc) {
    i8 o = truncate(int_scale * nc);
    f8 p_int = (f8)((u8)pc + (u8)(pc < 0.0f ? -o : o));
    return vabs(pc) < origin ? pc + float_scale * nc : p_int;
  };
  V3 m = {moved(p.x, n.x), moved(p.y, n.y), moved(p.z, n.z)};
  f8 largest = vmax(vmax(vabs(p.x), vabs(p.y)), vabs(p.z));
  return m + (scene_scale * largest) * n;
}

inline f8 solid_angle_of(V3 a, V3 b, V3 c) {
  f8 volume = vabs(dot(a, cross(b, c)));
  return 2.0f * atan2(volume, 1.0f + dot(a, b) + dot(b, c) + dot(c, a));
}
// pt_spherical_solid_angle for the lanes in `active`, 0 in the others; a, b and c are set only
// where it is not 0.
inline f8 spherical_solid_angle(i8 active, V3 p, V3 q0, V3 q1, V3 q2, V3* a, V3* b, V3* c) {
  V3 d0 = q0 - p, d1 = q1 - p, d2 = q2 - p;
  f8 l0 = length(d0), l1 = length(d1), l2 = length(d2);
  i8 need = active & (l0 > 0.0f) & (l1 > 0.0f) & (l2 > 0.0f);
  f8 volume = vabs(dot(d0, cross(d1, d2)));
  f8 denominator = l0 * l1 * l2 + dot(d0, d1) * l2 + dot(d1, d2) * l0 + dot(d2, d0) * l1;
  need &= ~((denominator > 0.0f) & (volume < PT_TAN_HALF_MIN_SPHERICAL * denominator));
  if (!any(need)) return splat(0.0f);
  *a = d0 / l0;
  *b = d1 / l1;
  *c = d2 / l2;
  f8 solid_angle = solid_angle_of(*a, *b, *c);
  i8 use = need & (solid_angle >= PT_MIN_SPHERICAL_SOLID_ANGLE) & (solid_angle <= PT_MAX_SPHERICAL_SOLID_ANGLE);
  return use ? solid_angle : splat(0.0f);
}
inline f8 triangle_light_pdf(f8 pick_per_area, f8 area, f8 spherical_solid_angle, f8 dist2, f8 cos_light) {
  return pick_per_area * (spherical_solid_angle > 0.0f ? area / spherical_solid_angle : dist2 / cos_light);
}
inline V3 orthonormalize(V3 v, V3 w) { return normalize(v - dot(v, w) * w); }
inline V3 sample_spherical_triangle(V3 a, V3 b, V3 c, f8 solid_angle, f8 u0, f8 u1) {
  V3 n_ab = normalize(cross(a, b)), n_ca = normalize(cross(c, a));
  f8 cos_alpha = -dot(n_ab, n_ca), sin_alpha = length(cross(n_ab, n_ca));
  f8 half_area = 0.5f * u0 * solid_angle, sin_half, cos_half;
  sincos(half_area, &sin_half, &cos_half);
  f8 sin_area = 2.0f * sin_half * cos_half, cos_area = 1.0f - 2.0f * sin_half * sin_half;
  f8 s = sin_area * cos_alpha - cos_area * sin_alpha, t = cos_area * cos_alpha + sin_area * sin_alpha;
  V3 ab = a - b;
  f8 u = 2.0f * sin_half * (sin_alpha * cos_half - cos_alpha * sin_half);
  f8 v = 2.0f * sin_half * (cos_half * cos_alpha + sin_half * sin_alpha) - sin_alpha * 0.5f * dot(ab, ab);
  f8 one_minus_q = (2.0f * v * sin_half * sin_half + u * sin_area) / ((v * s + u * t) * sin_alpha);
  one_minus_q = vmin(vmax(one_minus_q, splat(0.0f)), splat(2.0f));
  V3 c_sub = (1.0f - one_minus_q) * a + vsqrt(one_minus_q * (2.0f - one_minus_q)) * orthonormalize(c, a);
  V3 bc = c_sub - b;
  f8 one_minus_z = vmin(u1 * 0.5f * dot(bc, bc), splat(2.0f));
  return normalize((1.0f - one_minus_z) * b + vsqrt(one_minus_z * (2.0f - one_minus_z)) * orthonormalize(c_sub, b));
}

}  // namespace lane8
