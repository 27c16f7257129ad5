// The binned top of the tree (build_binned.h). Bin counts are integers, so their sums do not
// depend on how the counting pass was divided among threads; candidate costs are then computed
// in a fixed order, and nodes are divided in fixed-size blocks written at offsets known before
// any is written. The tree is therefore the same for any thread count.
#include "build_binned.h"

#include "build_bins.h"
#include "build_events.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace kdray::detail {
namespace {

// Triangles per block of a node's division: a fixed size, so that what each block counts and
// where it writes its triangles do not depend on the thread count.
constexpr size_t kBlockTriangles = 8192;

// Per axis: triangles starting in each bin, ending in each bin, and lying in each boundary.
class BinCounts {
 public:
  enum Kind { kStarts = 0, kEnds = 1, kPlanar = 2 };
  explicit BinCounts(uint32_t bins) : stride_(bins + 1), counts_(9 * stride_, 0) {}
  uint32_t* of(int axis, Kind kind) { return &counts_[(3 * axis + kind) * stride_]; }
  void add(const BinCounts& other) {
    for (size_t i = 0; i < counts_.size(); ++i) counts_[i] += other.counts_[i];
  }

 private:
  size_t stride_;
  std::vector<uint32_t> counts_;
};

// The side of the split a triangle with `bounds` goes to before clipping: the rule of
// classify() (build_common.h), from the bounds instead of the events.
Side side_of(const Box3& bounds, const SplitChoice& split) {
  const float lo = bounds.min[split.axis], hi = bounds.max[split.axis], p = split.position;
  if (lo == hi) return lo < p || (lo == p && split.planar_left) ? kLeftOnly : kRightOnly;
  if (hi <= p) return kLeftOnly;
  if (lo >= p) return kRightOnly;
  return kBothSides;
}

class BinnedBuilder {
 public:
  explicit BinnedBuilder(BuildContext& context) : context_(context), bins_(context.settings.bins) {}

  void build(BinnedNode& node, Piece& out) {
    if (!binned(context_.settings, node.triangles.size())) {
      NodeWork work = node_with_events(node.voxel, node.depth, std::move(node.triangles), std::move(node.bounds),
                                       context_.settings.perfect_splits);
      build_exact_subtree(context_, work, out);
      return;
    }
    const SplitChoice split = choose_split(node);
    if (split.axis < 0) {
      out.serial.add_leaf(node.triangles.data(), node.triangles.size());
      context_.finished.report(node.depth);
      return;
    }
    out.axis = split.axis;
    out.position = split.position;
    out.below = std::make_unique<Piece>();
    out.above = std::make_unique<Piece>();
    const int whole_side = side_taking_all(split, node.triangles.size());
    if (whole_side >= 0) {
      context_.finished.report(node.depth + 1);  // the empty child
      become_child(node, split, whole_side);
      build(node, whole_side == 0 ? *out.below : *out.above);
      return;
    }
    BinnedNode left, right;
    divide(node, split, left, right);
    node = BinnedNode{};  // the parent's arrays are not needed while the children build
    tbb::parallel_invoke([&] { build(left, *out.below); }, [&] { build(right, *out.above); });
  }

 private:
  // The cheapest boundary plane, or axis -1 when a leaf is cheaper or the depth limit is reached.
  SplitChoice choose_split(const BinnedNode& node) const {
    const size_t n = node.triangles.size();
    SplitChoice split;
    if (n == 0 || node.depth >= context_.max_depth) return split;
    const AxisBins axes[3] = {{node.voxel, 0, bins_}, {node.voxel, 1, bins_}, {node.voxel, 2, bins_}};
    tbb::enumerable_thread_specific<BinCounts> per_thread(bins_);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kBlockTriangles), [&](const tbb::blocked_range<size_t>& range) {
      BinCounts& counts = per_thread.local();
      for (size_t i = range.begin(); i != range.end(); ++i)
        for (int axis = 0; axis < 3; ++axis) count(axes[axis], node.bounds[i], axis, counts);
    });
    BinCounts total(bins_);
    for (const BinCounts& counts : per_thread) total.add(counts);

