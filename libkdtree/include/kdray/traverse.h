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

// The arrays a traversal reads, as plain pointers (the CPU side of kernels/kd_scene_view.h's
// KdSceneView): a tree's (traversal_arrays), or copies of them (a renderer's scene buffers).
struct TraversalArrays {
  const KdNode* nodes;
  const uint32_t* leaf_blocks;
  float bounds_min[3], bounds_max[3];
};
TraversalArrays traversal_arrays(const KdTree& tree);

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
  // trace_closest with the short stack and the fast path: 16 rays at a time per thread in AVX2
  // lanes (the same hits) where traces_in_lanes says so; false: one ray at a time.
  bool lanes = true;
  // trace_closest and trace_any with the short stack and the fast path: kPacketRays consecutive
  // rays at a time as one packet (the same hits) where packets_supported(), in place of lanes.
  bool packets = false;
};

// Whether trace_closest runs `options` on `tree` in AVX2 lanes: where the CPU has AVX2 and the
// tree has more than kLanesMinNodes nodes. A ray through a tree that small takes a few steps,
// too few to repay handing it to a lane (bench/LOG.md, "Rays in AVX2 lanes").
constexpr size_t kLanesMinNodes = 256;
bool traces_in_lanes(const KdTree& tree, const TraceOptions& options);
// Whether trace_closest and trace_any run `options` as packets (TraceOptions::packets).
bool traces_in_packets(const TraceOptions& options);

// Rays traced together as one packet (an AVX2 register's lanes): each inner node's step and each
// triangle's test are made once for all of them. Rays that run close together (camera rays of
// neighbouring pixels or samples, shadow rays from neighbouring points towards one light) meet
// nearly the same nodes and triangles and are traced 2-3 times as fast so; rays that run apart
// (random rays, bounces off diffuse surfaces) share few and are slower (bench/LOG.md, "Packets
// of eight rays"). The hits are one ray at a time's, byte for byte.
constexpr int kPacketRays = 8;
bool packets_supported();  // where the CPU has AVX2
// The closest hits of rays [0, count), count <= kPacketRays, as trace_closest's; and whether each
// is occluded, as trace_any's (1 or 0).
void trace_packet(const TraversalArrays& arrays, const RayRecord* rays, int count, HitRecord* hits);
void trace_packet_any(const TraversalArrays& arrays, const RayRecord* rays, int count, uint8_t* occluded);

// Each triangle's three corners copied from the scene's positions, KD_TRIANGLE_FLOATS floats
// (36 bytes) per triangle in triangle order: what shading reads of a hit triangle.
TraversalArray<float> gather_triangle_vertices(const Scene& scene);

// Work of a batch of closest-hit traversals, summed over its rays (kernels/kd_traverse.h's
// counters): inner-node visit steps, leaves visited (empty children, which are no
// nodes, not counted) and ray/triangle tests; the rays that took the fast path, and those of them traced
// again robustly when its stack overflowed.
struct TraversalWork {
  uint64_t rays = 0, inner_steps = 0, leaves = 0, triangle_tests = 0, fast_path_rays = 0, fast_path_restarts = 0;
};

// Closest hit per ray (t = +inf, triangle = KD_NO_HIT on a miss): the index of a triangle of the
// scene the tree was built for. hits is resized to rays.size(). The tree holds its triangles'
// corners, so the scene is not needed; its node and leaf arrays are traced where they are.
void trace_closest(const KdTree& tree, const std::vector<RayRecord>& rays, std::vector<HitRecord>& hits,
                   const TraceOptions& options = {});

// 1 per ray that hits anything with tmin < t < tmax, else 0.
void trace_any(const KdTree& tree, const std::vector<RayRecord>& rays, std::vector<uint8_t>& occluded,
               const TraceOptions& options = {});

// trace_closest with the short stack, counting its work: a separate, slower build of the
// traversal, so timings of trace_closest never include the counting. The kernels run the same
// code, so their work is the same.
TraversalWork count_traversal_work(const KdTree& tree, const std::vector<RayRecord>& rays, std::vector<HitRecord>& hits,
                                   const TraceOptions& options = {});

// Copies the arrays of a tree read from a file (they view its mapping) into memory of its own
// when `rays` rays are to be traced on the host, and returns whether it did. That memory is on
// huge pages where the kernel gives them (TraversalArray), while a page cache may hold the file
// in 4 KiB pages, on which random rays miss the TLB at nearly every node. The copy is a pass
// over the tree (on `threads` threads, 0: all), so it is made only for rays enough to repay it:
// one per kTreeBytesPerRay bytes of tree.
constexpr uint64_t kTreeBytesPerRay = 128;
bool copy_tree_for_rays(KdTree& tree, size_t rays, unsigned threads = 0);

// One ray, on the calling thread: for tests and single queries; batches belong in trace_closest.
HitRecord intersect_closest(const KdTree& tree, const RayRecord& ray, TraversalStack stack = TraversalStack::Short);

}  // namespace kdray
