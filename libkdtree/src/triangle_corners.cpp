// Triangles' corners copied from the scene's positions: the leaf triangles a tree's leaves are
// ranges of (KdLeafTriangle, kernels/kd_types.h) and the shading copy in triangle order.
#include <kdray/kdtree.h>
#include <kdray/traverse.h>

#include <kernels/kd_scene_view.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace kdray {
namespace {

// The corners a, b, c of `triangle`, x, y, z each, into corners[0..8].
void copy_corners(const Scene& scene, size_t triangle, float* corners) {
  for (size_t corner = 0; corner < 3; ++corner) {
    const Vec3& p = scene.positions[scene.indices[3 * triangle + corner]];
    corners[3 * corner + 0] = p.x;
    corners[3 * corner + 1] = p.y;
    corners[3 * corner + 2] = p.z;
  }
}

// Runs fill(i) for i in [0, count), in parallel.
template <typename Fill>
void fill_in_parallel(size_t count, const Fill& fill) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 16384), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i) fill(i);
  });
}

}  // namespace

TraversalArray<KdLeafTriangle> leaf_triangles_of(const Scene& scene, const uint32_t* triangles, size_t count) {
  TraversalArray<KdLeafTriangle> entries(count);
  fill_in_parallel(count, [&](size_t i) {
    entries[i].triangle = triangles[i];
    copy_corners(scene, triangles[i], entries[i].corners);
  });
  return entries;
}

TraversalArray<float> gather_triangle_vertices(const Scene& scene) {
  TraversalArray<float> vertices(scene.triangle_count() * KD_TRIANGLE_FLOATS);
  fill_in_parallel(scene.triangle_count(),
                   [&](size_t triangle) { copy_corners(scene, triangle, vertices.data() + triangle * KD_TRIANGLE_FLOATS); });
  return vertices;
}

}  // namespace kdray
