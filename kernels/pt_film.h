/* Film accumulation: a finished sample's radiance and AOVs added, in fixed point, into its
 * pixel's channel sums. */
#ifndef PT_FILM_H
#define PT_FILM_H

#include "pt_path_state.h"

/* Fixed-point value of one sample (see PT_FIXED_BITS); non-finite values count as 0. */
KD_INLINE long pt_fixed(float value, uint* nonfinite) {
  if (!isfinite(value)) {
    *nonfinite += 1;
    return 0;
  }
  value = clamp(value, -PT_FIXED_MAX, PT_FIXED_MAX);
  return (long)rint(value * (float)(1 << PT_FIXED_BITS));
}

/* Adds the finished sample into per-pixel channel sums: radiance, then the enabled AOVs. */
KD_INLINE void pt_path_accumulate(const PtPath* path, KD_GLOBAL const PtRenderParams* params, long* sums,
                               uint* nonfinite) {
  uint c = 0;
  sums[c++] += pt_fixed(path->radiance.x, nonfinite);
  sums[c++] += pt_fixed(path->radiance.y, nonfinite);
  sums[c++] += pt_fixed(path->radiance.z, nonfinite);
  if (params->aov_mask & PT_AOV_ALBEDO) {
    sums[c++] += pt_fixed(path->albedo.x, nonfinite);
    sums[c++] += pt_fixed(path->albedo.y, nonfinite);
    sums[c++] += pt_fixed(path->albedo.z, nonfinite);
  }
  if (params->aov_mask & PT_AOV_NORMAL) {
    sums[c++] += pt_fixed(path->normal.x, nonfinite);
    sums[c++] += pt_fixed(path->normal.y, nonfinite);
    sums[c++] += pt_fixed(path->normal.z, nonfinite);
  }
  if (params->aov_mask & PT_AOV_DEPTH) sums[c++] += pt_fixed(path->depth, nonfinite);
}

#endif /* PT_FILM_H */
