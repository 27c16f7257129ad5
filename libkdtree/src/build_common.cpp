#include "build_common.h"

#include <kdray/error.h>

#include <tbb/parallel_for.h>

#include <string>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace kdray::detail {
namespace {

bool finite_triangle(const Scene& scene, size_t triangle) {
  for (int corner = 0; corner < 3; ++corner) {
    const Vec3& p = scene.positions[scene.indices[3 * triangle + corner]];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
  }
  return true;
}

}  // namespace

double surface_area(const Box3& box) {
  const double dx = static_cast<double>(box.max[0]) - box.min[0];
  const double dy = static_cast<double>(box.max[1]) - box.min[1];
  const double dz = static_cast<double>(box.max[2]) - box.min[2];
  return 2.0 * (dx * dy + dy * dz + dz * dx);
}

Box3 box_of(const Bounds& bounds) {
  return Box3{{bounds.min.x, bounds.min.y, bounds.min.z}, {bounds.max.x, bounds.max.y, bounds.max.z}};
}

Box3 below_plane(const Box3& voxel, int axis, float position) {
  Box3 below = voxel;
  below.max[axis] = position;
  return below;
}

Box3 above_plane(const Box3& voxel, int axis, float position) {
  Box3 above = voxel;
  above.min[axis] = position;
  return above;
}


double CostModel::split_cost(double p_left, double p_right, uint64_t n_left, uint64_t n_right) const {
  const double cost = split_cost_both_sides(p_left, p_right, n_left, n_right);
  // Only the first and last candidates of a sweep can have an empty side: the others skip
  // choosing lambda (1, whose product is exact).
  if (n_left != 0 && n_right != 0) return cost;
  const double lambda = p_left != 1.0 && p_right != 1.0 ? empty_bonus : 1.0;
  return lambda * cost;
}

CostModel cost_model_of(const BuildSettings& settings) {
  return CostModel{settings.traversal_cost, settings.intersection_cost, settings.empty_bonus};
}

CostModel cost_model_of(const BuildSettings& settings, const Box3& root_voxel, uint64_t triangles) {
  CostModel cost = cost_model_of(settings);
  if (triangles > 0) cost.reference_price = cost.intersection * surface_area(root_voxel) / static_cast<double>(triangles);
  return cost;
}

bool CostModel::split_pays(const SplitChoice& split, uint64_t n, const Box3& voxel) const {
  const double leaf = leaf_cost(n);
  if (!(split.cost < leaf)) return false;
  const uint64_t references = split.n_left + split.n_right;
  if (references <= n) return true;
  // Both sides in the node's cost units (one ray entering the node) times its area: the saving
  // and the price weighed per ray entering the root, up to the root's area.
  return (leaf - split.cost) * surface_area(voxel) > reference_price * static_cast<double>(references - n);
}

