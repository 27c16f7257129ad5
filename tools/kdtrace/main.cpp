// kdtrace SCENE TREE: closest hit of every ray of a ray file (or of a generated ray set),
// written as a hit file, with the tracing rate in Mrays/s.
#include <kdray/kdtree.h>
#include <kdray/tree_cache.h>
#include <kdray/ray_files.h>
#include <kdray/ray_sets.h>
#include <kdray/scene_file.h>
#include <kdray/trace_opencl.h>
#include <kdray/traverse.h>

#include "device_option.h"
#include "process_stats.h"
#include "tool_main.h"

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

namespace {

struct TraceRun {
  std::vector<HitRecord> hits;
  double seconds = 0;      // tracing only: for OpenCL the kernel time, rays already on the device
  double cpu_seconds = 0;  // user + system: with the wall time, tells a busy machine
  kdray::TraceOpenClStats opencl;
};

// Where the rays are traced: on the host, libkdtree's CPU traversal; on an OpenCL device,
// librender's kd_trace kernel. Both run the same kernels/kd_traverse.h.
TraceRun trace_on(bool host, const kdray::Scene& scene, const kdray::KdTree& tree,
                  const std::vector<RayRecord>& rays, const kdray::TraceOptions& options,
                  kdray::DeviceSelection opencl_device) {
  TraceRun run;
  // Gathering the triangle vertices is set-up, like the OpenCL upload: not part of the rate.
  const std::optional<kdray::PreparedTraversal> cpu_traversal =
      host ? std::optional<kdray::PreparedTraversal>(std::in_place, scene, tree) : std::nullopt;
  const double cpu_start = kdray::tool::cpu_seconds();
  const auto start = std::chrono::steady_clock::now();
  if (host) {
    cpu_traversal->closest(rays, run.hits, options);
  } else {
    opencl_device.short_stack_size = kdray::kernel_stack_size(options.stack);
    opencl_device.robust_traversal = options.path == kdray::TraversalPath::Robust;
    run.hits = kdray::trace_rays_opencl(scene, tree, rays, opencl_device, &run.opencl);
  }
  run.seconds = host ? std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
                     : run.opencl.trace_seconds;
  run.cpu_seconds = kdray::tool::cpu_seconds() - cpu_start;
  return run;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"kdtrace: closest hit of every ray against a scene and its k-d tree"};
  kdray::tool::OutputFlags output;
  kdray::tool::add_contract(app, "kdtrace", output, "Print the summary as JSON on stdout");
  std::string scene_path, tree_path, cache_folder, rays_path, hits_path, generate, write_rays_path, stack_name = "short",
              path_name = "fast";
  size_t count = 1000000;
  uint32_t width = 1024, height = 768;
  uint64_t seed = 1;
  kdray::TraceOptions options;
  kdray::DeviceSelection opencl_device;
  opencl_device.device = "host";
  app.add_option("SCENE", scene_path, "Scene (.kdscene)");
  app.add_option("TREE", tree_path, "Its k-d tree (.kdtree, from kdbuild)");
  app.add_option("--cache", cache_folder,
                 "Instead of TREE: a tree cache folder (kdbuild --cache) where the scene's tree is found, or built "
                 "with the default settings");
  auto* rays_option = app.add_option("--rays", rays_path, "Ray file to trace (formats/rays.md)")->group("Rays");
  auto* generate_option =
      app.add_option("--generate", generate,
                     "Trace a generated ray set instead: camera (the scene's first camera, --width x --height), "
                     "random (origins on the bounding sphere aimed into the box, --count) or hard (axis-aligned with "
                     "+0/-0 components, on and in split planes, through vertices and edges, --count)")
          ->check(CLI::IsMember({"camera", "random", "hard"}))->group("Rays");
  rays_option->excludes(generate_option);
  app.add_option("--count", count, "Rays of a random or hard set")
      ->check(CLI::Range(size_t{1}, size_t{1} << 32))->capture_default_str()->group("Rays");
  app.add_option("--width", width, "Camera rays per row")->check(CLI::Range(1u, 65536u))->capture_default_str()->group("Rays");
  app.add_option("--height", height, "Camera rows")->check(CLI::Range(1u, 65536u))->capture_default_str()->group("Rays");
  app.add_option("--seed", seed, "Seed of a random or hard set")->capture_default_str()->group("Rays");
  app.add_option("--write-rays", write_rays_path, "Also write the generated rays to this ray file")->group("Rays");
  app.add_option("--hits", hits_path, "Hit file to write (formats/rays.md)")->group("Output");
  kdray::tool::add_device_option(app, opencl_device.device);
  app.add_option("--local-size", opencl_device.local_size, "OpenCL work-group size; 0: the device's default")
      ->capture_default_str()->group("Device");
  kdray::tool::add_threads_option(app, options.threads);
  app.add_option("--stack", stack_name, "Traversal stack: short (8 entries, restart), depth1, full")
      ->check(CLI::IsMember({"short", "depth1", "full"}))->capture_default_str()->group("Device");
  app.add_option("--traversal", path_name,
                 "Traversal: fast (the fast path for every ray it gives the same hits, the robust code for the rest) "
                 "or robust (every ray takes the robust code; with the short stack only on the host)")
      ->check(CLI::IsMember({"fast", "robust"}))->capture_default_str()->group("Device");

