// CPU traversal of a k-d tree: the reference the OpenCL kernels are checked against. It runs
// the very code the kernels run (kernels/kd_traverse.h), compiled once per stack size.
#pragma once

#include <kdray/kdtree.h>
#include <kdray/scene.h>

#include <kernels/kd_types.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace kdray {
namespace detail {
struct TraversalArrays;
}

enum class TraversalStack {
  Short,   // KD_SHORT_STACK_SIZE entries (8), restart when it runs empty: what the kernels use
  Depth1,  // one entry: forces restarts, for tests
  Full,    // KD_MAX_TREE_DEPTH entries: never restarts
};

// Which rays take the traversal's fast path (kernels/kd_traverse_fast.h): every one that gives the robust
// traversal's hits there (the default), or none (KD_TRAVERSAL_ROBUST_ONLY, the short stack only):
// the robust traversal alone, to compare the two.
enum class TraversalPath { FastWhereSafe, Robust };

struct TraceOptions {
  unsigned threads = 0;  // 0: all hardware threads
  TraversalStack stack = TraversalStack::Short;
  TraversalPath path = TraversalPath::FastWhereSafe;
};

// Each triangle's three corners copied from the scene's positions, KD_TRIANGLE_FLOATS floats
// (36 bytes) per triangle in triangle order: what shading reads of a hit triangle.
TraversalArray<float> gather_triangle_vertices(const Scene& scene);

// One bit per node of the tree, set for empty leaves (bit n % 32 of word n / 32): derived at
// load for traversals built with KD_EMPTY_LEAF_BITS (KdSceneView.empty_leaves), which skip
// empty leaves without fetching them.
std::vector<uint32_t> empty_leaf_bits(const KdTree& tree);

// Work of a batch of closest-hit traversals, summed over its rays (kernels/kd_traverse.h's
// counters): inner-node visit steps, leaves visited (empty ones skipped by their bit not
// counted) and ray/triangle tests; the rays that took the fast path, and those of them traced
// again robustly when its stack overflowed.
struct TraversalWork {
  uint64_t rays = 0, inner_steps = 0, leaves = 0, triangle_tests = 0, fast_path_rays = 0, fast_path_restarts = 0;
};

// A tree ready for batches of rays: its empty-leaf bits derived once, so repeated batches (and
// timings of them) do not pay for it again. Keeps a reference to the tree and traces its own
// arrays (a tree holds its triangles' corners, so the scene is not needed).
class PreparedTraversal {
 public:
  explicit PreparedTraversal(const KdTree& tree);

  // Closest hit per ray (t = +inf, triangle = KD_NO_HIT on a miss): the index of a triangle of
  // the scene the tree was built for. hits is resized to rays.size().
  void closest(const std::vector<RayRecord>& rays, std::vector<HitRecord>& hits, const TraceOptions& options = {}) const;

  // 1 per ray that hits anything with tmin < t < tmax, else 0.
  void any(const std::vector<RayRecord>& rays, std::vector<uint8_t>& occluded, const TraceOptions& options = {}) const;

  // closest() with the short stack, counting its work: a separate, slower build of the
  // traversal, so timings of closest() never include the counting. The kernels run the same
  // code, so their work is the same.
  TraversalWork count_work(const std::vector<RayRecord>& rays, std::vector<HitRecord>& hits,
                           const TraceOptions& options = {}) const;

 private:
  detail::TraversalArrays arrays() const;

  const KdTree& tree_;  // its node and leaf arrays are traced where they are
  std::vector<uint32_t> empty_leaves_;    // empty_leaf_bits
};

// One-batch forms of PreparedTraversal::closest and ::any.
void trace_closest(const KdTree& tree, const std::vector<RayRecord>& rays, std::vector<HitRecord>& hits,
                   const TraceOptions& options = {});
void trace_any(const KdTree& tree, const std::vector<RayRecord>& rays, std::vector<uint8_t>& occluded,
               const TraceOptions& options = {});

// One ray, on the calling thread. Derives the empty-leaf bits for this one ray, so it is for
// tests and single queries; batches belong in trace_closest.
HitRecord intersect_closest(const KdTree& tree, const RayRecord& ray, TraversalStack stack = TraversalStack::Short);

}  // namespace kdray
