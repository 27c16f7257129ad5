// Closest hits for a batch of rays with the OpenCL traversal kernel (kdtrace with an OpenCL --device).
#pragma once

#include <kdray/kdtree.h>
#include <kdray/opencl_device.h>
#include <kdray/scene.h>
#include <kdray/traverse.h>

#include <kernels/kd_types.h>

#include <optional>
#include <string>
#include <vector>

namespace kdray {

struct TraceOpenClStats {
  std::string device;
  double build_seconds = 0;
  std::string build_source;  // "compiled", "disk cache" or "memory"
  double upload_seconds = 0;
  double trace_seconds = 0;  // kernel time only, rays already on the device
  std::string kernel_variant;  // how kd_trace.cl was built for this device (trace_rays_opencl)
  TraversalPath traversal = TraversalPath::FastWhereSafe;  // the one it compiled
};

// The traversal a device's programs compile unless the selection names one: the robust code
// alone on a GPU, the fast path where it applies on a CPU device. Both give the same hits bit
// for bit. On a GPU the fast path's second code path, and the robust re-trace of the rays that
// leave it, cost more in registers and divergence than its lean step saves; a CPU runs one ray
// at a time and gains the lean step (bench/LOG.md, "The traversal chosen per device").
TraversalPath traversal_path_for(const DeviceSelection& device, bool gpu);
// The traversal's build options for a device, each with a leading space: its short stack's size
// (KD_SHORT_STACK_SIZE, when set) and its path (KD_TRAVERSAL_ROBUST_ONLY for the robust one).
// Every program that traverses (kd_trace.cl and the render kernels) is built with them.
std::string traversal_build_options(const DeviceSelection& device, bool gpu);
// "fast" or "robust", as the tools' --traversal and --json name them.
const char* traversal_path_name(TraversalPath path);
// The path a --traversal value names: "fast" or "robust"; "auto" is none (the device's own).
// Throws kdray::Error for any other name.
std::optional<TraversalPath> parse_traversal_path(const std::string& name);

// DeviceSelection::short_stack_size for a traversal stack: Depth1 one entry, Full as deep as a
// tree can be (never restarts), Short 0, the kernel's default KD_SHORT_STACK_SIZE as on the CPU.
unsigned kernel_stack_size(TraversalStack stack);

// Whether kd_trace.cl traces `tree` 24 rays per work-item in float8 lanes
// (kernels/kd_traverse_lanes.h): on a CPU device with the fast path and the default short stack,
// where DeviceSelection::lanes and the tree has more than kLanesMinNodes nodes, as on the host.
bool opencl_traces_in_lanes(const KdTree& tree, const DeviceSelection& device, bool gpu);

// kd_trace.cl's build options and its variant's name (TraceOpenClStats::kernel_variant) for a
// GPU or a CPU device, in lanes or not, before the device's own (device_build_options.h).
struct TraceKernelBuild {
  std::string options;
  std::string variant;
  TraversalPath traversal;
};
TraceKernelBuild trace_kernel_build(const DeviceSelection& device, bool gpu, bool lanes = false);

// Same contract as trace_closest (libkdtree): t = +inf and KD_NO_HIT on a miss.
std::vector<HitRecord> trace_rays_opencl(const KdTree& tree, const std::vector<RayRecord>& rays,
                                         const DeviceSelection& device, TraceOpenClStats* stats = nullptr);

}  // namespace kdray
