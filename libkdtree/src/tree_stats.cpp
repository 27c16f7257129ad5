// compute_tree_stats: the tree's structure and its SAH cost, walked in parallel over the
// subtrees below its top levels; the subtrees' sums are combined in a fixed order, so the
// figures do not depend on the thread count.
#include <kdray/kdtree.h>

#include "build_common.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

namespace kdray {
namespace {

// Levels walked before the subtrees below them are walked in parallel (up to 2^levels).
constexpr int kSerialLevels = 8;

struct Pending {
  uint32_t node;
  uint32_t depth;
  double weight;  // the product of the lambdas of the inner nodes above (see Walk)
  detail::Box3 voxel;
};

struct Totals {
  uint64_t inner_nodes = 0, leaves = 0, empty_leaves = 0, references = 0, depth_sum = 0;
  uint32_t max_depth = 0;
  double sah_cost = 0;

  void add(const Totals& other) {
    inner_nodes += other.inner_nodes;
    leaves += other.leaves;
    empty_leaves += other.empty_leaves;
    references += other.references;
    depth_sum += other.depth_sum;
    max_depth = std::max(max_depth, other.max_depth);
    sah_cost += other.sah_cost;
  }
};

// The SAH cost is the cost the builder minimises, C = lambda * (K_T + P_L C_L + P_R C_R) for an
// inner node (lambda: the empty bonus when a child is an empty leaf and neither child is the
// whole voxel, else 1) and C = K_I N for a leaf, summed node by node: each node's term is
// weighted by its relative area and by the lambdas of the inner nodes above it.
class Walk {
 public:
  explicit Walk(const KdTree& tree)
      : tree_(tree), cost_(detail::cost_model_of(tree.settings)), root_area_(detail::surface_area(root())) {}

  detail::Box3 root() const { return detail::box_of(tree_.bounds); }

  // Adds the node's terms to `totals`; returns how many of its children are nodes (an inner
  // node's empty children are counted here, as the empty leaves they stand for) and puts them
  // in `children`, below first.
  int visit(const Pending& item, Totals& totals, Pending children[2]) const {
    const KdNode node = tree_.nodes[item.node];
    if (kd_node_is_leaf(node)) {
      add_leaf(item.depth, kd_leaf_count(node), item.weight, relative_area(item.voxel), totals);
      return 0;
    }
    ++totals.inner_nodes;
    const int axis = static_cast<int>(kd_node_axis(node));
    const float split = kd_node_split(node);
    const detail::SplitAreas areas(item.voxel, axis);
    const bool whole_voxel_child = areas.below(split) == 1.0 || areas.above(split) == 1.0;
    const bool below_empty = kd_node_below_empty(node), above_empty = kd_node_above_empty(node);
    const double weight =
        item.weight * ((below_empty || above_empty) && !whole_voxel_child ? cost_.empty_bonus : 1.0);
    totals.sah_cost += weight * cost_.traversal * relative_area(item.voxel);
    int count = 0;
    if (below_empty)
      add_leaf(item.depth + 1, 0, 0.0, 0.0, totals);
    else
      children[count++] = {item.node + 1, item.depth + 1, weight, detail::below_plane(item.voxel, axis, split)};
    if (above_empty)
      add_leaf(item.depth + 1, 0, 0.0, 0.0, totals);
    else
      children[count++] = {kd_node_far_child(node), item.depth + 1, weight,
                           detail::above_plane(item.voxel, axis, split)};
    return count;
  }

  // The totals of the subtree of `top`, depth first.
  Totals subtree(const Pending& top) const {
    Totals totals;
    std::vector<Pending> stack{top};
    Pending children[2];
    while (!stack.empty()) {
      const Pending item = stack.back();
      stack.pop_back();
      const int count = visit(item, totals, children);
      for (int c = count - 1; c >= 0; --c) stack.push_back(children[c]);
    }
    return totals;
  }

 private:
  // Without area (an empty or degenerate scene) every node counts as the root's size.
  double relative_area(const detail::Box3& box) const {
    return root_area_ > 0.0 ? detail::surface_area(box) / root_area_ : 1.0;
  }
  // A leaf's terms (an empty leaf's SAH term is 0).
  void add_leaf(uint32_t depth, uint32_t count, double weight, double area, Totals& totals) const {
    ++totals.leaves;
    totals.empty_leaves += count == 0;
    totals.references += count;
    totals.depth_sum += depth;
    totals.max_depth = std::max(totals.max_depth, depth);
    totals.sah_cost += weight * cost_.leaf_cost(count) * area;
  }

  const KdTree& tree_;
  const detail::CostModel cost_;
  const double root_area_;
};

}  // namespace

TreeStats compute_tree_stats(const KdTree& tree, uint64_t scene_triangles) {
  TreeStats stats;
  stats.triangles = scene_triangles;
  if (tree.nodes.empty()) return stats;
  const Walk walk(tree);
  // The top levels, level by level, leave the subtrees below them in depth-first order.
  Totals totals;
  std::vector<Pending> subtrees{{0, 0, 1.0, walk.root()}};
  for (int level = 0; level < kSerialLevels; ++level) {
    std::vector<Pending> next;
    for (const Pending& item : subtrees) {
      Pending children[2];
      const int count = walk.visit(item, totals, children);
      next.insert(next.end(), children, children + count);
    }
    subtrees.swap(next);
  }
  std::vector<Totals> below(subtrees.size());
  tbb::parallel_for(size_t{0}, subtrees.size(), [&](size_t i) { below[i] = walk.subtree(subtrees[i]); });
  for (const Totals& subtree : below) totals.add(subtree);

  stats.inner_nodes = totals.inner_nodes;
  stats.leaves = totals.leaves;
  stats.empty_leaves = totals.empty_leaves;
  stats.leaf_references = totals.references;  // each leaf's triangles, counted in every leaf
  stats.max_depth = totals.max_depth;
  stats.sah_cost = totals.sah_cost;
  const uint64_t non_empty_leaves = stats.leaves - stats.empty_leaves;
  stats.mean_leaf_depth = static_cast<double>(totals.depth_sum) / static_cast<double>(stats.leaves);
  stats.mean_triangles_per_leaf =
      non_empty_leaves ? static_cast<double>(stats.leaf_references) / static_cast<double>(non_empty_leaves) : 0.0;
  stats.references_per_triangle =
      scene_triangles ? static_cast<double>(stats.leaf_references) / static_cast<double>(scene_triangles) : 0.0;
  return stats;
}

}  // namespace kdray
