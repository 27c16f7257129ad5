// The exact event builder (build_events.h). Subtrees above a size threshold are built in
// parallel into their own pieces, joined in a fixed order, so the bytes do not depend on the
// thread count.
#include "build_events.h"

#include "radix_sort.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <utility>

namespace kdray::detail {
namespace {

// Nodes with at least this many triangles build their two children in parallel.
constexpr size_t kParallelTriangles = 4096;

// Events as 64-bit integers in the order of operator<: the position's bits made monotone in
// the high half, the packed word in the low half. -0 and +0 are equal positions but different
// bits, so it does not apply to -0 (has_key is false).
constexpr uint32_t kSignBit = 0x80000000u;
inline bool has_key(const Event& event) {
  uint32_t bits;
  std::memcpy(&bits, &event.position, sizeof bits);
  return bits != kSignBit;
}
inline uint64_t event_key(const Event& event) {
  uint32_t bits;
  std::memcpy(&bits, &event.position, sizeof bits);
  const uint32_t monotone = bits & kSignBit ? ~bits : bits | kSignBit;
  return uint64_t{monotone} << 32 | event.packed;
}
inline Event event_of_key(uint64_t key) {
  const uint32_t monotone = static_cast<uint32_t>(key >> 32);
  const uint32_t bits = monotone & kSignBit ? monotone & ~kSignBit : ~monotone;
  Event event;
  std::memcpy(&event.position, &bits, sizeof bits);
  event.packed = static_cast<uint32_t>(key);
  return event;
}

using KeyArray = std::vector<uint64_t, UninitialisedAllocator<uint64_t>>;

// Below this many events, keys are sorted by comparison: a radix sort's fixed cost (its 2048
// byte counts) is more than it saves.
constexpr size_t kRadixSortEvents = 1024;

// Sorts events by sorting their keys (integers, which a radix sort takes), unless one is -0:
// then by comparison, `sort_with_comparison`. The events come in the order of their local
// triangle indices (each node makes them triangle by triangle), which fill the keys' three low
// bytes: the radix sort, stable, needs no pass over those.
template <typename SortEvents>
void sort_events(EventArray& events, KeyArray& keys, KeyArray& scratch, SortEvents sort_with_comparison) {
  if (!std::all_of(events.begin(), events.end(), has_key)) {
    sort_with_comparison();
    return;
  }
  keys.resize(events.size());
  std::transform(events.begin(), events.end(), keys.begin(), event_key);
  if (keys.size() < kRadixSortEvents) {
    std::sort(keys.begin(), keys.end());
  } else {
    scratch.resize(keys.size());
    radix_sort(keys.data(), scratch.data(), keys.size(), 3);
  }
  std::transform(keys.begin(), keys.end(), events.begin(), event_of_key);
}

// The re-clipped events of one node, on this thread.
void sort_events(EventArray& events) {
  thread_local KeyArray keys, scratch;
  sort_events(events, keys, scratch, [&] { std::sort(events.begin(), events.end()); });
}

// The events of one axis of a large node: the axes are sorted in parallel, and so are the
// events by comparison.
void sort_large_node_events(EventArray& events) {
  KeyArray keys, scratch;
  sort_events(events, keys, scratch, [&] { tbb::parallel_sort(events.begin(), events.end()); });
}

class EventBuilder {
 public:
  explicit EventBuilder(BuildContext& context)
      : scene_(context.scene),
        perfect_splits_(context.settings.perfect_splits),
        cost_(context.cost),
        max_depth_(context.max_depth),
        small_parameters_(context.small_parameters),
        finished_(context.finished) {}

  // Builds the subtree of `work` into `out`. Nodes with many triangles build their children
  // in parallel; below that size a thread builds the whole subtree itself (build_serial).
  void build(NodeWork& work, Piece& out) {
    const size_t n = work.triangles.size();
    if (n < kParallelTriangles) {
      const uint32_t depth = work.depth;  // build_serial may make `work` its own child
      build_serial(work, out.serial);
      finished_.report(depth);
      return;
    }
    const SplitChoice split = choose_split(work);
    if (split.axis < 0) {
      out.serial.add_leaf(work.triangles.data(), n);
      finished_.report(work.depth);
      return;
    }
    out.axis = split.axis;
    out.position = split.position;
    out.below = std::make_unique<Piece>();
    out.above = std::make_unique<Piece>();
    const int whole_side = side_taking_all(split, n);
    if (whole_side >= 0) {
      finished_.report(work.depth + 1);  // the empty child
      become_child(work, split, whole_side);
      build(work, whole_side == 0 ? *out.below : *out.above);
      return;
    }
    NodeWork left, right;
    divide(work, split, left, right);
    work = NodeWork{};  // the parent's arrays are not needed while the children build
    tbb::parallel_invoke([&] { build(left, *out.below); }, [&] { build(right, *out.above); });
  }

