// Closest hits for a batch of rays with the OpenCL traversal kernel (kdtrace with an OpenCL --device).
#pragma once

#include <kdray/kdtree.h>
#include <kdray/opencl_device.h>
#include <kdray/scene.h>

#include <kernels/kd_types.h>

#include <vector>

namespace kdray {

struct TraceOpenClStats {
  std::string device;
  double build_seconds = 0;
  std::string build_source;  // "compiled", "disk cache" or "memory"
  double upload_seconds = 0;
  double trace_seconds = 0;  // kernel time only, rays already on the device
  std::string kernel_variant;  // how kd_trace.cl was built for this device (trace_rays_opencl)
};

// Same contract as trace_closest (libkdtree): t = +inf and KD_NO_HIT on a miss.
std::vector<HitRecord> trace_rays_opencl(const Scene& scene, const KdTree& tree, const std::vector<RayRecord>& rays,
                                         const DeviceSelection& device, TraceOpenClStats* stats = nullptr);

}  // namespace kdray
