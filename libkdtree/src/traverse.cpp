#include <kdray/traverse.h>

#include "traversal_variant.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace kdray {
namespace {

detail::TraversalArrays arrays_of(const Scene& scene, const KdTree& tree) {
  detail::TraversalArrays arrays{};
  arrays.nodes = tree.nodes.data();
  arrays.leaf_triangles = tree.leaf_triangles.data();
  arrays.indices = scene.indices.data();
  arrays.positions = reinterpret_cast<const float*>(scene.positions.data());
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

void trace_closest(const Scene& scene, const KdTree& tree, const std::vector<RayRecord>& rays,
                   std::vector<HitRecord>& hits, const TraceOptions& options) {
  hits.resize(rays.size());
  const detail::TraversalArrays arrays = arrays_of(scene, tree);
  const detail::TraversalVariant& variant = variant_of(options.stack);
  parallel_chunks(rays.size(), options.threads, [&](size_t begin, size_t end) {
    variant.closest(arrays, rays.data() + begin, hits.data() + begin, end - begin);
  });
}

void trace_any(const Scene& scene, const KdTree& tree, const std::vector<RayRecord>& rays,
               std::vector<uint8_t>& occluded, const TraceOptions& options) {
  occluded.resize(rays.size());
  const detail::TraversalArrays arrays = arrays_of(scene, tree);
  const detail::TraversalVariant& variant = variant_of(options.stack);
  parallel_chunks(rays.size(), options.threads, [&](size_t begin, size_t end) {
    variant.any(arrays, rays.data() + begin, occluded.data() + begin, end - begin);
  });
}

HitRecord intersect_closest(const Scene& scene, const KdTree& tree, const RayRecord& ray, TraversalStack stack) {
  HitRecord hit;
  variant_of(stack).closest(arrays_of(scene, tree), &ray, &hit, 1);
  return hit;
}

}  // namespace kdray
