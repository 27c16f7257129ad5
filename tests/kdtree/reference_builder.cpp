#include "reference_builder.h"

#include "build_common.h"

#include <algorithm>
#include <vector>

namespace kdray::test {
namespace {

using namespace kdray::detail;

class ResortingBuilder {
 public:
  ResortingBuilder(const Scene& scene, const BuildSettings& settings, const CostModel& cost, uint32_t max_depth)
      : scene_(scene), settings_(settings), cost_(cost), max_depth_(max_depth) {}

  void build(const Box3& voxel, uint32_t depth, const std::vector<uint32_t>& triangles,
             const std::vector<Box3>& bounds, Subtree& out) const {
    const size_t n = triangles.size();
    std::vector<Event> events[3];
    SplitChoice split;
    if (n > 0 && depth < max_depth_) {
      for (int axis = 0; axis < 3; ++axis) {
        for (size_t i = 0; i < n; ++i) append_events(events[axis], bounds[i], axis, static_cast<uint32_t>(i));
        std::sort(events[axis].begin(), events[axis].end());
        sweep_axis(events[axis].data(), events[axis].size(), axis, voxel, n, cost_, split);
      }
    }
    if (split.axis < 0 || !cost_.split_pays(split, n, voxel)) {
      out.add_leaf(triangles.data(), n);
      return;
    }
    std::vector<uint8_t> sides(n, kBothSides);
    classify(events[split.axis].data(), events[split.axis].size(), split, sides.data());
    const Box3 child_voxels[2] = {below_plane(voxel, split.axis, split.position),
                                  above_plane(voxel, split.axis, split.position)};
    std::vector<uint32_t> left, right;
    std::vector<Box3> left_bounds, right_bounds;
    for (size_t i = 0; i < n; ++i) {
      if (sides[i] == kLeftOnly) {
        left.push_back(triangles[i]);
        left_bounds.push_back(bounds[i]);
      } else if (sides[i] == kRightOnly) {
        right.push_back(triangles[i]);
        right_bounds.push_back(bounds[i]);
      } else {
        const StraddlerBounds straddler =
            straddler_bounds(scene_, triangles[i], bounds[i], child_voxels, split.axis, settings_.perfect_splits);
        if (straddler.reaches[0]) {
          left.push_back(triangles[i]);
          left_bounds.push_back(straddler.bounds[0]);
        }
        if (straddler.reaches[1]) {
          right.push_back(triangles[i]);
          right_bounds.push_back(straddler.bounds[1]);
        }
      }
    }
    out.add_inner(split.axis, split.position, [&] { build(child_voxels[0], depth + 1, left, left_bounds, out); },
                  [&] { build(child_voxels[1], depth + 1, right, right_bounds, out); });
  }

 private:
  const Scene& scene_;
  const BuildSettings& settings_;
  const CostModel cost_;
  const uint32_t max_depth_;
};

}  // namespace

KdTree build_kdtree_by_resorting(const Scene& scene, const BuildSettings& given) {
  validate_settings(given);
  const BuildSettings settings = given.resolved(scene.triangle_count());
  const RootWork root = prepare_root(scene);
  Subtree built;
  const CostModel cost = cost_model_of(settings, root.voxel, root.triangles.size());
  ResortingBuilder(scene, settings, cost, settings.max_depth)
      .build(root.voxel, 0, root.triangles, root.bounds, built);
  return finish_tree(scene, settings, root.voxel, std::move(built));
}

}  // namespace kdray::test
