// kdtrace SCENE TREE: closest hit of every ray of a ray file (or of a generated ray set),
// written as a hit file, with the tracing rate in Mrays/s.
//
//   kdtrace scene.kdscene scene.kdtree --rays rays.bin --hits hits.bin
//   kdtrace scene.kdscene --cache trees/ --generate random --count 1000000 --device cpu --json
#include "trace_options.h"
#include "trace_report.h"
#include "trace_run.h"

#include <kdray/ray_files.h>
#include <kdray/tree_cache.h>

#include "device_option.h"
#include "tool_main.h"

#include <string>

int main(int argc, char** argv) {
  CLI::App app{"kdtrace: closest hit of every ray against a scene and its k-d tree"};
  kdtrace::Options o;
  kdray::tool::add_contract(app, "kdtrace", o.flags, "Print the summary as JSON on stdout");
  kdtrace::add_options(app, o);

  return kdray::tool::run(app, argc, argv, [&]() -> int {
    const kdray::tool::DeviceKind device = kdtrace::checked_device(o);
    if (device == kdray::tool::DeviceKind::List) return kdray::tool::list_opencl_devices(o.flags.json);
    const bool host = device == kdray::tool::DeviceKind::Host;
    kdray::SceneAndTree read;
    const bool scene_arrays = kdtrace::needs_scene_arrays(o);
    if (scene_arrays)
      read = kdray::read_scene_and_tree(o.scene_path, o.tree_path, o.cache_folder, [](const std::string& line) {
        kdray::tool::print_warning("kdtrace", line);
      });
    else
      read.tree = kdray::read_tree_for_scene(o.scene_path, o.tree_path);
    kdray::KdTree& tree = read.tree;
    const std::vector<RayRecord> rays =
        kdtrace::rays_to_trace(o, scene_arrays ? &read.scene : nullptr, tree);
    const kdray::TraceOptions options = kdtrace::traversal_options(o, host);
    const kdtrace::TraceRun run = kdtrace::trace_on(host, tree, rays, options, kdtrace::opencl_selection(o));
    if (!o.hits_path.empty()) kdray::write_hits(o.hits_path, run.hits);

    if (o.flags.json) {
      const kdray::TraversalWork work = kdtrace::count_work(tree, rays, options.threads);
      kdray::tool::print_json(kdtrace::trace_json(o, host, rays.size(), run, work));
    } else if (!o.flags.quiet) {
      kdtrace::print_trace(host, rays.size(), run);
    }
    return kdray::tool::kExitOk;
  });
}
