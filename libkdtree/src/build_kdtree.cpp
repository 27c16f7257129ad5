// build_kdtree: the root's triangles and bounds, then the binned top (build_binned.h) down to
// nodes of settings.binned_above triangles and the exact event sweep (build_events.h) below,
// or the exact sweep from the root when binned_above is 0; then the pieces built in parallel
// are joined and the statistics computed.
#include <kdray/kdtree.h>
#include <kdray/threads.h>

#include "build_binned.h"
#include "build_events.h"

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
  return explicit_settings;
}

KdTree build_kdtree(const Scene& scene, const BuildSettings& given, const BuildControl& control) {
  detail::validate_settings(given);
  const BuildSettings settings = given.resolved(scene.triangle_count());
  BuildTimings timings;
  auto lap = [last = std::chrono::steady_clock::now()](double& phase) mutable {
    const auto now = std::chrono::steady_clock::now();
    phase = std::chrono::duration<double>(now - last).count();
    last = now;
  };
  KdTree tree;
  run_with_threads(control.threads, [&] {
    detail::RootWork root = detail::prepare_root(scene);
    lap(timings.prepare);
    const detail::Box3 voxel = root.voxel;
    detail::BuildContext context(scene, settings, control, voxel, root.triangles.size());
    detail::Piece root_piece;
    if (detail::binned(settings, root.triangles.size())) {
      detail::BinnedNode node{voxel, 0, std::move(root.triangles), std::move(root.bounds)};
      lap(timings.events);
      detail::build_binned_subtree(context, node, root_piece);
    } else {
      detail::NodeWork work = detail::node_with_events(voxel, 0, std::move(root.triangles), std::move(root.bounds),
                                                       settings.perfect_splits);
      lap(timings.events);
      detail::build_exact_subtree(context, work, root_piece);
    }
    lap(timings.subdivide);
    detail::Subtree built = detail::flatten(std::move(root_piece));
    lap(timings.assemble);
    if (control.progress) control.progress(1.0);
    tree = detail::finish_tree(scene, settings, voxel, std::move(built));
    lap(timings.statistics);
  });
  if (control.timings) *control.timings = timings;
  return tree;
}

}  // namespace kdray
