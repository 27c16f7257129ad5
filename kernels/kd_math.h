/* Vector and trigonometric functions of the device code, written out once for both languages.
 *
 * The path tracer's C++ build (librender/src/render_host_pixels.cpp) must give the kernel's bits
 * (tests/render/cpu_integrator.h).
 * OpenCL's dot, length, normalize, mix and rsqrt may sum in another order or approximate, and
 * each platform's sin, cos, acos and atan2 differ in their last bits; the versions here use only
 * + - * /, sqrt and exact operations, in a fixed order, with contraction into FMA off on both
 * sides (kd_compat.h) and correctly rounded
 * division and square root (-cl-fp32-correctly-rounded-divide-sqrt; IEEE in C++).
 *
 * The polynomials are the minimax fits of Cephes' single-precision sinf, cosf, asinf and atanf
 * (Moshier), with argument reductions sized for the arguments the path tracer passes: angles of
 * a few turns at most. tests/render/kd_math_test.cpp measures their error against double libm. */
#ifndef KD_MATH_H
#define KD_MATH_H

#include "kd_compat.h"
#include "kd_lane.h"
#include "kd_vector.h"

#define KD_PI_F 3.14159274f     /* pi rounded to float */
#define KD_PI_2_F 1.57079637f   /* pi / 2 rounded to float */
#define KD_PI_4_F 0.785398163f  /* pi / 4 rounded to float */

KD_LANE_FN kd_lane kd_dot(kd_lane3 a, kd_lane3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
KD_LANE_FN kd_lane3 kd_cross(kd_lane3 a, kd_lane3 b) {
  return KD_LANE3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
KD_LANE_FN kd_lane kd_length(kd_lane3 v) { return sqrt(kd_dot(v, v)); }
KD_LANE_FN kd_lane kd_rsqrt(kd_lane x) { return 1.0f / sqrt(x); }
KD_LANE_FN kd_lane3 kd_normalize(kd_lane3 v) { return v * kd_rsqrt(kd_dot(v, v)); }
/* a + (b - a) t, OpenCL's definition of mix. */
KD_INLINE float3 kd_mix3(float3 a, float3 b, float t) { return a + (b - a) * t; }
KD_INLINE float4 kd_mix4(float4 a, float4 b, float t) {
  return KD_FLOAT4(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.z + (b.z - a.z) * t, a.w + (b.w - a.w) * t);
}

/* sin and cos of x together. x is reduced to r in [-pi/4, pi/4] by the nearest multiple k of
 * pi/2, subtracted in three parts (Cody and Waite): 1.5703125 and 0x1.fb4p-12 have so few bits
 * that k times them is exact for |k| < 2^13, so r keeps full precision for |x| up to about 1e4
 * (the path tracer passes angles within [-4 pi, 4 pi]). */
KD_LANE_FN void kd_sincos(kd_lane x, kd_lane* s, kd_lane* c) {
  kd_lane k = rint(x * 0.636619747f);
  kd_lane r = ((x - k * 1.5703125f) - k * 0x1.fb4p-12f) - k * 0x1.4442d2p-24f;
  kd_lane r2 = r * r;
  kd_lane sin_r = r + r * r2 * ((-1.9515295891e-4f * r2 + 8.3321608736e-3f) * r2 - 1.6666654611e-1f);
  kd_lane cos_r = 1.0f - 0.5f * r2 + r2 * r2 * ((2.443315711809948e-5f * r2 - 1.388731625493765e-3f) * r2 +
                                                4.166664568298827e-2f);
  KD_LANE_INT quadrant = kd_lane_to_int(k) & 3;
  kd_lane sin_x = kd_select((quadrant & 1) != 0, cos_r, sin_r);
  kd_lane cos_x = kd_select((quadrant & 1) != 0, sin_r, cos_r);
  *s = kd_select((quadrant & 2) != 0, -sin_x, sin_x);
  *c = kd_select((quadrant == 1) | (quadrant == 2), -cos_x, cos_x);
}
KD_INLINE float kd_sin(float x) {
  float s, c;
  kd_sincos(x, &s, &c);
  return s;
}
KD_INLINE float kd_cos(float x) {
  float s, c;
  kd_sincos(x, &s, &c);
  return c;
}

/* asin(s) / s - 1 as a polynomial in z = s^2, for 0 <= s <= 1/2. */
KD_INLINE float kd_asin_tail(float z) {
  return ((((4.2163199048e-2f * z + 2.4181311049e-2f) * z + 4.5470025998e-2f) * z + 7.4953002686e-2f) * z +
          1.6666752422e-1f) *
         z;
}
/* acos(x) for x in [-1, 1]: pi/2 - asin(x) near 0, else 2 asin(sqrt((1 - |x|) / 2)), which keeps
 * precision near |x| = 1 where acos is steep. NaN outside [-1, 1]. */
KD_INLINE float kd_acos(float x) {
  float ax = fabs(x);
  if (ax <= 0.5f) return KD_PI_2_F - (x + x * kd_asin_tail(x * x));
  float z = 0.5f * (1.0f - ax);
  float s = sqrt(z);
  float r = 2.0f * (s + s * kd_asin_tail(z));
  return x > 0.0f ? r : KD_PI_F - r;
}

/* atan(a) for a in [0, 1]: above tan(pi/8) through atan(a) = pi/4 + atan((a - 1) / (a + 1)). */
KD_LANE_FN kd_lane kd_atan_unit(kd_lane a) {
  KD_LANE_MASK reduced = a > 0.414213562f;
  a = kd_select(reduced, (a - 1.0f) / (a + 1.0f), a);
  kd_lane base = kd_select(reduced, (kd_lane)KD_PI_4_F, (kd_lane)0.0f);
  kd_lane z = a * a;
  return base + ((((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) *
                     z * a +
                 a);
}
/* atan2(y, x) from the atan of min(|x|, |y|) / max(|x|, |y|), moved to its octant; +-0 when
 * both are 0 (whatever the sign of x), NaN when either is NaN. */
KD_LANE_FN kd_lane kd_atan2(kd_lane y, kd_lane x) {
  kd_lane ax = fabs(x), ay = fabs(y);
  kd_lane hi = fmax(ax, ay), lo = fmin(ax, ay);
  kd_lane r = kd_select(hi > 0.0f, kd_atan_unit(lo / hi), (kd_lane)0.0f);
  r = kd_select(ay > ax, KD_PI_2_F - r, r);
  r = kd_select(x < 0.0f, KD_PI_F - r, r);
  return kd_select((x == x) & (y == y), copysign(r, y), x + y);
}

#endif /* KD_MATH_H */
