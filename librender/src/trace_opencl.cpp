// trace_rays_opencl: the kd_trace.cl kernel over a ray buffer (see trace_opencl.h).
#include "device_scene.h"

#include <kdray/clock.h>
#include <kdray/error.h>
#include <kdray/trace_opencl.h>
#include <kdray/traverse.h>

#include <kernels/kd_trace_args.h>


namespace kdray {

unsigned kernel_stack_size(TraversalStack stack) {
  switch (stack) {
    case TraversalStack::Depth1: return 1;
    case TraversalStack::Full: return BuildSettings::kMaxDepthLimit;
    case TraversalStack::Short: break;
  }
  return 0;
}

TraversalPath traversal_path_for(const DeviceSelection& device, bool gpu) {
  if (device.traversal) return *device.traversal;
  return gpu ? TraversalPath::Robust : TraversalPath::FastWhereSafe;
}

std::string traversal_build_options(const DeviceSelection& device, bool gpu) {
  std::string options;
  if (device.short_stack_size) options += " -DKD_SHORT_STACK_SIZE=" + std::to_string(device.short_stack_size);
  if (traversal_path_for(device, gpu) == TraversalPath::Robust) options += " -DKD_TRAVERSAL_ROBUST_ONLY";
  // On a CPU a leaf's triangles are tested four at a time in vector lanes (kernels/kd_scene_view.h).
  if (!gpu) options += " -DKD_LEAF_TESTS_IN_LANES";
  return options;
}

const char* traversal_path_name(TraversalPath path) { return path == TraversalPath::Robust ? "robust" : "fast"; }

std::optional<TraversalPath> parse_traversal_path(const std::string& name) {
  if (name == "auto") return std::nullopt;
  for (TraversalPath path : {TraversalPath::FastWhereSafe, TraversalPath::Robust})
    if (name == traversal_path_name(path)) return path;
  throw Error("", "unknown traversal '" + name + "': auto, fast or robust");
}

bool opencl_traces_in_lanes(const KdTree& tree, const DeviceSelection& device, bool gpu) {
  return !gpu && device.lanes && device.short_stack_size == 0 &&
         traversal_path_for(device, gpu) == TraversalPath::FastWhereSafe && tree.nodes.size() > kLanesMinNodes;
}

TraceKernelBuild trace_kernel_build(const DeviceSelection& device, bool gpu, bool lanes) {
  const TraversalPath traversal = traversal_path_for(device, gpu);
  const std::string options = "-cl-std=CL1.2" + traversal_build_options(device, gpu);
  // One ray per work-item on a GPU, which vectorises across work-items. On a CPU device (PoCL)
  // a work-item runs as scalar code and waits on its node fetches: it traces 24 rays in lanes
  // where the tree is large enough, else one ray whose far children are prefetched when pushed;
  // GPU compilers need not know __builtin_prefetch. A CPU's work-items take 256 rays at a time
  // from the shared counter (kernels/kd_trace.cl).
  if (gpu) return {options, "one-ray-per-work-item", traversal};
  const std::string cpu_options = options + " -DKD_PREFETCH_NODES -DKD_TRACE_BATCH=256u";
  if (lanes) return {cpu_options + " -DKD_TRACE_LANES", "24-rays-per-work-item-in-float8-lanes+prefetch", traversal};
  return {cpu_options, "one-ray-per-work-item+prefetch", traversal};
}

std::vector<HitRecord> trace_rays_opencl(const KdTree& tree, const std::vector<RayRecord>& rays,
                                         const DeviceSelection& device, TraceOpenClStats* stats_out) {
  TraceOpenClStats stats;
  cl::Runtime& runtime = cl::runtime_for(device);
  stats.device = runtime.info().name;
  const bool lanes = opencl_traces_in_lanes(tree, device, runtime.info().is_gpu);
  const TraceKernelBuild kernel_build = trace_kernel_build(device, runtime.info().is_gpu, lanes);
  stats.kernel_variant = kernel_build.variant;
  stats.traversal = kernel_build.traversal;
  cl::ProgramBuild build = runtime.program("kd_trace.cl", kernel_build.options);
  stats.build_seconds = build.seconds;
  stats.build_source = build.source;

  auto upload_start = Clock::now();
  const GeometryArrays arrays = geometry_arrays(tree);
  DeviceGeometry geometry = upload_geometry(runtime, arrays);
  // The kernel's arguments that are not DeviceGeometry buffers, named as in KD_TRACE_ARGS.
  struct {
    cl::Buffer rays, hits;
    cl_float4 bounds_min, bounds_max;
    cl_uint ray_count;
  } args;
  args.rays = runtime.buffer(rays.size() * sizeof(RayRecord), rays.data());
  args.hits = runtime.buffer(rays.size() * sizeof(HitRecord), nullptr, CL_MEM_WRITE_ONLY);
  args.bounds_min = {{arrays.bounds_min[0], arrays.bounds_min[1], arrays.bounds_min[2], 0}};
  args.bounds_max = {{arrays.bounds_max[0], arrays.bounds_max[1], arrays.bounds_max[2], 0}};
  args.ray_count = static_cast<cl_uint>(rays.size());
  cl::Buffer next_ray = runtime.buffer(sizeof(cl_uint), nullptr, CL_MEM_READ_WRITE);
  cl::zero_buffer(runtime.queue(), next_ray, sizeof(cl_uint));
  // The hits' storage is made before the clock, as the host's is (kdtrace): on a CPU device the
  // kernel would otherwise take the page faults of a buffer it is the first to write.
  if (!rays.empty()) cl::zero_buffer(runtime.queue(), args.hits, rays.size() * sizeof(HitRecord));
  cl::Kernel kernel = cl::create_kernel(build.program, lanes ? "kd_trace_closest_lanes" : "kd_trace_closest");
  cl_uint arg = 0;
#define KD_BIND_GEOMETRY(type, name) cl::set_arg(kernel.get(), arg++, geometry.name);
#define KD_BIND_ARG(type, name) cl::set_arg(kernel.get(), arg++, args.name);
  KD_TRACE_ARGS(KD_BIND_GEOMETRY, KD_BIND_ARG, KD_BIND_ARG)
#undef KD_BIND_GEOMETRY
#undef KD_BIND_ARG
  cl::set_arg(kernel.get(), arg++, next_ray);
  cl::check(clFinish(runtime.queue()), "clFinish");
  stats.upload_seconds = seconds_since(upload_start);

  std::vector<HitRecord> hits(rays.size());
  auto trace_start = Clock::now();
  if (!rays.empty()) {
    // In lanes a work-item is a thread's whole work: one per compute unit.
    const size_t local = lanes ? 1 : runtime.local_size(device);
    cl::run_kernel(runtime.queue(), kernel.get(), runtime.persistent_global_size(local), local);
    cl::check(clFinish(runtime.queue()), "clFinish");
  }
  stats.trace_seconds = seconds_since(trace_start);
  if (!rays.empty()) cl::read_buffer(runtime.queue(), args.hits, hits.size() * sizeof(HitRecord), hits.data());
  if (stats_out) *stats_out = stats;
  return hits;
}

}  // namespace kdray
