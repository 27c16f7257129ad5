// The bins of a binned node's axis (AxisBins) against their definition, searched for plane by
// plane: a triangle starting at v is in the last bin whose lower boundary is <= v, one ending at
// v in the first bin whose upper boundary is >= v (the first and the last bin when there is none).
// The values include every boundary itself and its neighbouring floats, and voxels so thin for
// their coordinates that boundaries coincide, or wider than the float range.
#include "build_bins.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace kdray {
namespace {

using namespace kdray::detail;

uint32_t start_bin_by_search(const AxisBins& bins, uint32_t count, float v) {
  uint32_t k = 0;
  for (uint32_t b = 1; b < count; ++b)
    if (bins.boundary(b) <= v) k = b;
  return k;
}

uint32_t end_bin_by_search(const AxisBins& bins, uint32_t count, float v) {
  for (uint32_t b = 0; b + 1 < count; ++b)
    if (bins.boundary(b + 1) >= v) return b;
  return count - 1;
}

TEST(AxisBins, FindTheBinsTheirDefinitionGives) {
  std::mt19937 random(5);
  const Box3 voxels[] = {
      {{-1, -2, -3}, {1, 2, 3}},
      {{0.1f, 0, 0}, {0.7f, 1, 1}},
      {{1000.0f, 0, 0}, {1000.01f, 1, 1}},       // boundaries a few floats apart, some equal
      {{-3e5f, 0, 0}, {std::nextafter(-3e5f, 0.0f), 1, 1}},  // one float wide
      {{-1e30f, 0, 0}, {1e30f, 1, 1}},
      {{-3e38f, 0, 0}, {3e38f, 1, 1}},  // an extent beyond the float range
      {{5.0f, 0, 0}, {5.0f, 1, 1}},     // no extent: every boundary is 5
      {{1.0f, 0, 0}, {std::nextafter(1.0f, 2.0f), 1, 1}},
  };
  for (const Box3& voxel : voxels)
    for (uint32_t count : {2u, 3u, 16u, 256u}) {
      const AxisBins bins(voxel, 0, count);
      std::vector<float> values;
      for (uint32_t b = 0; b <= count; ++b) {
        const float boundary = bins.boundary(b);
        values.insert(values.end(), {boundary, std::nextafter(boundary, -INFINITY), std::nextafter(boundary, INFINITY)});
      }
      std::uniform_real_distribution<double> unit(0.0, 1.0);
      const double lo = voxel.min[0], hi = voxel.max[0];
      for (int i = 0; i < 200; ++i) values.push_back(static_cast<float>(lo + (hi - lo) * unit(random)));
      values.insert(values.end(), {-INFINITY, INFINITY});
      for (float v : values) {
        SCOPED_TRACE(std::to_string(count) + " bins of [" + std::to_string(voxel.min[0]) + ", " +
                     std::to_string(voxel.max[0]) + "], v " + std::to_string(v));
        EXPECT_EQ(bins.bin_of_start(v), start_bin_by_search(bins, count, v));
        EXPECT_EQ(bins.bin_of_end(v), end_bin_by_search(bins, count, v));
      }
    }
}

}  // namespace
}  // namespace kdray
