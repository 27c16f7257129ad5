#include <kdray/traverse.h>

#include <kdray/error.h>
#include <kdray/threads.h>

#include "traversal_variant.h"

#include <kernels/kd_traverse.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>

namespace kdray {
namespace {

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
void trace_in_chunks(const TraversalArrays& arrays, const std::vector<RayRecord>& rays,
                     std::vector<Result>& out, unsigned threads, const Trace& trace) {
  constexpr size_t kChunk = 1024;  // rays per task: amortises scheduling, keeps load balanced
  out.resize(rays.size());
  run_with_threads(threads, [&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), kChunk), [&](const tbb::blocked_range<size_t>& range) {
      trace(arrays, rays.data() + range.begin(), out.data() + range.begin(), range.size());
    });
  });
}

}  // namespace

TraversalArrays traversal_arrays(const KdTree& tree) {
  TraversalArrays arrays{};
  arrays.nodes = tree.nodes.data();
  arrays.leaf_blocks = tree.leaf_blocks.data();
  const float* lo = &tree.bounds.min.x;
  const float* hi = &tree.bounds.max.x;
  for (int k = 0; k < 3; ++k) {
    arrays.bounds_min[k] = lo[k];
    arrays.bounds_max[k] = hi[k];
  }
  return arrays;
}

bool packets_supported() { return detail::closest_in_lanes_supported(); }

void trace_packet(const TraversalArrays& arrays, const RayRecord* rays, int count, HitRecord* hits) {
  detail::closest_in_packets(arrays, rays, hits, static_cast<size_t>(count));
}

void trace_packet_any(const TraversalArrays& arrays, const RayRecord* rays, int count, uint8_t* occluded) {
  detail::any_in_packets(arrays, rays, occluded, static_cast<size_t>(count));
}

bool traces_in_packets(const TraceOptions& options) {
  return options.packets && options.stack == TraversalStack::Short && options.path == TraversalPath::FastWhereSafe &&
         packets_supported();
}

bool traces_in_lanes(const KdTree& tree, const TraceOptions& options) {
  return options.lanes && tree.nodes.size() > kLanesMinNodes && options.stack == TraversalStack::Short &&
         options.path == TraversalPath::FastWhereSafe && detail::closest_in_lanes_supported();
}

void trace_closest(const KdTree& tree, const std::vector<RayRecord>& rays, std::vector<HitRecord>& hits,
                   const TraceOptions& options) {
  const auto closest = traces_in_packets(options)       ? &detail::closest_in_packets
                       : traces_in_lanes(tree, options) ? &detail::closest_in_lanes
                                                        : variant_of(options.stack, options.path).closest;
  trace_in_chunks(traversal_arrays(tree), rays, hits, options.threads, closest);
}

void trace_any(const KdTree& tree, const std::vector<RayRecord>& rays, std::vector<uint8_t>& occluded,
               const TraceOptions& options) {
  const auto any = traces_in_packets(options) ? &detail::any_in_packets : variant_of(options.stack, options.path).any;
  trace_in_chunks(traversal_arrays(tree), rays, occluded, options.threads, any);
}

TraversalWork count_traversal_work(const KdTree& tree, const std::vector<RayRecord>& rays,
                                   std::vector<HitRecord>& hits, const TraceOptions& options) {
  std::atomic<uint64_t> inner_steps{0}, leaves{0}, triangle_tests{0}, fast_path_rays{0}, fast_path_restarts{0};
  auto count_chunk = [&](const TraversalArrays& arrays, const RayRecord* chunk, HitRecord* chunk_hits,
                         size_t count) {
    const detail::TraversalCounts counts = detail::count_closest(arrays, chunk, chunk_hits, count);
    inner_steps += counts.inner_steps;
    leaves += counts.leaves;
    triangle_tests += counts.triangle_tests;
    fast_path_rays += counts.fast_path_rays;
    fast_path_restarts += counts.fast_path_restarts;
  };
  trace_in_chunks(traversal_arrays(tree), rays, hits, options.threads, count_chunk);
  TraversalWork work;
  work.rays = rays.size();
  work.inner_steps = inner_steps;
  work.leaves = leaves;
  work.triangle_tests = triangle_tests;
  work.fast_path_rays = fast_path_rays;
  work.fast_path_restarts = fast_path_restarts;
  return work;
}

namespace {

// The array copied into memory of its own, in parallel pieces of a huge page each: the pages'
// first touches (faults, zeroing) are most of the copy's time, and they run on every thread.
template <typename T>
void copy_out_of_file(TreeArray<T>& array) {
  constexpr size_t kPiece = (size_t{2} << 20) / sizeof(T);
  TraversalArray<T> copy;
  copy.resize(array.size());
  const T* from = array.data();
  tbb::parallel_for(size_t{0}, (array.size() + kPiece - 1) / kPiece, [&](size_t piece) {
    const size_t begin = piece * kPiece, end = std::min(array.size(), begin + kPiece);
    std::copy(from + begin, from + end, copy.data() + begin);
  });
  array = TreeArray<T>(std::move(copy));
}

}  // namespace

bool copy_tree_for_rays(KdTree& tree, size_t rays, unsigned threads) {
  const uint64_t bytes = tree.nodes.size() * sizeof(KdNode) + tree.leaf_blocks.size() * sizeof(uint32_t);
  if (!tree.nodes.mapped() || rays < bytes / kTreeBytesPerRay) return false;
  run_with_threads(threads, [&] {
    copy_out_of_file(tree.nodes);
    copy_out_of_file(tree.leaf_blocks);
  });
  return true;
}

HitRecord intersect_closest(const KdTree& tree, const RayRecord& ray, TraversalStack stack) {
  HitRecord hit;
  variant_of(stack).closest(traversal_arrays(tree), &ray, &hit, 1);
  return hit;
}

}  // namespace kdray
