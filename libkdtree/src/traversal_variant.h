// One CPU build of kernels/kd_traverse.h per stack size. The stack size is a macro, so each
// size lives in its own translation unit (traversal_stack_*.cpp) inside its own namespace,
// and exposes its loops through this table.
#pragma once

#include <kernels/kd_types.h>

#include <cstddef>
#include <cstdint>

namespace kdray::detail {

// The arrays a traversal reads, as plain pointers (the CPU side of KdSceneView).
struct TraversalArrays {
  const KdNode* nodes;
  const uint32_t* leaf_triangles;
  const float* triangle_vertices;  // KD_TRIANGLE_FLOATS per triangle: gather_triangle_vertices
  const uint32_t* empty_leaves;    // empty_leaf_bits: every CPU build defines KD_EMPTY_LEAF_BITS
  float bounds_min[3], bounds_max[3];
};

// The KdSceneView of one compilation of kd_traverse.h (each lives in its own namespace).
template <typename View>
View make_view(const TraversalArrays& arrays) {
  View view{};
  view.nodes = arrays.nodes;
  view.leaf_triangles = arrays.leaf_triangles;
  view.triangle_vertices = arrays.triangle_vertices;
  view.empty_leaves = arrays.empty_leaves;
  for (int k = 0; k < 3; ++k) {
    view.bounds_min[k] = arrays.bounds_min[k];
    view.bounds_max[k] = arrays.bounds_max[k];
  }
  return view;
}

struct TraversalVariant {
  void (*closest)(const TraversalArrays& arrays, const RayRecord* rays, HitRecord* hits, size_t count);
  void (*any)(const TraversalArrays& arrays, const RayRecord* rays, uint8_t* occluded, size_t count);
};

const TraversalVariant& traversal_short_stack();
const TraversalVariant& traversal_depth1_stack();
const TraversalVariant& traversal_full_stack();

// Closest hits with the short stack, like traversal_short_stack().closest, adding the work
// done (kernels/kd_traverse.h's counters): a build of its own, so the timed ones count nothing.
struct TraversalCounts {
  uint64_t inner_steps = 0, leaves = 0, triangle_tests = 0;
};
TraversalCounts count_closest(const TraversalArrays& arrays, const RayRecord* rays, HitRecord* hits, size_t count);

}  // namespace kdray::detail
