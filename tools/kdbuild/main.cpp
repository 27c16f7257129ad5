// kdbuild SCENE.kdscene OUTPUT.kdtree: builds the SAH k-d tree of a scene and writes it.
// kdbuild --cache DIR SCENE [OUTPUT]: takes the tree from a tree cache, building and storing it on a miss.
#include "build_report.h"

#include <kdray/clock.h>
#include <kdray/kdtree.h>
#include <kdray/scene_file.h>
#include <kdray/tree_cache.h>

#include "process_stats.h"
#include "progress.h"
#include "tool_main.h"
#include "tree_json.h"

#include <cstdio>
#include <string>
#include <vector>

namespace {

// Peak memory of kdbuild per triangle, scene and tree included, with a margin for meshes whose
// triangles are referenced by more leaves (measured figures: RELIABILITY.md, "Resource limits").
constexpr uint64_t kBuildBytesPerTriangle = 320;

}  // namespace

int main(int argc, char** argv) {
  using kdray::BuildSettings;
  CLI::App app{"kdbuild: build the SAH k-d tree of a .kdscene and write it as a .kdtree"};
  kdray::tool::OutputFlags output;
  kdray::tool::add_contract(app, "kdbuild", output, "Print the statistics as JSON on stdout");
  std::string scene_path, tree_path, cache_folder;
  uint64_t cache_max_bytes = 0;
  BuildSettings settings;
  unsigned threads = 0;
  bool no_perfect_splits = false;
  app.add_option("SCENE", scene_path, "Input scene (.kdscene)")->required();
  auto* tree_option =
      app.add_option("OUTPUT", tree_path, "Output tree (.kdtree), written atomically; optional with --cache");
  app.add_option("--kt", settings.traversal_cost, "Cost of traversing an inner node (K_T)")
      ->capture_default_str()->check(CLI::NonNegativeNumber)->group("Cost model");
  app.add_option("--ki", settings.intersection_cost, "Cost of one ray/triangle test (K_I)")
      ->capture_default_str()->check(CLI::PositiveNumber)->group("Cost model");
  app.add_option("--empty-bonus", settings.empty_bonus, "Factor lambda on splits that cut off empty space, in (0, 1]")
      ->capture_default_str()->check(CLI::Range(1e-6, 1.0))->group("Cost model");
  app.add_option("--max-depth", settings.max_depth,
                 "Depth limit; 0: 8 + log2 N, at most " + std::to_string(BuildSettings::kAutoMaxDepthCap) +
                     " (limit " + std::to_string(BuildSettings::kMaxDepthLimit) + ")")
      ->capture_default_str()->check(CLI::Range(0u, BuildSettings::kMaxDepthLimit))->group("Tree");
  app.add_flag("--no-perfect-splits", no_perfect_splits,
               "Take candidate planes from triangle bounding boxes instead of triangles clipped to the voxel")
      ->group("Tree");
  bool exact = false;
  auto* exact_flag =
      app.add_flag("--exact", exact,
                   "Choose every split by the exact sweep over all candidate planes: a slower build, for "
                   "comparing tree quality (the same as --binned-above 0)")
          ->group("Tree");
  app.add_option("--binned-above", settings.binned_above,
                 "Nodes of more triangles choose their split among binned planes, smaller ones by the exact sweep; "
                 "0: exact everywhere")
      ->capture_default_str()->excludes(exact_flag)->group("Tree");
  // The names are the JSON report's (tree_json.h), so one list serves the option and the report.
  const kdray::LeafLayout layouts[] = {kdray::LeafLayout::automatic, kdray::LeafLayout::grouped,
                                       kdray::LeafLayout::paged};
  std::vector<std::string> layout_names;
  for (kdray::LeafLayout layout : layouts) layout_names.push_back(kdray::tool::leaf_layout_name(layout));
  std::string layout_name = layout_names[0];
  app.add_option("--leaf-layout", layout_name,
                 "Leaf blocks: grouped (four triangles' corners by axis, read in one load each; about twice the "
                 "bytes), paged (each distinct corner once), or auto (grouped up to " +
                     std::to_string(BuildSettings::kGroupedLeavesUpTo) + " triangles)")
      ->check(CLI::IsMember(layout_names))->capture_default_str()->group("Tree");
  app.add_option("--bins", settings.bins, "Bins per axis of the binned nodes")
      ->capture_default_str()->check(CLI::Range(2u, BuildSettings::kMaxBins))->group("Tree");
  auto* cache_option = app.add_option("--cache", cache_folder,
                                      "Tree cache folder: a tree already built for this geometry and these settings "
                                      "is checked and copied, else built and stored")->group("Cache");
  app.add_option("--cache-max-bytes", cache_max_bytes,
                 "Then remove least recently used cache entries until the cache holds at most this many bytes")
      ->needs(cache_option)->check(CLI::PositiveNumber)->group("Cache");
  app.add_option("--threads", threads, "Build threads; 0: all cores (the tree is the same for any count)")
      ->capture_default_str()->group("Run");
  uint64_t max_memory = 0;
  kdray::tool::add_max_memory_option(app, max_memory);
  app.callback([&] {
    if (tree_option->count() == 0 && cache_option->count() == 0) throw CLI::RequiredError("OUTPUT (or --cache DIR)");
  });

  return kdray::tool::run(app, argc, argv, [&] {
    settings.perfect_splits = !no_perfect_splits;
    for (kdray::LeafLayout layout : layouts)
      if (layout_name == kdray::tool::leaf_layout_name(layout)) settings.leaf_layout = layout;
    if (exact) settings.binned_above = 0;
    kdbuild::Report report;
    report.scene_path = scene_path;
    report.tree_path = tree_path;
    const auto start = kdray::Clock::now();
    const kdray::Scene scene = kdray::read_scene(scene_path);
    report.scene_hash = scene.content_hash;
    report.load_seconds = kdray::seconds_since(start);
    kdray::check_memory_estimate(scene_path, "building its tree",
                                 kBuildBytesPerTriangle * scene.triangle_count(), max_memory);

    kdray::tool::ProgressBar progress("kdbuild", !output.quiet);
    const kdray::BuildControl control{threads, [&](double fraction) { progress.update(fraction); }, &report.phases};
    const auto build_start = kdray::Clock::now();
    const double cpu_start = kdray::tool::cpu_seconds();
    if (cache_folder.empty()) {
      report.tree = kdray::build_tree_file(scene, tree_path, settings, control);
      report.write_seconds = report.phases.write;
      report.build_seconds = kdray::seconds_since(build_start) - report.write_seconds;
    } else {
      kdray::TreeCache trees(cache_folder, [](const std::string& line) { kdray::tool::print_warning("kdbuild", line); });
      kdray::CachedTree cached = kdray::cached_tree(trees, scene, scene_path, settings, control, tree_path);
      report.cache = cached.hit ? "hit" : "miss";
      report.cache_entry = cached.entry;
      report.tree = std::move(cached.tree);
      report.build_seconds = kdray::seconds_since(build_start);
      if (cache_max_bytes > 0) report.evicted = trees.evict(cache_max_bytes, report.tree.key);
    }
    report.build_cpu_seconds = kdray::tool::cpu_seconds() - cpu_start;
    progress.finish();
    if (output.json)
      kdray::tool::print_json(kdbuild::report_json(report));
    else if (!output.quiet)
      std::fputs(kdbuild::report_text(report).c_str(), stdout);
    return kdray::tool::kExitOk;
  });
}
