// The bin boundaries of one axis of a binned node's voxel (build_binned.h), and the bins a
// triangle's bounds fall in.
#pragma once

#include "build_common.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace kdray::detail {

// The bin boundaries of one axis of a voxel: bins + 1 float positions from its min to its max.
// They are the candidate planes, so a triangle's bins are found by the same float comparisons
// with them that later divide the node: the counts are exactly the children's sizes (before
// clipping drops a straddler from a side it only touches at a corner of its bounds).
class AxisBins {
 public:
  AxisBins(const Box3& voxel, int axis, uint32_t bins) : boundaries_(bins + 1) {
    const double lo = voxel.min[axis], hi = voxel.max[axis];
    for (uint32_t k = 1; k < bins; ++k) boundaries_[k] = static_cast<float>(lo + (hi - lo) * k / bins);
    boundaries_[0] = voxel.min[axis];
    boundaries_[bins] = voxel.max[axis];
    search_ = boundaries_;
    search_[0] = search_[bins] = std::numeric_limits<float>::quiet_NaN();
    lo_ = voxel.min[axis];
    scale_ = hi > lo ? static_cast<float>(bins / (hi - lo)) : 0.0f;
    last_bin_ = static_cast<float>(bins - 1);
  }

  float boundary(uint32_t k) const { return boundaries_[k]; }
  // The bin of a triangle starting at v: the last whose lower boundary is <= v, so that it
  // starts below boundary k exactly when its bin is below k.
  uint32_t bin_of_start(float v) const {
    uint32_t k = estimate(v);
    while (search_[k] > v) --k;
    while (search_[k + 1] <= v) ++k;
    return k;
  }
  // The bin of a triangle ending at v: the first whose upper boundary is >= v, so that it ends
  // above boundary k exactly when its bin is k or above.
  uint32_t bin_of_end(float v) const {
    uint32_t k = estimate(v);
    while (search_[k] >= v) --k;
    while (search_[k + 1] < v) ++k;
    return k;
  }

 private:
  // A guess from the arithmetic, in [0, bins - 1], which the searches above correct (float
  // is enough for a guess).
  uint32_t estimate(float v) const {
    const float bin = (v - lo_) * scale_;
    return static_cast<uint32_t>(bin > 0.0f ? std::min(bin, last_bin_) : 0.0f);
  }

  std::vector<float> boundaries_;
  // The boundaries with NaN for the voxel's faces: every comparison with NaN is false, so the
  // searches stop at the first and the last bin without a range test, whatever v is.
  std::vector<float> search_;
  float lo_, scale_, last_bin_;
};

}  // namespace kdray::detail
