// The short-stack traversal once more, with the work counters of kernels/kd_traverse.h compiled
// in: count_traversal_work. A translation unit of its own keeps them out of the timed
// variants.
#include "traversal_variant.h"

#include <kdray/traverse.h>

#include <kernels/kd_compat.h>
#include <kernels/kd_geometry.h>
#include <kernels/kd_types.h>

namespace kdray::detail {
namespace counting_short_stack {

#define KD_TRAVERSAL_COUNTERS
#include <kernels/kd_traverse.h>

}  // namespace counting_short_stack

TraversalCounts count_closest(const TraversalArrays& arrays, const RayRecord* rays, HitRecord* hits, size_t count) {
  counting_short_stack::KdSceneView view = make_view(&counting_short_stack::kd_scene_view, arrays);
  counting_short_stack::KdTraversalCounters counters{0, 0, 0, 0, 0};
  view.counters = &counters;
  for (size_t i = 0; i < count; ++i) hits[i] = counting_short_stack::kd_intersect_closest(&view, rays[i]);
  TraversalCounts counts;
  counts.inner_steps = counters.inner_steps;
  counts.leaves = counters.leaves;
  counts.triangle_tests = counters.triangle_tests;
  counts.fast_path_rays = counters.fast_path_rays;
  counts.fast_path_restarts = counters.fast_path_restarts;
  return counts;
}

}  // namespace kdray::detail
