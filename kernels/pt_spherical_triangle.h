/* Triangle emitters seen from a shading point: the solid angle they subtend and uniform
 * sampling of directions inside it (spherical triangles, Arvo 1995, "Stratified Sampling of
 * Spherical Triangles"). Next-event estimation samples a triangle by solid angle where it
 * subtends a large solid angle, and by area where it is small (area sampling is nearly as good
 * there, and cheaper) or covers nearly the whole hemisphere (as pbrt-v4 decides: the spherical
 * construction loses precision there). A BSDF-sampled ray that hits the triangle makes the same
 * decision from its origin (the shading point moved off the surface by a few ulps), so both
 * strategies' MIS weights use the same light density.
 */
#ifndef PT_SPHERICAL_TRIANGLE_H
#define PT_SPHERICAL_TRIANGLE_H

#include "kd_math.h"

/* Solid angles (sr) outside which a triangle light is sampled by area. Above the upper bound
 * (pbrt-v4's) the spherical construction loses precision. Below the lower one, area sampling's
 * density, d^2 / (A cos), varies across the triangle by a few per cent at most, so it is nearly
 * as good and costs less than the solid angle's arctangent and the spherical construction. The
 * lower bound was chosen by error x cost on the Cornell box (bench/LOG.md, "traversal setup
 * and light-sampling cost"): 0.05 sr gave 7% fewer kernel instructions for 1.3% more error
 * than pbrt-v4's 3e-4. */
#define PT_MIN_SPHERICAL_SOLID_ANGLE 0.05f
#define PT_TAN_HALF_MIN_SPHERICAL 0.0250052096f /* tan(PT_MIN_SPHERICAL_SOLID_ANGLE / 2) */
#define PT_MAX_SPHERICAL_SOLID_ANGLE 6.22f

/* Solid angle of the triangle with unit corner directions a, b, c (Van Oosterom & Strackee
 * 1983: tan(omega / 2) = |a . (b x c)| / (1 + a.b + b.c + c.a)). */
KD_LANE_FN kd_lane pt_solid_angle_of(kd_lane3 a, kd_lane3 b, kd_lane3 c) {
  kd_lane volume = fabs(kd_dot(a, kd_cross(b, c)));
  return 2.0f * kd_atan2(volume, 1.0f + kd_dot(a, b) + kd_dot(b, c) + kd_dot(c, a));
}

/* Whether a triangle of this solid angle is sampled by solid angle (else by area). */
KD_LANE_FN KD_LANE_MASK pt_use_spherical_sampling(kd_lane solid_angle) {
  return (solid_angle >= PT_MIN_SPHERICAL_SOLID_ANGLE) & (solid_angle <= PT_MAX_SPHERICAL_SOLID_ANGLE);
}

/* How next-event estimation samples triangle q0 q1 q2 from p: returns its solid angle, with the
 * unit directions to its corners in a, b, c, when by solid angle, and 0 when by area (also when
 * p lies on a corner). Most triangles a path meets are small in its view, so the lower bound is
 * tested without the arctangent and the divisions: with corner vectors d_i of lengths l_i,
 * tan(omega / 2) = |d0 . (d1 x d2)| / (l0 l1 l2 + (d0.d1) l2 + (d1.d2) l0 + (d2.d0) l1), and
 * omega is below the bound when that ratio is below tan(bound / 2) with a positive denominator. */
KD_LANE_FN kd_lane pt_spherical_solid_angle(kd_lane3 p, kd_lane3 q0, kd_lane3 q1, kd_lane3 q2, kd_lane3* a, kd_lane3* b,
                                            kd_lane3* c) {
  kd_lane3 d0 = q0 - p, d1 = q1 - p, d2 = q2 - p;
  kd_lane l0 = kd_length(d0), l1 = kd_length(d1), l2 = kd_length(d2);
  KD_LANE_MASK spherical = (l0 > 0.0f) & (l1 > 0.0f) & (l2 > 0.0f);
  kd_lane volume = fabs(kd_dot(d0, kd_cross(d1, d2)));
  kd_lane denominator = l0 * l1 * l2 + kd_dot(d0, d1) * l2 + kd_dot(d1, d2) * l0 + kd_dot(d2, d0) * l1;
  spherical = spherical & !((denominator > 0.0f) & (volume < PT_TAN_HALF_MIN_SPHERICAL * denominator));
  if (!kd_any(spherical)) return (kd_lane)0.0f;
  *a = d0 / l0;
  *b = d1 / l1;
  *c = d2 / l2;
  kd_lane solid_angle = pt_solid_angle_of(*a, *b, *c);
  return kd_select(spherical & pt_use_spherical_sampling(solid_angle), solid_angle, (kd_lane)0.0f);
}

