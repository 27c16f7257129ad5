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
  float bounds_min[3], bounds_max[3];
};

struct TraversalVariant {
  void (*closest)(const TraversalArrays& arrays, const RayRecord* rays, HitRecord* hits, size_t count);
  void (*any)(const TraversalArrays& arrays, const RayRecord* rays, uint8_t* occluded, size_t count);
};

const TraversalVariant& traversal_short_stack();
const TraversalVariant& traversal_depth1_stack();
const TraversalVariant& traversal_full_stack();

}  // namespace kdray::detail
