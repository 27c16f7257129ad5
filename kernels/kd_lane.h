/* Lane functions: device code written once for one path and, in the host's C++ build, for 8
 * paths side by side in vector lanes (librender/src/lane8.h, librender/src/path_lanes.h).
 *
 * A function declared KD_LANE_FN takes kd_lane where it means a float and kd_lane3 where it means
 * a float3 (made with KD_LANE3). In OpenCL C they are float and float3. In C++ the function is a
 * template over the lane type: the scalar code instantiates it with float (kd_lane3 is then
 * float3), the host's lanes with 8 floats, and each lane computes the float instantiation's bits.
 *
 * So a lane function has no branch on a value: comparisons give masks (KD_LANE_MASK), combined
 * with & | and !; kd_select(mask, a, b) picks a or b per lane; an early exit is taken when no lane
 * needs what follows (if (!kd_any(mask)) return ...), which for one lane is the scalar branch.
 * KD_LANE_INT is the integer of a lane. */
#ifndef KD_LANE_H
#define KD_LANE_H

#include "kd_compat.h"
#include "kd_vector.h"

#ifdef __OPENCL_VERSION__

typedef float kd_lane;
typedef float3 kd_lane3;
#define KD_LANE_FN KD_INLINE
#define KD_LANE_INT int
#define KD_LANE_MASK int
#define KD_LANE3(x, y, z) ((float3)((x), (y), (z)))
#define kd_select(mask, a, b) ((mask) ? (a) : (b))
#define kd_any(mask) (mask)

#else

/* The integer and mask types of a lane type; lane8.h adds its own. */
template <typename L>
struct kd_lane_types;
template <>
struct kd_lane_types<float> {
  typedef int integer;
  typedef bool mask;
};
#define KD_LANE_FN template <typename kd_lane> KD_INLINE
#define kd_lane3 kd_vec3<kd_lane>
#define KD_LANE_INT typename kd_lane_types<kd_lane>::integer
#define KD_LANE_MASK typename kd_lane_types<kd_lane>::mask
#define KD_LANE3(x, y, z) (kd_lane3{(x), (y), (z)})
template <typename T>
KD_INLINE T kd_select(bool mask, T a, T b) {
  return mask ? a : b;
}
KD_INLINE bool kd_any(bool mask) { return mask; }

#endif

/* (int)x, truncating; and x with its bit pattern moved by `steps` as an unsigned integer (which
 * wraps like the signed sum would). */
KD_INLINE int kd_lane_to_int(float x) { return (int)x; }
KD_INLINE float kd_lane_step_bits(float x, int steps) { return kd_as_float(kd_as_uint(x) + (kd_u32)steps); }

#endif /* KD_LANE_H */