 private:
  // The cheapest split, or axis -1 when a leaf is cheaper or the depth limit is reached.
  SplitChoice choose_split(const NodeWork& work) const {
    const size_t n = work.triangles.size();
    SplitChoice split;
    if (n == 0 || work.depth >= max_depth_) return split;
    // Each axis keeps its own best; combining them in axis order with "strictly lower wins"
    // gives what one sweep over x, y, z in turn gives.
    SplitChoice per_axis[3];
    auto sweep = [&](int axis) {
      sweep_axis(work.events[axis].data(), work.events[axis].size(), axis, work.voxel, n, cost_, per_axis[axis]);
    };
    if (n >= kParallelTriangles)
      tbb::parallel_for(0, 3, sweep);
    else
      for (int axis = 0; axis < 3; ++axis) sweep(axis);
    for (const SplitChoice& candidate : per_axis)
      if (candidate.axis >= 0 && (split.axis < 0 || candidate.cost < split.cost)) split = candidate;
    if (split.axis >= 0 && !cost_.split_pays(split, n, work.voxel)) split.axis = -1;
    return split;
  }

  // Depth first on one thread.
  // `work` is changed into its own child where a split sends it whole to one side.
  void build_serial(NodeWork& work, Subtree& out) const {
    if (work.triangles.size() <= kSmallNodeTriangles) {
      const Event* const events[3] = {work.events[0].data(), work.events[1].data(), work.events[2].data()};
      const size_t counts[3] = {work.events[0].size(), work.events[1].size(), work.events[2].size()};
      build_small_subtree(scene_, small_parameters_, work.voxel, work.depth, work.triangles.data(),
                          work.triangles.size(), events, counts, out);
      return;
    }
    const SplitChoice split = choose_split(work);
    if (split.axis < 0) {
      out.add_leaf(work.triangles.data(), work.triangles.size());
      return;
    }
    const int whole_side = side_taking_all(split, work.triangles.size());
    if (whole_side >= 0) {
      become_child(work, split, whole_side);
      out.add_inner(split.axis, split.position, [&] { if (whole_side == 0) build_serial(work, out); },
                    [&] { if (whole_side == 1) build_serial(work, out); });
      return;
    }
    std::array<NodeWork, 2>& children = children_at_depth<NodeWork>(work.depth + 1);
    divide(work, split, children[0], children[1]);
    out.add_inner(split.axis, split.position, [&] { build_serial(children[0], out); },
                  [&] { build_serial(children[1], out); });
  }

 private:
  // Fills the two children of `work` (their arrays are overwritten; their capacity is kept).
  void divide(const NodeWork& work, const SplitChoice& split, NodeWork& left, NodeWork& right) const {
    const size_t n = work.triangles.size();
    // Scratch arrays reused by each thread's nodes: allocation dominated small nodes.
    thread_local std::vector<uint8_t> sides;
    thread_local std::vector<Event> renumberings;
    sides.assign(n, kBothSides);
    // Only grown, never shrunk: straddlers' entries are read too (and their events dropped),
    // so they must hold some value, and growing value-initialises only new entries.
    if (renumberings.size() < n) renumberings.resize(n);
    classify(work.events[split.axis].data(), work.events[split.axis].size(), split, sides.data());
    const Box3 child_voxels[2] = {below_plane(work.voxel, split.axis, split.position),
                                  above_plane(work.voxel, split.axis, split.position)};
    left.voxel = child_voxels[0];
    right.voxel = child_voxels[1];
    left.depth = right.depth = work.depth + 1;
    for (NodeWork* child : {&left, &right}) {
      child->triangles.clear();
      child->bounds.clear();
    }
    // Bounds are kept per triangle only without perfect splits: with them, a straddler's
    // child bounds come from clipping the triangle itself.
    const bool keep_bounds = !perfect_splits_;

    // Each kept triangle's renumbering (local indices are monotone, so the order of the kept
    // events survives). Straddlers get fresh bounds and events in each child they really
    // reach.
    thread_local EventArray fresh_left[3], fresh_right[3];
    for (int axis = 0; axis < 3; ++axis) {
      fresh_left[axis].clear();
      fresh_right[axis].clear();
    }
    auto place = [keep_bounds](NodeWork& child, EventArray* fresh, size_t i, uint32_t triangle,
                               const Box3& bounds) {
      const uint32_t local = static_cast<uint32_t>(child.triangles.size());
      child.triangles.push_back(triangle);
      if (keep_bounds) child.bounds.push_back(bounds);
      if (fresh)
        for (int axis = 0; axis < 3; ++axis) append_events(fresh[axis], bounds, axis, local);
      else
        renumberings[i] = event_renumbering(i, local);
    };
    size_t left_count = 0, right_count = 0;
    for (size_t i = 0; i < n; ++i) {
      left_count += sides[i] != kRightOnly;
      right_count += sides[i] != kLeftOnly;
    }
    for (NodeWork* child : {&left, &right}) {
      const size_t count = child == &left ? left_count : right_count;
      child->triangles.reserve(count);
      if (keep_bounds) child->bounds.reserve(count);
    }
    for (size_t i = 0; i < n; ++i) {
      const uint32_t triangle = work.triangles[i];
      const Box3& parent_bounds = keep_bounds ? work.bounds[i] : work.voxel;
      if (sides[i] == kLeftOnly) {
        place(left, nullptr, i, triangle, parent_bounds);
      } else if (sides[i] == kRightOnly) {
        place(right, nullptr, i, triangle, parent_bounds);
      } else {
        const StraddlerBounds straddler =
            straddler_bounds(scene_, triangle, parent_bounds, child_voxels, split.axis, perfect_splits_);
        if (straddler.reaches[0]) place(left, fresh_left, i, triangle, straddler.bounds[0]);
        if (straddler.reaches[1]) place(right, fresh_right, i, triangle, straddler.bounds[1]);
      }
    }

    // The three axes are independent; nodes large enough to be worth it split them in
    // parallel (the top of a tree is often a chain of empty-space cuts with no other
    // parallelism). The scratch arrays are this thread's, so they are passed on explicitly.
    const uint8_t* const node_sides = sides.data();
    const Event* const node_renumberings = renumberings.data();
    EventArray* const fresh_to_left = fresh_left;
    EventArray* const fresh_to_right = fresh_right;
    auto split_axis = [&](int axis, EventArray& kept_left, EventArray& kept_right) {
      split_events(work.events[axis], node_sides, node_renumberings, fresh_to_left[axis], fresh_to_right[axis],
                   kept_left, kept_right, left.events[axis], right.events[axis]);
    };
    if (n >= kParallelTriangles) {
      // Isolated: while it waits for the axes, this thread must not take up another node's
      // build, whose divide would reuse the scratch arrays the axes are still reading.
      tbb::this_task_arena::isolate([&] {
        tbb::parallel_for(0, 3, [&](int axis) {
          EventArray kept_left, kept_right;
          split_axis(axis, kept_left, kept_right);
        });
      });
    } else {
      thread_local EventArray kept_left, kept_right;
      for (int axis = 0; axis < 3; ++axis) split_axis(axis, kept_left, kept_right);
    }
  }

