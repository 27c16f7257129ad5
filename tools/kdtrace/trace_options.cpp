#include "trace_options.h"

#include <kdray/trace_opencl.h>

namespace kdtrace {

using kdray::tool::UsageError;

void add_options(CLI::App& app, Options& o) {
  o.opencl_device.device = "host";
  app.add_option("SCENE", o.scene_path, "Scene (.kdscene)");
  app.add_option("TREE", o.tree_path, "Its k-d tree (.kdtree, from kdbuild)");
  app.add_option("--cache", o.cache_folder,
                 "Instead of TREE: a tree cache folder (kdbuild --cache) where the scene's tree is found, or built "
                 "with the default settings");
  auto* rays_option = app.add_option("--rays", o.rays_path, "Ray file to trace (formats/rays.md)")->group("Rays");
  auto* generate_option =
      app.add_option("--generate", o.generate,
                     "Trace a generated ray set instead: camera (the scene's first camera, --width x --height), "
                     "random (origins on the bounding sphere aimed into the box, --count) or hard (axis-aligned with "
                     "+0/-0 components, on and in split planes, through vertices and edges, unnormalised "
                     "segments as shadow rays are, long directions from origins at or just off a plane, --count)")
          ->check(CLI::IsMember({"camera", "random", "hard"}))->group("Rays");
  rays_option->excludes(generate_option);
  app.add_option("--count", o.count, "Rays of a random or hard set")
      ->check(CLI::Range(size_t{1}, size_t{1} << 32))->capture_default_str()->group("Rays");
  app.add_option("--width", o.width, "Camera rays per row")->check(CLI::Range(1u, 65536u))->capture_default_str()->group("Rays");
  app.add_option("--height", o.height, "Camera rows")->check(CLI::Range(1u, 65536u))->capture_default_str()->group("Rays");
  app.add_option("--seed", o.seed, "Seed of a random or hard set")->capture_default_str()->group("Rays");
  app.add_option("--write-rays", o.write_rays_path, "Also write the generated rays to this ray file")->group("Rays");
  app.add_option("--hits", o.hits_path, "Hit file to write (formats/rays.md)")->group("Output");
  kdray::tool::add_device_option(app, o.opencl_device.device);
  app.add_option("--local-size", o.opencl_device.local_size,
                 "OpenCL work-group size where one ray is traced per work-item (in lanes a work-item is a "
                 "core's whole share); 0: the device's default")
      ->capture_default_str()->group("Device");
  kdray::tool::add_threads_option(app, o.traversal.threads);
  app.add_option("--stack", o.stack_name, "Traversal stack: short (8 entries, restart), depth1, full")
      ->check(CLI::IsMember({"short", "depth1", "full"}))->capture_default_str()->group("Device");
  app.add_option("--traversal", o.path_name,
                 "Traversal: fast (the fast path for every ray it gives the same hits, the robust code for the rest), "
                 "robust (every ray takes the robust code; with the short stack only on the host), or auto (the "
                 "device's own: robust on a GPU, fast on a CPU). All give the same hits")
      ->check(CLI::IsMember({"auto", "fast", "robust"}))->capture_default_str()->group("Device");
  app.add_flag("--no-lanes", o.no_lanes,
               "On a CPU: one ray at a time per thread (host) or per work-item (OpenCL), not 16 in AVX2 "
               "or 24 in float8 lanes (the same hits; lanes run where the tree has more than 256 nodes, on "
               "the host where the CPU has AVX2; a GPU always traces one ray per work-item)")
      ->group("Device");
  app.add_flag("--packets", o.packets,
               "On the host: 8 consecutive rays at a time as one packet (AVX2), which pays for rays that run "
               "close together in the file, such as camera rays in pixel order (2-3 times as fast), and "
               "costs for rays that run apart (0.65-0.85x on random rays); the same hits")
      ->group("Device");
}

kdray::tool::DeviceKind checked_device(const Options& o) {
  const kdray::tool::DeviceKind device = kdray::tool::device_kind(o.opencl_device.device);
  if (device == kdray::tool::DeviceKind::List) return device;
  if (device == kdray::tool::DeviceKind::All) throw UsageError("--device all: kdtrace traces on one device");
  kdray::tool::check_threads_option(o.opencl_device.device, o.traversal.threads);
  if (o.scene_path.empty() || o.tree_path.empty() == o.cache_folder.empty())
    throw UsageError("SCENE and either TREE or --cache DIR are required");
  if (o.rays_path.empty() == o.generate.empty()) throw UsageError("give one of --rays or --generate");
  return device;
}

kdray::DeviceSelection opencl_selection(const Options& o) {
  kdray::DeviceSelection device = o.opencl_device;
  device.traversal = kdray::parse_traversal_path(o.path_name);
  device.lanes = !o.no_lanes;
  return device;
}

kdray::TraceOptions traversal_options(const Options& o, bool host) {
  kdray::TraceOptions options = o.traversal;
  options.stack = o.stack_name == "depth1" ? kdray::TraversalStack::Depth1
                  : o.stack_name == "full" ? kdray::TraversalStack::Full
                                           : kdray::TraversalStack::Short;
  options.path = kdray::parse_traversal_path(o.path_name).value_or(kdray::TraversalPath::FastWhereSafe);
  options.lanes = !o.no_lanes;
  options.packets = o.packets;
  if (!host && o.packets) throw UsageError("--packets is for --device host");
  if (host && options.path == kdray::TraversalPath::Robust && options.stack != kdray::TraversalStack::Short)
    throw UsageError("--traversal robust on the host: with --stack short only");
  return options;
}

}  // namespace kdtrace
