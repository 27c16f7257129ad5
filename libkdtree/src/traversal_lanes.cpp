// The host's closest-hit traversal in lanes where the CPU has AVX2: kernels/kd_traverse_lanes.h,
// compiled here for AVX2 alone and chosen at run time (closest_in_lanes_supported).
#include "traversal_variant.h"

#include <kdray/traverse.h>

#include <kernels/kd_compat.h>
#include <kernels/kd_geometry.h>
#include <kernels/kd_types.h>

#include <immintrin.h>

#include <algorithm>
#include <cstdint>

#include "avx2_functions_begin.h"

namespace kdray::detail {
namespace lanes {

#include <kernels/kd_traverse_lanes.h>

}  // namespace lanes

void closest_in_lanes(const TraversalArrays& arrays, const RayRecord* rays, HitRecord* hits, size_t count) {
  const lanes::KdSceneView scene = make_view(&lanes::kd_scene_view, arrays);
  constexpr size_t kMostRays = size_t{1} << 31;  // KdLaneRays counts in 32 bits
  for (size_t first = 0; first < count; first += kMostRays) {
    lanes::KdLaneRays source{rays + first, hits + first, 0, static_cast<kd_u32>(std::min(count - first, kMostRays))};
    lanes::kd_trace_closest_in_lanes(&scene, &source);
  }
}

}  // namespace kdray::detail

#include "avx2_functions_end.h"

namespace kdray::detail {

bool closest_in_lanes_supported() { return __builtin_cpu_supports("avx2"); }

}  // namespace kdray::detail
