// The rays kdtrace traces and where it traces them: on the host, libkdtree's CPU traversal; on
// an OpenCL device, librender's kd_trace kernel. Both run the same kernels/kd_traverse.h.
#pragma once

#include "trace_options.h"

#include <kdray/kdtree.h>
#include <kdray/ray_files.h>
#include <kdray/scene.h>
#include <kdray/trace_opencl.h>
#include <kdray/traverse.h>

#include <vector>

namespace kdtrace {

struct TraceRun {
  std::vector<HitRecord> hits;
  double seconds = 0;      // tracing only: for OpenCL the kernel time, rays already on the device
  double cpu_seconds = 0;  // user + system: with the wall time, tells a busy machine
  double tree_copy_seconds = -1;  // the host's copy of a mapped tree (copy_tree_for_rays); -1: none
  kdray::TraversalPath traversal = kdray::TraversalPath::FastWhereSafe;  // the one that ran
  bool lanes = false;    // the host traced in AVX2 lanes (kdray::traces_in_lanes)
  bool packets = false;  // the host traced packets (kdray::traces_in_packets)
  kdray::TraceOpenClStats opencl;
};

// Whether the run reads the scene's arrays: a tree cache builds from them on a miss, camera rays
// frame the scene and hard-case rays are made from its triangles. Otherwise the tree, which holds
// the triangles' corners, is all the tracing reads, and the scene is only checked to match it.
bool needs_scene_arrays(const Options& o);

// The rays of --rays, or the generated set of --generate (also written to --write-rays); `scene`
// may be null unless needs_scene_arrays.
std::vector<RayRecord> rays_to_trace(const Options& o, const kdray::Scene* scene, const kdray::KdTree& tree);

// On the host (the tree first copied out of its file when the rays repay it), else on the
// OpenCL device (opencl_selection).
TraceRun trace_on(bool host, kdray::KdTree& tree, const std::vector<RayRecord>& rays,
                  const kdray::TraceOptions& options, kdray::DeviceSelection opencl_device);

// Per-ray work from a second, counting pass of the same traversal on the CPU (kept out of the
// timed run); the kernel runs the same code, so its hits and work are the same. The count is of
// the default traversal (the fast path where it applies) whatever --traversal says.
kdray::TraversalWork count_work(const kdray::KdTree& tree, const std::vector<RayRecord>& rays, unsigned threads);

}  // namespace kdtrace
