// The O(N log N) SAH builder (Wald & Havran 2006): events are sorted once per axis at the root;
// each split divides the sorted lists in one pass and merges in the few re-clipped events of
// straddling triangles, so no node re-sorts. Subtrees above a size threshold are built in
// parallel into their own arrays and concatenated in a fixed order, so the bytes do not
// depend on the thread count.
#include <kdray/error.h>
#include <kdray/kdtree.h>
#include <kdray/threads.h>

#include "build_common.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>

namespace kdray {

uint32_t BuildSettings::resolved_max_depth(uint64_t triangles) const {
  if (max_depth != 0) return max_depth;
  const double automatic = 8.0 + 1.3 * std::log2(static_cast<double>(std::max<uint64_t>(triangles, 1)));
  return std::min(kAutoMaxDepthCap, static_cast<uint32_t>(automatic));
}

namespace detail {
namespace {

// Nodes with at least this many triangles build their two children in parallel.
constexpr size_t kParallelTriangles = 4096;

struct NodeWork {
  Box3 voxel;
  uint32_t depth = 0;
  std::vector<uint32_t> triangles;  // scene triangle per local index
  std::vector<Box3> bounds;         // per local index: the triangle's bounds in this voxel
  EventArray events[3];             // sorted
};

// A subtree of the parallel levels: an inner node with its two pieces, or (axis -1) a subtree
// built by one thread. Pieces are joined into one array once, at the end (flatten), rather
// than copied up level by level.
struct Piece {
  int axis = -1;
  float position = 0;
  std::unique_ptr<Piece> below, above;
  Subtree serial;
};

void count_sizes(const Piece& piece, size_t& nodes, size_t& references) {
  if (piece.axis < 0) {
    nodes += piece.serial.nodes.size();
    references += piece.serial.leaf_triangles.size();
    return;
  }
  ++nodes;
  count_sizes(*piece.below, nodes, references);
  count_sizes(*piece.above, nodes, references);
}

void append_piece(const Piece& piece, Subtree& out) {
  if (piece.axis < 0) {
    out.append(piece.serial);
    return;
  }
  out.add_inner(piece.axis, piece.position, [&] { append_piece(*piece.below, out); },
                [&] { append_piece(*piece.above, out); });
}

Subtree flatten(Piece&& root) {
  if (root.axis < 0) return std::move(root.serial);
  size_t nodes = 0, references = 0;
  count_sizes(root, nodes, references);
  Subtree out;
  out.nodes.reserve(nodes);
  out.leaf_triangles.reserve(references);
  append_piece(root, out);
  return out;
}

// Events as 64-bit integers in the order of operator<: the position's bits made monotone in
// the high half, the order key in the low half. -0 and +0 are equal positions but different
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
  return uint64_t{monotone} << 32 | event_order_key(event.packed);
}
inline Event event_of_key(uint64_t key) {
  const uint32_t monotone = static_cast<uint32_t>(key >> 32);
  const uint32_t bits = monotone & kSignBit ? monotone & ~kSignBit : ~monotone;
  const uint32_t order_key = static_cast<uint32_t>(key);
  Event event;
  std::memcpy(&event.position, &bits, sizeof bits);
  event.packed = (order_key & kMaxLocalTriangles) << 2 | order_key >> 30;
  return event;
}

using KeyArray = std::vector<uint64_t, UninitialisedAllocator<uint64_t>>;

// Sorts events by sorting their keys (integer comparisons), unless one is -0.
template <typename SortKeys, typename SortEvents>
void sort_events(EventArray& events, KeyArray& keys, SortKeys sort_keys, SortEvents sort_with_comparison) {
  if (!std::all_of(events.begin(), events.end(), has_key)) {
    sort_with_comparison();
    return;
  }
  keys.resize(events.size());
  std::transform(events.begin(), events.end(), keys.begin(), event_key);
  sort_keys();
  std::transform(keys.begin(), keys.end(), events.begin(), event_of_key);
}

// The re-clipped events of one node, on this thread.
void sort_events(EventArray& events) {
  thread_local KeyArray keys;
  sort_events(
      events, keys, [&] { std::sort(keys.begin(), keys.end()); },
      [&] { std::sort(events.begin(), events.end()); });
}

// The events of the root, in parallel.
void parallel_sort_events(EventArray& events) {
  KeyArray keys;
  sort_events(
      events, keys, [&] { tbb::parallel_sort(keys.begin(), keys.end()); },
      [&] { tbb::parallel_sort(events.begin(), events.end()); });
}

class EventBuilder {
 public:
  EventBuilder(const Scene& scene, const BuildSettings& settings, const BuildControl& control,
               uint64_t triangle_count)
      : scene_(scene),
        settings_(settings),
        cost_(cost_model_of(settings)),
        max_depth_(settings.resolved_max_depth(triangle_count)),
        small_parameters_{cost_, max_depth_, settings.perfect_splits},
        control_(control) {}

