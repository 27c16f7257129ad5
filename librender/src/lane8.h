// Eight floats in one AVX2 register, and the device code's vector math (kernels/kd_math.h,
// kernels/kd_vector.h) over them: each lane computes what the scalar function computes for its
// own arguments, bit for bit (the same IEEE operations in the same order, no contraction into FMA,
// every branch a select; sqrt, division and rint are correctly rounded or exact in both). Compiled
// into the x86-64-v3 build of the host's path tracer only (render_host_pixels.cpp), after the
// device code, whose constants it uses. A function here is the device code's function of the same
// name with kd_ (or pt_) in front.
#pragma once

#include <immintrin.h>

#include <cstdint>
#include <cstring>

namespace lane8 {

typedef float f8 __attribute__((vector_size(32)));
typedef int32_t i8 __attribute__((vector_size(32)));
typedef uint32_t u8 __attribute__((vector_size(32)));
constexpr int kLanes = 8;

inline f8 splat(float s) { return f8{} + s; }
inline f8 load(const float* p) {
  f8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store(float* p, f8 v) { std::memcpy(p, &v, sizeof v); }
inline i8 loadi(const int32_t* p) {
  i8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline f8 vsqrt(f8 x) { return (f8)_mm256_sqrt_ps((__m256)x); }
inline f8 vabs(f8 x) { return (f8)((i8)x & 0x7fffffff); }
inline f8 vmax(f8 a, f8 b) {
  const f8 larger = a > b ? a : b;
  return b != b ? a : larger;
}
inline f8 vmin(f8 a, f8 b) {
  const f8 smaller = a < b ? a : b;
  return b != b ? a : smaller;
}
inline f8 vrint(f8 x) { return (f8)_mm256_round_ps((__m256)x, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC); }
inline f8 vcopysign(f8 magnitude, f8 sign) { return (f8)(((i8)magnitude & 0x7fffffff) | ((i8)sign & (int32_t)0x80000000u)); }
// (int)x, truncating.
inline i8 truncate(f8 x) { return (i8)_mm256_cvttps_epi32((__m256)x); }
// base[index] in the lanes of the mask, 0 in the others (index: 32-bit, signed).
inline f8 gather(const float* base, i8 index, i8 mask) {
  return (f8)_mm256_mask_i32gather_ps(_mm256_setzero_ps(), base, (__m256i)index, (__m256)mask, 4);
}
inline i8 gather(const int32_t* base, i8 index, i8 mask) {
  return (i8)_mm256_mask_i32gather_epi32(_mm256_setzero_si256(), reinterpret_cast<const int*>(base), (__m256i)index,
                                         (__m256i)mask, 4);
}
// Masks are -1 (true) or 0 per lane, as vector comparisons give them.
inline bool any(i8 m) { return _mm256_movemask_ps((__m256)m) != 0; }
// Bit l set where lane l of the mask is true.
inline int bits(i8 m) { return _mm256_movemask_ps((__m256)m); }

// A float3 of 8 lanes, with float3's element-wise operators.
struct V3 {
  f8 x, y, z;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(V3 a, V3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline V3 operator-(V3 a) { return {-a.x, -a.y, -a.z}; }
inline V3 operator*(V3 a, f8 s) { return {a.x * s, a.y * s, a.z * s}; }
inline V3 operator*(f8 s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline V3 operator/(V3 a, f8 s) { return {a.x / s, a.y / s, a.z / s}; }
inline V3 sel(i8 m, V3 a, V3 b) { return {m ? a.x : b.x, m ? a.y : b.y, m ? a.z : b.z}; }
inline V3 splat3(float s) { return {splat(s), splat(s), splat(s)}; }

inline f8 dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline f8 length(V3 v) { return vsqrt(dot(v, v)); }
inline f8 rsqrt(f8 x) { return 1.0f / vsqrt(x); }
inline V3 normalize(V3 v) { return v * rsqrt(dot(v, v)); }
// pt_max3 and pt_luminance (kernels/pt_sampling.h)
inline f8 max3(V3 v) { return vmax(v.x, vmax(v.y, v.z)); }
inline f8 luminance(V3 c) { return (c.x + c.y + c.z) * (1.0f / 3.0f); }

// kd_sincos, kd_atan_unit and kd_atan2
inline void sincos(f8 x, f8* s, f8* c) {
  f8 k = vrint(x * 0.636619747f);
  f8 r = ((x - k * 1.5703125f) - k * 0x1.fb4p-12f) - k * 0x1.4442d2p-24f;
  f8 r2 = r * r;
  f8 sin_r = r + r * r2 * ((-1.9515295891e-4f * r2 + 8.3321608736e-3f) * r2 - 1.6666654611e-1f);
  f8 cos_r = 1.0f - 0.5f * r2 + r2 * r2 * ((2.443315711809948e-5f * r2 - 1.388731625493765e-3f) * r2 +
                                           4.166664568298827e-2f);
  i8 quadrant = truncate(k) & 3;
  f8 sin_x = (quadrant & 1) != 0 ? cos_r : sin_r;
  f8 cos_x = (quadrant & 1) != 0 ? sin_r : cos_r;
  *s = (quadrant & 2) != 0 ? -sin_x : sin_x;
  *c = (quadrant == 1) | (quadrant == 2) ? -cos_x : cos_x;
}
inline f8 atan_unit(f8 a) {
  i8 big = a > 0.414213562f;
  a = big ? (a - 1.0f) / (a + 1.0f) : a;
  f8 base = big ? splat(KD_PI_4_F) : splat(0.0f);
  f8 z = a * a;
  return base + ((((8.05374449538e-2f * z - 1.38776856032e-1f) * z + 1.99777106478e-1f) * z - 3.33329491539e-1f) *
                     z * a +
                 a);
}
inline f8 atan2(f8 y, f8 x) {
  f8 ax = vabs(x), ay = vabs(y);
  f8 hi = vmax(ax, ay), lo = vmin(ax, ay);
  f8 r = hi > 0.0f ? atan_unit(lo / hi) : splat(0.0f);
  r = ay > ax ? KD_PI_2_F - r : r;
  r = x < 0.0f ? KD_PI_F - r : r;
  return (x == x) & (y == y) ? vcopysign(r, y) : x + y;
}

}  // namespace lane8
