#include <kdray/traverse.h>

#include <kdray/error.h>
#include <kdray/threads.h>

#include "traversal_variant.h"

#include <kernels/kd_traverse.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <sys/mman.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <new>

namespace kdray {
namespace {

detail::TraversalArrays arrays_of(const KdTree& tree, const KdNode* nodes, const uint32_t* leaf_triangles,
                                  const float* triangle_vertices, const uint32_t* empty_leaves) {
  detail::TraversalArrays arrays{};
  arrays.nodes = nodes;
  arrays.empty_leaves = empty_leaves;
  arrays.leaf_triangles = leaf_triangles;
  arrays.triangle_vertices = triangle_vertices;
  const float* lo = &tree.bounds.min.x;
  const float* hi = &tree.bounds.max.x;
  for (int k = 0; k < 3; ++k) {
    arrays.bounds_min[k] = lo[k];
    arrays.bounds_max[k] = hi[k];
  }
  return arrays;
}

const detail::TraversalVariant& variant_of(TraversalStack stack, TraversalPath path = TraversalPath::FastWhereSafe) {
  if (path == TraversalPath::Robust) {
    if (stack != TraversalStack::Short) throw Error("", "the robust traversal alone is built with the short stack only");
    return detail::traversal_robust_short_stack();
  }
  switch (stack) {
    case TraversalStack::Depth1: return detail::traversal_depth1_stack();
    case TraversalStack::Full: return detail::traversal_full_stack();
    case TraversalStack::Short: break;
  }
  return detail::traversal_short_stack();
}

// Sizes `out` to one result per ray and runs trace(arrays, rays, results, count) over chunks of
// `rays` on `threads` threads (0: all).
template <typename Result, typename Trace>
void trace_in_chunks(const detail::TraversalArrays& arrays, const std::vector<RayRecord>& rays,
                     std::vector<Result>& out, unsigned threads, const Trace& trace) {
  constexpr size_t kChunk = 1024;  // rays per task: amortises scheduling, keeps load balanced
  out.resize(rays.size());
  run_with_threads(threads, [&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), kChunk), [&](const tbb::blocked_range<size_t>& range) {
      trace(arrays, rays.data() + range.begin(), out.data() + range.begin(), range.size());
    });
  });
}

// Writes the KD_TRIANGLE_FLOATS floats per triangle of gather_triangle_vertices to out.
void gather_triangle_vertices_into(const Scene& scene, float* out) {
  const size_t triangles = scene.triangle_count();
  for (size_t triangle = 0; triangle < triangles; ++triangle) {
    float* corners = out + triangle * KD_TRIANGLE_FLOATS;
    for (size_t corner = 0; corner < 3; ++corner) {
      const Vec3& p = scene.positions[scene.indices[3 * triangle + corner]];
      corners[3 * corner + 0] = p.x;
      corners[3 * corner + 1] = p.y;
      corners[3 * corner + 2] = p.z;
    }
  }
}

}  // namespace

std::vector<uint32_t> empty_leaf_bits(const KdTree& tree) {
  std::vector<uint32_t> bits((tree.nodes.size() + 31) / 32, 0u);
  for (size_t node = 0; node < tree.nodes.size(); ++node)
    if (kd_node_is_leaf(tree.nodes[node]) && kd_leaf_count(tree.nodes[node]) == 0)
      bits[node / 32] |= 1u << (node % 32);
  return bits;
}

std::vector<float> gather_triangle_vertices(const Scene& scene) {
  std::vector<float> vertices(scene.triangle_count() * KD_TRIANGLE_FLOATS, 0.0f);
  gather_triangle_vertices_into(scene, vertices.data());
  return vertices;
}

template <typename T>
PreparedTraversal::HugePageArray<T>::HugePageArray(size_t count) : count_(count) {
  constexpr size_t kHugePage = size_t{2} << 20;
  // Arrays under one huge page gain nothing; they keep the ordinary alignment.
  const size_t bytes = std::max<size_t>(count * sizeof(T), 1);
  const size_t alignment = bytes >= kHugePage ? kHugePage : alignof(std::max_align_t);
  const size_t rounded = (bytes + alignment - 1) / alignment * alignment;
  void* memory = std::aligned_alloc(alignment, rounded);
  if (!memory) throw std::bad_alloc();
  // Advice only: where the kernel has no huge pages to give, the array keeps 4 KiB pages.
  if (alignment == kHugePage) madvise(memory, rounded, MADV_HUGEPAGE);
  data_.reset(static_cast<T*>(memory));
}

PreparedTraversal::PreparedTraversal(const Scene& scene, const KdTree& tree)
    : tree_(tree),
      nodes_(tree.nodes.size()),
      leaf_triangles_(tree.leaf_triangles.size()),
      triangle_vertices_(scene.triangle_count() * KD_TRIANGLE_FLOATS),
      empty_leaves_(empty_leaf_bits(tree)) {
  std::copy(tree.nodes.begin(), tree.nodes.end(), nodes_.data());
  std::copy(tree.leaf_triangles.begin(), tree.leaf_triangles.end(), leaf_triangles_.data());
  gather_triangle_vertices_into(scene, triangle_vertices_.data());
}

detail::TraversalArrays PreparedTraversal::arrays() const {
  return arrays_of(tree_, nodes_.data(), leaf_triangles_.data(), triangle_vertices_.data(), empty_leaves_.data());
}

void PreparedTraversal::closest(const std::vector<RayRecord>& rays, std::vector<HitRecord>& hits,
                                const TraceOptions& options) const {
  trace_in_chunks(arrays(), rays, hits, options.threads, variant_of(options.stack, options.path).closest);
}

TraversalWork PreparedTraversal::count_work(const std::vector<RayRecord>& rays, std::vector<HitRecord>& hits,
                                            const TraceOptions& options) const {
  std::atomic<uint64_t> inner_steps{0}, leaves{0}, triangle_tests{0}, fast_path_rays{0}, fast_path_restarts{0};
  auto count_chunk = [&](const detail::TraversalArrays& arrays, const RayRecord* chunk, HitRecord* chunk_hits,
                         size_t count) {
    const detail::TraversalCounts counts = detail::count_closest(arrays, chunk, chunk_hits, count);
    inner_steps += counts.inner_steps;
    leaves += counts.leaves;
    triangle_tests += counts.triangle_tests;
    fast_path_rays += counts.fast_path_rays;
    fast_path_restarts += counts.fast_path_restarts;
  };
  trace_in_chunks(arrays(), rays, hits, options.threads, count_chunk);
  TraversalWork work;
  work.rays = rays.size();
  work.inner_steps = inner_steps;
  work.leaves = leaves;
  work.triangle_tests = triangle_tests;
  work.fast_path_rays = fast_path_rays;
  work.fast_path_restarts = fast_path_restarts;
  return work;
}

void PreparedTraversal::any(const std::vector<RayRecord>& rays, std::vector<uint8_t>& occluded,
                            const TraceOptions& options) const {
  trace_in_chunks(arrays(), rays, occluded, options.threads, variant_of(options.stack, options.path).any);
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
  const std::vector<float> triangle_vertices = gather_triangle_vertices(scene);
  const std::vector<uint32_t> empty_leaves = empty_leaf_bits(tree);
  HitRecord hit;
  variant_of(stack).closest(
      arrays_of(tree, tree.nodes.data(), tree.leaf_triangles.data(), triangle_vertices.data(), empty_leaves.data()),
      &ray, &hit, 1);
  return hit;
}

}  // namespace kdray