  // Builds the subtree of `work` into `out`. Nodes with many triangles build their children
  // in parallel; below that size a thread builds the whole subtree itself (build_serial).
  void build(NodeWork& work, Piece& out) {
    const size_t n = work.triangles.size();
    if (n < kParallelTriangles) {
      build_serial(work, out.serial);
      report_finished(work.depth);
      return;
    }
    const SplitChoice split = choose_split(work);
    if (split.axis < 0) {
      out.serial.add_leaf(work.triangles.data(), n);
      report_finished(work.depth);
      return;
    }
    out.axis = split.axis;
    out.position = split.position;
    out.below = std::make_unique<Piece>();
    out.above = std::make_unique<Piece>();
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
    if (split.axis >= 0 && !(split.cost < cost_.leaf_cost(n))) split.axis = -1;
    return split;
  }

  // Depth first on one thread.
  void build_serial(const NodeWork& work, Subtree& out) const {
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
    thread_local std::vector<uint32_t> left_index, right_index;
    sides.assign(n, kBothSides);
    // Only grown, never shrunk: entries of triangles a child does not get are read (and their
    // events dropped), so they must hold some value, and growing zero-fills only new entries.
    if (left_index.size() < n) {
      left_index.resize(n);
      right_index.resize(n);
    }
    classify(work.events[split.axis].data(), work.events[split.axis].size(), split, sides.data());
    left.voxel = below_plane(work.voxel, split.axis, split.position);
    right.voxel = above_plane(work.voxel, split.axis, split.position);
    left.depth = right.depth = work.depth + 1;
    for (NodeWork* child : {&left, &right}) {
      child->triangles.clear();
      child->bounds.clear();
    }
    // Bounds are kept per triangle only without perfect splits: with them, a straddler's
    // child bounds come from clipping the triangle itself.
    const bool keep_bounds = !settings_.perfect_splits;

    // Local index of each parent triangle in each child: monotone, so the order of the kept
    // events survives. Straddlers get fresh bounds and events in each child they really reach.
    thread_local EventArray fresh_left[3], fresh_right[3];
    for (int axis = 0; axis < 3; ++axis) {
      fresh_left[axis].clear();
      fresh_right[axis].clear();
    }
    auto place = [keep_bounds](NodeWork& child, std::vector<uint32_t>& index, EventArray* fresh, size_t i,
                               uint32_t triangle, const Box3& bounds) {
      index[i] = static_cast<uint32_t>(child.triangles.size());
      child.triangles.push_back(triangle);
      if (keep_bounds) child.bounds.push_back(bounds);
      if (fresh)
        for (int axis = 0; axis < 3; ++axis) append_events(fresh[axis], bounds, axis, index[i]);
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
        place(left, left_index, nullptr, i, triangle, parent_bounds);
      } else if (sides[i] == kRightOnly) {
        place(right, right_index, nullptr, i, triangle, parent_bounds);
      } else {
        Box3 bounds;
        if (child_bounds(scene_, triangle, parent_bounds, left.voxel, settings_.perfect_splits, bounds))
          place(left, left_index, fresh_left, i, triangle, bounds);
        if (child_bounds(scene_, triangle, parent_bounds, right.voxel, settings_.perfect_splits, bounds))
          place(right, right_index, fresh_right, i, triangle, bounds);
      }
    }

