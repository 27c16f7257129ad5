#include <kdray/kdtree.h>

#include "build_common.h"

#include <algorithm>
#include <vector>

namespace kdray {

TreeStats compute_tree_stats(const KdTree& tree, uint64_t scene_triangles) {
  TreeStats stats;
  stats.triangles = scene_triangles;
  stats.leaf_references = tree.leaf_triangles.size();
  if (tree.nodes.empty()) return stats;
  const detail::Box3 root = detail::box_of(tree.bounds);
  const double root_area = detail::surface_area(root);
  // Without area (an empty or degenerate scene) every node counts as the root's size.
  auto relative_area = [&](const detail::Box3& box) {
    return root_area > 0.0 ? detail::surface_area(box) / root_area : 1.0;
  };
  // The cost the builder minimises, C = lambda * (K_T + P_L C_L + P_R C_R) for an inner node
  // (lambda: the empty bonus when a child is an empty leaf and neither child is the whole
  // voxel, else 1) and C = K_I N for a leaf, summed node by node: each node's term is weighted
  // by its relative area and by the lambdas of the inner nodes above it (`weight`).
  const detail::CostModel cost = detail::cost_model_of(tree.settings);
  auto is_empty_leaf = [&](uint32_t index) {
    return kd_node_is_leaf(tree.nodes[index]) && kd_leaf_count(tree.nodes[index]) == 0;
  };
  struct Pending {
    uint32_t node;
    uint32_t depth;
    double weight;
    detail::Box3 voxel;
  };
  std::vector<Pending> stack{{0, 0, 1.0, root}};
  uint64_t depth_sum = 0, non_empty_leaves = 0;
  while (!stack.empty()) {
    const Pending item = stack.back();
    stack.pop_back();
    const KdNode node = tree.nodes[item.node];
    if (kd_node_is_leaf(node)) {
      ++stats.leaves;
      const uint32_t count = kd_leaf_count(node);
      if (count == 0) ++stats.empty_leaves; else ++non_empty_leaves;
      depth_sum += item.depth;
      stats.max_depth = std::max(stats.max_depth, item.depth);
      stats.sah_cost += item.weight * cost.leaf_cost(count) * relative_area(item.voxel);
      continue;
    }
    ++stats.inner_nodes;
    const int axis = static_cast<int>(kd_node_axis(node));
    const float split = kd_node_split(node);
    const detail::SplitAreas areas(item.voxel, axis);
    const bool whole_voxel_child = areas.below(split) == 1.0 || areas.above(split) == 1.0;
    const bool empty_child = is_empty_leaf(item.node + 1) || is_empty_leaf(kd_node_far_child(node));
    const double weight = item.weight * (empty_child && !whole_voxel_child ? cost.empty_bonus : 1.0);
    stats.sah_cost += weight * cost.traversal * relative_area(item.voxel);
    stack.push_back({kd_node_far_child(node), item.depth + 1, weight, detail::above_plane(item.voxel, axis, split)});
    stack.push_back({item.node + 1, item.depth + 1, weight, detail::below_plane(item.voxel, axis, split)});
  }
  stats.mean_leaf_depth = static_cast<double>(depth_sum) / static_cast<double>(stats.leaves);
  stats.mean_triangles_per_leaf =
      non_empty_leaves ? static_cast<double>(stats.leaf_references) / static_cast<double>(non_empty_leaves) : 0.0;
  stats.references_per_triangle =
      scene_triangles ? static_cast<double>(stats.leaf_references) / static_cast<double>(scene_triangles) : 0.0;
  return stats;
}

}  // namespace kdray
