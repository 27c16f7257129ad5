/* OpenCL's float2/float3/float4 and the exact built-ins the path tracer uses, for its C++ build,
 * so kernels/pt_path.h and everything it includes compile as both languages.
 *
 * Both sides build vectors with KD_FLOAT2/3/4: in C++ an OpenCL literal such as (float3)(a, b, c)
 * would be a comma expression. Element-wise operators and the built-ins kept here (fmin, fmax,
 * fabs, floor, sqrt, copysign, rint, isfinite, clamp, vload2, vload3, vload4) give correctly rounded or
 * exact results in both languages, so the same expression has the same bits on both sides.
 * Operations whose OpenCL built-in may be computed in another order or approximated (dot,
 * length, normalize, mix, rsqrt, the trigonometric functions) are not provided here: the device
 * code calls the explicit versions of kernels/kd_math.h instead. */
#ifndef KD_VECTOR_H
#define KD_VECTOR_H

#include "kd_compat.h"

#ifdef __OPENCL_VERSION__

#define KD_FLOAT2(x, y) ((float2)((x), (y)))
#define KD_FLOAT3(x, y, z) ((float3)((x), (y), (z)))
#define KD_FLOAT4(x, y, z, w) ((float4)((x), (y), (z), (w)))
KD_INLINE float3 kd_xyz(float4 v) { return v.xyz; }
KD_INLINE float3 kd_splat3(float s) { return (float3)(s); }

#else

#include <cmath>

typedef unsigned int uint;
typedef unsigned long ulong; /* 64 bits, as OpenCL's, on the LP64 hosts kdray builds on */

using std::copysign;
using std::fabs;
using std::floor;
using std::isfinite;
using std::rint;
using std::sqrt;

/* fmax and fmin as glibc's x86-64 code computes them (a NaN operand gives the other operand; of
 * 0 and -0, whose sign C leaves open, the second), which GCC calls out of line in libm there:
 * written here they inline. */
KD_INLINE float fmax(float a, float b) {
  const float larger = a > b ? a : b;
  return b != b ? a : larger;
}
KD_INLINE float fmin(float a, float b) {
  const float smaller = a < b ? a : b;
  return b != b ? a : smaller;
}

struct float2 {
  float x, y;
};
/* A 3-vector of T. float3 is kd_vec3<float>: 16 bytes, as on OpenCL devices, so structs holding
 * float3 have the kernel's size. The host's lanes (librender/src/lane8.h) make one of 8-float
 * vectors for the device code's lane functions (kernels/kd_lane.h). The operators are friends, so
 * a scalar operand converts to T; a scalar operand stands for a vector of copies of itself, as in
 * OpenCL C. */
template <typename T>
struct kd_vec3 {
  T x, y, z, unused = T();
  friend KD_INLINE kd_vec3 operator+(kd_vec3 a, kd_vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend KD_INLINE kd_vec3 operator-(kd_vec3 a, kd_vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend KD_INLINE kd_vec3 operator*(kd_vec3 a, kd_vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
  friend KD_INLINE kd_vec3 operator/(kd_vec3 a, kd_vec3 b) { return {a.x / b.x, a.y / b.y, a.z / b.z}; }
  friend KD_INLINE kd_vec3 operator-(kd_vec3 a) { return {-a.x, -a.y, -a.z}; }
  friend KD_INLINE kd_vec3 operator+(kd_vec3 a, T s) { return {a.x + s, a.y + s, a.z + s}; }
  friend KD_INLINE kd_vec3 operator+(T s, kd_vec3 a) { return {s + a.x, s + a.y, s + a.z}; }
  friend KD_INLINE kd_vec3 operator-(kd_vec3 a, T s) { return {a.x - s, a.y - s, a.z - s}; }
  friend KD_INLINE kd_vec3 operator-(T s, kd_vec3 a) { return {s - a.x, s - a.y, s - a.z}; }
  friend KD_INLINE kd_vec3 operator*(kd_vec3 a, T s) { return {a.x * s, a.y * s, a.z * s}; }
  friend KD_INLINE kd_vec3 operator*(T s, kd_vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
  friend KD_INLINE kd_vec3 operator/(kd_vec3 a, T s) { return {a.x / s, a.y / s, a.z / s}; }
  friend KD_INLINE kd_vec3 operator/(T s, kd_vec3 a) { return {s / a.x, s / a.y, s / a.z}; }
  friend KD_INLINE kd_vec3& operator+=(kd_vec3& a, kd_vec3 b) { return a = a + b; }
  friend KD_INLINE kd_vec3& operator-=(kd_vec3& a, kd_vec3 b) { return a = a - b; }
  friend KD_INLINE kd_vec3& operator*=(kd_vec3& a, kd_vec3 b) { return a = a * b; }
  friend KD_INLINE kd_vec3& operator*=(kd_vec3& a, T s) { return a = a * s; }
  friend KD_INLINE kd_vec3& operator/=(kd_vec3& a, T s) { return a = a / s; }
};
typedef kd_vec3<float> float3;
struct float4 {
  float x, y, z, w;
};

#define KD_FLOAT2(x, y) (float2{(x), (y)})
#define KD_FLOAT3(x, y, z) (float3{(x), (y), (z), 0.0f})
#define KD_FLOAT4(x, y, z, w) (float4{(x), (y), (z), (w)})
KD_INLINE float3 kd_xyz(float4 v) { return float3{v.x, v.y, v.z, 0.0f}; }
KD_INLINE float3 kd_splat3(float s) { return float3{s, s, s, 0.0f}; }

KD_INLINE float2 operator+(float2 a, float2 b) { return {a.x + b.x, a.y + b.y}; }
KD_INLINE float2 operator-(float2 a, float2 b) { return {a.x - b.x, a.y - b.y}; }
KD_INLINE float2 operator*(float s, float2 a) { return {s * a.x, s * a.y}; }

KD_INLINE float4 operator+(float4 a, float4 b) { return {a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w}; }
KD_INLINE float4 operator*(float s, float4 a) { return {s * a.x, s * a.y, s * a.z, s * a.w}; }

KD_INLINE float clamp(float x, float lo, float hi) { return fmin(fmax(x, lo), hi); }
KD_INLINE int clamp(int x, int lo, int hi) { return x < lo ? lo : (x > hi ? hi : x); }

KD_INLINE float2 vload2(size_t i, const float* p) { return {p[2 * i], p[2 * i + 1]}; }
KD_INLINE float3 vload3(size_t i, const float* p) { return KD_FLOAT3(p[3 * i], p[3 * i + 1], p[3 * i + 2]); }
KD_INLINE float4 vload4(size_t i, const float* p) { return {p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]}; }

#endif

#endif /* KD_VECTOR_H */
