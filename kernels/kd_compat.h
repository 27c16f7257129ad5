/* Qualifier and type compatibility so device code compiles both as OpenCL C and as C++.
 * Every header under kernels/ includes this first and nothing outside kernels/. */
#ifndef KD_COMPAT_H
#define KD_COMPAT_H

#ifdef __OPENCL_VERSION__
/* ---- OpenCL C ---- */
/* No contraction of a * b + c into an FMA anywhere in device code: the watertight triangle test
 * needs exactly negated edge functions (kernels/kd_geometry.h), and the path tracer's C++ build
 * must give the kernel's bits (kernels/kd_math.h); C++ that must match is compiled with
 * -ffp-contract=off. */
#pragma OPENCL FP_CONTRACT OFF
/* static: OpenCL C's plain inline is C99's, which emits no body of its own, so a call the compiler
 * keeps (clang for nvptx64 keeps some) is left to a driver to resolve, and one that does not
 * inline it cannot link the program. */
#define KD_INLINE static inline
/* For the small functions of the traversal's inner loops: PoCL's LLVM keeps them as calls, whose
 * pointer arguments (t, u, v, near and far child) then go through memory. */
#define KD_HOT_INLINE static inline __attribute__((always_inline))
#define KD_GLOBAL __global
#define KD_CONSTANT __constant
typedef uint kd_u32;
typedef int kd_i32;
KD_INLINE float kd_as_float(kd_u32 bits) { return as_float(bits); }
KD_INLINE kd_u32 kd_as_uint(float value) { return as_uint(value); }
/* OpenCL C 1.2 has no static_assert: an array of negative size stops the kernel build, and
 * __COUNTER__ gives each check its own name in the single expanded program. */
#define KD_CONCAT_(a, b) a##b
#define KD_CONCAT(a, b) KD_CONCAT_(a, b)
#define KD_STATIC_ASSERT(cond, msg) typedef char KD_CONCAT(kd_static_assert_, __COUNTER__)[(cond) ? 1 : -1]
#define KD_OFFSETOF(type, member) __builtin_offsetof(type, member)
/* Four floats (ints) side by side in one vector register: comparisons give -1 or 0 per lane. */
typedef float4 kd_f4;
typedef int4 kd_i4;
#define KD_F4(a, b, c, d) ((float4)((a), (b), (c), (d)))
KD_HOT_INLINE void kd_f4_store(kd_f4 v, float* p) { vstore4(v, 0, p); }
KD_HOT_INLINE kd_f4 kd_f4_load(KD_GLOBAL const float* p) { return vload4(0, p); }
/* Bit k set where lane k of the mask is -1. */
KD_HOT_INLINE kd_u32 kd_i4_bits(kd_i4 mask) { return (kd_u32)((mask.x & 1) | (mask.y & 2) | (mask.z & 4) | (mask.w & 8)); }
/* The index of the lowest set bit of a nonzero word. */
KD_HOT_INLINE int kd_lowest_bit(kd_u32 bits) { return 31 - (int)clz(bits & (0u - bits)); }
#else
/* ---- C++ ---- */
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#define KD_INLINE inline
/* The traversal's inner-loop helpers, inlined as in OpenCL: left to itself, GCC kept the leaf
 * test out of line in the host's path tracer, a call per leaf with the ray in memory
 * (bench/LOG.md, "The leaf test inlined in the host's path tracer"). */
#define KD_HOT_INLINE inline __attribute__((always_inline))
#define KD_GLOBAL
#define KD_CONSTANT
typedef uint32_t kd_u32;
typedef int32_t kd_i32;
inline float kd_as_float(kd_u32 bits) {
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}
inline kd_u32 kd_as_uint(float value) {
  kd_u32 bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}
#define KD_STATIC_ASSERT(cond, msg) static_assert(cond, msg)
#define KD_OFFSETOF(type, member) offsetof(type, member)
typedef float kd_f4 __attribute__((vector_size(16)));
typedef kd_i32 kd_i4 __attribute__((vector_size(16)));
#define KD_F4(a, b, c, d) (kd_f4{(a), (b), (c), (d)})
inline void kd_f4_store(kd_f4 v, float* p) { std::memcpy(p, &v, sizeof v); }
inline kd_f4 kd_f4_load(const float* p) {
  kd_f4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline kd_u32 kd_i4_bits(kd_i4 mask) {
#ifdef __SSE__
  return (kd_u32)__builtin_ia32_movmskps((kd_f4)mask);
#else
  return (kd_u32)((mask[0] & 1) | (mask[1] & 2) | (mask[2] & 4) | (mask[3] & 8));
#endif
}
inline int kd_lowest_bit(kd_u32 bits) { return __builtin_ctz(bits); }
#endif

#endif /* KD_COMPAT_H */
