// Eight floats side by side in one AVX2 register: the lane type with which the host's paths in
// lanes (path_lanes.h) instantiate the device code's lane functions (kernels/kd_lane.h). Its
// operators and the few built-ins those functions call (sqrt, fabs, fmax, fmin, clamp, rint, copysign)
// give each lane what the float operation gives, bit for bit: IEEE arithmetic with no contraction
// into FMA (render_host_pixels.cpp's flags), correctly rounded sqrt and division, exact selects,
// and fmax and fmin with kernels/kd_vector.h's answers for NaN and signed zeros.
//
// Included by the x86-64-v3 build of render_host_pixels.cpp, inside its namespace after the
// device code.
#pragma once

#include <immintrin.h>

#include <cstdint>
#include <cstring>

namespace lane8 {

constexpr int kLanes = 8;
typedef float FloatVector __attribute__((vector_size(32)));
typedef int32_t IntVector __attribute__((vector_size(32)));
typedef uint32_t UintVector __attribute__((vector_size(32)));

// A comparison's answer per lane: -1 where true, 0 where false.
struct Mask8 {
  IntVector m;
  friend Mask8 operator&(Mask8 a, Mask8 b) { return {a.m & b.m}; }
  friend Mask8 operator|(Mask8 a, Mask8 b) { return {a.m | b.m}; }
  friend Mask8 operator!(Mask8 a) { return {~a.m}; }
};
// Bit l set where lane l of the mask is true.
inline int bits(Mask8 mask) { return _mm256_movemask_ps((__m256)mask.m); }
inline bool kd_any(Mask8 mask) { return bits(mask) != 0; }
// The mask of the lanes whose bits are set in `lanes`.
inline Mask8 lanes_of(int lanes) {
  const IntVector lane_bit = {1, 2, 4, 8, 16, 32, 64, 128};
  return {(lane_bit & lanes) != 0};
}

struct Int8 {
  IntVector v;
  Int8() = default;
  Int8(int32_t s) : v(IntVector{} + s) {}
  explicit Int8(IntVector x) : v(x) {}
  friend Int8 operator+(Int8 a, Int8 b) { return Int8(a.v + b.v); }
  friend Int8 operator*(Int8 a, Int8 b) { return Int8(a.v * b.v); }
  friend Int8 operator&(Int8 a, Int8 b) { return Int8(a.v & b.v); }
  friend Mask8 operator==(Int8 a, Int8 b) { return {a.v == b.v}; }
  friend Mask8 operator!=(Int8 a, Int8 b) { return {a.v != b.v}; }
  friend Mask8 operator<=(Int8 a, Int8 b) { return {a.v <= b.v}; }
  friend Mask8 operator>=(Int8 a, Int8 b) { return {a.v >= b.v}; }
};

struct Float8 {
  FloatVector v;
  Float8() = default;
  Float8(float s) : v(FloatVector{} + s) {}
  explicit Float8(FloatVector x) : v(x) {}
  float operator[](int lane) const { return v[lane]; }
  friend Float8 operator+(Float8 a, Float8 b) { return Float8(a.v + b.v); }
  friend Float8 operator-(Float8 a, Float8 b) { return Float8(a.v - b.v); }
  friend Float8 operator*(Float8 a, Float8 b) { return Float8(a.v * b.v); }
  friend Float8 operator/(Float8 a, Float8 b) { return Float8(a.v / b.v); }
  friend Float8 operator-(Float8 a) { return Float8(-a.v); }
  friend Float8& operator+=(Float8& a, Float8 b) { return a = a + b; }
  friend Mask8 operator<(Float8 a, Float8 b) { return {a.v < b.v}; }
  friend Mask8 operator>(Float8 a, Float8 b) { return {a.v > b.v}; }
  friend Mask8 operator<=(Float8 a, Float8 b) { return {a.v <= b.v}; }
  friend Mask8 operator>=(Float8 a, Float8 b) { return {a.v >= b.v}; }
  friend Mask8 operator==(Float8 a, Float8 b) { return {a.v == b.v}; }
  friend Mask8 operator!=(Float8 a, Float8 b) { return {a.v != b.v}; }
  friend Float8 sqrt(Float8 x) { return Float8((FloatVector)_mm256_sqrt_ps((__m256)x.v)); }
  friend Float8 fabs(Float8 x) { return Float8((FloatVector)((IntVector)x.v & 0x7fffffff)); }
  friend Float8 rint(Float8 x) {
    return Float8((FloatVector)_mm256_round_ps((__m256)x.v, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
  }
  friend Float8 copysign(Float8 magnitude, Float8 sign) {
    return Float8((FloatVector)(((IntVector)magnitude.v & 0x7fffffff) | ((IntVector)sign.v & INT32_MIN)));
  }
  // kernels/kd_vector.h's: a NaN operand gives the other operand, and of 0 and -0 the second.
  friend Float8 fmax(Float8 a, Float8 b) {
    const FloatVector larger = a.v > b.v ? a.v : b.v;
    return Float8(b.v != b.v ? a.v : larger);
  }
  friend Float8 fmin(Float8 a, Float8 b) {
    const FloatVector smaller = a.v < b.v ? a.v : b.v;
    return Float8(b.v != b.v ? a.v : smaller);
  }
  // kernels/kd_vector.h's clamp
  friend Float8 clamp(Float8 x, Float8 lo, Float8 hi) { return fmin(fmax(x, lo), hi); }
};
typedef kd_vec3<Float8> Float8x3;

inline Float8 kd_select(Mask8 mask, Float8 a, Float8 b) { return Float8(mask.m ? a.v : b.v); }
inline Int8 kd_select(Mask8 mask, Int8 a, Int8 b) { return Int8(mask.m ? a.v : b.v); }
inline Float8x3 kd_select(Mask8 mask, Float8x3 a, Float8x3 b) {
  return {kd_select(mask, a.x, b.x), kd_select(mask, a.y, b.y), kd_select(mask, a.z, b.z)};
}
// kernels/kd_lane.h's conversions.
inline Int8 kd_lane_to_int(Float8 x) { return Int8((IntVector)_mm256_cvttps_epi32((__m256)x.v)); }
inline Float8 kd_lane_step_bits(Float8 x, Int8 steps) {
  return Float8((FloatVector)((UintVector)x.v + (UintVector)steps.v));
}

// 8 values from, and to, consecutive memory.
inline Float8 load(const float* p) {
  Float8 x;
  std::memcpy(&x.v, p, sizeof x.v);
  return x;
}
inline Int8 load(const int32_t* p) {
  Int8 x;
  std::memcpy(&x.v, p, sizeof x.v);
  return x;
}
inline Int8 load(const uint32_t* p) { return load(reinterpret_cast<const int32_t*>(p)); }
inline void store(float* p, Float8 x) { std::memcpy(p, &x.v, sizeof x.v); }
inline void store(int32_t* p, Int8 x) { std::memcpy(p, &x.v, sizeof x.v); }
// base[index] in the lanes of the mask, 0 in the others (index: 32-bit, signed).
inline Float8 gather(const float* base, Int8 index, Mask8 mask) {
  return Float8((FloatVector)_mm256_mask_i32gather_ps(_mm256_setzero_ps(), base, (__m256i)index.v, (__m256)mask.m, 4));
}
inline Int8 gather(const int32_t* base, Int8 index, Mask8 mask) {
  return Int8((IntVector)_mm256_mask_i32gather_epi32(_mm256_setzero_si256(), reinterpret_cast<const int*>(base),
                                                     (__m256i)index.v, (__m256i)mask.m, 4));
}

}  // namespace lane8

template <>
struct kd_lane_types<lane8::Float8> {
  typedef lane8::Int8 integer;
  typedef lane8::Mask8 mask;
};
