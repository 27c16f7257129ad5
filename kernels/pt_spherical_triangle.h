/* Triangle emitters seen from a shading point: the solid angle they subtend and uniform
 * sampling of directions inside it (spherical triangles, Arvo 1995, "Stratified Sampling of
 * Spherical Triangles"). Next-event estimation samples a triangle by solid angle where it
 * subtends a mid-sized solid angle, and by area where it is tiny (float cancellation makes the
 * spherical construction unreliable, and area sampling is as good there) or covers nearly the
 * whole hemisphere, as pbrt-v4 decides. A BSDF-sampled ray that hits the triangle makes the same
 * decision from its origin (the shading point moved off the surface by a few ulps), so both
 * strategies' MIS weights use the same light density.
 */
#ifndef PT_SPHERICAL_TRIANGLE_H
#define PT_SPHERICAL_TRIANGLE_H

#include "kd_math.h"

/* Solid angles (sr) outside which a triangle light is sampled by area (pbrt-v4's thresholds). */
#define PT_MIN_SPHERICAL_SOLID_ANGLE 3e-4f
#define PT_MAX_SPHERICAL_SOLID_ANGLE 6.22f

/* Solid angle of the triangle with unit corner directions a, b, c (Van Oosterom & Strackee
 * 1983: tan(omega / 2) = |a . (b x c)| / (1 + a.b + b.c + c.a)). */
KD_INLINE float pt_solid_angle_of(float3 a, float3 b, float3 c) {
  float volume = fabs(kd_dot(a, kd_cross(b, c)));
  return 2.0f * kd_atan2(volume, 1.0f + kd_dot(a, b) + kd_dot(b, c) + kd_dot(c, a));
}

/* Solid angle that triangle q0 q1 q2 subtends at p, and the unit directions from p to its
 * corners; 0 when p lies on a corner. */
KD_INLINE float pt_triangle_solid_angle(float3 p, float3 q0, float3 q1, float3 q2, float3* a, float3* b, float3* c) {
  float3 d0 = q0 - p, d1 = q1 - p, d2 = q2 - p;
  float l0 = kd_length(d0), l1 = kd_length(d1), l2 = kd_length(d2);
  if (!(l0 > 0.0f && l1 > 0.0f && l2 > 0.0f)) return 0.0f;
  *a = d0 / l0;
  *b = d1 / l1;
  *c = d2 / l2;
  return pt_solid_angle_of(*a, *b, *c);
}

/* Whether a triangle of this solid angle is sampled by solid angle (else by area). */
KD_INLINE int pt_use_spherical_sampling(float solid_angle) {
  return solid_angle >= PT_MIN_SPHERICAL_SOLID_ANGLE && solid_angle <= PT_MAX_SPHERICAL_SOLID_ANGLE;
}

/* Solid-angle density of next-event estimation's sample in a direction that meets the triangle
 * (area `area`, solid angle `solid_angle`) at squared distance dist2 and cosine cos_light, given
 * the light's pick probability per unit area. */
KD_INLINE float pt_triangle_light_pdf(float pick_per_area, float area, float solid_angle, float dist2,
                                      float cos_light) {
  return pick_per_area * (pt_use_spherical_sampling(solid_angle) ? area / solid_angle : dist2 / cos_light);
}

/* The component of v orthogonal to unit w, normalized. */
KD_INLINE float3 pt_orthonormalize(float3 v, float3 w) { return kd_normalize(v - kd_dot(v, w) * w); }

/* A direction uniformly distributed (density 1 / solid_angle) over the spherical triangle with
 * unit corners a, b, c, from u0, u1 in [0, 1). u0 sweeps the area from edge ab (Arvo's
 * sub-triangle a b c' of area u0 * solid_angle, c' on arc ac) and u1 moves from b along the arc
 * to c', so a stratified (u0, u1) gives stratified directions. Arvo's formulas are rewritten so
 * that small triangles (arcs of 0.01 rad) keep float precision: every 1 - cos of a small angle
 * comes from a half-angle sine or a chord length, never from subtracting numbers near 1 (the
 * literal form skews the density by several percent there). */
KD_INLINE float3 pt_sample_spherical_triangle(float3 a, float3 b, float3 c, float solid_angle, float u0, float u1) {
  /* the interior angle alpha at a, between the planes of arcs ab and ac, by its cosine and sine */
  float3 n_ab = kd_normalize(kd_cross(a, b)), n_ca = kd_normalize(kd_cross(c, a));
  float cos_alpha = -kd_dot(n_ab, n_ca), sin_alpha = kd_length(kd_cross(n_ab, n_ca));
  /* the sub-triangle's area by its half angle, the only trigonometric call */
  float half_area = 0.5f * u0 * solid_angle, sin_half, cos_half;
  kd_sincos(half_area, &sin_half, &cos_half);
  float sin_area = 2.0f * sin_half * cos_half, cos_area = 1.0f - 2.0f * sin_half * sin_half;
  /* Arvo's s = sin(area - alpha), t = cos(area - alpha), and, by sum-to-product,
   * u = t - cos(alpha) and v = s + sin(alpha) cos(arc ab) */
  float s = sin_area * cos_alpha - cos_area * sin_alpha, t = cos_area * cos_alpha + sin_area * sin_alpha;
  float3 ab = a - b;
  float u = 2.0f * sin_half * (sin_alpha * cos_half - cos_alpha * sin_half);
  float v = 2.0f * sin_half * (cos_half * cos_alpha + sin_half * sin_alpha) - sin_alpha * 0.5f * kd_dot(ab, ab);
  /* 1 - cos of the arc a c' (Arvo's 1 - q), with s sin(alpha) - t cos(alpha) = -cos(area) */
  float one_minus_q = (2.0f * v * sin_half * sin_half + u * sin_area) / ((v * s + u * t) * sin_alpha);
  one_minus_q = fmin(fmax(one_minus_q, 0.0f), 2.0f);
  float3 c_sub = (1.0f - one_minus_q) * a + sqrt(one_minus_q * (2.0f - one_minus_q)) * pt_orthonormalize(c, a);
  /* 1 - cos of the arc from b to the sample: u1 (1 - b . c') */
  float3 bc = c_sub - b;
  float one_minus_z = fmin(u1 * 0.5f * kd_dot(bc, bc), 2.0f);
  return kd_normalize((1.0f - one_minus_z) * b + sqrt(one_minus_z * (2.0f - one_minus_z)) * pt_orthonormalize(c_sub, b));
}

#endif /* PT_SPHERICAL_TRIANGLE_H */