    // One best over x, y, z in turn, as the exact sweep takes it.
    for (int axis = 0; axis < 3; ++axis) {
      const SplitAreas areas(node.voxel, axis);
      if (!areas.has_area()) continue;
      const uint32_t* starts = total.of(axis, BinCounts::kStarts);
      const uint32_t* ends = total.of(axis, BinCounts::kEnds);
      const uint32_t* planar = total.of(axis, BinCounts::kPlanar);
      const float lo = node.voxel.min[axis], hi = node.voxel.max[axis];
      uint64_t n_left = 0, n_right = n;
      for (uint32_t k = 1; k < bins_; ++k) {
        n_left += starts[k - 1];
        n_right -= ends[k - 1];
        const float position = axes[axis].boundary(k);
        // Boundaries that coincide (a voxel thin in float) are one candidate, the last.
        if (!(position > lo && position < hi) || position == axes[axis].boundary(k + 1)) continue;
        consider_split(context_.cost, areas, axis, position, n_left, n_right, planar[k], split);
      }
    }
    if (split.axis >= 0 && !context_.cost.split_pays(split, n, node.voxel)) split.axis = -1;
    return split;
  }

  // Counts a triangle: the bin it starts in and the bin it ends in; one lying exactly in a
  // boundary is also counted there, where it is neither below nor above the plane.
  static void count(const AxisBins& bins, const Box3& bounds, int axis, BinCounts& counts) {
    const float lo = bounds.min[axis], hi = bounds.max[axis];
    const uint32_t start = bins.bin_of_start(lo);
    ++counts.of(axis, BinCounts::kStarts)[start];
    ++counts.of(axis, BinCounts::kEnds)[bins.bin_of_end(hi)];
    if (lo == hi && bins.boundary(start) == lo) ++counts.of(axis, BinCounts::kPlanar)[start];
  }

  // Divides the triangles of `node` between its children, keeping their order: a first pass
  // counts each block's triangles per side (clipping straddlers to see which sides they
  // reach, and keeping what the clipping gave), a second writes them at the offsets those
  // counts give.
  void divide(const BinnedNode& node, const SplitChoice& split, BinnedNode& left, BinnedNode& right) const {
    const size_t n = node.triangles.size();
    const size_t blocks = (n + kBlockTriangles - 1) / kBlockTriangles;
    const Box3 child_voxels[2] = {below_plane(node.voxel, split.axis, split.position),
                                  above_plane(node.voxel, split.axis, split.position)};
    left.voxel = child_voxels[0];
    right.voxel = child_voxels[1];
    left.depth = right.depth = node.depth + 1;
    const bool perfect_splits = context_.settings.perfect_splits;
    const Scene& scene = context_.scene;
    std::vector<uint8_t> sides(n);
    std::vector<std::vector<StraddlerBounds>> straddlers(blocks);  // per block, in order
    std::vector<size_t> left_offset(blocks + 1, 0), right_offset(blocks + 1, 0);
    tbb::parallel_for(size_t{0}, blocks, [&](size_t block) {
      size_t to_left = 0, to_right = 0;
      for (size_t i = block * kBlockTriangles; i < std::min(n, (block + 1) * kBlockTriangles); ++i) {
        const Side side = side_of(node.bounds[i], split);
        sides[i] = side;
        if (side == kBothSides) {
          const StraddlerBounds& straddler = straddlers[block].emplace_back(
              straddler_bounds(scene, node.triangles[i], node.bounds[i], child_voxels, split.axis, perfect_splits));
          to_left += straddler.reaches[0];
          to_right += straddler.reaches[1];
        } else {
          to_left += side == kLeftOnly;
          to_right += side == kRightOnly;
        }
      }
      left_offset[block + 1] = to_left;
      right_offset[block + 1] = to_right;
    });
    for (size_t block = 0; block < blocks; ++block) {
      left_offset[block + 1] += left_offset[block];
      right_offset[block + 1] += right_offset[block];
    }
    for (BinnedNode* child : {&left, &right}) {
      const size_t count = (child == &left ? left_offset : right_offset)[blocks];
      child->triangles.resize(count);
      child->bounds.resize(count);
    }
    tbb::parallel_for(size_t{0}, blocks, [&](size_t block) {
      size_t l = left_offset[block], r = right_offset[block];
      const StraddlerBounds* straddler = straddlers[block].data();
      for (size_t i = block * kBlockTriangles; i < std::min(n, (block + 1) * kBlockTriangles); ++i) {
        const uint32_t triangle = node.triangles[i];
        auto place = [&](BinnedNode& child, size_t& at, const Box3& bounds) {
          child.triangles[at] = triangle;
          child.bounds[at] = bounds;
          ++at;
        };
        if (sides[i] == kLeftOnly) {
          place(left, l, node.bounds[i]);
        } else if (sides[i] == kRightOnly) {
          place(right, r, node.bounds[i]);
        } else {
          if (straddler->reaches[0]) place(left, l, straddler->bounds[0]);
          if (straddler->reaches[1]) place(right, r, straddler->bounds[1]);
          ++straddler;
        }
      }
    });
  }

  BuildContext& context_;
  const uint32_t bins_;
};

}  // namespace

void build_binned_subtree(BuildContext& context, BinnedNode& node, Piece& out) {
  BinnedBuilder(context).build(node, out);
}

}  // namespace kdray::detail