namespace {

// What an event adds to the running counts, by type: ends and planar ones leave the right side
// at their position (low half), starts and planar ones join the left side after it (high
// half). A node has fewer than 2^32 events (2 per triangle, fewer than 2^30 triangles), so the
// halves do not spill into each other.
constexpr uint64_t kRunCounts[4] = {1, 1 | uint64_t{1} << 32, uint64_t{1} << 32, 0};

// The two halves of the running counts (kRunCounts).
uint64_t ends_of(uint64_t counts) { return counts & 0xffffffffu; }
uint64_t starts_of(uint64_t counts) { return counts >> 32; }

// The first pass of a sweep over events [begin, end) of the `count` sorted events of an axis.
// Which event ends a run of equal positions is unpredictable, so the runs are found without a
// branch on it: each event writes the running counts and its index at the slot of the run in
// progress, and the slot moves on where the position changes. Events of one position come ends
// first, then planar, then starts (the event order), and the running counts are one sum without
// a branch on the type. Slot 0 holds the last run completed before `begin` (none before the
// first run: counts 0, ending before event 0). Returns the slots used, slot 0 included: the
// runs completed in the range, the axis's last among them when the range ends the axis. A run
// still in progress is left uncounted at the slot returned; the next range makes it again.
size_t find_runs(const Event* events, size_t begin, size_t end, size_t count, uint64_t& counts,
                 uint64_t* run_counts, uint32_t* run_last) {
  size_t runs = 1;
  auto add = [&](size_t i) {
    counts += kRunCounts[events[i].type()];
    run_counts[runs] = counts;
    run_last[runs] = static_cast<uint32_t>(i);
  };
  const size_t paired_end = std::min(end, count - 1);
  for (size_t i = begin; i < paired_end; ++i) {
    add(i);
    // Sorted, so a different position is a greater one; -0 and +0 are one run.
    runs += events[i + 1].position > events[i].position;
  }
  if (end == count) {
    add(count - 1);
    ++runs;
  }
  return runs;
}

// The second pass: costs runs [1, runs) of those find_runs left (slot 0 is never costed), the
// run in slot `last_run` the axis's last (0: none of them), `first_run` until the axis's first
// has been costed.
void cost_runs(const Event* events, const uint64_t* run_counts, const uint32_t* run_last, size_t runs,
               size_t last_run, bool& first_run, const SplitAreas& areas, int axis, uint64_t triangles,
               const CostModel& cost, SplitChoice& best_here) {
  constexpr size_t kRunGroup = 4;
  for (size_t group = 1; group < runs; group += kRunGroup) {
    const size_t group_end = std::min(runs, group + kRunGroup);
    // A group of runs between the first and the last cannot hold a cheaper split when a
    // floor of their costs is no lower than the best: the cost with the group's fewest
    // triangles below (its first run's) and above (its last run's), its first run's area
    // below and its last run's above. Every run's cost is computed by the same operations
    // from values at least as large, all of them non-negative, and rounding is monotone, so
    // the floor is at most each run's computed cost: skipping the group changes no choice.
    // Nor, so, does where the groups begin: sweep_axis's chunks and AxisRuns's whole axis
    // choose alike.
    const bool holds_end_run = (first_run && group == 1) || (last_run >= group && last_run < group_end);
    if (!holds_end_run) {
      const size_t last_in_group = group_end - 1;
      const float first_position = events[uint32_t{run_last[group - 1] + 1}].position;
      const float last_position = events[uint32_t{run_last[last_in_group - 1] + 1}].position;
      const uint64_t fewest_left = starts_of(run_counts[group - 1]);
      const uint64_t fewest_right = triangles - ends_of(run_counts[last_in_group]);
      const double floor = cost.split_cost_both_sides(areas.below_inside(first_position),
                                                      areas.above_inside(last_position), fewest_left, fewest_right);
      if (floor >= best_here.cost) continue;
    }
    for (size_t r = group; r < group_end; ++r) {
      const uint64_t through = run_counts[r], before = run_counts[r - 1];
      const size_t run_start = uint32_t{run_last[r - 1] + 1};  // slot 0 of the first chunk: 0
      const float position = events[run_start].position;  // the first event's: -0 or +0
      const uint64_t n_left = starts_of(before), n_right = triangles - ends_of(through);
      // Each event counts once in ends + starts, a planar one twice.
      const uint64_t planar = (ends_of(through) + starts_of(through) - (uint64_t{run_last[r]} + 1)) -
                              (ends_of(before) + starts_of(before) - run_start);
      if (first_run | (r == last_run) | (planar != 0)) {
        // The first and the last run, where a side may be empty and the plane may be the
        // voxel's face, and runs with planar triangles, tried on both sides.
        consider_split(cost, areas, axis, position, n_left, n_right, planar, best_here);
        first_run = false;
      } else {
        // A run between the first and the last lies strictly inside the voxel (positions are
        // sorted and within it), with a triangle on each side: the first run holds a start or
        // a planar event, the last an end or a planar one. So its costing needs neither the
        // voxel-face case of the areas nor the empty bonus: consider_split's arithmetic
        // without its branches.
        const double split_cost =
            cost.split_cost_both_sides(areas.below_inside(position), areas.above_inside(position), n_left, n_right);
        if (split_cost < best_here.cost) best_here = SplitChoice{split_cost, axis, position, true, n_left, n_right};
      }
    }
  }
}

}  // namespace

void sweep_axis(const Event* events, size_t count, int axis, const Box3& voxel, uint64_t triangles,
                const CostModel& cost, SplitChoice& best) {
  const SplitAreas areas(voxel, axis);
  if (!areas.has_area() || count == 0) return;
  // A local copy: `best` might alias the events, which would force reloads.
  SplitChoice best_here = best;
  // The events are swept a chunk at a time, so that the runs of a node of millions of events
  // take no more than a few KiB.
  constexpr size_t kChunk = 256;
  uint64_t run_counts[kChunk + 1];  // counts through the run's last event
  uint32_t run_last[kChunk + 1];    // the index of the run's last event (a node has < 2^31)
  run_counts[0] = 0;
  run_last[0] = UINT32_MAX;  // the first run starts at 0
  uint64_t counts = 0;
  bool first_run = true;
  for (size_t begin = 0; begin < count; begin += kChunk) {
    const size_t end = std::min(count, begin + kChunk);
    const size_t runs = find_runs(events, begin, end, count, counts, run_counts, run_last);
    cost_runs(events, run_counts, run_last, runs, end == count ? runs - 1 : 0, first_run, areas, axis, triangles,
              cost, best_here);
    run_counts[0] = run_counts[runs - 1];
    run_last[0] = run_last[runs - 1];
  }
  best = best_here;
}

