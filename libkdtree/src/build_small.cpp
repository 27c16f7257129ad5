// The small-node path of the event builder: nodes of at most kSmallNodeTriangles triangles,
// which are most of a tree's nodes and most of its build time, are built from fixed-size
// arrays reused per depth, with the same split-and-merge of sorted events as the large nodes
// (insertion sort for the few re-clipped events). It takes the same candidates, costs and
// decisions in the same order, so it builds the same tree bytes as the general path.
#include "build_common.h"

#include <algorithm>
#include <array>
#include <vector>

namespace kdray::detail {
namespace {

constexpr size_t kMaxEvents = AxisRuns::kMaxEvents;  // two per triangle

struct SmallNode {
  Box3 voxel;
  uint32_t depth = 0;
  uint32_t count = 0;
  uint32_t triangles[kSmallNodeTriangles];
  Box3 bounds[kSmallNodeTriangles];  // each triangle's bounds in the voxel
  uint32_t event_count[3];
  Event events[3][kMaxEvents];  // sorted
};

// Sorts a handful of events in place.
void insertion_sort(Event* events, size_t count) {
  for (size_t i = 1; i < count; ++i) {
    const Event event = events[i];
    size_t j = i;
    for (; j > 0 && event < events[j - 1]; --j) events[j] = events[j - 1];
    events[j] = event;
  }
}

// classify() from each triangle's bounds instead of its events (the node's events are made
// from these bounds, so the sides are the same): one pass over the triangles, without a branch
// on the event type or a store through the triangle index.
void classify_by_bounds(const Box3* bounds, size_t count, const SplitChoice& split, uint8_t* sides) {
  const int axis = split.axis;
  const float plane = split.position;
  for (size_t i = 0; i < count; ++i) {
    const float lo = bounds[i].min[axis];
    const float hi = bounds[i].max[axis];
    // Equal bounds make one planar event, at `lo`.
    const bool planar = lo == hi;
    const bool planar_left = (lo < plane) | ((lo == plane) & split.planar_left);
    const bool left = planar ? planar_left : hi <= plane;
    const bool right = planar ? !planar_left : lo >= plane;
    sides[i] = static_cast<uint8_t>(left * kLeftOnly | right * kRightOnly);
  }
}

class SmallBuilder {
 public:
  SmallBuilder(const Scene& scene, const SmallBuildParameters& parameters)
      : scene_(scene), parameters_(parameters) {}

  // `node` is the parent's room for it, and is changed into its own child where a split sends
  // it whole to one side.
  void build(SmallNode& node, Subtree& out) const {
    OneSidedNodes one_sided;
    const SplitChoice split = choose_split(node, out, one_sided);
    if (split.axis < 0) {
      out.add_leaf(node.triangles, node.count);
    } else {
      std::array<SmallNode, 2>& children = children_at_depth<SmallNode>(node.depth + 1);
      divide(node, split, children[0], children[1]);
      out.add_inner(split.axis, split.position, [&] { build(children[0], out); }, [&] { build(children[1], out); });
    }
    for (size_t i = one_sided.count; i-- > 0;) out.finish_one_sided(one_sided.inner[i], one_sided.side[i]);
  }

 private:
  // The nodes a build adds before its split or leaf, each a split that sends all of the node's
  // triangles to one side (side_taking_all), and the side; at most one a level.
  struct OneSidedNodes {
    size_t count = 0;
    size_t inner[BuildSettings::kMaxDepthLimit + 1];
    int side[BuildSettings::kMaxDepthLimit + 1];
  };

  // The split of `node` that divides its triangles between two children, or axis -1 for a
  // leaf. A split that sends them all to one side is taken on the way (added to `out` and
  // `one_sided`, the node made that child), and the node's runs, found once, are costed again
  // for the smaller voxel. Not inlined: its runs (18 KB) would then be on the stack once per
  // level of the recursion of build().
  [[gnu::noinline]] SplitChoice choose_split(SmallNode& node, Subtree& out, OneSidedNodes& one_sided) const {
    if (node.count == 0 || node.depth >= parameters_.max_depth) return SplitChoice{};
    AxisRuns runs[3];
    for (int axis = 0; axis < 3; ++axis) runs[axis].find(node.events[axis], node.event_count[axis]);
    for (;;) {
      // One best over x, y, z in turn: what the per-axis bests combined in axis order give.
      SplitChoice split;
      for (int axis = 0; axis < 3; ++axis) runs[axis].cost(axis, node.voxel, node.count, parameters_.cost, split);
      if (split.axis >= 0 && !parameters_.cost.split_pays(split, node.count, node.voxel)) split.axis = -1;
      if (split.axis < 0) return split;
      const int whole_side = side_taking_all(split, node.count);
      if (whole_side < 0) return split;
      one_sided.inner[one_sided.count] = out.add_one_sided(split.axis, split.position);
      one_sided.side[one_sided.count] = whole_side;
      ++one_sided.count;
      become_child(node, split, whole_side);
      if (node.depth >= parameters_.max_depth) return SplitChoice{};
    }
  }