  return kdray::tool::run(app, argc, argv, [&]() -> int {
    const kdray::tool::DeviceKind device = kdray::tool::device_kind(opencl_device.device);
    if (device == kdray::tool::DeviceKind::List) return kdray::tool::list_opencl_devices(output.json);
    if (device == kdray::tool::DeviceKind::All) throw kdray::tool::UsageError("--device all: kdtrace traces on one device");
    kdray::tool::check_threads_option(opencl_device.device, options.threads);
    if (scene_path.empty() || tree_path.empty() == cache_folder.empty())
      throw kdray::tool::UsageError("SCENE and either TREE or --cache DIR are required");
    if (rays_path.empty() == generate.empty()) throw kdray::tool::UsageError("give one of --rays or --generate");
    const bool host = device == kdray::tool::DeviceKind::Host;
    const kdray::Scene scene = kdray::read_scene(scene_path);
    const kdray::KdTree tree = kdray::tree_for_scene(scene, scene_path, tree_path, cache_folder, [](const std::string& line) {
      kdray::tool::print_warning("kdtrace", line);
    });

    std::vector<RayRecord> rays;
    if (!rays_path.empty()) rays = kdray::read_rays(rays_path);
    else if (generate == "camera") rays = kdray::camera_rays(scene, width, height);
    else if (generate == "random") rays = kdray::random_rays(tree.bounds, count, seed);
    else rays = kdray::hard_case_rays(scene, tree, count, seed);
    if (!write_rays_path.empty()) kdray::write_rays(write_rays_path, rays);

    options.stack = stack_name == "depth1" ? kdray::TraversalStack::Depth1
                    : stack_name == "full" ? kdray::TraversalStack::Full
                                           : kdray::TraversalStack::Short;
    options.path = path_name == "robust" ? kdray::TraversalPath::Robust : kdray::TraversalPath::FastWhereSafe;
    if (host && options.path == kdray::TraversalPath::Robust && options.stack != kdray::TraversalStack::Short)
      throw kdray::tool::UsageError("--traversal robust on the host: with --stack short only");
    const TraceRun run = trace_on(host, scene, tree, rays, options, opencl_device);
    if (!hits_path.empty()) kdray::write_hits(hits_path, run.hits);

    size_t hit_count = 0;
    for (const HitRecord& hit : run.hits) hit_count += hit.triangle != KD_NO_HIT ? 1 : 0;
    const double mrays_per_s = run.seconds > 0 ? static_cast<double>(rays.size()) / run.seconds / 1e6 : 0.0;
    if (output.json) {
      nlohmann::json summary = {{"scene", scene_path}, {"tree", tree_path}, {"rays", rays.size()}, {"hits", hit_count},
                                {"seconds", run.seconds}, {"cpu_seconds", run.cpu_seconds}, {"mrays_per_s", mrays_per_s},
                                {"stack", stack_name}, {"traversal", path_name}};
      // Per-ray work from a second, counting pass of the same traversal on the CPU (kept out
      // of the timed run); the kernel runs the same code, so its hits and work are the same. The
      // count is of the default traversal (the fast path where it applies) whatever --traversal says.
      std::vector<HitRecord> counted_hits;
      const kdray::TraversalWork work =
          kdray::PreparedTraversal(scene, tree).count_work(rays, counted_hits, {options.threads, kdray::TraversalStack::Short});
      const double per_ray = rays.empty() ? 0.0 : 1.0 / static_cast<double>(rays.size());
      summary["per_ray"] = {{"inner_steps", static_cast<double>(work.inner_steps) * per_ray},
                            {"leaves", static_cast<double>(work.leaves) * per_ray},
                            {"triangle_tests", static_cast<double>(work.triangle_tests) * per_ray},
                            {"fast_path", static_cast<double>(work.fast_path_rays) * per_ray},
                            {"fast_path_restarts", static_cast<double>(work.fast_path_restarts) * per_ray}};
      if (host) {
        summary["device"] = "host";
        summary["threads"] = options.threads;
        summary["variant"] = "cpu-one-ray-per-thread+prefetch";
      } else {
        summary["device"] = run.opencl.device;
        summary["build_seconds"] = run.opencl.build_seconds;
        summary["build_source"] = run.opencl.build_source;
        summary["upload_seconds"] = run.opencl.upload_seconds;
        summary["variant"] = run.opencl.kernel_variant;
      }
      kdray::tool::print_json(summary);
      return kdray::tool::kExitOk;
    }
    if (output.quiet) return kdray::tool::kExitOk;
    if (!host)
      std::printf("OpenCL device %s (%s): program %s in %.3f s, upload %.3f s\n", run.opencl.device.c_str(),
                  run.opencl.kernel_variant.c_str(), run.opencl.build_source.c_str(), run.opencl.build_seconds,
                  run.opencl.upload_seconds);
    std::printf("%zu rays, %zu hits (%.1f%%) in %.3f s: %.2f Mrays/s\n", rays.size(), hit_count,
                rays.empty() ? 0.0 : 100.0 * static_cast<double>(hit_count) / static_cast<double>(rays.size()),
                run.seconds, mrays_per_s);
    return kdray::tool::kExitOk;
  });
}
