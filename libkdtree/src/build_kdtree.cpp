// build_kdtree: the root's triangles and bounds, then the binned top (build_binned.h) down to
// nodes of settings.binned_above triangles and the exact event sweep (build_events.h) below,
// or the exact sweep from the root when binned_above is 0; then the pieces built in parallel
// are joined and the statistics computed, and the leaf blocks made in memory (build_kdtree)
// or as the file is written (build_tree_file).
#include <kdray/kdtree.h>
#include <kdray/threads.h>

#include "build_binned.h"
#include "build_events.h"
#include "tree_writing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

namespace kdray {

BuildSettings BuildSettings::resolved(uint64_t triangles) const {
  BuildSettings explicit_settings = *this;
  if (max_depth == 0) {
    const double automatic = 8.0 + std::log2(static_cast<double>(std::max<uint64_t>(triangles, 1)));
    explicit_settings.max_depth = std::min(kAutoMaxDepthCap, static_cast<uint32_t>(automatic));
  }
  if (leaf_layout == LeafLayout::automatic)
    explicit_settings.leaf_layout = triangles <= kGroupedLeavesUpTo ? LeafLayout::grouped : LeafLayout::paged;
  return explicit_settings;
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point start, Clock::time_point end) {
  return std::chrono::duration<double>(end - start).count();
}

// The subtree of the whole scene as the builder leaves it, with the root voxel and the
// resolved settings; the phases up to `assemble` timed.
struct Built {
  detail::Subtree subtree;
  detail::Box3 voxel;
  BuildSettings settings;
};

Built build(const Scene& scene, const BuildSettings& given, const BuildControl& control, BuildTimings& timings) {
  detail::validate_settings(given);
  Built result{{}, {}, given.resolved(scene.triangle_count())};
  const BuildSettings& settings = result.settings;
  auto lap = [last = Clock::now()](double& phase) mutable {
    const auto now = Clock::now();
    phase = seconds_between(last, now);
    last = now;
  };
  run_with_threads(control.threads, [&] {
    detail::RootWork root = detail::prepare_root(scene);
    lap(timings.prepare);
    result.voxel = root.voxel;
    detail::BuildContext context(scene, settings, control, result.voxel, root.triangles.size());
    detail::Piece root_piece;
    if (detail::binned(settings, root.triangles.size())) {
      detail::BinnedNode node{result.voxel, 0, std::move(root.triangles), std::move(root.bounds)};
      lap(timings.events);
      detail::build_binned_subtree(context, node, root_piece);
    } else {
      detail::NodeWork work = detail::node_with_events(result.voxel, 0, std::move(root.triangles),
                                                       std::move(root.bounds), settings.perfect_splits);
      lap(timings.events);
      detail::build_exact_subtree(context, work, root_piece);
    }
    lap(timings.subdivide);
    result.subtree = detail::flatten(std::move(root_piece));
    lap(timings.assemble);
  });
  if (control.progress) control.progress(1.0);
  return result;
}

}  // namespace

KdTree build_kdtree(const Scene& scene, const BuildSettings& settings, const BuildControl& control) {
  BuildTimings timings;
  Built built = build(scene, settings, control, timings);
  const auto start = Clock::now();
  KdTree tree;
  run_with_threads(control.threads, [&] {
    tree = detail::finish_tree(scene, built.settings, built.voxel, std::move(built.subtree));
  });
  timings.statistics = seconds_between(start, Clock::now());
  if (control.timings) *control.timings = timings;
  return tree;
}

TreeSummary build_tree_file(const Scene& scene, const std::string& path, const BuildSettings& settings,
                            const BuildControl& control) {
  BuildTimings timings;
  Built built = build(scene, settings, control, timings);
  const auto start = Clock::now();
  TreeSummary summary;
  run_with_threads(control.threads, [&] {
    const uint32_t* triangles = built.subtree.leaf_triangles.data();
    const detail::LeafBlockPlan plan =
        detail::plan_leaf_blocks(scene, built.subtree.nodes, triangles, built.settings.leaf_layout);
    const KdTree described =
        detail::describe_tree(scene, built.settings, built.voxel, std::move(built.subtree.nodes));
    const auto described_at = Clock::now();
    timings.statistics = seconds_between(start, described_at);
    detail::write_tree_with_planned_blocks(path, described, scene, triangles, plan);
    timings.write = seconds_between(described_at, Clock::now());
    summary = described;
  });
  if (control.timings) *control.timings = timings;
  return summary;
}

}  // namespace kdray