    // The three axes are independent; nodes large enough to be worth it split them in
    // parallel (the top of a tree is often a chain of empty-space cuts with no other
    // parallelism). The scratch arrays are this thread's, so they are passed on explicitly.
    const std::vector<uint8_t>& node_sides = sides;
    const auto& to_left_index = left_index;
    const auto& to_right_index = right_index;
    EventArray* const fresh_to_left = fresh_left;
    EventArray* const fresh_to_right = fresh_right;
    auto split_axis = [&](int axis, EventArray& kept_left, EventArray& kept_right) {
      split_events(work.events[axis], node_sides, to_left_index.data(), to_right_index.data(), fresh_to_left[axis],
                   fresh_to_right[axis], kept_left, kept_right, left.events[axis], right.events[axis]);
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
  // merges in the child's re-clipped (fresh) events. It does not branch on the side (the
  // sides of neighbouring events are unpredictable): every event is written to both outputs,
  // and each output advances only over its own. Kept events go straight to the child when
  // there is nothing to merge in.
  static void split_events(const EventArray& events, const std::vector<uint8_t>& sides,
                           const uint32_t* left_index, const uint32_t* right_index,
                           EventArray& fresh_left, EventArray& fresh_right,
                           EventArray& kept_left, EventArray& kept_right,
                           EventArray& left_events, EventArray& right_events) {
    EventArray& to_left = fresh_left.empty() ? left_events : kept_left;
    EventArray& to_right = fresh_right.empty() ? right_events : kept_right;
    to_left.resize(events.size());
    to_right.resize(events.size());
    Event* l = to_left.data();
    Event* r = to_right.data();
    for (const Event& event : events) {
      const uint32_t local = event.triangle();
      const uint32_t type = event.packed & 3u;
      const uint8_t side = sides[local];
      *l = Event{event.position, left_index[local] << 2 | type};
      *r = Event{event.position, right_index[local] << 2 | type};
      l += side == kLeftOnly;
      r += side == kRightOnly;
    }
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

  // Progress is the share of the tree's "mass" in finished subtrees, a subtree at depth d
  // weighing 2^-d: for a binary tree these weights sum to exactly 1 (Kraft), so it ends at
  // 100%. Only subtrees of the parallel levels report, which keeps the shared counter cold.
  void report_finished(uint32_t depth) {
    if (!control_.progress) return;
    const uint64_t weight = uint64_t{1} << (63 - std::min<uint32_t>(depth, 63));
    const uint64_t before = finished_mass_.fetch_add(weight);
    constexpr uint64_t kPercent = (uint64_t{1} << 63) / 100;
    if ((before + weight) / kPercent != before / kPercent) {
      // Reading the total under the lock keeps the reported fractions increasing.
      std::lock_guard<std::mutex> lock(progress_mutex_);
      control_.progress(std::min(1.0, std::ldexp(static_cast<double>(finished_mass_.load()), -63)));
    }
  }

  const Scene& scene_;
  const BuildSettings& settings_;
  const CostModel cost_;
  const uint32_t max_depth_;
  const SmallBuildParameters small_parameters_;
  const BuildControl& control_;
  std::atomic<uint64_t> finished_mass_{0};
  std::mutex progress_mutex_;
};

}  // namespace

}  // namespace detail

KdTree build_kdtree(const Scene& scene, const BuildSettings& settings, const BuildControl& control) {
  detail::validate_settings(settings);
  BuildTimings timings;
  auto lap = [last = std::chrono::steady_clock::now()](double& phase) mutable {
    const auto now = std::chrono::steady_clock::now();
    phase = std::chrono::duration<double>(now - last).count();
    last = now;
  };
  detail::RootWork root = detail::prepare_root(scene);
  lap(timings.prepare);
  detail::Subtree built;
  run_with_threads(control.threads, [&] {
    detail::NodeWork work;
    work.voxel = root.voxel;
    work.triangles = std::move(root.triangles);
    work.bounds = std::move(root.bounds);
    tbb::parallel_for(0, 3, [&](int axis) {
      detail::EventArray& events = work.events[axis];
      events.reserve(2 * work.triangles.size());
      for (size_t i = 0; i < work.triangles.size(); ++i)
        detail::append_events(events, work.bounds[i], axis, static_cast<uint32_t>(i));
      detail::parallel_sort_events(events);
    });
    lap(timings.events);
    detail::EventBuilder builder(scene, settings, control, work.triangles.size());
    detail::Piece root_piece;
    builder.build(work, root_piece);
    lap(timings.subdivide);
    built = detail::flatten(std::move(root_piece));
    lap(timings.assemble);
  });
  if (control.progress) control.progress(1.0);
  KdTree tree = detail::finish_tree(scene, settings, root.voxel, std::move(built));
  lap(timings.statistics);
  if (control.timings) *control.timings = timings;
  return tree;
}

}  // namespace kdray
