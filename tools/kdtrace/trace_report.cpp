#include "trace_report.h"

#include "tree_memory.h"

#include <cstdio>

namespace kdtrace {
namespace {

size_t hit_count(const TraceRun& run) {
  size_t hits = 0;
  for (const HitRecord& hit : run.hits) hits += hit.triangle != KD_NO_HIT ? 1 : 0;
  return hits;
}

double mrays_per_s(size_t ray_count, const TraceRun& run) {
  return run.seconds > 0 ? static_cast<double>(ray_count) / run.seconds / 1e6 : 0.0;
}

}  // namespace

nlohmann::json trace_json(const Options& o, bool host, size_t ray_count, const TraceRun& run,
                          const kdray::TraversalWork& work) {
  nlohmann::json summary = {{"scene", o.scene_path},      {"tree", o.tree_path},
                            {"rays", ray_count},          {"hits", hit_count(run)},
                            {"seconds", run.seconds},     {"cpu_seconds", run.cpu_seconds},
                            {"mrays_per_s", mrays_per_s(ray_count, run)},
                            {"stack", o.stack_name},      {"traversal", kdray::traversal_path_name(run.traversal)}};
  const double per_ray = ray_count == 0 ? 0.0 : 1.0 / static_cast<double>(ray_count);
  summary["per_ray"] = {{"inner_steps", static_cast<double>(work.inner_steps) * per_ray},
                        {"leaves", static_cast<double>(work.leaves) * per_ray},
                        {"triangle_tests", static_cast<double>(work.triangle_tests) * per_ray},
                        {"fast_path", static_cast<double>(work.fast_path_rays) * per_ray},
                        {"fast_path_restarts", static_cast<double>(work.fast_path_restarts) * per_ray}};
  if (host) {
    summary["device"] = "host";
    summary["threads"] = o.traversal.threads;
    summary["variant"] = run.packets ? "cpu-8-ray-packets-in-avx2"
                         : run.lanes ? "cpu-16-rays-per-thread-in-avx2-lanes+prefetch"
                                     : "cpu-one-ray-per-thread+prefetch";
    kdray::tool::add_tree_memory(summary, run.tree_copy_seconds);
  } else {
    summary["device"] = run.opencl.device;
    summary["build_seconds"] = run.opencl.build_seconds;
    summary["build_source"] = run.opencl.build_source;
    summary["upload_seconds"] = run.opencl.upload_seconds;
    summary["variant"] = run.opencl.kernel_variant;
  }
  return summary;
}

void print_trace(bool host, size_t ray_count, const TraceRun& run) {
  if (!host)
    std::printf("OpenCL device %s (%s, %s traversal): program %s in %.3f s, upload %.3f s\n",
                run.opencl.device.c_str(), run.opencl.kernel_variant.c_str(),
                kdray::traversal_path_name(run.traversal), run.opencl.build_source.c_str(), run.opencl.build_seconds,
                run.opencl.upload_seconds);
  const size_t hits = hit_count(run);
  std::printf("%zu rays, %zu hits (%.1f%%) in %.3f s: %.2f Mrays/s\n", ray_count, hits,
              ray_count == 0 ? 0.0 : 100.0 * static_cast<double>(hits) / static_cast<double>(ray_count), run.seconds,
              mrays_per_s(ray_count, run));
}

}  // namespace kdtrace