/* Solid-angle density of next-event estimation's sample in a direction that meets the triangle
 * (area `area`) at squared distance dist2 and cosine cos_light, given the light's pick
 * probability per unit area and pt_spherical_solid_angle's answer (0: sampled by area). */
KD_LANE_FN kd_lane pt_triangle_light_pdf(kd_lane pick_per_area, kd_lane area, kd_lane spherical_solid_angle,
                                         kd_lane dist2, kd_lane cos_light) {
  return pick_per_area * kd_select(spherical_solid_angle > 0.0f, area / spherical_solid_angle, dist2 / cos_light);
}

/* The component of v orthogonal to unit w, normalized. */
KD_LANE_FN kd_lane3 pt_orthonormalize(kd_lane3 v, kd_lane3 w) { return kd_normalize(v - kd_dot(v, w) * w); }

/* A direction uniformly distributed (density 1 / solid_angle) over the spherical triangle with
 * unit corners a, b, c, from u0, u1 in [0, 1). u0 sweeps the area from edge ab (Arvo's
 * sub-triangle a b c' of area u0 * solid_angle, c' on arc ac) and u1 moves from b along the arc
 * to c', so a stratified (u0, u1) gives stratified directions. Arvo's formulas are rewritten so
 * that small triangles (arcs of 0.01 rad) keep float precision: every 1 - cos of a small angle
 * comes from a half-angle sine or a chord length, never from subtracting numbers near 1 (the
 * literal form skews the density by several percent there). */
KD_LANE_FN kd_lane3 pt_sample_spherical_triangle(kd_lane3 a, kd_lane3 b, kd_lane3 c, kd_lane solid_angle, kd_lane u0,
                                                 kd_lane u1) {
  /* the interior angle alpha at a, between the planes of arcs ab and ac, by its cosine and sine */
  kd_lane3 n_ab = kd_normalize(kd_cross(a, b)), n_ca = kd_normalize(kd_cross(c, a));
  kd_lane cos_alpha = -kd_dot(n_ab, n_ca), sin_alpha = kd_length(kd_cross(n_ab, n_ca));
  /* the sub-triangle's area by its half angle, the only trigonometric call */
  kd_lane half_area = 0.5f * u0 * solid_angle, sin_half, cos_half;
  kd_sincos(half_area, &sin_half, &cos_half);
  kd_lane sin_area = 2.0f * sin_half * cos_half, cos_area = 1.0f - 2.0f * sin_half * sin_half;
  /* Arvo's s = sin(area - alpha), t = cos(area - alpha), and, by sum-to-product,
   * u = t - cos(alpha) and v = s + sin(alpha) cos(arc ab) */
  kd_lane s = sin_area * cos_alpha - cos_area * sin_alpha, t = cos_area * cos_alpha + sin_area * sin_alpha;
  kd_lane3 ab = a - b;
  kd_lane u = 2.0f * sin_half * (sin_alpha * cos_half - cos_alpha * sin_half);
  kd_lane v = 2.0f * sin_half * (cos_half * cos_alpha + sin_half * sin_alpha) - sin_alpha * 0.5f * kd_dot(ab, ab);
  /* 1 - cos of the arc a c' (Arvo's 1 - q), with s sin(alpha) - t cos(alpha) = -cos(area) */
  kd_lane one_minus_q = (2.0f * v * sin_half * sin_half + u * sin_area) / ((v * s + u * t) * sin_alpha);
  one_minus_q = fmin(fmax(one_minus_q, 0.0f), 2.0f);
  kd_lane3 c_sub = (1.0f - one_minus_q) * a + sqrt(one_minus_q * (2.0f - one_minus_q)) * pt_orthonormalize(c, a);
  /* 1 - cos of the arc from b to the sample: u1 (1 - b . c') */
  kd_lane3 bc = c_sub - b;
  kd_lane one_minus_z = fmin(u1 * 0.5f * kd_dot(bc, bc), 2.0f);
  return kd_normalize((1.0f - one_minus_z) * b + sqrt(one_minus_z * (2.0f - one_minus_z)) * pt_orthonormalize(c_sub, b));
}

#endif /* PT_SPHERICAL_TRIANGLE_H */
