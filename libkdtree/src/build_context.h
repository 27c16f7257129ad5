// What the parts of one build share: the scene, the settings, the cost model (with the price of
// a reference for this root), the depth limit resolved for the scene, and the progress report.
#pragma once

#include "build_common.h"

#include <atomic>
#include <cstdint>
#include <mutex>

namespace kdray::detail {

// Progress is the share of the tree's "mass" in finished subtrees, a subtree at depth d
// weighing 2^-d: for a binary tree these weights sum to exactly 1 (Kraft), so it ends at 100%.
// Only subtrees of the parallel levels report, which keeps the shared counter cold.
class FinishedSubtrees {
 public:
  explicit FinishedSubtrees(const BuildProgress& progress) : progress_(progress) {}
  // Counts the subtree at `depth` as finished.
  void report(uint32_t depth);

 private:
  const BuildProgress& progress_;
  std::atomic<uint64_t> finished_mass_{0};
  std::mutex mutex_;
};

struct BuildContext {
  // `settings` resolved (BuildSettings::resolved): max_depth is the limit applied. The root
  // voxel holds `triangles` triangles.
  BuildContext(const Scene& scene, const BuildSettings& settings, const BuildControl& control, const Box3& root_voxel,
               uint64_t triangles)
      : scene(scene),
        settings(settings),
        cost(cost_model_of(settings, root_voxel, triangles)),
        max_depth(settings.max_depth),
        small_parameters{cost, max_depth, settings.perfect_splits},
        finished(control.progress) {}

  const Scene& scene;
  const BuildSettings& settings;
  const CostModel cost;
  const uint32_t max_depth;
  const SmallBuildParameters small_parameters;
  FinishedSubtrees finished;
};

}  // namespace kdray::detail
