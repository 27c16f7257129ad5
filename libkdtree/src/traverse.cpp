#include <kdray/traverse.h>

#include "traversal_variant.h"

#include <kernels/kd_traverse.h>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace kdray {
namespace {

detail::TraversalArrays arrays_of(const KdTree& tree, const std::vector<float>& triangle_vertices) {
  detail::TraversalArrays arrays{};
  arrays.nodes = tree.nodes.data();
  arrays.leaf_triangles = tree.leaf_triangles.data();
  arrays.triangle_vertices = triangle_vertices.data();
  const float* lo = &tree.bounds.min.x;
  const float* hi = &tree.bounds.max.x;
  for (int k = 0; k < 3; ++k) {
    arrays.bounds_min[k] = lo[k];
    arrays.bounds_max[k] = hi[k];
  }
  return arrays;
}

const detail::TraversalVariant& variant_of(TraversalStack stack) {
  switch (stack) {
    case TraversalStack::Depth1: return detail::traversal_depth1_stack();
    case TraversalStack::Full: return detail::traversal_full_stack();
    case TraversalStack::Short: break;
  }
  return detail::traversal_short_stack();
}

// Runs body(begin, end) over [0, count) in chunks on `threads` threads (0: all).
template <typename Body>
void parallel_chunks(size_t count, unsigned threads, const Body& body) {
  constexpr size_t kChunk = 1024;  // rays per task: amortises scheduling, keeps load balanced
  tbb::task_arena arena(threads == 0 ? tbb::task_arena::automatic : static_cast<int>(threads));
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, kChunk),
                      [&](const tbb::blocked_range<size_t>& range) { body(range.begin(), range.end()); });
  });
}

}  // namespace

std::vector<float> gather_triangle_vertices(const Scene& scene) {
  const size_t triangles = scene.triangle_count();
  std::vector<float> vertices(triangles * KD_TRIANGLE_FLOATS, 0.0f);
  for (size_t triangle = 0; triangle < triangles; ++triangle) {
    float* corners = vertices.data() + triangle * KD_TRIANGLE_FLOATS;
    for (size_t corner = 0; corner < 3; ++corner) {
      const Vec3& p = scene.positions[scene.indices[3 * triangle + corner]];
      corners[3 * corner + 0] = p.x;
      corners[3 * corner + 1] = p.y;
      corners[3 * corner + 2] = p.z;
    }
  }
  return vertices;
}

PreparedTraversal::PreparedTraversal(const Scene& scene, const KdTree& tree)
    : tree_(tree), triangle_vertices_(gather_triangle_vertices(scene)) {}

void PreparedTraversal::closest(const std::vector<RayRecord>& rays, std::vector<HitRecord>& hits,
                                const TraceOptions& options) const {
  hits.resize(rays.size());
  const detail::TraversalArrays arrays = arrays_of(tree_, triangle_vertices_);
  const detail::TraversalVariant& variant = variant_of(options.stack);
  parallel_chunks(rays.size(), options.threads, [&](size_t begin, size_t end) {
    variant.closest(arrays, rays.data() + begin, hits.data() + begin, end - begin);
  });
}

void PreparedTraversal::any(const std::vector<RayRecord>& rays, std::vector<uint8_t>& occluded,
                            const TraceOptions& options) const {
  occluded.resize(rays.size());
  const detail::TraversalArrays arrays = arrays_of(tree_, triangle_vertices_);
  const detail::TraversalVariant& variant = variant_of(options.stack);
  parallel_chunks(rays.size(), options.threads, [&](size_t begin, size_t end) {
    variant.any(arrays, rays.data() + begin, occluded.data() + begin, end - begin);
  });
}

void trace_closest(const Scene& scene, const KdTree& tree, const std::vector<RayRecord>& rays,
                   std::vector<HitRecord>& hits, const TraceOptions& options) {
  PreparedTraversal(scene, tree).closest(rays, hits, options);
}

void trace_any(const Scene& scene, const KdTree& tree, const std::vector<RayRecord>& rays,
               std::vector<uint8_t>& occluded, const TraceOptions& options) {
  PreparedTraversal(scene, tree).any(rays, occluded, options);
}

HitRecord intersect_closest(const Scene& scene, const KdTree& tree, const RayRecord& ray, TraversalStack stack) {
  HitRecord hit;
  variant_of(stack).closest(arrays_of(tree, gather_triangle_vertices(scene)), &ray, &hit, 1);
  return hit;
}

}  // namespace kdray
