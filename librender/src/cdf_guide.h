// Internal to librender: the guides of the kernels' cdf searches (kernels/pt_sampling.h).
#pragma once

#include <cstdint>
#include <vector>

namespace kdray {

// The guide of the n ascending values at `values` (the last 1): for each k < G =
// pt_cdf_guide_size(n) the first index whose value exceeds k / G, compared in float as the
// search compares, then n - 1.
std::vector<uint32_t> cdf_guide(const float* values, uint32_t n);

}  // namespace kdray
