#include "trace_run.h"

#include <kdray/clock.h>
#include <kdray/ray_sets.h>

#include "process_stats.h"
#include "tree_memory.h"


namespace kdtrace {

bool needs_scene_arrays(const Options& o) {
  return !o.cache_folder.empty() || (o.rays_path.empty() && o.generate != "random");
}

std::vector<RayRecord> rays_to_trace(const Options& o, const kdray::Scene* scene, const kdray::KdTree& tree) {
  std::vector<RayRecord> rays;
  if (!o.rays_path.empty()) rays = kdray::read_rays(o.rays_path);
  else if (o.generate == "camera") rays = kdray::camera_rays(*scene, o.width, o.height);
  else if (o.generate == "random") rays = kdray::random_rays(tree.bounds, o.count, o.seed);
  else rays = kdray::hard_case_rays(*scene, tree, o.count, o.seed);
  if (!o.write_rays_path.empty()) kdray::write_rays(o.write_rays_path, rays);
  return rays;
}

TraceRun trace_on(bool host, kdray::KdTree& tree, const std::vector<RayRecord>& rays,
                  const kdray::TraceOptions& options, kdray::DeviceSelection opencl_device) {
  TraceRun run;
  if (host) run.tree_copy_seconds = kdray::tool::copy_tree_if_repaid(tree, rays.size(), options.threads);
  // The hits' storage is made before the clock starts, as a device's buffers are made before its
  // kernel runs, and as the Embree harness the rates are compared with does: the clock times the
  // tracing, not the zero-filling of its output.
  if (host) run.hits.resize(rays.size());
  const double cpu_start = kdray::tool::cpu_seconds();
  const auto start = kdray::Clock::now();
  if (host) {
    kdray::trace_closest(tree, rays, run.hits, options);
    run.traversal = options.path;
    run.packets = kdray::traces_in_packets(options);
    run.lanes = !run.packets && kdray::traces_in_lanes(tree, options);
  } else {
    opencl_device.short_stack_size = kdray::kernel_stack_size(options.stack);
    run.hits = kdray::trace_rays_opencl(tree, rays, opencl_device, &run.opencl);
    run.traversal = run.opencl.traversal;
  }
  run.seconds = host ? kdray::seconds_since(start) : run.opencl.trace_seconds;
  run.cpu_seconds = kdray::tool::cpu_seconds() - cpu_start;
  return run;
}

kdray::TraversalWork count_work(const kdray::KdTree& tree, const std::vector<RayRecord>& rays, unsigned threads) {
  std::vector<HitRecord> counted_hits;
  return kdray::count_traversal_work(tree, rays, counted_hits, {threads, kdray::TraversalStack::Short});
}

}  // namespace kdtrace
