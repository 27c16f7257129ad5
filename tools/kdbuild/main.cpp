// kdbuild SCENE.kdscene OUTPUT.kdtree: builds the SAH k-d tree of a scene and writes it.
#include <kdray/container_file.h>
#include <kdray/kdtree.h>
#include <kdray/scene_file.h>

#include "process_stats.h"
#include "progress.h"
#include "tool_main.h"
#include "tree_json.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
  using kdray::BuildSettings;
  CLI::App app{"kdbuild: build the SAH k-d tree of a .kdscene and write it as a .kdtree"};
  kdray::tool::OutputFlags output;
  kdray::tool::add_contract(app, "kdbuild", output, "Print the statistics as JSON on stdout");
  std::string scene_path, tree_path;
  BuildSettings settings;
  unsigned threads = 0;
  bool no_perfect_splits = false;
  app.add_option("SCENE", scene_path, "Input scene (.kdscene)")->required();
  app.add_option("OUTPUT", tree_path, "Output tree (.kdtree), written atomically")->required();
  app.add_option("--kt", settings.traversal_cost, "Cost of traversing an inner node (K_T)")
      ->capture_default_str()->check(CLI::NonNegativeNumber)->group("Cost model");
  app.add_option("--ki", settings.intersection_cost, "Cost of one ray/triangle test (K_I)")
      ->capture_default_str()->check(CLI::PositiveNumber)->group("Cost model");
  app.add_option("--empty-bonus", settings.empty_bonus, "Factor lambda on splits that cut off empty space, in (0, 1]")
      ->capture_default_str()->check(CLI::Range(1e-6, 1.0))->group("Cost model");
  app.add_option("--max-depth", settings.max_depth,
                 "Depth limit; 0: 8 + 1.3 log2 N, at most " + std::to_string(BuildSettings::kAutoMaxDepthCap) +
                     " (limit " + std::to_string(BuildSettings::kMaxDepthLimit) + ")")
      ->capture_default_str()->check(CLI::Range(0u, BuildSettings::kMaxDepthLimit))->group("Tree");
  app.add_flag("--no-perfect-splits", no_perfect_splits,
               "Take candidate planes from triangle bounding boxes instead of triangles clipped to the voxel")
      ->group("Tree");
  app.add_option("--threads", threads, "Build threads; 0: all cores (the tree is the same for any count)")
      ->capture_default_str()->group("Run");

  return kdray::tool::run(app, argc, argv, [&] {
    settings.perfect_splits = !no_perfect_splits;
    const auto start = std::chrono::steady_clock::now();
    const kdray::Scene scene = kdray::read_scene(scene_path);
    const double load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    kdray::tool::ProgressBar progress("kdbuild", !output.quiet);
    const auto build_start = std::chrono::steady_clock::now();
    const double cpu_start = kdray::tool::cpu_seconds();
    kdray::BuildTimings phases;
    const kdray::KdTree tree = kdray::build_kdtree(
        scene, settings, {threads, [&](double fraction) { progress.update(fraction); }, &phases});
    const double build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();
    const double build_cpu_seconds = kdray::tool::cpu_seconds() - cpu_start;
    progress.finish();
    const auto write_start = std::chrono::steady_clock::now();
    kdray::write_tree(tree_path, tree);
    const double write_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - write_start).count();
    const uint64_t tree_bytes = std::filesystem::file_size(tree_path);
    const uint64_t nodes = tree.nodes.size();

    const kdray::TreeStats& s = tree.stats;
    if (output.json) {
      nlohmann::json out = kdray::tool::tree_stats_json(tree);
      out.update({{"scene", scene_path}, {"tree", tree_path}, {"scene_hash", kdray::hash_hex(tree.scene_hash)},
                  {"build_seconds", build_seconds}, {"build_cpu_seconds", build_cpu_seconds},
                  {"load_seconds", load_seconds}, {"write_seconds", write_seconds},
                  {"phase_seconds", {{"load", load_seconds}, {"prepare", phases.prepare}, {"events", phases.events},
                                     {"subdivide", phases.subdivide}, {"assemble", phases.assemble},
                                     {"statistics", phases.statistics}, {"write", write_seconds}}},
                  {"peak_memory_mib", kdray::tool::peak_memory_mib()}, {"tree_bytes", tree_bytes}});
      kdray::tool::print_json(out);
      return kdray::tool::kExitOk;
    }
    if (output.quiet) return kdray::tool::kExitOk;
    const double empty_share = s.leaves ? 100.0 * static_cast<double>(s.empty_leaves) / s.leaves : 0.0;
    std::printf("%s -> %s\n", scene_path.c_str(), tree_path.c_str());
    std::printf("  triangles                %llu\n", static_cast<unsigned long long>(s.triangles));
    std::printf("  SAH cost                 %.3f\n", s.sah_cost);
    std::printf("  inner nodes              %llu\n", static_cast<unsigned long long>(s.inner_nodes));
    std::printf("  leaves                   %llu (%llu empty, %.1f%%)\n", static_cast<unsigned long long>(s.leaves),
                static_cast<unsigned long long>(s.empty_leaves), empty_share);
    std::printf("  leaf depth               max %u, mean %.2f (limit %u)\n", s.max_depth, s.mean_leaf_depth,
                tree.settings.resolved_max_depth(s.triangles));
    std::printf("  triangles per leaf       %.2f (non-empty leaves)\n", s.mean_triangles_per_leaf);
    std::printf("  references per triangle  %.3f\n", s.references_per_triangle);
    std::printf("  build                    %.3f s, %.3f s CPU (scene load %.3f s)\n", build_seconds,
                build_cpu_seconds, load_seconds);
    std::printf("  phases                   prepare %.3f, events %.3f, subdivide %.3f, assemble %.3f, statistics %.3f, "
                "write %.3f s\n",
                phases.prepare, phases.events, phases.subdivide, phases.assemble, phases.statistics, write_seconds);
    std::printf("  peak memory              %.1f MiB (scene, build and tree)\n", kdray::tool::peak_memory_mib());
    std::printf("  tree size                %.1f MiB (%llu nodes)\n", static_cast<double>(tree_bytes) / (1024.0 * 1024.0),
                static_cast<unsigned long long>(nodes));
    return kdray::tool::kExitOk;
  });
}
