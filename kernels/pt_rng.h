/* Counter-based random numbers: a value is a pure function of (seed, pixel, sample, dimension),
 * so an image does not depend on which work-item rendered which pixel, the local size, the
 * number of threads or the device. Compiles as OpenCL C and as C++. */
#ifndef PT_RNG_H
#define PT_RNG_H

#include "kd_compat.h"

/* Dimensions used per bounce; bounce b uses dimensions b*PT_DIMS_PER_BOUNCE + PT_DIM_*. */
#define PT_DIMS_PER_BOUNCE 8u
#define PT_DIM_CAMERA_X 0u
#define PT_DIM_CAMERA_Y 1u
#define PT_DIM_LIGHT_PICK 2u
#define PT_DIM_LIGHT_U 3u
#define PT_DIM_LIGHT_V 4u
#define PT_DIM_BSDF_U 5u
#define PT_DIM_BSDF_V 6u
#define PT_DIM_ROULETTE 7u

/* A 32-bit integer hash with low bias (C. Wellons, "Prospecting for Hash Functions"). */
KD_INLINE kd_u32 pt_hash32(kd_u32 x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

KD_INLINE kd_u32 pt_random_bits(kd_u32 seed, kd_u32 pixel, kd_u32 sample, kd_u32 dimension) {
  kd_u32 h = pt_hash32(seed ^ 0x9e3779b9u);
  h = pt_hash32(h ^ pixel);
  h = pt_hash32(h ^ sample);
  return pt_hash32(h ^ dimension);
}

/* Uniform in [0, 1): the top 24 bits, exactly representable as float. */
KD_INLINE float pt_random(kd_u32 seed, kd_u32 pixel, kd_u32 sample, kd_u32 bounce, kd_u32 dim) {
  kd_u32 bits = pt_random_bits(seed, pixel, sample, bounce * PT_DIMS_PER_BOUNCE + dim);
  return (float)(bits >> 8) * (1.0f / 16777216.0f);
}

#endif /* PT_RNG_H */