  // Sends each event of one axis whose triangle goes to only one side to that child, then
  // merges in the child's re-clipped (fresh) events. Kept events go straight to the child when
  // there is nothing to merge in.
  static void split_events(const EventArray& events, const uint8_t* sides, const Event* renumberings,
                           EventArray& fresh_left, EventArray& fresh_right, EventArray& kept_left,
                           EventArray& kept_right, EventArray& left_events, EventArray& right_events) {
    EventArray& to_left = fresh_left.empty() ? left_events : kept_left;
    EventArray& to_right = fresh_right.empty() ? right_events : kept_right;
    to_left.resize(events.size());
    to_right.resize(events.size());
    Event* l = to_left.data();
    Event* r = to_right.data();
    split_kept_events(events.data(), events.size(), sides, renumberings, l, r);
    to_left.resize(static_cast<size_t>(l - to_left.data()));
    to_right.resize(static_cast<size_t>(r - to_right.data()));
    merge_fresh(kept_left, fresh_left, left_events);
    merge_fresh(kept_right, fresh_right, right_events);
  }

  // Merges sorted re-clipped events into the kept ones (already in `out` when there are none).
  static void merge_fresh(const EventArray& kept, EventArray& fresh, EventArray& out) {
    if (fresh.empty()) return;
    sort_events(fresh);
    out.resize(kept.size() + fresh.size());
    merge_events(kept.data(), kept.data() + kept.size(), fresh.data(), fresh.data() + fresh.size(), out.data());
  }

  const Scene& scene_;
  const bool perfect_splits_;
  const CostModel& cost_;
  const uint32_t max_depth_;
  const SmallBuildParameters& small_parameters_;
  FinishedSubtrees& finished_;
};

}  // namespace

NodeWork node_with_events(const Box3& voxel, uint32_t depth, std::vector<uint32_t>&& triangles,
                          std::vector<Box3> bounds, bool perfect_splits) {
  NodeWork work;
  work.voxel = voxel;
  work.depth = depth;
  work.triangles = std::move(triangles);
  auto create = [&](int axis) {
    EventArray& events = work.events[axis];
    events.reserve(2 * work.triangles.size());
    for (size_t i = 0; i < work.triangles.size(); ++i)
      append_events(events, bounds[i], axis, static_cast<uint32_t>(i));
    if (work.triangles.size() >= kParallelTriangles)
      sort_large_node_events(events);
    else
      sort_events(events);
  };
  if (work.triangles.size() >= kParallelTriangles)
    tbb::parallel_for(0, 3, create);
  else
    for (int axis = 0; axis < 3; ++axis) create(axis);
  // With perfect splits the events say all that is needed of the bounds.
  if (!perfect_splits) work.bounds = std::move(bounds);
  return work;
}

void build_exact_subtree(BuildContext& context, NodeWork& work, Piece& out) { EventBuilder(context).build(work, out); }

}  // namespace kdray::detail