  // Not inlined into the recursion of build(): its scratch arrays (32 KB) would then be on the
  // stack once per level of the subtree.
  [[gnu::noinline]] void divide(const SmallNode& node, const SplitChoice& split, SmallNode& left,
                                SmallNode& right) const {
    const size_t n = node.count;
    uint8_t sides[kSmallNodeTriangles];
    classify_by_bounds(node.bounds, n, split, sides);
    const Box3 child_voxels[2] = {below_plane(node.voxel, split.axis, split.position),
                                  above_plane(node.voxel, split.axis, split.position)};
    left.voxel = child_voxels[0];
    right.voxel = child_voxels[1];
    left.depth = right.depth = node.depth + 1;
    left.count = right.count = 0;

    // Each kept triangle's renumbering (local indices are monotone, so kept events stay
    // sorted); straddlers get fresh bounds, and fresh events in each child they reach.
    Event renumberings[kSmallNodeTriangles];
    Event fresh[2][3][kMaxEvents];
    size_t fresh_count[2][3] = {};
    SmallNode* const children[2] = {&left, &right};
    const bool with_events = left.depth < parameters_.max_depth;
    auto place = [&](int c, size_t i, const Box3& bounds, bool straddles) {
      SmallNode& child = *children[c];
      const uint32_t local = child.count++;
      if (!straddles) renumberings[i] = event_renumbering(i, local);
      child.triangles[local] = node.triangles[i];
      child.bounds[local] = bounds;
      if (straddles && with_events)
        for (int axis = 0; axis < 3; ++axis) {
          Event* const events = fresh[c][axis];
          size_t& count = fresh_count[c][axis];
          if (bounds.min[axis] == bounds.max[axis]) {
            events[count++] = event_of(bounds.min[axis], local, kEventPlanar);
          } else {
            events[count++] = event_of(bounds.min[axis], local, kEventStart);
            events[count++] = event_of(bounds.max[axis], local, kEventEnd);
          }
        }
    };
    for (size_t i = 0; i < n; ++i) {
      if (sides[i] == kLeftOnly) {
        place(0, i, node.bounds[i], false);
      } else if (sides[i] == kRightOnly) {
        place(1, i, node.bounds[i], false);
      } else {
        const StraddlerBounds straddler = straddler_bounds(scene_, node.triangles[i], node.bounds[i], child_voxels,
                                                           split.axis, parameters_.perfect_splits);
        // Its events are read and dropped: the renumbering only needs to hold a value.
        renumberings[i] = Event{};
        for (int c = 0; c < 2; ++c)
          if (straddler.reaches[c]) place(c, i, straddler.bounds[c], true);
      }
    }

    // Children at the depth limit become leaves whatever their events say: they get none.
    if (!with_events) return;
    // Kept events go straight to the child when it has no fresh ones to merge in.
    for (int axis = 0; axis < 3; ++axis) {
      Event kept[2][kMaxEvents];
      Event* const to_left = fresh_count[0][axis] == 0 ? left.events[axis] : kept[0];
      Event* const to_right = fresh_count[1][axis] == 0 ? right.events[axis] : kept[1];
      Event* l = to_left;
      Event* r = to_right;
      split_kept_events(node.events[axis], node.event_count[axis], sides, renumberings, l, r);
      Event* const ends[2] = {l, r};
      Event* const starts[2] = {to_left, to_right};
      for (int c = 0; c < 2; ++c) {
        Event* const fresh_events = fresh[c][axis];
        const size_t count = fresh_count[c][axis];
        const size_t kept_count = static_cast<size_t>(ends[c] - starts[c]);
        children[c]->event_count[axis] = static_cast<uint32_t>(kept_count + count);
        if (count == 0) continue;
        insertion_sort(fresh_events, count);
        merge_events(starts[c], ends[c], fresh_events, fresh_events + count, children[c]->events[axis]);
      }
    }
  }

  const Scene& scene_;
  const SmallBuildParameters& parameters_;
};

}  // namespace

void build_small_subtree(const Scene& scene, const SmallBuildParameters& parameters, const Box3& voxel,
                         uint32_t depth, const uint32_t* triangles, size_t count, const Event* const events[3],
                         const size_t event_counts[3], Subtree& out) {
  thread_local SmallNode root;
  root.voxel = voxel;
  root.depth = depth;
  root.count = static_cast<uint32_t>(count);
  std::copy(triangles, triangles + count, root.triangles);
  // The bounds of each triangle in the voxel are what its events say.
  for (int axis = 0; axis < 3; ++axis) {
    root.event_count[axis] = static_cast<uint32_t>(event_counts[axis]);
    std::copy(events[axis], events[axis] + event_counts[axis], root.events[axis]);
    for (size_t e = 0; e < event_counts[axis]; ++e) {
      const Event& event = events[axis][e];
      Box3& bounds = root.bounds[event.triangle()];
      if (event.type() != kEventEnd) bounds.min[axis] = event.position;
      if (event.type() != kEventStart) bounds.max[axis] = event.position;
    }
  }
  SmallBuilder(scene, parameters).build(root, out);
}

}  // namespace kdray::detail