void AxisRuns::find(const Event* events, size_t count) {
  events_ = events;
  count_ = count;
  runs_ = 0;
  if (count == 0) return;
  run_counts_[0] = 0;
  run_last_[0] = UINT32_MAX;
  uint64_t counts = 0;
  runs_ = find_runs(events, 0, count, count, counts, run_counts_, run_last_);
}

void AxisRuns::cost(int axis, const Box3& voxel, uint64_t triangles, const CostModel& cost, SplitChoice& best) const {
  const SplitAreas areas(voxel, axis);
  if (!areas.has_area() || count_ == 0) return;
  SplitChoice best_here = best;
  bool first_run = true;
  cost_runs(events_, run_counts_, run_last_, runs_, runs_ - 1, first_run, areas, axis, triangles, cost, best_here);
  best = best_here;
}

void classify(const Event* events, size_t count, const SplitChoice& split, uint8_t* sides) {
  // Without a branch on the type (it is unpredictable): each event's side bit comes from a
  // table by its type and how it lies to the plane. An end on or below the plane and a start on
  // or above it cannot both be a triangle's (its start lies below its end), so OR-ing in each
  // event's bit never marks both sides.
  const uint8_t planar_side = split.planar_left ? kLeftOnly : kRightOnly;
  // Index: type << 2 | (position < plane) << 1 | (position == plane).
  const uint8_t side_bits[12] = {
      0, kLeftOnly, kLeftOnly, kLeftOnly,                  // end: left when on or below the plane
      kRightOnly, planar_side, kLeftOnly, kLeftOnly,       // planar: above, in the plane, below
      kRightOnly, kRightOnly, 0, 0,                        // start: right when on or above it
  };
  const float plane = split.position;
  for (size_t i = 0; i < count; ++i) {
    const Event& event = events[i];
    const float p = event.position;
    const uint32_t index = event.type() << 2 | uint32_t{p < plane} << 1 | uint32_t{p == plane};
    sides[event.triangle()] |= side_bits[index];
  }
}

void Subtree::add_leaf(const uint32_t* triangles, size_t count) {
  if (count == 0) return;
  if (count > KD_MAX_LEAF_COUNT || leaf_triangles.size() + count > UINT32_MAX)
    throw Error("", "the tree is too large for 32-bit leaf indices");
  nodes.push_back(kd_leaf_node(static_cast<uint32_t>(leaf_triangles.size()), static_cast<uint32_t>(count), 0));
  leaf_triangles.insert(leaf_triangles.end(), triangles, triangles + count);
}

size_t Subtree::add_inner_node(int axis, float position) {
  uint32_t bits;
  std::memcpy(&bits, &position, sizeof bits);
  nodes.push_back(KdNode{bits, static_cast<uint32_t>(axis)});
  return nodes.size() - 1;
}

void Subtree::finish_inner_node(size_t inner, size_t far_child) {
  const bool below_empty = far_child == inner + 1, above_empty = far_child == nodes.size();
  if (below_empty && above_empty) {
    nodes.pop_back();
    return;
  }
  if (far_child > KD_MAX_CHILD_INDEX) throw Error("", "the tree is too large for 28-bit child indices");
  const uint32_t far_field = above_empty ? 0u : static_cast<uint32_t>(far_child) << KD_CHILD_SHIFT;
  nodes[inner].header = far_field | (above_empty ? KD_ABOVE_EMPTY : 0u) | (below_empty ? KD_BELOW_EMPTY : 0u) |
                        (nodes[inner].header & 3u);
}

void validate_settings(const BuildSettings& settings) {
  if (!(settings.traversal_cost >= 0.0f) || !std::isfinite(settings.traversal_cost))
    throw Error("", "traversal cost (K_T) must be a finite number >= 0");
  if (!(settings.intersection_cost > 0.0f) || !std::isfinite(settings.intersection_cost))
    throw Error("", "intersection cost (K_I) must be a finite number > 0");
  if (!(settings.empty_bonus > 0.0f && settings.empty_bonus <= 1.0f))
    throw Error("", "empty bonus must be in (0, 1]");
  if (settings.max_depth > BuildSettings::kMaxDepthLimit)
    throw Error("", "max depth must be at most " + std::to_string(BuildSettings::kMaxDepthLimit));
  if (settings.binned_above != 0 && (settings.bins < 2 || settings.bins > BuildSettings::kMaxBins))
    throw Error("", "bins must be from 2 to " + std::to_string(BuildSettings::kMaxBins));
}

