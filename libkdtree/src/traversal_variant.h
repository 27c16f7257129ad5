// One CPU build of kernels/kd_traverse.h per stack size. The stack size is a macro, so each
// size lives in its own translation unit (traversal_stack_*.cpp) inside its own namespace,
// and exposes its loops through this table.
#pragma once

#include <kernels/kd_types.h>

#include <cstddef>
#include <cstdint>

namespace kdray {
struct TraversalArrays;  // kdray/traverse.h, which the files that read one include
}  // namespace kdray

namespace kdray::detail {

using kdray::TraversalArrays;

// The KdSceneView of one compilation of kd_traverse.h: each lives in its own namespace, so the
// caller passes that namespace's kd_scene_view.
template <typename SceneView, typename Arrays = TraversalArrays>
auto make_view(SceneView scene_view, const Arrays& arrays) {
  const float* lo = arrays.bounds_min;
  const float* hi = arrays.bounds_max;
  return scene_view(arrays.nodes, arrays.leaf_blocks, lo[0], lo[1], lo[2], hi[0], hi[1],
                    hi[2]);
}

struct TraversalVariant {
  void (*closest)(const TraversalArrays& arrays, const RayRecord* rays, HitRecord* hits, size_t count);
  void (*any)(const TraversalArrays& arrays, const RayRecord* rays, uint8_t* occluded, size_t count);
};

const TraversalVariant& traversal_short_stack();
const TraversalVariant& traversal_depth1_stack();
const TraversalVariant& traversal_full_stack();
const TraversalVariant& traversal_robust_short_stack();

// Closest hits with the short stack and the fast path, like traversal_short_stack().closest, for
// 16 rays at a time in AVX2 lanes (traversal_lanes.cpp): only where closest_in_lanes_supported().
bool closest_in_lanes_supported();
void closest_in_lanes(const TraversalArrays& arrays, const RayRecord* rays, HitRecord* hits, size_t count);

// traversal_short_stack()'s closest and any, kPacketRays consecutive rays at a time as one packet
// (traversal_packets.cpp): only where closest_in_lanes_supported() (AVX2).
void closest_in_packets(const TraversalArrays& arrays, const RayRecord* rays, HitRecord* hits, size_t count);
void any_in_packets(const TraversalArrays& arrays, const RayRecord* rays, uint8_t* occluded, size_t count);

// Closest hits with the short stack, like traversal_short_stack().closest, adding the work
// done (kernels/kd_scene_view.h's counters): a build of its own, so the timed ones count nothing.
struct TraversalCounts {
  uint64_t inner_steps = 0, leaves = 0, triangle_tests = 0, fast_path_rays = 0, fast_path_restarts = 0;
};
TraversalCounts count_closest(const TraversalArrays& arrays, const RayRecord* rays, HitRecord* hits, size_t count);

}  // namespace kdray::detail
