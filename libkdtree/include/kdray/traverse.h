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

enum class TraversalStack {
  Short,   // KD_SHORT_STACK_SIZE entries (8), restart when it runs empty: what the kernels use
  Depth1,  // one entry: forces restarts, for tests
  Full,    // KD_MAX_TREE_DEPTH entries: never restarts
};

struct TraceOptions {
  unsigned threads = 0;  // 0: all hardware threads
  TraversalStack stack = TraversalStack::Short;
};

// The triangle layout traversal reads (KdSceneView.triangle_vertices in kernels/kd_traverse.h):
// KD_TRIANGLE_FLOATS floats per triangle, its three corners copied from the scene's positions
// (9 floats, 36 bytes per triangle). PreparedTraversal gathers it once; device code uploads it
// next to the tree.
std::vector<float> gather_triangle_vertices(const Scene& scene);

// A scene and its tree ready for batches of rays: the triangle vertices gathered once, so
// repeated batches (and timings of them) do not pay for it again. Keeps references to both.
class PreparedTraversal {
 public:
  PreparedTraversal(const Scene& scene, const KdTree& tree);

  // Closest hit per ray (t = +inf, triangle = KD_NO_HIT on a miss). The tree must match the
  // scene (check_tree_matches_scene). hits is resized to rays.size().
  void closest(const std::vector<RayRecord>& rays, std::vector<HitRecord>& hits, const TraceOptions& options = {}) const;

  // 1 per ray that hits anything with tmin < t < tmax, else 0.
  void any(const std::vector<RayRecord>& rays, std::vector<uint8_t>& occluded, const TraceOptions& options = {}) const;

 private:
  const KdTree& tree_;
  std::vector<float> triangle_vertices_;
};

// One-batch forms of PreparedTraversal::closest and ::any.
void trace_closest(const Scene& scene, const KdTree& tree, const std::vector<RayRecord>& rays,
                   std::vector<HitRecord>& hits, const TraceOptions& options = {});
void trace_any(const Scene& scene, const KdTree& tree, const std::vector<RayRecord>& rays,
               std::vector<uint8_t>& occluded, const TraceOptions& options = {});

// One ray, on the calling thread. Gathers the triangle vertices for this one ray, so it is for
// tests and single queries; batches belong in trace_closest.
HitRecord intersect_closest(const Scene& scene, const KdTree& tree, const RayRecord& ray,
                            TraversalStack stack = TraversalStack::Short);

}  // namespace kdray