// The root of both builders: the finite triangles, their bounds and the root voxel, in
// parallel over fixed blocks. The blocks' voxels are combined in block order, which keeps the
// first of equal minima and maxima (-0 and +0) as a sequential pass would.
RootWork prepare_root(const Scene& scene) {
  constexpr size_t kBlockTriangles = 16384;
  RootWork root;
  const size_t count = scene.triangle_count();
  if (count > kMaxLocalTriangles) throw Error("", "too many triangles for a k-d tree (at most 2^30 - 1)");
  const Box3 everything{{-INFINITY, -INFINITY, -INFINITY}, {INFINITY, INFINITY, INFINITY}};
  const size_t blocks = (count + kBlockTriangles - 1) / kBlockTriangles;
  root.triangles.resize(count);
  root.bounds.resize(count);
  std::vector<uint8_t> finite(count);
  std::vector<Box3> block_voxels(blocks);
  std::vector<size_t> block_finite(blocks);
  tbb::parallel_for(size_t{0}, blocks, [&](size_t block) {
    Box3 voxel{};
    size_t found = 0;
    for (size_t t = block * kBlockTriangles; t < std::min(count, (block + 1) * kBlockTriangles); ++t) {
      finite[t] = finite_triangle(scene, t);
      if (!finite[t]) continue;
      Box3& bounds = root.bounds[t];
      triangle_bounds_in_voxel(scene, static_cast<uint32_t>(t), everything, false, bounds);
      root.triangles[t] = static_cast<uint32_t>(t);
      for (int k = 0; k < 3; ++k) {
        voxel.min[k] = found == 0 ? bounds.min[k] : std::min(voxel.min[k], bounds.min[k]);
        voxel.max[k] = found == 0 ? bounds.max[k] : std::max(voxel.max[k], bounds.max[k]);
      }
      ++found;
    }
    block_voxels[block] = voxel;
    block_finite[block] = found;
  });
  bool first = true;
  for (size_t block = 0; block < blocks; ++block) {
    if (block_finite[block] == 0) continue;
    const Box3& voxel = block_voxels[block];
    for (int k = 0; k < 3; ++k) {
      root.voxel.min[k] = first ? voxel.min[k] : std::min(root.voxel.min[k], voxel.min[k]);
      root.voxel.max[k] = first ? voxel.max[k] : std::max(root.voxel.max[k], voxel.max[k]);
    }
    first = false;
  }
  if (first) root.voxel = Box3{{0, 0, 0}, {0, 0, 0}};
  // Triangles with a non-finite corner are left out, keeping the others in index order.
  size_t kept = 0;
  for (size_t found : block_finite) kept += found;
  if (kept == count) return root;
  kept = 0;
  for (size_t t = 0; t < count; ++t)
    if (finite[t]) {
      root.triangles[kept] = root.triangles[t];
      root.bounds[kept] = root.bounds[t];
      ++kept;
    }
  root.triangles.resize(kept);
  root.bounds.resize(kept);
  return root;
}

KdTree describe_tree(const Scene& scene, const BuildSettings& settings, const Box3& voxel,
                     TraversalArray<KdNode>&& nodes) {
  KdTree tree;
  if (nodes.empty()) nodes.push_back(kd_leaf_node(0, 0, 0));  // no triangles: the root is an empty leaf
  tree.nodes = std::move(nodes);
  tree.bounds = Bounds{{voxel.min[0], voxel.min[1], voxel.min[2]}, {voxel.max[0], voxel.max[1], voxel.max[2]}};
  tree.settings = settings;
  tree.geometry_hash = compute_geometry_hash(scene);
  tree.key = tree_key(tree.geometry_hash, settings);
  tree.stats = compute_tree_stats(tree, scene.triangle_count());
  return tree;
}

KdTree finish_tree(const Scene& scene, const BuildSettings& settings, const Box3& voxel, Subtree&& built) {
  TraversalArray<uint32_t> blocks =
      leaf_blocks_of(scene, built.nodes, built.leaf_triangles.data(), settings.leaf_layout);
  KdTree tree = describe_tree(scene, settings, voxel, std::move(built.nodes));
  tree.leaf_blocks = std::move(blocks);
  return tree;
}

}  // namespace kdray::detail
